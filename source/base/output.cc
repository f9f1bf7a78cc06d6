#include <granular_dg/base/checkpoint.h>
#include <granular_dg/base/errors.h>
#include <granular_dg/base/input_path.h>
#include <granular_dg/base/output.h>

#include <deal.II/base/utilities.h>

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

namespace granular_dg
{
  namespace fs = std::filesystem;
  using namespace dealii;

  std::string
  format_number(const double x)
  {
    if (std::isnan(x))
      return "nan";
    if (std::isinf(x))
      return x > 0 ? "inf" : "-inf";
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.12g", x);
    return buffer;
  }

  namespace
  {
    /// Write content to filename through a temporary file and a rename (a
    /// reader never sees half a file) and note it in the run's manifest.
    void
    write_file_atomically(const std::string &filename, const std::string &content)
    {
      const std::string tmp = filename + ".tmp";
      claim_output_file(filename);
      std::ofstream out(tmp);
      out << content;
      out.close();
      std::error_code ec;
      if (!out)
        fs::remove(tmp, ec);
      require_written(out, filename);
      fs::rename(tmp, filename);
    }

    std::string
    quoted(const std::string &s)
    {
      std::string out = "\"";
      for (const char c : s)
        {
          if (c == '"' || c == '\\')
            out += '\\';
          if (c == '\n')
            {
              out += "\\n";
              continue;
            }
          out += c;
        }
      return out + "\"";
    }

    std::string
    json_number(const double x)
    {
      // JSON has no NaN/inf: write them as strings
      return std::isfinite(x) ? format_number(x) : quoted(format_number(x));
    }
  } // namespace

  void
  require_written(const bool written, const std::string &filename)
  {
    if (!written)
      throw RunError("cannot write " + filename + " (disk full or not writable)");
  }

  void
  agree_on_run_error(const MPI_Comm comm, const std::function<void()> &f, const std::string &suffix)
  {
    std::string error;
    try
      {
        f();
      }
    catch (const RunError &e)
      {
        error = e.what();
      }
    if (Utilities::MPI::n_mpi_processes(comm) > 1)
      {
        const unsigned int rank   = Utilities::MPI::this_mpi_process(comm);
        const unsigned int failed = Utilities::MPI::min(error.empty() ? ~0u : rank, comm);
        error = failed == ~0u ? "" : Utilities::MPI::broadcast(comm, error, failed);
      }
    if (!error.empty())
      throw RunError(error + suffix);
  }

  void
  JsonObject::add(const std::string &key, const double value)
  {
    items.emplace_back(key, json_number(value));
  }

  void
  JsonObject::add(const std::string &key, const long long value)
  {
    items.emplace_back(key, std::to_string(value));
  }

  void
  JsonObject::add(const std::string &key, const std::string &value)
  {
    items.emplace_back(key, quoted(value));
  }

  void
  JsonObject::add(const std::string &key, const std::vector<double> &values)
  {
    std::string s = "[";
    for (unsigned int i = 0; i < values.size(); ++i)
      s += (i ? ", " : "") + json_number(values[i]);
    items.emplace_back(key, s + "]");
  }

  void
  JsonObject::add_object(const std::string &key, const JsonObject &object)
  {
    // summary.json nests one level deep: render with that indentation
    items.emplace_back(key, object.str(2));
  }

  void
  JsonObject::add_fields(const JsonObject &object)
  {
    items.insert(items.end(), object.items.begin(), object.items.end());
  }

  std::string
  JsonObject::str(const unsigned int indent) const
  {
    const std::string pad(indent + 2, ' ');
    std::string       s = "{\n";
    for (unsigned int i = 0; i < items.size(); ++i)
      {
        s += pad + quoted(items[i].first) + ": " + items[i].second +
             (i + 1 < items.size() ? ",\n" : "\n");
      }
    return s + std::string(indent, ' ') + "}";
  }

  void
  JsonObject::write(const std::string &filename) const
  {
    write_file_atomically(filename, str() + '\n');
  }

  void
  CsvWriter::open(const std::string              &filename,
                  const std::vector<std::string> &header,
                  const std::string              &comment)
  {
    name = filename;
    claim_output_file(filename);
    out.open(filename);
    if (!comment.empty())
      out << "# " << comment << '\n';
    for (unsigned int i = 0; i < header.size(); ++i)
      out << (i ? "," : "") << header[i];
    out << '\n';
    out.flush();
    require_written(out, name);
  }

  void
  CsvWriter::row(const std::vector<double> &values)
  {
    for (unsigned int i = 0; i < values.size(); ++i)
      out << (i ? "," : "") << format_number(values[i]);
    out << '\n';
    out.flush();
    require_written(out, name);
  }

