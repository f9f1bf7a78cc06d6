# input tests (included by tests/CMakeLists.txt)
# Bad input: exit code 2, exactly one line on stderr naming the parameter,
# its value and what is allowed (compared verbatim), and no file written.
foreach(t unknown_parameter unknown_scene degree_9 negative_cfl)
  granular_dg_test(input/${t} PRM input/${t}.prm EXIT 2 KEEP_OUTPUT)
endforeach()
granular_dg_test(input/missing_prm ARGS no_such_case.prm EXIT 2 KEEP_OUTPUT)
granular_dg_test(input/unwritable_output PRM input/base.prm
  ARGS --set Output/directory=/dev/null/out EXIT 2 KEEP_OUTPUT)
granular_dg_test(input/unknown_set_parameter PRM input/base.prm
  ARGS --set Discretization/degre=2 EXIT 2 KEEP_OUTPUT)
granular_dg_test(input/bad_expression PRM input/base.prm
  ARGS "--set" "Initial condition/strain=sin(2*pi*z)" EXIT 2 KEEP_OUTPUT)

# An existing result directory is refused (the shock run's, via a fixture).
granular_dg_test(input/output_exists PRM input/base.prm
  ARGS --set Output/directory=../../shock_run/out EXIT 2 KEEP_OUTPUT
  FIXTURES_REQUIRED shock_output)

# Physical inadmissibility: a wall accelerating into the medium compresses it
# past eps = -1/(2 beta K), where sigma' < 0 and the system stops being
# hyperbolic. Exit code 2, one line naming time, step, position, state and
# the failed test, and the last good state written (relative tolerance 1e-6).
granular_dg_test(input/loss_of_hyperbolicity PRM input/loss_of_hyperbolicity.prm
  EXIT 3 KEEP_OUTPUT NUMDIFF -r 1e-6
  EXPECT_FILES out/summary.json out/solution-0001.vtu out/profile-0001.csv)

# Time stepping/check stability limit = false lets a stability study run a
# CFL number above SSP-RK3's limit (0.25 > 0.2097 at P2; refused by default,
# tests/bad_input): the short run completes (exact text).
granular_dg_test(input/cfl_check_off PRM ../prm/layered_1d.prm
  ARGS --set "Time stepping/CFL number=0.25" --set "Time stepping/check stability limit=false"
       --set "Time stepping/final time=1" --set "Output/output times=" --set "Output/write vtu=false"
  COMPARE summary.json:status NUMDIFF -a 0 -r 0)

# A threshold with Limiter/indicator = everywhere has no effect: the run
# completes, with one warning line on stderr (it was silently ignored).
granular_dg_test(input/threshold_without_indicator PRM input/threshold_without_indicator.prm
  EXPECT_FILES out/summary.json)

# include: relative to the parameter file (here run from the test's own
# directory with the file's absolute path in the source tree), and a bad value
# in an included file named with that file and line.
granular_dg_test(input/include_relative
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/input/include_relative.prm --set Output/directory=out
  COMPARE summary.json:status,final_time NUMDIFF -a 0 -r 0)
granular_dg_test(input/include_bad PRM input/include_bad.prm
  COPY input/include_common.prm input/include_bad_value.prm EXIT 2 KEEP_OUTPUT)
# the scene set in an included file (nested includes: relative to the
# parameter file), and two scenes in a file and the file it includes
granular_dg_test(input/include_scene PRM input/include_scene.prm
  COPY input/include_scene_common.prm input/include_common.prm
  ARGS --set Output/directory=out
  COMPARE summary.json:status,final_time NUMDIFF -a 0 -r 0)
granular_dg_test(input/include_two_scenes PRM input/include_two_scenes.prm
  COPY input/include_scene_common.prm input/include_common.prm EXIT 2 KEEP_OUTPUT)

# --version names the revision built (cmake/git_revision.cmake runs at every
# build), the launcher's and the engine's alike.
granular_dg_test(input/version_is_head EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/input/version_is_head.py $<TARGET_FILE:granular_dg>
       $<TARGET_FILE:granular_dg_engine> ${CMAKE_SOURCE_DIR}
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)
