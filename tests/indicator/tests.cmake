# indicator tests (included by tests/CMakeLists.txt): the troubled-cell
# indicator (Limiter/indicator = modal_energy, doc/engine.md): the limiter
# examines only the cells whose indicator variable is not smooth.

# A smooth wave is flagged nowhere: the linear wave of
# prm/elasticity_linear_wave.prm (P2, 32 cells, one period) with the
# characteristic limiter: flagged_cells and troubled_cells are 0 at every
# output time (with the limiter in every cell, its TVB test clips the
# extrema), and the L2 error is the unlimited scheme's.
granular_dg_test(indicator/smooth_flags_nothing PRM ../prm/elasticity_linear_wave.prm
  ARGS --set Limiter/scheme=characteristic --set Limiter/indicator=modal_energy
  COMPARE timeseries.csv:time,flagged_cells,troubled_cells NUMDIFF -a 0 -r 0)

# A shock is flagged, and little else: prm/elasticity_shock.prm with the
# indicator at its automatic threshold; at t = 80, 160, 240 between 1 and 12
# of the 1200 cells are flagged, and the solution has no undershoot (strain
# >= -0.01), so the flagged cells hold the shock
# (tests/indicator/shock_cells.py).
granular_dg_test(indicator/shock_flagged EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/indicator/shock_cells.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/../prm/elasticity_shock.prm
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)
# The case as shipped (modal_energy_neighbours, threshold 1e-4): the limiter
# examines 1 to 80 of the 1200 cells at t = 80, 160, 240 (measured 10, 54,
# 9), and there is no undershoot; its crest is tested by
# elasticity/shock_crest.
granular_dg_test(indicator/shock_flagged_shipped EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/indicator/shock_cells.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/../prm/elasticity_shock.prm
       --indicator modal_energy_neighbours --threshold 1e-4 --max-flagged 80
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)

# The same two cases with the KXRCF indicator (face jumps of the stress):
# nothing flagged on the smooth wave; at the shock, 1 to 30 of 1200 cells.
granular_dg_test(indicator/kxrcf_smooth_flags_nothing PRM ../prm/elasticity_linear_wave.prm
  ARGS --set Limiter/scheme=characteristic --set Limiter/indicator=kxrcf
  COMPARE timeseries.csv:time,flagged_cells,troubled_cells NUMDIFF -a 0 -r 0)
granular_dg_test(indicator/kxrcf_shock_flagged EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/indicator/shock_cells.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/../prm/elasticity_shock.prm --indicator kxrcf --max-flagged 30
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)

# Subcell blending (Limiter/subcell blending, no limiter; doc/engine.md).
# On the smooth linear wave no cell is blended at any output time, and the
# L2 error against the exact solution is the unlimited scheme's, bit for bit (3.7e-6 at
# t = 1; -r 1e-10 in case the FMA contraction of the blended engine ever differs).
granular_dg_test(indicator/blending_smooth PRM ../prm/elasticity_linear_wave.prm
  ARGS --set "Limiter/subcell blending=true"
  COMPARE timeseries.csv:time,blended_cells,l2_error NUMDIFF -a 0 -r 1e-10)
# At the shock of prm/elasticity_shock.prm blending alone (Limiter/scheme =
# none) holds it: 1 to 40 of 1200 cells blended at t = 80, 160, 240, no
# undershoot (strain >= -0.01) and the largest strain within 1 % of the
# 9600-cell reference's plateau 0.3567 (without blending or limiter: 0.407).
granular_dg_test(indicator/blending_shock EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/indicator/shock_cells.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/../prm/elasticity_shock.prm --count blended_cells
       --max-flagged 40 --set Limiter/scheme=none --set "Limiter/subcell blending=true"
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)
