#pragma once

#include <granular_dg/base/benchmark.h>
#include <granular_dg/base/checkpoint.h>
#include <granular_dg/base/output.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace granular_dg
{
  /// Where and why a state left the admissible set: the time loop turns it
  /// into the one-line report of a failed run.
  struct Inadmissible
  {
    double                   time    = 0;
    bool                     initial = false;
    /// "x = (1.5)", "Edge 3 x = 0.25", "vertex 2": where the state is
    std::string              where;
    std::vector<std::string> names;
    std::vector<double>      state;
    std::string              reason;
  };

  /// The outcome of one run, for summary.json and the convergence table.
  struct RunResult
  {
    std::string   status = "completed";
    unsigned long n_steps = 0;
    double        final_time = 0;
    double        wall_time_s = 0;
    double        time_loop_s = 0;     ///< wall time of the steps
    double        time_loop_cpu_s = 0; ///< CPU time of the steps (rank 0)
    double        dof_updates_per_cpu_s_per_rank = 0;
    double        dof_updates_per_s = 0;
    unsigned long n_dofs = 0, n_cells = 0;
    double        h_min = 0;
    /// per component (L1, L2, Linf) against the exact solution, if any
    std::vector<std::array<double, 3>> errors;
    double        l2_error = -1; ///< all components
    double        l1_error = -1; ///< sum over the components
    /// the step a resumed run started from (0: not resumed)
    unsigned long resumed_from_step = 0;
    /// the time from which the run was at rest to its end (Evolution::at_rest();
    /// only steps of another size than the last were computed); -1: it
    /// did not end at rest
    double        at_rest_from = -1;
    JsonObject    diagnostics;
  };

  /// What a run is, for messages, checkpoints and summary.json.
  struct EvolutionInfo
  {
    std::string   scene, physics;
    int           dim    = 1;
    unsigned int  degree = 0;
    unsigned long n_cells = 0, n_dofs = 0;
    double        h_min = 0;
    /// operator evaluations per step (DoF-stage updates = n_dofs * n_stages)
    unsigned int  n_stages = 1;
    /// the evolution variable in messages ("t"; the hopper marches in "tau")
    std::string   time_name = "t";
    /// the files a snapshot writes, for the banner ("solution.pvd, profile-NNNN.csv")
    std::string   snapshot_files;
    /// the banner's line: what is discretised how ("400 cells, 3600 DoFs,
    /// degree 2, nonlinear elasticity")
    std::string   description;
    /// how (engine, flux, limiter, scheme by name), for benchmark.json
    JsonObject    method;
    /// the size of one snapshot's files, for the refusal of snapshot counts
    /// that cannot be meant
    double        bytes_per_snapshot = 0;
  };

  /// What a snapshot wrote: the file solution.pvd lists (VTU/PVTU, "" if
  /// none), the snapshot's <Grid> element for solution.xdmf (HDF5 output,
  /// the same on every rank; "" if none) and the file a message names (the
  /// VTU/HDF5 file, or a CSV profile).
  struct SnapshotFiles
  {
    std::string pvd_entry, xdmf_entry, main_file;
  };

  /**
   * A discretised evolution problem as the TimeLoop drives it: a state that
   * advances in steps, with output, diagnostics and checkpoints. The DG
   * solver of one mesh (dg::Solver) and the network of coupled edges are
   * two of them; the loop itself knows neither.
   *
   * Collective calls (under MPI every rank calls them in the same order):
   * all but info(), timeseries_names() and set_phases().
   */
  class Evolution
  {
  public:
    /// Copies of the state the loop keeps: the last good one of a failed
    /// run, the start of a benchmark (restarted when it would pass the
    /// final time).
    enum class Slot
    {
      last_good,
      benchmark_start
    };

    virtual ~Evolution() = default;

    virtual EvolutionInfo
    info() const = 0;

    /// Set the initial state and return its time (a resumed run calls
    /// load() instead).
    virtual double
    initialize() = 0;

    /// Throw Inadmissible (initial = true) unless the current state is admissible.
    virtual void
    check_initial_state(double t) = 0;

    /// The largest stable step of the current state (CFL number included);
    /// a RunError when it is not positive and finite.
    virtual double
    time_step(double t) = 0;

    /// One step from t to t + dt; throws Inadmissible.
    virtual void
    advance(double t, double dt) = 0;

    /// After every completed step (cheap per-step diagnostics).
    virtual void
    end_of_step(double /*t*/, double /*dt*/, unsigned long /*step*/)
    {}

    /// True when a step of the size of the last one would change nothing
    /// (the last step, a CFL step of the size of the one before it, changed
    /// nothing). A step of another size may still change the state.
    virtual bool
    at_rest() const
    {
      return false;
    }

    /// Count a step of size dt as taken without computing it, when that
    /// changes nothing: at rest, and dt is the CFL step and the size of the
    /// last step. Returns false, and does nothing, otherwise (the step must
    /// be taken with advance()).
    virtual bool
    skip_step(double /*dt*/)
    {
      return false;
    }

    virtual void
    store(Slot slot) = 0;
    virtual void
    restore(Slot slot) = 0;

    /// Write snapshot number index of the current state at time t.
    virtual SnapshotFiles
    write_snapshot(const std::string &directory, unsigned int index, double t) = 0;

    /// Columns of timeseries.csv after time, step, dt, and their values.
    virtual std::vector<std::string>
    timeseries_names() const = 0;
    virtual std::vector<double>
    timeseries_values(double t) = 0;
    /// A comment line above the header of timeseries.csv ("" for none).
    virtual std::string
    timeseries_comment() const
    {
      return "";
    }

    /// The state and the running diagnostics for a checkpoint; rank 0's
    /// bytes are stored and every rank reads them back in load().
    virtual void
    save(ByteWriter &w) = 0;
    virtual void
    load(ByteReader &r) = 0;

    /// End of the run (of a failed one with the last good state): errors and
    /// diagnostics into the result, and the scene's final files when
    /// write_files.
    virtual void
    finish(double t, RunResult &result, bool write_files) = 0;

    /// Charge the phases of the following steps to this (nullptr: untimed).
    virtual void
    set_phases(StepPhases * /*phases*/)
    {}
  };
} // namespace granular_dg
