# docs tests (included by tests/CMakeLists.txt): every granular_dg command
# quoted in README.md and doc/*.md runs as written (tests/docs/doc_commands.py:
# each started in a scratch directory, exit 0, the announced exit code, or
# still running after 3 s with its input accepted).
granular_dg_test(docs/doc_commands EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/docs/doc_commands.py ${CMAKE_SOURCE_DIR}
       $<TARGET_FILE:granular_dg>
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)
