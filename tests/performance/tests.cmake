# performance smoke tests (label performance): granular_dg --benchmark on tiny
# cases (3 steps x 2 repetitions); check_benchmark.py checks benchmark.json is
# complete and consistent (rates = n_dofs * stages / CPU per step, phases,
# load recorded, no snapshots) and prints only what does not vary between
# runs, compared exactly (numdiff default). No timing assertions: the
# throughput table is contrib/benchmark.py's (doc/performance.md).
set(perf_check ${CMAKE_CURRENT_SOURCE_DIR}/performance/check_benchmark.py)
set(perf_steps --set Benchmark/steps=3 --set Benchmark/repetitions=2 --set "Benchmark/warm-up steps=1"
  --exe=$<TARGET_FILE:granular_dg>)
# 1D line engine, with the limiter (its benchmark.json is read by python/readers_benchmark)
granular_dg_test(performance/benchmark_layered_1d PRM ../prm/layered_1d.prm EXE ${perf_check}
  ARGS --set "Mesh/x max=20" --set "Mesh/cells x=40" ${perf_steps} COMPARE stdout LABELS performance
  FIXTURES_SETUP benchmark_layered_1d_output)
# 2D MatrixFree engine
granular_dg_test(performance/benchmark_layered_2d PRM ../prm/layered_2d.prm EXE ${perf_check}
  ARGS --set "Mesh/cells x=20" --set "Mesh/cells y=4" --set "Mesh/x max=20" ${perf_steps}
  COMPARE stdout LABELS performance)
# the network's own time loop (coupling phase)
granular_dg_test(performance/benchmark_network PRM ../prm/network_example_7_3.prm EXE ${perf_check}
  ARGS --set "Network/cells per unit length=16" ${perf_steps} COMPARE stdout LABELS performance)
# The study driver's quick variant (contrib/study.py --quick, 2 processes at a
# time): every chart kind written with its CSV, every stability run classified,
# the failure modes reproduced (check_study.py prints no numbers that vary).
granular_dg_test(performance/study_quick EXE ${CMAKE_CURRENT_SOURCE_DIR}/performance/check_study.py
  ARGS --study=${CMAKE_SOURCE_DIR}/contrib/study.py --exe=$<TARGET_FILE:granular_dg>
  COMPARE stdout LABELS performance)
# (about 2 min on 2 idle cores; generous for a loaded CI machine)
set_tests_properties(performance/study_quick PROPERTIES TIMEOUT 1200)
# The SIMD build (VectorizedArray of the native width, cmake/simd.cmake)
# against deal.II's width 1 on the 2D strip: 150 SSP-RK3 steps at P1-P3 with
# both operators in one program; it fails itself if the states differ by
# 1e-12 relative (doc/performance.md, "SIMD build").
granular_dg_unit_test(performance/simd_widths_agree NUMDIFF -r 1e-6)