  std::uint64_t
  CsvWriter::size()
  {
    out.flush();
    return out.is_open() ? static_cast<std::uint64_t>(out.tellp()) : 0;
  }

  void
  truncate_file(const std::string &filename, const std::uint64_t size)
  {
    std::error_code ec;
    const auto      now = fs::file_size(filename, ec);
    if (ec || now < size)
      throw RunError("cannot resume: " + filename + " has " +
                     (ec ? std::string("gone missing") : std::to_string(now) + " bytes") +
                     ", the checkpoint expects at least " + std::to_string(size));
    fs::resize_file(filename, size);
  }

  void
  CsvWriter::reopen(const std::string &filename, const std::uint64_t size)
  {
    truncate_file(filename, size);
    name = filename;
    out.open(filename, std::ios::app);
    require_written(out, name);
  }

  namespace
  {
    const char *const manifest_name = ".granular_dg-manifest";

    /// The files this process created in an output directory (rank 0):
    /// the names relative to it, appended to DIR/.granular_dg-manifest as
    /// they come, so that a killed run leaves a complete list. A run in a
    /// subdirectory of another (a scene's part run) has its own as well.
    struct Manifest
    {
      std::set<std::string> names;
      std::ofstream         file;
      /// begun by this run (not continued by a resume)
      bool fresh = false;
    };

    /// the output directories this process created
    std::set<fs::path> &
    created_directories()
    {
      static std::set<fs::path> d;
      return d;
    }

    std::map<fs::path, Manifest> &
    manifests()
    {
      static std::map<fs::path, Manifest> m;
      return m;
    }

    std::vector<std::string>
    read_manifest(const fs::path &directory)
    {
      std::vector<std::string> names;
      std::ifstream            in(directory / manifest_name);
      std::string              line;
      while (std::getline(in, line))
        if (!line.empty())
          names.push_back(line);
      return names;
    }

    /// a write lock on a whole file (fcntl)
    struct flock
    whole_file_write_lock()
    {
      struct flock whole = {};
      whole.l_type       = F_WRLCK;
      whole.l_whence     = SEEK_SET;
      return whole;
    }

    /// Removes the lock file `lock` unless a running process holds it (not
    /// this one: closing the descriptor would release this process's lock on
    /// the file; a run's parts lock their folders after the run cleared them).
    void
    remove_unheld_lock(const fs::path &lock)
    {
      const int fd = ::open(lock.c_str(), O_RDWR);
      if (fd < 0)
        return;
      struct flock whole = whole_file_write_lock();
      if (::fcntl(fd, F_SETLK, &whole) == 0)
        ::unlink(lock.c_str());
      ::close(fd);
    }

    /// Remove what the previous run in directory wrote: the files its
    /// manifest lists and its checkpoint files (those of its part runs in
    /// subdirectories too). A file is removed only if it lies inside
    /// directory (a manifest is plain text a user could edit) and is not
    /// this run's parameter file; files a user put beside them are kept. A
    /// part's folder goes too when nothing else is left in it.
    void
    remove_previous_run(const fs::path &directory)
    {
      std::error_code       ec;
      const fs::path        root = fs::weakly_canonical(directory, ec);
      std::set<std::string> subdirectories;
      for (const auto &name : read_manifest(directory))
        {
          const fs::path file = fs::weakly_canonical(directory / name, ec);
          const auto     rel  = file.lexically_relative(root);
          if (rel.empty() || rel.string().rfind("..", 0) == 0)
            continue;
          if (std::distance(rel.begin(), rel.end()) > 1)
            subdirectories.insert(rel.begin()->string());
          if (fs::is_regular_file(file, ec) && !is_parameter_file(file.string()))
            fs::remove(file, ec);
        }
      remove_checkpoints(directory.string());
      for (const auto &sub : subdirectories)
        {
          // a part's folder (before-periodic/) goes with its bookkeeping if
          // nothing else is left in it
          remove_checkpoints((directory / sub).string());
          fs::remove(directory / sub / manifest_name, ec);
          remove_unheld_lock(directory / sub / ".lock");
          fs::remove(directory / sub, ec);
        }
      fs::remove(directory / manifest_name, ec);
    }

    /// What says that directory holds a previous run's results ("" if none).
    std::string
    previous_results(const fs::path &directory)
    {
      for (const char *m : {"summary.json", "solution.pvd", "timeseries.csv", "convergence.csv"})
        if (fs::exists(directory / m))
          return m;
      // a run that was killed before it wrote any of them
      return read_manifest(directory).empty() ? "" : std::string(manifest_name);
    }

