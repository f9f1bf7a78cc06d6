# checkpoint tests (included by tests/CMakeLists.txt): checkpoint/restart
# equivalence. tests/checkpoint/resume_test.py runs a case twice,
# uninterrupted (the reference) and stopped / killed / interrupted and then
# resumed, and compares everything the reference wrote: files byte for byte
# (same rank count), CSV numbers column-scaled, summary.json but timings.
# The stored outputs say: no file differs (compared exactly, -a 0), and the
# largest CSV difference is 0 (serial: -a 0, bitwise) or below 1e-12 (a
# resume on another number of MPI ranks: -a 1e-12).
set(resume_test ${CMAKE_CURRENT_SOURCE_DIR}/checkpoint/resume_test.py)
function(checkpoint_test NAME PRM MODE)
  cmake_parse_arguments(C "" "TOLERANCE" "OPTIONS;LABELS" ${ARGN})
  if(NOT C_TOLERANCE)
    set(C_TOLERANCE 0)
  endif()
  granular_dg_test(checkpoint/${NAME} EXE ${TEST_PYTHON}
    ARGS ${resume_test} $<TARGET_FILE:granular_dg> ${CMAKE_CURRENT_SOURCE_DIR}/${PRM} ${MODE}
         ${C_OPTIONS}
    COMPARE stdout KEEP_OUTPUT NUMDIFF -a ${C_TOLERANCE} -r 0 LABELS ${C_LABELS})
endfunction()

# The column (line engine, friction projection, characteristic limiter):
# history.csv, sgn-map.csv and the scene's counters continue across the
# restart. Stopped at max steps = 1000 (every 300), and killed at random.
set(column_options --set "Mesh/cells=400" --set "Mesh/length=10" --set "Time stepping/final time=8"
  --set "Diagnostics/write sgn map=true" --set "Output/output times=2, 4, 6")
checkpoint_test(column_stop_resume column/m15_t20.prm stop:1000
  OPTIONS --every 300 ${column_options})
checkpoint_test(column_kill column/m15_t20.prm kill OPTIONS --every 100 ${column_options})

# A column run that skips quiet cells (tests/column/m15_rest.prm, skip
# tolerance 1e-15, at rest from t = 29 at step 7120): which cells a step leaves
# out (dg::ActiveCells), the limiter's flags and the friction states of the
# cells left out continue across the restart, so the resumed run is the
# uninterrupted one bit for bit. Stopped after skipping has begun (step 3000),
# and killed at random.
set(skip_options --set "Time stepping/skip tolerance=1e-15")
checkpoint_test(column_skip_stop_resume column/m15_rest.prm stop:3000
  OPTIONS --every 1000 ${skip_options})
checkpoint_test(column_skip_kill column/m15_rest.prm kill OPTIONS --every 500 ${skip_options})

# The layered strip with the (sigma, u) limiter: interrupted by SIGINT
# (exit 130, a checkpoint, status 'interrupted'), then resumed.
set(layered_options --set "Mesh/x max=60" --set "Mesh/cells x=240"
  --set "Time stepping/final time=40" --set "Output/output times=10, 20, 30")
checkpoint_test(layered_sigint ../prm/layered_1d.prm sigint OPTIONS --every 50 ${layered_options})

# Two runs in one (Boundary conditions/periodic from = 20: part 1 in
# before-periodic/, part 2 periodic): stopped in part 1, and killed at
# random (in either part).
checkpoint_test(layered_periodic_stop ../prm/layered_1d.prm stop:150
  OPTIONS --every 40 ${layered_options} --set "Boundary conditions/periodic from=20")
checkpoint_test(layered_periodic_kill ../prm/layered_1d.prm kill
  OPTIONS --every 40 ${layered_options} --set "Boundary conditions/periodic from=20")

# The hopper march (MatrixFree 1D engine, tau the time): hopper-steps.csv,
# the stored rows of the field and the stress profiles continue.
checkpoint_test(hopper_kill hopper/base.prm kill OPTIONS --every 20
  --set "Hopper/cells=200" --set "Time stepping/final time=0.3" --set "Hopper output/step series interval=10"
  --set "Output/output interval=0.1")

# The network (its own time loop): stopped at max steps and killed.
set(network_options --set "Network/cells per unit length=512" --set "Discretization/degree=1"
  --set "Limiter/scheme=componentwise" --set "Time stepping/CFL number=0.3"
  --set "Output/output interval=0.1")
checkpoint_test(network_stop_resume ../prm/network_example_7_3.prm stop:500
  OPTIONS --every 200 ${network_options})
