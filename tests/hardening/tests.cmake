# hardening tests (included by tests/CMakeLists.txt): the defects a new user
# found in main at 120e9ea, one test each; every one of them
# failed before its fix.

# 1. A 2D convergence study refines every direction: EOC p + 1 (it reported
# 17.6 and 62.1 for P1 when only cells x was refined); within 0.15.
granular_dg_test(hardening/convergence_2d PRM hardening/linear_wave_2d.prm
  ARGS --set Convergence/enabled=true --set "Convergence/degrees=1,2"
       --set "Convergence/cells=8,16,32"
  COMPARE convergence-rates.csv:degree,eoc_finest,eoc_l1_finest NUMDIFF -a 0.15)
# 6. ... and under MPI it exits (rank 0 built a mesh alone and hung)
granular_dg_test(hardening/convergence_2d_mpi PRM hardening/linear_wave_2d.prm MPI 2
  ARGS --set Convergence/enabled=true --set "Convergence/degrees=1,2"
       --set "Convergence/cells=8,16,32"
  COMPARE convergence-rates.csv:degree,eoc_finest,eoc_l1_finest NUMDIFF -a 0.15 LABELS mpi)
set_tests_properties(hardening/convergence_2d_mpi PROPERTIES TIMEOUT 120)

# 2. A reference solution of another time is bad input (it gave an L2 error
# of 1.41 instead of 0.005): exit 2, one line.
granular_dg_test(hardening/reference_other_time PRM ../prm/layered_1d.prm EXIT 2
  COPY hardening/reference_t10.csv
  ARGS --set "Mesh/x max=1" --set "Mesh/cells x=2" --set "Layers/layer width=0.5"
       --set "Exact solution/reference file=reference_t10.csv" --set "Time stepping/final time=20"
       --set "Output/output times=")

# 3. A run whose max steps land on its final step has completed (it said
# "stopped at max steps", and the resume was then refused).
granular_dg_test(hardening/max_steps_at_the_end PRM ../prm/elasticity_shock.prm
  ARGS --set "Time stepping/final time=30" --set "Output/output times=10, 20"
       --set "Time stepping/max steps=884" --set "Output/write vtu=false"
  COMPARE summary.json:status,n_time_steps)

# 5. and the smaller benchmark defects: blocks restart from the initial state
# (the calibration stepped past the final time into item 4), only
# benchmark.json is written (a second benchmark into the directory was
# refused), the limiter by name.
granular_dg_test(hardening/benchmark_twice EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/hardening/benchmark_twice.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/../prm/layered_1d.prm
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)

# 7. The hopper marches at degree 0 (an internal error read mode 1).
granular_dg_test(hardening/hopper_degree_0 PRM ../prm/hopper_cone_30_25.prm
  ARGS --set Discretization/degree=0 --set "Time stepping/CFL number=0.5"
       --set "Output/write vtu=false" --set "Hopper output/step series interval=0"
  COMPARE summary.json:status,final_time)

# 8. A snapshot count that cannot be meant is refused before anything is
# written (an interval of 1e-9 exhausted 24 GB): exit 2, one line with the
# count and the size of a snapshot.
granular_dg_test(hardening/output_interval_tiny PRM ../prm/elasticity_shock.prm EXIT 2
  ARGS --set "Output/output times=" --set "Output/output interval=1e-9")

# 9. The output directory is locked while a run writes it.
granular_dg_test(hardening/lock EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/hardening/lock.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/../prm/elasticity_shock.prm
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)

# 10. Two SIGINTs leave a complete checkpoint (2 of 4 trials left only a .tmp).
granular_dg_test(hardening/double_sigint EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/hardening/double_sigint.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/../prm/layered_1d.prm
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)

# 11. Resume compares canonical paths and sorted time lists.
granular_dg_test(hardening/resume_normalised EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/hardening/resume_normalised.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/input/base.prm
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)

# Sliver steps before output times are merged into the step before: the
# vertical column takes 20000 steps, not 20007 (dt = 9.1e-12 at seven of ten
# outputs).
granular_dg_test(hardening/no_sliver_steps PRM ../prm/column_vertical.prm
  ARGS --set "Output/write vtu=false" --set "Diagnostics/write sgn map=false"
  COMPARE summary.json:n_time_steps)

# 12. A mesh that cannot fit is refused before it is allocated (it ended in
# std::bad_alloc, or in swapping): exit 2, one line with the estimate, the
# memory available and what to change. The available memory (MemAvailable)
# varies between runs: -r 1 on the numbers, the words compared as they are.
granular_dg_test(hardening/memory_does_not_fit PRM hardening/memory_does_not_fit.prm EXIT 2
  KEEP_OUTPUT NUMDIFF -a 0 -r 1)

# The memory report (summary.json diagnostics/memory): the state
# vectors each hold 8 bytes per DoF (the solution, SSP-RK3's stage vector, the
# last good state), measured with deal.II's memory_consumption() on the 2D
# strip (432000 DoFs, 2 steps); 1e-3 relative (the vectors' fixed overhead is
# 1e-4 of them).
granular_dg_test(hardening/memory_report PRM ../prm/layered_2d.prm
  ARGS --set "Time stepping/final time=0.003" --set "Output/output times=0.003"
       --set "Output/write vtu=false"
  COMPARE summary.json:diagnostics/memory/solution_bytes_per_dof,diagnostics/memory/rk_stages_bytes_per_dof,diagnostics/memory/last_good_bytes_per_dof
  NUMDIFF -r 1e-3 -a 0)

# A run never removes or writes over a user's file in its output directory:
# overwrite keeps a file the user put into OUT/checkpoints/ (it removed the
# whole folder), and a case file named parameters.prm in its own output
# directory is refused (it was replaced by the parameter dump).
granular_dg_test(hardening/user_files_kept EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/hardening/user_files_kept.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/../prm/elasticity_shock.prm
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)
# Overwriting a two-part run of the layered strip removes its
# before-periodic/ folder unless the user put a file into it.
granular_dg_test(hardening/overwrite_two_part EXE ${TEST_PYTHON}
  ARGS ${CMAKE_CURRENT_SOURCE_DIR}/hardening/overwrite_two_part.py $<TARGET_FILE:granular_dg>
       ${CMAKE_CURRENT_SOURCE_DIR}/../prm/layered_1d.prm
  COMPARE stdout KEEP_OUTPUT NUMDIFF -a 0 -r 0)
# The memory refusal counts what writing a snapshot adds (DataOut's patches
# and the file's buffers): a run that passed the check could be killed at its
# first snapshot. The words name the format; the numbers at -r 1 as above.
granular_dg_test(hardening/memory_does_not_fit_hdf5 PRM hardening/memory_does_not_fit.prm EXIT 2
  ARGS --set Output/format=hdf5 KEEP_OUTPUT NUMDIFF -a 0 -r 1)

# A run started without mpirun (an isolated Open MPI singleton, see
# source/launcher.cc) makes no session directory: isolated singletons share
# one, and a run ending removed it while another was starting (MPI_Init
# failed in about 1 of 150 starts, two to four at a time). With the
# temporary directory unusable (TMPDIR=/proc), a run that made one would
# fail at MPI_Init; the 2D strip's mesh is p4est's, and its HDF5
# output goes through MPI-IO.
granular_dg_test(hardening/singleton_without_session_directory PRM ../prm/layered_2d.prm
  ENV TMPDIR=/proc
  ARGS --set "Time stepping/final time=0.003" --set "Output/output times=0.003"
       --set Output/format=hdf5
  COMPARE summary.json:status,final_time)
