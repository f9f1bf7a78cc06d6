# bad_input tests (included by tests/CMakeLists.txt): the bad-input suite.
# Every NAME.prm here is a malformed case run as
# `granular_dg NAME.prm`: exit code 2, exactly one line on stderr naming the
# file and line where applicable, the parameter, its value and what is
# allowed (compared verbatim with NAME.output: numdiff -a 0 -r 0 on the
# fields, so any change of wording or number fails), and no file written.
# Further bad input of the scenes lives in tests/input, tests/column,
# tests/hopper and tests/network (doc/program.md lists them all).
file(GLOB bad_input_cases RELATIVE ${CMAKE_CURRENT_SOURCE_DIR}/bad_input
  CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/bad_input/*.prm)
foreach(file ${bad_input_cases})
  get_filename_component(t ${file} NAME_WE)
  granular_dg_test(bad_input/${t} PRM bad_input/${file} EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
endforeach()

# Cases without a file of their own (command line); base: a valid quick case.
set(base bad_input/../input/base.prm)
granular_dg_test(bad_input/directory_as_prm ARGS . EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
granular_dg_test(bad_input/set_without_name PRM ${base} ARGS --set =3
  EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
granular_dg_test(bad_input/set_without_value_sign PRM ${base} ARGS --set "Mesh/cells x"
  EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
granular_dg_test(bad_input/set_unknown_section PRM ${base} ARGS --set "Meshes/cells x=3"
  EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
granular_dg_test(bad_input/unknown_option PRM ${base} ARGS --restart
  EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
granular_dg_test(bad_input/two_prm_files PRM ${base} ARGS other.prm
  EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
granular_dg_test(bad_input/print_parameters_unknown_scene ARGS --print-parameters elastic
  EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
granular_dg_test(bad_input/set_scene_mismatch PRM ${base} ARGS --set scene=column
  EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
granular_dg_test(bad_input/resume_without_prm ARGS --resume EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
granular_dg_test(bad_input/subnormal_number PRM ${base} ARGS --set "Time stepping/final time=1e-320"
  EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
granular_dg_test(bad_input/print_parameters_extra ARGS --print-parameters column extra
  EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)

# An output directory with a previous run (scenario script, exact text).
granular_dg_test(bad_input/previous_run EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/bad_input/previous_run.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/input/base.prm
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)
# A periodic side without its partner: the periodic side is named, and its
# partner's condition (the message had named the other side, contradicting
# itself).
granular_dg_test(bad_input/periodic_without_partner PRM ${base}
  ARGS --set "Boundary conditions/left=wall" EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
# The line engine in 2D (it had been ignored: the run used matrix_free and
# parameters.prm said line).
granular_dg_test(bad_input/engine_line_2d PRM bad_input/../hardening/linear_wave_2d.prm
  ARGS --set Discretization/engine=line EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
# A 2D mesh too large for memory through its cells y: named as such (it had
# been 'Mesh/cells x', from the file, with cells y in brackets).
# MemAvailable varies between runs: -r 1 on the numbers.
granular_dg_test(bad_input/memory_cells_y PRM bad_input/../hardening/linear_wave_2d.prm
  ARGS --set "Mesh/cells y=400000000" EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 1)
# --benchmark into a directory with a benchmark.json that no benchmark of the
# program wrote (its manifest does not list it): refused, the file kept (it
# had been overwritten).
granular_dg_test(bad_input/benchmark_user_file PRM ${base} COPY bad_input/benchmark.json
  ARGS --benchmark --set Output/directory=. EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
# Settings that cannot act are refused (they had been accepted and ignored):
# Output/write modes in 2D and in the network (modes-NNNN.csv is a 1D file of
# the DG solver), Time stepping/max steps in a convergence study (every mesh
# runs to the final time), and an initial value of a network vertex without
# volume (its value balances its ends' fluxes at every stage).
granular_dg_test(bad_input/write_modes_2d PRM bad_input/../hardening/linear_wave_2d.prm
  ARGS --set "Output/write modes=true" EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
granular_dg_test(bad_input/write_modes_network PRM ../prm/network_example_7_3.prm
  ARGS --set "Output/write modes=true" EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
granular_dg_test(bad_input/max_steps_in_study PRM ${base}
  ARGS --set "Time stepping/max steps=10" --set Convergence/enabled=true
  EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
granular_dg_test(bad_input/vertex_without_volume_value PRM ../prm/network_two_stars.prm
  ARGS --set "Network/Vertex 2/width factor=0" --set "Network/Vertex 2/initial value=0.3"
  EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
granular_dg_test(bad_input/skip_at_rest_network PRM ../prm/network_example_7_3.prm
  ARGS --set "Time stepping/skip cells at rest=true" EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
granular_dg_test(bad_input/checkpoint_in_study PRM ${base}
  ARGS --set "Checkpoint/every steps=10" --set Convergence/enabled=true
  EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
# 2D entries set in 1D (they had been ignored): Mesh/cells y, and the top side.
granular_dg_test(bad_input/cells_y_in_1d PRM ${base} ARGS --set "Mesh/cells y=9"
  EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
granular_dg_test(bad_input/top_side_in_1d PRM ${base} ARGS --set "Boundary conditions/top=wall"
  EXIT 2 KEEP_OUTPUT NUMDIFF -a 0 -r 0)