checkpoint_test(network_kill ../prm/network_example_7_3.prm kill
  OPTIONS --every 50 ${network_options})

# 2D under MPI (the small strip of tests/mpi, 2 ranks): killed at random and
# resumed on 2 ranks, with VTU snapshots (every .vtu piece and .pvtu record
# byte for byte as the uninterrupted run's); stopped at step 60 and resumed
# on 1 and on 3 ranks (the checkpoint stores the solution per cell,
# independent of the partition). To 1e-12 column-scaled.
set(mpi_options --np 2 --set "Time stepping/final time=2" --set "Output/output times=0.5, 1, 1.5")
checkpoint_test(mpi_2d_kill mpi/layered_2d_small.prm kill OPTIONS --every 10 ${mpi_options}
  --set "Output/write vtu=true" TOLERANCE 1e-12 LABELS mpi)
checkpoint_test(mpi_2d_resume_on_1_rank mpi/layered_2d_small.prm stop:60
  OPTIONS --every 20 ${mpi_options} --resume-np 1 TOLERANCE 1e-12 LABELS mpi)
checkpoint_test(mpi_2d_resume_on_3_ranks mpi/layered_2d_small.prm stop:60
  OPTIONS --every 20 ${mpi_options} --resume-np 3 TOLERANCE 1e-12 LABELS mpi)
# The same with HDF5 snapshots (Output/format = hdf5): solution.xdmf of the
# resumed run lists the snapshots before the stop too, byte for byte as the
# uninterrupted run's; the .h5 files exist in both.
checkpoint_test(mpi_2d_hdf5_stop_resume mpi/layered_2d_small.prm stop:60
  OPTIONS --every 20 ${mpi_options} --set Output/format=hdf5 --set "Output/write vtu=true"
  TOLERANCE 1e-12 LABELS mpi)
# With the cells at rest left out (mpi/layered_2d_rest.prm): which cells a
# step computes depends only on the state, and the count of the updates left
# out continues from the checkpoint, so the resumed run ends byte for byte as
# the uninterrupted one (summary.json's skipped_cell_updates included); and
# resumed on 3 ranks after 2, to 1e-12.
checkpoint_test(layered_2d_rest_stop_resume mpi/layered_2d_rest.prm stop:60
  OPTIONS --every 20 --set "Time stepping/final time=2" --set "Output/output times=0.5, 1, 1.5")
checkpoint_test(mpi_2d_rest_resume_on_3_ranks mpi/layered_2d_rest.prm stop:60 TOLERANCE 1e-12
  OPTIONS --every 20 --np 2 --resume-np 3 --set "Time stepping/final time=2"
          --set "Output/output times=0.5, 1, 1.5" LABELS mpi)
# What a run killed while writing a checkpoint leaves must not harm later
# runs: on 2 ranks, the checkpoint of step 10 is written although Open MPI's
# MPI-IO semaphore for that file name is left taken (the run would wait in
# MPI_File_open; the test's deadline is 120 s), and a killed write's partial
# file and MPI-IO lock file are removed by the next checkpoint.
granular_dg_test(checkpoint/killed_write_leftovers EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/checkpoint/killed_write_leftovers.py
       $<TARGET_FILE:granular_dg> ${CMAKE_CURRENT_SOURCE_DIR}/mpi/layered_2d_small.prm
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0 LABELS mpi)
set_tests_properties(checkpoint/mpi_2d_kill checkpoint/mpi_2d_resume_on_1_rank
  checkpoint/mpi_2d_resume_on_3_ranks checkpoint/mpi_2d_hdf5_stop_resume
  checkpoint/mpi_2d_rest_resume_on_3_ranks checkpoint/killed_write_leftovers
  PROPERTIES RUN_SERIAL TRUE)

# What cannot be resumed: exit 2 and one line each (verbatim).
granular_dg_test(checkpoint/bad_resume EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/checkpoint/bad_resume.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/input/base.prm ${CMAKE_CURRENT_SOURCE_DIR}/column/m15_t20.prm
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)

# A general graph (the shipped city grid from CSV files: 84 roads, 36
# junctions, every vertex value in the checkpoint), stopped and resumed, and
# killed at random and resumed: bitwise equal to the uninterrupted run.
set(city_options --set "Network/cells per unit length=8" --set "Time stepping/final time=3"
  --set "Output/output times=1, 2, 3" --set "Network/edge profiles=one_file")
checkpoint_test(network_graph_stop_resume ../prm/network_city_grid.prm stop:250
  OPTIONS --every 100 ${city_options})
checkpoint_test(network_graph_kill ../prm/network_city_grid.prm kill
  OPTIONS --every 50 ${city_options})
