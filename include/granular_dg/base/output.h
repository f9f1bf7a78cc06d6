#pragma once

#include <mpi.h>

#include <chrono>
#include <cstdint>
#include <fstream>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace granular_dg
{
  /// Numbers in every file the program writes: 12 significant digits.
  std::string
  format_number(double x);

  /// A RunError naming filename if out failed, or written is false
  /// ("cannot write FILE (disk full or not writable)").
  void
  require_written(bool written, const std::string &filename);
  inline void
  require_written(const std::ostream &out, const std::string &filename)
  {
    require_written(static_cast<bool>(out), filename);
  }

  /// Before this run creates path in its output directory (rank 0): a
  /// RunError if a file is there that neither this run nor the earlier run
  /// it continues or replaces wrote (not in the manifest): a user's file is
  /// never overwritten. Then path is recorded (record_output_file()).
  void
  claim_output_file(const std::string &path);

  /// Write filename by write(std::ostream &) and close it (claimed first);
  /// a RunError naming the file if that fails (a full disk: deal.II's
  /// writers throw ExcIO then, a plain stream only fails).
  template <typename Write>
  void
  write_to_file(const std::string &filename, const Write &write)
  {
    claim_output_file(filename);
    std::ofstream out(filename);
    try
      {
        write(out);
        out.close();
      }
    catch (...)
      {
        if (out)
          throw;
      }
    require_written(out, filename);
  }

  /// f() on this rank, then collective: a RunError that f threw on any rank
  /// of comm is thrown on every rank, with the lowest failed rank's message
  /// and then suffix, so that all ranks stop together.
  void
  agree_on_run_error(MPI_Comm comm, const std::function<void()> &f,
                     const std::string &suffix = "");

  /// A flat JSON object with keys in insertion order (summary.json).
  class JsonObject
  {
  public:
    void add(const std::string &key, double value);
    void add(const std::string &key, long long value);
    void add(const std::string &key, unsigned int value) { add(key, static_cast<long long>(value)); }
    void add(const std::string &key, const std::string &value);
    void add(const std::string &key, const char *value) { add(key, std::string(value)); }
    void add(const std::string &key, const std::vector<double> &values);
    void add_object(const std::string &key, const JsonObject &object);
    /// The entries of another object, appended at this level.
    void add_fields(const JsonObject &object);
    std::string str(unsigned int indent = 0) const;
    /// Write to a temporary file and rename, so a reader never sees half.
    void write(const std::string &filename) const;

  private:
    std::vector<std::pair<std::string, std::string>> items;
  };

  /// A CSV file written row by row and flushed after each row, so a run
  /// that dies still leaves every finished row.
  class CsvWriter
  {
  public:
    CsvWriter() = default;
    void open(const std::string &filename, const std::vector<std::string> &header,
              const std::string &comment = "");
    void row(const std::vector<double> &values);
    bool is_open() const { return out.is_open(); }

    /// The bytes written so far (a checkpoint records it).
    std::uint64_t size();
    /// Continue a file written up to size bytes by an earlier run (what
    /// follows, e.g. rows after the checkpoint of a killed run, is cut).
    void reopen(const std::string &filename, std::uint64_t size);

  private:
    std::ofstream out;
    std::string   name;
  };

  /// Cut filename to size bytes (an appended file continued by a resumed
  /// run); a RunError if it is shorter.
  void
  truncate_file(const std::string &filename, std::uint64_t size);

  /// The output directory of a run: created if missing, locked (see
  /// lock_output_directory()), refused if it holds a previous run's results
  /// unless overwrite is set, checked for writing; then this run's manifest
  /// starts. Overwrite removes exactly the files the previous run's manifest
  /// lists (and its checkpoints/), nothing a user put there. Errors name the
  /// parameter 'Output/directory'.
  void
  prepare_output_directory(const std::string &directory, bool overwrite);

  /// A benchmark's directory: created if missing and locked; it only gets
  /// benchmark.json, so earlier results stay and are no reason to refuse.
  void
  prepare_benchmark_directory(const std::string &directory);

  /// Take an exclusive lock on DIRECTORY/.lock for the life of the process
  /// (flock: the OS releases it when the process dies, also by kill -9). A
  /// directory locked by another process is an InputError naming its PID.
  void
  lock_output_directory(const std::string &directory);

  /// Note in the manifest of the run writing to the directory begun last
  /// (prepare_output_directory() or begin_manifest()) that this run created
  /// path (a file under that directory; others are ignored). Rank 0 only;
  /// every writer of this program calls it, through claim_output_file()
  /// (CsvWriter, JsonObject, PVD, write_to_file()) or for the other ranks'
  /// snapshot pieces.
  void
  record_output_file(const std::string &path);
  void
  record_output_file(const std::string &directory, const std::string &name);

  /// Continue the manifest of the run in directory (a resumed run).
  void
  begin_manifest(const std::string &directory, bool continue_existing);

  /// A run that ends with an error before it wrote anything (bad input,
  /// exit 2, found after the output directory was prepared, or a benchmark
  /// that failed): remove what preparing it wrote (parameters.prm, the
  /// manifest and the lock file) and the directories this process created,
  /// as far as they are empty. Directories of a run that wrote more, or
  /// that a resume continues, are left alone. Rank 0 (the one that prepares).
  void
  abandon_new_output();

  /// "1.5 MB", "320 kB", "12 B"
  std::string
  format_bytes(double bytes);

  /// ParaView's time-series index: solution.pvd with the physical times.
  void
  write_pvd(const std::string &filename,
            const std::vector<std::pair<double, std::string>> &records);

  /// A snapshot's .pvtu record, as deal.II's write_pvtu_record() made it, but
  /// for the comment deal.II 9.4.1 starts it with: the date and time of
  /// writing (VtkFlags::print_date_and_time is not consulted there). Two runs
  /// with the same results then write the same bytes, as their .vtu pieces do.
  /// Written atomically and recorded in the directory's manifest.
  void
  write_pvtu(const std::string &filename, std::string record);

  /// The XDMF index of HDF5 snapshots: solution.xdmf, a temporal collection
  /// of the snapshots' <Grid> elements (DataOutBase::XDMFEntry's content).
  void
  write_xdmf(const std::string &filename, const std::vector<std::string> &grids);

  /// Progress with percentage and ETA, at most every interval seconds
  /// (interval 0: silent).
  class Progress
  {
  public:
    Progress(double t_start, double t_end, double interval_s);
    void update(unsigned long step, double t, double dt);

  private:
    using Clock = std::chrono::steady_clock;
    double            t_start, t_end, interval;
    Clock::time_point wall_start, last_print;
  };

  /// "1 h 02 min", "3 min 12 s", "4.2 s"
  std::string
  format_duration(double seconds);
} // namespace granular_dg
