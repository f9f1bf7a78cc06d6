# paraview tests (included by tests/CMakeLists.txt)
# ParaView opens the shock case's solution.pvd by absolute path: 4 steps at
# t = 0, 80, 160, 240, the arrays, 3600 points per step, no NaN.
if(PVPYTHON_EXECUTABLE)
  granular_dg_test(paraview/shock_pvd EXE ${PVPYTHON_EXECUTABLE}
    ARGS --no-mpi ${CMAKE_CURRENT_SOURCE_DIR}/paraview/read_pvd.py
         ${CMAKE_CURRENT_BINARY_DIR}/shock_run/out/solution.pvd
    COMPARE stdout NUMDIFF -a 0 -r 0 KEEP_OUTPUT FIXTURES_REQUIRED shock_output)
else()
  message(WARNING "pvpython not found (Debian package python3-paraview): the ParaView test is skipped")
endif()
