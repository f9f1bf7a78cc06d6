# mpi tests (included by tests/CMakeLists.txt)

# Rank-count equivalence: the small 2D layered strip (48 x 8 P2 cells, 4
# time units, snapshots at t = 1, 2, 3, 4) on 1, 2 and 3 ranks
# (mpirun --oversubscribe): every column of timeseries.csv and of the four
# slice-NNNN.csv files must agree with the one-rank run to
# max |a - b| <= 1e-12 max |a| (column-scaled: several integrals are
# round-off zeros, where a relative test means nothing). The script prints
# that scaled difference per file and rank count; compared with 0 at
# -a 1e-12. Runs alone (RUN_SERIAL): three processes on two cores.
granular_dg_test(mpi/layered_2d_rank_equivalence EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/mpi/rank_equivalence.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/mpi/layered_2d_small.prm 1 2 3
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 1e-12 -r 0 LABELS mpi)
set_tests_properties(mpi/layered_2d_rank_equivalence PROPERTIES RUN_SERIAL TRUE)

# The same with subcell blending in 2D (layered_2d_blending.prm: the
# pulse of amplitude 5, no limiter, 134-206 of the 384 cells blended): the
# factors read the ghost neighbours' modes and the floor is reduced over the
# ranks, so 1, 2 and 3 ranks agree to 1e-12 (blended_cells exactly: an
# integer column). RUN_SERIAL: three processes on two cores.
granular_dg_test(mpi/layered_2d_blending_ranks EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/mpi/rank_equivalence.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/mpi/layered_2d_blending.prm 1 2 3
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 1e-12 -r 0 LABELS mpi)
set_tests_properties(mpi/layered_2d_blending_ranks PROPERTIES RUN_SERIAL TRUE)

# The same with the cells at rest left out (layered_2d_rest.prm: the reach
# of a step crosses rank boundaries through the ghost cells' flags).
granular_dg_test(mpi/layered_2d_rest_ranks EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/mpi/rank_equivalence.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/mpi/layered_2d_rest.prm 1 2 3
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 1e-12 -r 0 LABELS mpi)
set_tests_properties(mpi/layered_2d_rest_ranks PROPERTIES RUN_SERIAL TRUE)

# An inadmissible state found on rank 1 of 2 (the top row of a 2D strip):
# summary.json's status (rank 0 writes it, and prints the same line) names
# the position and state of that rank's point, not "on another MPI rank"
# (relative 1e-6; stderr is not compared: mpirun adds its own lines).
granular_dg_test(mpi/failure_on_other_rank PRM mpi/failure_on_rank_1.prm MPI 2 EXIT 3
  KEEP_OUTPUT COMPARE summary.json:status,final_time NUMDIFF -r 1e-6 LABELS mpi)

# A 1D scene on 2 ranks is bad input: its mesh is not spread over the ranks
# (each rank would compute the whole column and write every file into the
# same directory): the one line on stderr (mpirun's own lines aside), exit 2
# and nothing written.
granular_dg_test(mpi/one_dimensional_on_2_ranks PRM mpi/column_on_2_ranks.prm MPI 2 EXIT 2
  KEEP_OUTPUT NUMDIFF -a 0 -r 0 LABELS mpi)