    void
    require_writable(const std::string &directory)
    {
      const fs::path probe = fs::path(directory) / ".granular_dg-write-test";
      {
        std::ofstream test(probe);
        require(static_cast<bool>(test << "x" << std::flush), "Output/directory", directory,
                "a writable directory");
      }
      std::error_code ec;
      fs::remove(probe, ec);
    }

    void
    create_directory(const std::string &directory)
    {
      require(!directory.empty(), "Output/directory", directory, "a directory name");
      std::error_code ec;
      for (fs::path d = fs::absolute(directory).lexically_normal(); !fs::exists(d, ec);
           d = d.parent_path())
        created_directories().insert(d);
      fs::create_directories(directory, ec);
      require(!ec && fs::is_directory(directory), "Output/directory", directory,
              "a directory that can be created (" + ec.message() + ")");
    }
  } // namespace

  void
  begin_manifest(const std::string &directory, const bool continue_existing)
  {
    const fs::path root = fs::absolute(directory).lexically_normal();
    Manifest      &m    = manifests()[root];
    m.file.close();
    m.names.clear();
    // (a manifest to continue that is not there yet starts a fresh one)
    m.fresh = !continue_existing || !fs::exists(root / manifest_name);
    if (continue_existing)
      for (const auto &name : read_manifest(root))
        m.names.insert(name);
    m.file.open(root / manifest_name, continue_existing ? std::ios::app : std::ios::trunc);
  }

  void
  abandon_new_output()
  {
    for (auto &[root, m] : manifests())
      {
        if (!m.fresh || !(m.names.empty() || (m.names.size() == 1 && m.names.count("parameters.prm"))))
          continue;
        m.file.close();
        std::error_code ec;
        for (const char *name : {"parameters.prm", manifest_name, ".lock"})
          fs::remove(root / name, ec);
        // and the directories created for it, as far as they are empty
        // (remove() does not delete a directory with files)
        for (fs::path d = root; created_directories().count(d) && fs::remove(d, ec);)
          d = d.parent_path();
      }
  }

  void
  claim_output_file(const std::string &path)
  {
    const fs::path file = fs::absolute(path).lexically_normal();
    for (auto &[root, m] : manifests())
      {
        const std::string rel = file.lexically_relative(root).string();
        std::error_code   ec;
        if (rel.empty() || rel.rfind("..", 0) == 0 || m.names.count(rel) || !fs::exists(file, ec))
          continue;
        throw RunError("the output directory " + root.string() + " holds " + rel +
                       ", which this run would overwrite but no run of granular_dg wrote (the "
                       "directory's manifest does not list it): move it away or choose another "
                       "Output/directory");
      }
    // listed before it exists: a run killed while writing it leaves it listed
    record_output_file(path);
  }

  void
  record_output_file(const std::string &path)
  {
    const fs::path file = fs::absolute(path).lexically_normal();
    for (auto &[root, m] : manifests())
      {
        const std::string rel = file.lexically_relative(root).string();
        if (rel.empty() || rel.rfind("..", 0) == 0 || !m.names.insert(rel).second)
          continue;
        m.file << rel << '\n' << std::flush;
      }
  }

  void
  record_output_file(const std::string &directory, const std::string &name)
  {
    record_output_file((fs::path(directory) / name).string());
  }

  void
  lock_output_directory(const std::string &directory)
  {
    // held until the process ends: the descriptors are never closed (a POSIX
    // record lock, whose holder F_GETLK names; the file itself stays empty)
    static std::map<std::string, int> held;
    std::error_code                   ec;
    const std::string key = fs::weakly_canonical(directory, ec).string();
    if (held.count(key))
      return;
    const std::string lock = (fs::path(directory) / ".lock").string();
    const int         fd   = ::open(lock.c_str(), O_RDWR | O_CREAT, 0644);
    require(fd >= 0, "Output/directory", directory,
            "a directory where " + lock + " can be created");
    struct flock whole = whole_file_write_lock();
    if (::fcntl(fd, F_SETLK, &whole) != 0)
      {
        struct flock holder = whole;
        const bool   known  = ::fcntl(fd, F_GETLK, &holder) == 0 && holder.l_type != F_UNLCK;
        ::close(fd);
        require(false, "Output/directory", directory,
                "a directory no other run is using: process " +
                  (known ? std::to_string(holder.l_pid) : std::string("?")) +
                  " (a run or resume of granular_dg) holds its lock " + lock +
                  "; wait for it to end, or choose another directory");
      }
    held[key] = fd;
  }

