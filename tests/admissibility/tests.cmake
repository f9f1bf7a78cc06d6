# admissibility tests (included by tests/CMakeLists.txt): one run per
# physics driven into its inadmissible set. Each case gives two tests:
#   NAME          exit code 3; exactly one line on stderr naming time, step,
#                 position, state and the failed test (relative 1e-6: the
#                 numbers of a failing nonlinear run are round-off sensitive
#                 in their last digits); the last good state and
#                 summary.json written;
#   NAME_summary  summary.json: status (the same text), final_time and
#                 n_time_steps of the last good state (relative 1e-6).
function(admissibility_case name)
  cmake_parse_arguments(A "" "PRM" "ARGS;FILES;ABSENT" ${ARGN})
  granular_dg_test(admissibility/${name} PRM ${A_PRM} ARGS ${A_ARGS} EXIT 3 KEEP_OUTPUT
    NUMDIFF -r 1e-6 EXPECT_FILES out/summary.json ${A_FILES} ABSENT_FILES ${A_ABSENT})
  granular_dg_test(admissibility/${name}_summary PRM ${A_PRM} ARGS ${A_ARGS} EXIT 3 KEEP_OUTPUT
    COMPARE summary.json:status,final_time,n_time_steps NUMDIFF -r 1e-6)
endfunction()

# layered media, law (1.4), beta < 0: sigma'(eps) <= 0 under strong tension
admissibility_case(layered_tension PRM admissibility/layered_tension.prm
  FILES out/solution-0001.vtu out/profile-0001.csv)
# ... and beta > 0 under strong compression (tests/input/loss_of_hyperbolicity
# checks its message; here its summary)
granular_dg_test(admissibility/layered_compression_summary PRM input/loss_of_hyperbolicity.prm
  EXIT 3 KEEP_OUTPUT COMPARE summary.json:status,final_time,n_time_steps NUMDIFF -r 1e-6)
# the column: the stress law overflows (inf/NaN state)
admissibility_case(column_overflow PRM admissibility/column_overflow.prm
  FILES out/solution-0001.vtu out/profile-0001.csv)
# the network: NaN inflow data reach an edge
admissibility_case(network_nan_inflow PRM admissibility/network_nan_inflow.prm
  FILES out/solution-0001.vtu out/profile-0001-edge-1.csv)
# the hopper: the 30 -> 35 deg cone transition loses hyperbolicity
# (tests/hopper/hyperbolicity_loss checks its message; here its summary)
granular_dg_test(admissibility/hopper_hyperbolicity_loss_summary PRM ../prm/hopper_cone_30_35.prm
  ARGS --set Output/directory=out EXIT 3 KEEP_OUTPUT
  COMPARE summary.json:status,final_time,n_time_steps NUMDIFF -r 1e-6)
# ... whose last good state has its row in timeseries.csv too (the last
# row: the tau and step of summary.json)
granular_dg_test(admissibility/hopper_last_good_row PRM ../prm/hopper_cone_30_35.prm
  ARGS --set Output/directory=out EXIT 3 KEEP_OUTPUT
  COMPARE timeseries.csv:time,step NUMDIFF -r 1e-6)
# the network at degree 0: the maximum principle, broken by a CFL number
# above the monotone limit (Example 7.3 at CFL 1.2, the stability check off;
# a vertex cell 3 times the paper's, wide enough that its own bound does not
# shorten the step) in the first step: the last good state is the initial
# snapshot, not written a second time (solution.pvd lists t = 0 once)
admissibility_case(network_maximum_principle PRM ../prm/network_example_7_3.prm
  ARGS --set "Time stepping/CFL number=1.2" --set "Time stepping/check stability limit=false"
       --set "Network/vertex width factor=3" --set Output/directory=out
  FILES out/solution-0000.vtu out/profile-0000-edge-1.csv
  ABSENT out/solution-0001.vtu out/profile-0001-edge-1.csv)
# layered media with Limiter/strain positivity = true: the model declares
# eps >= 0; the tensile tail of case (b) (mean strain < 0) stops the run
# (with the limiter in every cell, as in doc/layered_strip.md)
admissibility_case(layered_negative_strain PRM ../prm/layered_1d.prm
  ARGS --set "Limiter/strain positivity=true" --set Limiter/indicator=everywhere --set Output/directory=out
       --set "Output/write vtu=false"
  FILES out/profile-0001.csv)
