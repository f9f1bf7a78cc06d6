# paraview tests (included by tests/CMakeLists.txt)
# ParaView opens the shock case's solution.pvd by absolute path: 4 steps at
# t = 0, 80, 160, 240, the arrays, 3600 points per step, no NaN.
if(PVPYTHON_EXECUTABLE)
  granular_dg_test(paraview/shock_pvd EXE ${PVPYTHON_EXECUTABLE}
    ARGS --no-mpi ${CMAKE_CURRENT_SOURCE_DIR}/paraview/read_pvd.py
         ${CMAKE_CURRENT_BINARY_DIR}/shock_run/out/solution.pvd
    COMPARE stdout NUMDIFF -a 0 -r 0 KEEP_OUTPUT FIXTURES_REQUIRED shock_output)
  # HDF5/XDMF output (Output/format = hdf5): the 2D strip, cut to
  # 40 x 8 P2 cells, to t = 2 on 1 and 2 ranks; all ranks write one .h5 per
  # snapshot, rank 0 the .xdmf. The runs agree (timeseries, 1e-12), and
  # ParaView's XDMF reader opens solution.xdmf by absolute path: 3 steps at
  # t = 0, 1, 2, the arrays, 2880 points per step (320 cells x 9 points, DG:
  # not merged), no NaN, the same on both rank counts.
  foreach(ranks 1 2)
    granular_dg_test(paraview/hdf5_run_np${ranks} PRM ../prm/layered_2d.prm
      ARGS --set "Mesh/x max=20" --set "Mesh/cells x=40" --set "Mesh/cells y=8"
           --set "Time stepping/final time=2" --set "Output/output times=1"
           --set Output/format=hdf5
      MPI ${ranks} COMPARE timeseries.csv:time,energy NUMDIFF -a 1e-12 -r 0
      FIXTURES_SETUP hdf5_np${ranks} WORKDIR ${CMAKE_CURRENT_BINARY_DIR}/hdf5_np${ranks} LABELS mpi)
    granular_dg_test(paraview/hdf5_xdmf_np${ranks} EXE ${PVPYTHON_EXECUTABLE}
      ARGS --no-mpi ${CMAKE_CURRENT_SOURCE_DIR}/paraview/read_pvd.py
           ${CMAKE_CURRENT_BINARY_DIR}/hdf5_np${ranks}/out/solution.xdmf
      COMPARE stdout NUMDIFF -a 0 -r 0 KEEP_OUTPUT FIXTURES_REQUIRED hdf5_np${ranks})
  endforeach()
  # A network VTU in several pieces: the 6 x 6 city grid at 17,000 cells
  # per unit length and p = 2 (1,428,000 cells, 4,284,072 points with the
  # vertices) is above the writer's 2^22 points per piece, so one rank's file
  # holds two pieces (on 2 ranks each rank's file one). Two steps keep the
  # mass balance (residual below 1e-12), and ParaView reads every point of
  # every piece: 4,284,072 per step on both rank counts.
  foreach(ranks 1 2)
    granular_dg_test(paraview/network_pieces_run_np${ranks} PRM ../prm/network_city_grid.prm
      COPY ../prm/network_city_grid.csv ../prm/network_city_grid_vertices.csv
      ARGS --set "Network/cells per unit length=17000" --set "Network/edge profiles=none"
           --set "Time stepping/final time=5e-6" --set "Output/output times=5e-6"
      MPI ${ranks} COMPARE timeseries.csv:time,mass_balance_residual NUMDIFF -a 1e-12 -r 0
      FIXTURES_SETUP network_pieces_np${ranks}
      WORKDIR ${CMAKE_CURRENT_BINARY_DIR}/network_pieces_np${ranks} LABELS mpi)
    granular_dg_test(paraview/network_pieces_np${ranks} EXE ${PVPYTHON_EXECUTABLE}
      ARGS --no-mpi ${CMAKE_CURRENT_SOURCE_DIR}/paraview/read_pvd.py
           ${CMAKE_CURRENT_BINARY_DIR}/network_pieces_np${ranks}/out/solution.pvd --pieces
      COMPARE stdout NUMDIFF -a 0 -r 0 KEEP_OUTPUT FIXTURES_REQUIRED network_pieces_np${ranks})
  endforeach()
else()
  message(WARNING "pvpython not found (Debian package python3-paraview): the ParaView test is skipped")
endif()