  void
  prepare_benchmark_directory(const std::string &directory)
  {
    // benchmark.json is overwritten only if a benchmark wrote it
    if (fs::exists(fs::path(directory) / "benchmark.json"))
      {
        const auto listed = read_manifest(directory);
        require(std::find(listed.begin(), listed.end(), "benchmark.json") != listed.end(),
                "Output/directory", directory,
                "a directory without a benchmark.json that granular_dg did not write (its "
                "manifest " +
                  std::string(manifest_name) +
                  " does not list it): move the file away or choose another directory");
      }
    create_directory(directory);
    lock_output_directory(directory);
    require_writable(directory);
    begin_manifest(directory, true);
  }

  void
  prepare_output_directory(const std::string &directory, const bool overwrite)
  {
    create_directory(directory);
    lock_output_directory(directory);
    const std::string marker = previous_results(directory);
    if (!marker.empty())
      {
        require(overwrite, "Output/directory", directory,
                std::string("a directory without a previous run's results (it holds ") +
                  marker + "); choose another one or set Output/overwrite = true" +
                  (has_checkpoints(directory, true) ? ", or continue that run with --resume" :
                                                      ""));
        remove_previous_run(directory);
      }
    require_writable(directory);
    begin_manifest(directory, false);
  }

  void
  write_pvd(const std::string                                  &filename,
            const std::vector<std::pair<double, std::string>> &records)
  {
    std::ostringstream out;
    out << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <Collection>\n";
    for (const auto &r : records)
      out << "    <DataSet timestep=\"" << format_number(r.first)
          << "\" group=\"\" part=\"0\" file=\"" << r.second << "\"/>\n";
    out << "  </Collection>\n</VTKFile>\n";
    write_file_atomically(filename, out.str());
  }

  void
  write_pvtu(const std::string &filename, std::string record)
  {
    const auto begin = record.find("<!--\n#This file was generated by the deal.II library");
    const auto end   = record.find("-->\n", begin);
    if (begin != std::string::npos && end != std::string::npos)
      record.erase(begin, end + 4 - begin);
    write_file_atomically(filename, record);
  }

  void
  write_xdmf(const std::string &filename, const std::vector<std::string> &grids)
  {
    // the frame of DataOutBase's write_xdmf_file(), written from the
    // entries the loop keeps (also across a resume)
    std::string out = "<?xml version=\"1.0\" ?>\n"
                      "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
                      "<Xdmf Version=\"2.0\">\n"
                      "  <Domain>\n"
                      "    <Grid Name=\"CellTime\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
    for (const auto &g : grids)
      out += g;
    write_file_atomically(filename, out + "    </Grid>\n  </Domain>\n</Xdmf>\n");
  }

  std::string
  format_bytes(const double bytes)
  {
    const char *unit[] = {"B", "kB", "MB", "GB", "TB", "PB"};
    double      x      = bytes;
    unsigned    u      = 0;
    while (x >= 1000 && u < 5)
      {
        x /= 1000;
        ++u;
      }
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), u == 0 ? "%.0f %s" : "%.3g %s", x, unit[u]);
    return buffer;
  }

  std::string
  format_duration(const double seconds)
  {
    std::ostringstream s;
    if (!std::isfinite(seconds))
      return "?";
    if (seconds < 60)
      s << std::fixed << std::setprecision(1) << seconds << " s";
    else if (seconds < 3600)
      s << int(seconds / 60) << " min " << std::setw(2) << std::setfill('0')
        << int(seconds) % 60 << " s";
    else if (seconds < 3600e6)
      s << int(seconds / 3600) << " h " << std::setw(2) << std::setfill('0')
        << int(std::fmod(seconds / 60, 60.)) << " min";
    else // (beyond int's hours)
      s << format_number(seconds / 3600) << " h";
    return s.str();
  }

  Progress::Progress(const double t_start, const double t_end, const double interval_s)
    : t_start(t_start)
    , t_end(t_end)
    , interval(interval_s)
    , wall_start(Clock::now())
    , last_print(wall_start)
  {}

  void
  Progress::update(const unsigned long step, const double t, const double dt)
  {
    if (interval <= 0)
      return;
    const auto now = Clock::now();
    if (std::chrono::duration<double>(now - last_print).count() < interval &&
        t < t_end)
      return;
    last_print           = now;
    const double elapsed = std::chrono::duration<double>(now - wall_start).count();
    const double fraction = (t - t_start) / (t_end - t_start);
    const double eta = fraction > 0 ? elapsed * (1. - fraction) / fraction : NAN;
    std::cout << "  step " << std::setw(7) << step << "  (" << std::setw(3)
              << int(100 * fraction) << "%)  t = " << std::setw(10)
              << format_number(t) << "  dt = " << std::setw(10)
              << format_number(dt) << "  elapsed " << format_duration(elapsed)
              << "  ETA " << format_duration(eta) << std::endl;
  }
} // namespace granular_dg
