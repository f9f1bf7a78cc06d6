# elasticity tests (included by tests/CMakeLists.txt)
# EOC of degrees 0-4 on the periodic linear wave against the exact solution:
# the .output holds the theoretical rate p + 1 of the L2 and of the L1 error;
# |EOC - (p + 1)| <= 0.2, so
# every degree converges at >= p + 0.8. (Its convergence.csv is read by
# python/readers_convergence.)
granular_dg_test(elasticity/linear_wave_eoc PRM ../prm/elasticity_linear_wave.prm
  ARGS --set Convergence/enabled=true
  COMPARE convergence-rates.csv NUMDIFF -a 0.2 -r 0 FIXTURES_SETUP elasticity_eoc_output)

# The shock case of the prm/ file as it ships: the strain integral equals the
# wall displacement int_0^60 0.2 (1 + cos(pi (t - 30)/30)) dt = 12 exactly
# (conservation through the moving-wall flux; hand-computed .output).
granular_dg_test(elasticity/shock_conservation PRM ../prm/elasticity_shock.prm
  COMPARE timeseries.csv:time,integral_strain NUMDIFF -a 1e-8 -r 0
  FIXTURES_SETUP shock_output WORKDIR ${CMAKE_CURRENT_BINARY_DIR}/shock_run)
# The crest of the shipped case where the default profiles sample it (3
# points per cell): at t = 240 within 0.5 % of the 9600-cell run's 0.3567,
# and at t = 80, 84, ..., 240 at most 0.5 % above the crest 0.3630
# (tests/elasticity/shock_crest.py). The modal-energy indicator at its
# automatic threshold, limiting only the flagged cells, left the cells above
# the shock's foot alone: 0.3643 at t = 240, 0.3900 at t = 200.
granular_dg_test(elasticity/shock_crest EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/elasticity/shock_crest.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/../prm/elasticity_shock.prm
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)
# Regression of the profiles at t = 240 (cell centres) with the limiter in
# every cell, stored from a reviewed run (doc/elasticity.md shows the figure;
# the shipped case is tested by indicator/shock_flagged_shipped and
# elasticity/shock_crest). Tolerance 1e-7 absolute.
granular_dg_test(elasticity/shock_profile PRM ../prm/elasticity_shock.prm
  ARGS "--set" "Output/profile points per cell=1" "--set" "Output/write vtu=false"
       "--set" "Limiter/indicator=everywhere" "--set" "Limiter/indicator threshold=0"
  COMPARE profile-0003.csv NUMDIFF -a 1e-7 -r 1e-6)
