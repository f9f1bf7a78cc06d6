#pragma once

#include <granular_dg/base/output.h>

#include <array>
#include <chrono>
#include <functional>
#include <string>
#include <vector>

namespace granular_dg
{
  /// Benchmark/ parameters: instead of the output schedule, time blocks of
  /// steps of the scene as configured (doc/performance.md).
  struct BenchmarkParameters
  {
    bool         enabled      = false;
    unsigned int repetitions  = 5;
    unsigned int steps        = 0;   ///< per repetition; 0: calibrated to min_time
    double       min_time     = 0.3; ///< CPU seconds per repetition when calibrating
    unsigned int warmup_steps = 2;
  };

  /**
   * Wall clocks of the phases of a time step. A null StepPhases* costs one
   * branch per scope, so the time loop carries the scopes always.
   */
  struct StepPhases
  {
    enum Phase : unsigned int
    {
      operator_apply,  ///< dst = M^-1 R(src), all stages
      vector_updates,  ///< the Runge-Kutta combinations of the stages
      post_stage_hook, ///< scene stage operations (friction projection)
      limiter,
      post_limiter_hook,
      admissibility,
      time_step,       ///< max wave speed / h
      end_of_step_hook,
      state_copy,      ///< the last good state kept for failures
      n_phases
    };
    static const char *
    name(Phase p);

    std::array<double, n_phases> seconds{};

    void
    reset()
    {
      seconds.fill(0.);
    }

    double
    total() const;

    class Scope
    {
    public:
      Scope(StepPhases *phases, const Phase phase)
        : phases(phases)
        , phase(phase)
      {
        if (phases)
          start = std::chrono::steady_clock::now();
      }
      ~Scope()
      {
        if (phases)
          phases->seconds[phase] +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      }

    private:
      StepPhases                           *phases;
      Phase                                 phase;
      std::chrono::steady_clock::time_point start;
    };
  };

  /// CPU time of this process (all threads), seconds.
  double
  process_cpu_time();

  /// The first three numbers of /proc/loadavg ("" where unavailable).
  std::string
  load_average();

  /// Per repetition: steps, CPU seconds (summed over ranks), wall seconds
  /// (max over ranks) and the phases of rank 0.
  struct BenchmarkRepetition
  {
    unsigned long steps = 0;
    double        cpu_s = 0, wall_s = 0;
    StepPhases    phases;
  };

  /**
   * Runs the benchmark protocol: warm-up steps, calibration of the steps per
   * repetition (doubling until a block takes min_time of CPU), then the
   * repetitions. step(phases) advances one time step, charges its phases
   * and returns the seconds of work in it that are not part of a step (a
   * restart from the initial state), which the block's times leave out.
   * Returns the repetitions (collective over MPI_COMM_WORLD).
   */
  std::vector<BenchmarkRepetition>
  run_benchmark(const BenchmarkParameters &params, const std::function<double(StepPhases *)> &step);

  /// benchmark.json in directory (rank 0): the case, the load before and
  /// after, per repetition and as min/median the CPU time per step, the
  /// DoF-stage updates per second per core of the whole step and of
  /// operator + vector updates alone, and the phases in microseconds per step.
  void
  write_benchmark(const std::string &directory, const JsonObject &run_case,
                  const std::vector<BenchmarkRepetition> &repetitions, double n_dofs,
                  unsigned int n_stages, const std::string &load_before);
} // namespace granular_dg
