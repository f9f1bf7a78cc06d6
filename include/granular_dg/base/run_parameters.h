#pragma once

#include <deal.II/base/parameter_handler.h>

#include <granular_dg/base/benchmark.h>
#include <granular_dg/base/checkpoint.h>

#include <string>
#include <vector>

namespace granular_dg
{
  class ParameterBinding;

  using namespace dealii;

  /**
   * What every run has, whatever it discretises: the end of the run, the
   * output, checkpoints, the convergence study and benchmark modes
   * (subsections Time stepping, Output, Checkpoint, Convergence, Benchmark).
   * The discretisation adds its own entries (dg::DiscretizationParameters).
   */
  struct RunParameters
  {
    double        final_time = 1.;
    /// stop (with a checkpoint) when the step counter reaches this (0: never)
    unsigned long max_steps  = 0;

    /// Checkpoint/: every so many steps and wall seconds (0: not), resume
    unsigned long checkpoint_steps   = 0;
    double        checkpoint_seconds = 600.;
    bool          resume             = false;
    /// the parameters of the run (parameters.prm, and what a checkpoint
    /// must match when resumed)
    std::string   parameters_text;
    ParameterList parameters;

    std::string         directory = "output";
    bool                overwrite = false;
    std::vector<double> output_times;
    double              output_interval   = 0.;
    bool                write_vtu         = true;
    /// the snapshots' format (Output/format): VTU (+ solution.pvd) or, in
    /// 2D, HDF5 written by all ranks into one file (+ solution.xdmf)
    bool                hdf5              = false;
    /// Refuse Output/format = hdf5 for a scene of dimension dim < 2 (exit 2,
    /// before anything is written).
    void
    require_format_fits(unsigned int dim) const;
    double              progress_interval = 5.;

    bool                      convergence = false;
    std::vector<unsigned int> convergence_degrees;
    std::vector<unsigned int> convergence_cells;
    /// one per convergence degree (empty: the CFL number of the run)
    std::vector<double>       convergence_cfl;

    BenchmarkParameters benchmark;

    /// Every entry, declared once (bind()).
    static void
    declare(ParameterHandler &prm);

    /// Read and check every entry (bind()) and record the run's parameters.
    void
    parse(ParameterHandler &prm);

    /// The entries, each with its field, pattern, documentation and checks
    /// (ParameterBinding).
    void
    bind(ParameterBinding &b);

    /// Where a scene writes files of its own: the output directory of a
    /// single run, "" in convergence studies and benchmarks (which write
    /// only their tables and benchmark.json).
    std::string
    scene_directory() const
    {
      return convergence || benchmark.enabled ? "" : directory;
    }

    /// The output times of a run from start_time: the list, or multiples of
    /// the interval, always ending with the final time.
    std::vector<double>
    output_schedule(double start_time) const;

  private:
    void
    bind_output(ParameterBinding &b);
    void
    bind_modes(ParameterBinding &b);
    void
    bind_checkpoint(ParameterBinding &b);
    void
    read_convergence_cfl(const std::string &text);
    void
    record_parameters(ParameterHandler &prm);
  };

  /// The one-line message of a snapshot count that cannot be meant
  /// (more than max_snapshots), naming the bytes a snapshot needs.
  void
  require_reasonable_snapshot_count(const RunParameters &params, double bytes_per_snapshot,
                                    unsigned long max_snapshots = 100000);

  /// The memory this MPI rank may use: MemAvailable of /proc/meminfo shared
  /// by the ranks on this machine (0 if it cannot be read). Collective on
  /// the first call of it or of cores_per_rank().
  double
  available_memory_per_rank();

  /// The cores this process may run on (its affinity mask: 1 for a rank
  /// that mpirun bound to a core) shared by the ranks on this machine, at
  /// least 1: the threads a rank may start without oversubscribing the
  /// machine. Collective on the first call of it or of
  /// available_memory_per_rank().
  unsigned int
  cores_per_rank();

  /// The peak resident set size of this process (VmHWM of
  /// /proc/self/status) in bytes, 0 if it cannot be read.
  double
  peak_resident_bytes();

  /// Create (or, with Output/overwrite, clear) the output directory and write
  /// parameters.prm, the parameters actually used. Call after all input has
  /// been validated, so that bad input leaves nothing behind. With
  /// Checkpoint/resume: check_resumable() instead of creating.
  void
  begin_output(const RunParameters &params);

  /// An InputError unless Output/directory holds a run that wrote a
  /// checkpoint and had the same parameters (but those a resume may change).
  void
  check_resumable(const RunParameters &params);

  /// An InputError unless the final time and max steps lie beyond the
  /// checkpoint a run resumes from.
  void
  require_beyond_checkpoint(const RunParameters &params, const Checkpoint &checkpoint,
                            const std::string &time_name);

  /// Parse "a, b, c" as numbers; an InputError naming parameter otherwise.
  std::vector<double>
  parse_doubles(const std::string &text, const std::string &parameter);
} // namespace granular_dg
