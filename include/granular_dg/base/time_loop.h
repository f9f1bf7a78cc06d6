#pragma once

#include <deal.II/base/timer.h>

#include <granular_dg/base/evolution.h>
#include <granular_dg/base/output.h>
#include <granular_dg/base/run_parameters.h>

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace granular_dg
{
  /**
   * The one time loop of the program: it drives any Evolution from its
   * initial (or checkpointed) state to the final time, writing snapshots at
   * the output times, timeseries.csv, checkpoints and summary.json; it
   * stops at max steps or on SIGINT/SIGTERM with a checkpoint, times blocks
   * of steps in benchmark mode, and turns an inadmissible state into a
   * failed run whose last good state is written. With write_files false
   * (convergence studies) it writes nothing.
   *
   * The time step lands on every output time; a step that would leave a
   * remainder shorter than sliver_fraction of itself takes the remainder
   * with it instead.
   */
  class TimeLoop
  {
  public:
    static constexpr double sliver_fraction = 1e-3;

    /// dt_factor scales the problem's time step (convergence studies).
    TimeLoop(Evolution &problem, const RunParameters &params, bool write_files,
             double dt_factor = 1.);
    ~TimeLoop();

    /// Throws RunError (failed run, after writing what it can) or
    /// Interrupted (stopped by a signal, after a checkpoint).
    RunResult
    run();

  private:
    void
    start();
    void
    resume(const Checkpoint &checkpoint);
    void
    open_timeseries();
    RunResult
    benchmark();
    /// The steps to the final time (or until a stop). While the problem is
    /// at rest, a CFL step of the size of the last one that does not land on
    /// an output time is counted without computing it (skip_step()).
    void
    steps();
    /// dt of the next step towards t_out; sets lands when it reaches it.
    double
    next_step(double t_out, bool &lands);
    void
    take_step(double dt, bool lands, double t_out);
    /// Snapshot and timeseries row of the current state.
    void
    record();
    /// A step that changes nothing (Evolution::skip_step() said so): time,
    /// step counter and the per-step diagnostics as after a computed step.
    void
    skip_step(double dt);
    /// After a computed step: where the current stretch at rest began
    /// (rest_from), announced once; repeats: the step had the size of the
    /// one before it and did not land on an output time.
    void
    watch_rest(bool repeats);
    /// Checkpoint when due; returns true when the run stops here.
    bool
    poll();
    std::string
    save_checkpoint();
    /// A stop at max steps or by a signal (throws Interrupted for a signal).
    void
    stop(const std::string &status, int signal);
    [[noreturn]] void
    fail(const Inadmissible &failure);
    [[noreturn]] void
    fail(const RunError &error);
    /// A failed run's end: write_state() (the last good state), the run's
    /// end in result, the problem's last words and summary.json; "" or, if a
    /// file cannot be written, "; then: " and why.
    template <typename WriteState>
    std::string
    finish_failed(const WriteState &write_state);
    RunResult
    complete();
    /// The run's end in result, however it ends: steps, time, wall time and
    /// the time loop's cost and throughput (of the steps since the start or
    /// the resume).
    void
    record_end();
    void
    write_summary() const;
    /// The state of the loop in a checkpoint (time, step, dt, snapshots, the
    /// size of timeseries.csv), written and read by the same calls.
    template <typename Archive>
    void
    loop_state(Archive &ar, std::uint64_t &timeseries_size);

    Evolution          &problem;
    const RunParameters params;
    const bool          write_files, root;
    const double        dt_factor;
    const EvolutionInfo info;

    double        t = 0., dt = 0.;
    unsigned long step = 0, first_step = 0;
    std::vector<double> output_times;
    unsigned int        next_output = 0;
    /// (time, file) of every snapshot: solution.pvd
    std::vector<std::pair<double, std::string>> snapshots;
    /// the <Grid> elements of solution.xdmf (HDF5 output)
    std::vector<std::string> xdmf_grids;
    /// the time from which the problem has been at rest (-1: it is not);
    /// steps of another size than the last do not end a rest
    double        rest_from = -1;
    bool          rest_announced = false;
    unsigned int  n_snapshots = 0;
    double        last_record_time = -1;
    std::string   last_main_file;
    CsvWriter     timeseries;
    RunResult     result;
    dealii::Timer wall_timer, loop_timer;
    /// an optional, so that a failed run can destroy it before throwing: a
    /// TimerOutput destroyed during stack unwinding prints an MPI warning
    std::unique_ptr<dealii::ConditionalOStream> timer_out;
    std::optional<dealii::TimerOutput>          timer;
    std::unique_ptr<Progress>                   progress;
    std::unique_ptr<CheckpointSchedule>         schedule;
  };

  /// Write summary.json of a run (rank 0).
  void
  write_summary(const std::string &directory, const EvolutionInfo &info,
                const RunResult &result);
} // namespace granular_dg
