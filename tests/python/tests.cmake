# python tests (included by tests/CMakeLists.txt): the readers of the
# contrib/granular_dg package against outputs other tests write (their
# fixtures): tests/python/readers.py checks what they parse against what the
# program wrote (rows of timeseries.csv against summary.json's steps, times
# across files, known values), that a malformed file raises OutputError
# naming the file and line, and the comparison of runs; one line per check,
# compared exactly.
set(readers ${CMAKE_CURRENT_SOURCE_DIR}/python/readers.py)
foreach(t "layered;shock_run/out;shock_output"
          "network;network_7_1_run/out;network_7_1_output"
          "hopper;hopper_preservation_run/out;hopper_field"
          "convergence;elasticity/linear_wave_eoc/out;elasticity_eoc_output"
          "benchmark;performance/benchmark_layered_1d/out;benchmark_layered_1d_output"
          "malformed;shock_run/out;shock_output"
          "compare;shock_run/out;shock_output")
  list(GET t 0 what)
  list(GET t 1 run)
  list(GET t 2 fixture)
  granular_dg_test(python/readers_${what} EXE ${TEST_PYTHON}
    ARGS ${readers} ${what} ${CMAKE_CURRENT_BINARY_DIR}/${run}
    COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0 FIXTURES_REQUIRED ${fixture})
endforeach()
