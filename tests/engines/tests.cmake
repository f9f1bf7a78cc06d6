# engines tests (included by tests/CMakeLists.txt): the line engine and the
# MatrixFree engine discretise alike. Per 1D scene a short run with each
# engine; every CSV output agrees to 1e-11 of its column's scale
# (tests/engines/engines_agree.py; the stored outputs say "yes").
set(engines_agree ${CMAKE_CURRENT_SOURCE_DIR}/engines/engines_agree.py)
function(engines_test NAME PRM)
  granular_dg_test(engines/${NAME} EXE ${TEST_PYTHON}
    ARGS ${engines_agree} $<TARGET_FILE:granular_dg> ${CMAKE_CURRENT_SOURCE_DIR}/${PRM} ${ARGN}
    COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)
endfunction()

# the column: friction projection, characteristic limiter, m = 3/2
engines_test(column column/m15_t20.prm --set "Mesh/cells=200" --set "Mesh/length=5"
  --set "Time stepping/final time=2" --set "Output/output times=1")
# layered 1D: interfaces, impedance flux, the (sigma, u) limiter
engines_test(layered_1d ../prm/layered_1d.prm --set "Mesh/x max=40" --set "Mesh/cells x=160"
  --set "Time stepping/final time=20" --set "Output/output times=10")
# the hopper march: source term, symmetry and friction-wall boundaries
engines_test(hopper hopper/base.prm --set "Hopper/cells=100"
  --set "Time stepping/final time=0.2" --set "Output/output interval=0.1")
