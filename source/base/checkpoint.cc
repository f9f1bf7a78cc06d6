#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <granular_dg/base/checkpoint.h>
#include <granular_dg/base/output.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

namespace granular_dg
{
  namespace fs = std::filesystem;
  using namespace dealii;

  namespace
  {
    const char *const magic = "granular_dg checkpoint 3";

    volatile std::sig_atomic_t received_signal = 0;

    sigset_t
    interrupt_signals()
    {
      sigset_t set;
      sigemptyset(&set);
      sigaddset(&set, SIGINT);
      sigaddset(&set, SIGTERM);
      return set;
    }

    /// While it lives, SIGINT and SIGTERM are held back (delivered when it ends).
    struct SignalBlock
    {
      SignalBlock()
      {
        const sigset_t set = interrupt_signals();
        sigprocmask(SIG_BLOCK, &set, &previous);
      }
      ~SignalBlock()
      {
        sigprocmask(SIG_SETMASK, &previous, nullptr);
      }
      sigset_t previous;
    };

    void
    on_interrupt(const int signal)
    {
      received_signal = signal;
    }

    /// step-NNNNNNNNNN.ckpt -> NNNNNNNNNN (or -1 for other names)
    long long
    step_of(const std::string &name)
    {
      if (name.size() != 20 || name.rfind("step-", 0) != 0 ||
          name.compare(15, 5, ".ckpt") != 0)
        return -1;
      for (unsigned int i = 5; i < 15; ++i)
        if (name[i] < '0' || name[i] > '9')
          return -1;
      return std::stoll(name.substr(5, 10));
    }

    /// The checkpoint files of a directory, newest first.
    std::vector<fs::path>
    checkpoint_files(const std::string &directory)
    {
      std::vector<std::pair<long long, fs::path>> found;
      std::error_code                             ec;
      const fs::path                              dir = checkpoint_directory(directory);
      if (fs::is_directory(dir, ec))
        for (const auto &entry : fs::directory_iterator(dir, ec))
          {
            const long long s = step_of(entry.path().filename().string());
            if (s >= 0 && entry.is_regular_file())
              found.emplace_back(s, entry.path());
          }
      std::sort(found.begin(), found.end(),
                [](const auto &a, const auto &b) { return a.first > b.first; });
      std::vector<fs::path> files;
      for (const auto &f : found)
        files.push_back(f.second);
      return files;
    }

    std::string
    hex(const std::uint64_t x)
    {
      char buffer[17];
      std::snprintf(buffer, sizeof(buffer), "%016llx", static_cast<unsigned long long>(x));
      return buffer;
    }

    /// A checkpoint file parsed: its header entries, parameters and payload.
    struct ParsedFile
    {
      std::map<std::string, std::string> header;
      ParameterList                      parameters;
      std::string                        payload;
    };

    /// Read and verify one file; a RunError says why it is unusable.
    ParsedFile
    parse_file(const fs::path &file)
    {
      std::ifstream in(file, std::ios::binary);
      if (!in)
        throw RunError("cannot be read");
      std::string line;
      if (!std::getline(in, line) || line != magic)
        throw RunError(line.rfind("granular_dg checkpoint ", 0) == 0 ?
                         "written by another version of granular_dg ('" + line.substr(0, 40) +
                           "'; this build reads '" + magic + "'): rerun without --resume" :
                         "not a granular_dg checkpoint (first line '" + line.substr(0, 40) +
                           "')");
      ParsedFile f;
      while (std::getline(in, line))
        {
          if (line.rfind("payload ", 0) == 0)
            {
              std::istringstream s(line.substr(8));
              std::size_t        size = 0;
              std::string        sum;
              if (!(s >> size >> sum))
                throw RunError("garbled payload line");
              f.payload.resize(size);
              in.read(f.payload.data(), size);
              if (static_cast<std::size_t>(in.gcount()) != size)
                throw RunError("truncated: the payload has " + std::to_string(in.gcount()) +
                               " of " + std::to_string(size) + " bytes");
              if (in.peek() != std::char_traits<char>::eof())
                throw RunError("bytes after the payload");
              if (hex(fnv1a(f.payload)) != sum)
                throw RunError("checksum mismatch (the file is corrupt)");
              return f;
            }
          const auto eq = line.find(" = ");
          if (eq == std::string::npos)
            throw RunError("garbled header line '" + line.substr(0, 60) + "'");
          const std::string key = line.substr(0, eq), value = line.substr(eq + 3);
          if (key.rfind("parameter ", 0) == 0)
            f.parameters.emplace_back(key.substr(10), value);
          else
            f.header[key] = value;
        }
      throw RunError("truncated: no payload");
    }

    /// Why a checkpoint does not belong to this run ("" if it does).
    std::string
    mismatch(const ParsedFile &f, const CheckpointIdentity &id)
    {
      const std::pair<const char *, std::string> fields[] = {
        {"scene", id.scene},
        {"physics", id.physics},
        {"dim", std::to_string(id.dim)},
        {"degree", std::to_string(id.degree)},
        {"n_cells", std::to_string(id.n_cells)},
        {"n_dofs", std::to_string(id.n_dofs)}};
      for (const auto &[key, value] : fields)
        {
          const auto it = f.header.find(key);
          const std::string theirs = it == f.header.end() ? "(missing)" : it->second;
          if (theirs != value)
            return std::string("it was written with ") + key + " = " + theirs +
                   ", this run has " + key + " = " + value;
        }
      return "";
    }
  } // namespace

  std::vector<std::string>
  gather_bytes(const MPI_Comm comm, const std::string &mine, const std::size_t chunk)
  {
    const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
    const unsigned int n    = Utilities::MPI::n_mpi_processes(comm);
    if (n == 1)
      return {mine};
    const auto sizes =
      Utilities::MPI::gather(comm, static_cast<unsigned long long>(mine.size()), 0);
    if (rank != 0)
      {
        for (std::size_t o = 0; o < mine.size(); o += chunk)
          MPI_Send(mine.data() + o, static_cast<int>(std::min(chunk, mine.size() - o)), MPI_CHAR,
                   0, 0, comm);
        return {};
      }
    std::vector<std::string> all(n);
    all[0] = mine;
    for (unsigned int r = 1; r < n; ++r)
      {
        all[r].resize(sizes[r]);
        for (std::size_t o = 0; o < all[r].size(); o += chunk)
          MPI_Recv(&all[r][o], static_cast<int>(std::min(chunk, all[r].size() - o)), MPI_CHAR,
                   r, 0, comm, MPI_STATUS_IGNORE);
      }
    return all;
  }

  void
  broadcast_bytes(const MPI_Comm comm, std::string &bytes, const std::size_t chunk)
  {
    if (Utilities::MPI::n_mpi_processes(comm) == 1)
      return;
    const auto size =
      Utilities::MPI::broadcast(comm, static_cast<unsigned long long>(bytes.size()), 0);
    bytes.resize(size);
    for (std::size_t o = 0; o < bytes.size(); o += chunk)
      MPI_Bcast(&bytes[o], static_cast<int>(std::min(chunk, bytes.size() - o)), MPI_CHAR, 0, comm);
  }

  std::uint64_t
  fnv1a(const std::string &bytes)
  {
    std::uint64_t h = 1469598103934665603ull;
    for (const unsigned char c : bytes)
      {
        h ^= c;
        h *= 1099511628211ull;
      }
    return h;
  }

  ParameterList
  flatten_parameters(const std::string &text)
  {
    ParameterList            list;
    std::vector<std::string> path;
    std::istringstream       in(text);
    std::string              line;
    while (std::getline(in, line))
      {
        line = Utilities::trim(line);
        if (line.rfind("subsection ", 0) == 0)
          path.push_back(Utilities::trim(line.substr(11)));
        else if (line == "end" && !path.empty())
          path.pop_back();
        else if (line.rfind("set ", 0) == 0)
          {
            const auto  eq   = line.find('=');
            std::string name = Utilities::trim(line.substr(4, eq - 4));
            for (auto p = path.rbegin(); p != path.rend(); ++p)
              name = *p + "/" + name;
            list.emplace_back(name, eq == std::string::npos ?
                                      "" :
                                      Utilities::trim(line.substr(eq + 1)));
          }
      }
    return list;
  }

  bool
  may_change_on_resume(const std::string &parameter)
  {
    return parameter == "Time stepping/final time" || parameter == "Time stepping/max steps" ||
           parameter.rfind("Checkpoint/", 0) == 0 || parameter == "Output/progress interval" ||
           parameter == "Output/overwrite";
  }

  namespace
  {
    /// A parameter's value as resume compares it: the output directory as a
    /// canonical path (rel, ./rel/ and /abs/rel are one directory), the
    /// output times as a sorted list of numbers.
    std::string
    normalised(const std::string &name, const std::string &value)
    {
      if (name == "Output/directory")
        {
          std::error_code ec;
          const auto      p = fs::weakly_canonical(fs::absolute(value, ec), ec);
          return ec ? value : p.string();
        }
      if (name == "Output/output times")
        {
          std::vector<double> times;
          for (const auto &s : Utilities::split_string_list(value, ','))
            {
              char        *end = nullptr;
              const double t   = std::strtod(s.c_str(), &end);
              if (end == s.c_str() || *end != '\0')
                return value;
              times.push_back(t);
            }
          std::sort(times.begin(), times.end());
          std::ostringstream out;
          for (const double t : times)
            out << t << ',';
          return out.str();
        }
      return value;
    }
  } // namespace

  void
  require_same_parameters(const ParameterList &before, const ParameterList &now,
                          const std::string &what)
  {
    std::map<std::string, std::string> old(before.begin(), before.end());
    for (const auto &[name, value] : now)
      {
        if (may_change_on_resume(name))
          continue;
        const auto it = old.find(name);
        if (it == old.end() || normalised(name, it->second) != normalised(name, value))
          throw InputError(
            "cannot resume " + what + ": it was run with '" + name + "' = '" +
            (it == old.end() ? "(not set)" : it->second) + "', this run has '" + value +
            "' (a resumed run may change only Time stepping/final time, Time stepping/max "
            "steps, Checkpoint/*, Output/progress interval)");
      }
  }

  bool
  has_incomplete_checkpoint(const std::string &directory)
  {
    std::error_code ec;
    const fs::path  dir = checkpoint_directory(directory);
    if (fs::is_directory(dir, ec))
      for (const auto &entry : fs::directory_iterator(dir, ec))
        {
          const std::string n = entry.path().filename().string();
          if (n.size() > 9 && n[0] == '.' && n.compare(n.size() - 9, 9, ".ckpt.tmp") == 0)
            return true;
        }
    return false;
  }

  std::string
  checkpoint_directory(const std::string &directory)
  {
    return (fs::path(directory) / "checkpoints").string();
  }

  bool
  has_checkpoints(const std::string &directory, const bool search_subdirectories)
  {
    if (!checkpoint_files(directory).empty())
      return true;
    std::error_code ec;
    if (search_subdirectories && fs::is_directory(directory, ec))
      for (const auto &entry : fs::directory_iterator(directory, ec))
        if (entry.is_directory() && entry.path().filename() != "checkpoints" &&
            !checkpoint_files(entry.path().string()).empty())
          return true;
    return false;
  }

  std::string
  write_checkpoint(const std::string &directory, const CheckpointIdentity &id,
                   const ParameterList &parameters, const unsigned long step, const double time,
                   const std::string &payload, const MPI_Comm comm)
  {
    const fs::path dir  = checkpoint_directory(directory);
    char           name[32];
    std::snprintf(name, sizeof(name), "step-%010lu.ckpt", step);
    const fs::path file = dir / name;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        // a second Ctrl-C must not cut the checkpoint in half: SIGINT and
        // SIGTERM wait until it is renamed into place
        const SignalBlock block;
        std::error_code   ec;
        fs::create_directories(dir, ec);
        const fs::path tmp = dir / (std::string(".") + name + ".tmp");
        {
          std::ofstream out(tmp, std::ios::binary);
          char          t[40];
          std::snprintf(t, sizeof(t), "%.17g", time);
          out << magic << '\n'
              << "scene = " << id.scene << '\n'
              << "physics = " << id.physics << '\n'
              << "dim = " << id.dim << '\n'
              << "degree = " << id.degree << '\n'
              << "n_cells = " << id.n_cells << '\n'
              << "n_dofs = " << id.n_dofs << '\n'
              << "n_mpi_ranks = " << Utilities::MPI::n_mpi_processes(comm) << '\n'
              << "step = " << step << '\n'
              << "time = " << t << '\n';
          for (const auto &[key, value] : parameters)
            out << "parameter " << key << " = " << value << '\n';
          out << "payload " << payload.size() << ' ' << hex(fnv1a(payload)) << '\n';
          out.write(payload.data(), payload.size());
          out.flush();
          if (!out)
            throw RunError("cannot write checkpoint " + tmp.string() +
                           " (disk full or not writable)");
        }
        fs::rename(tmp, file);
        // keep the newest two; drop what a run killed while writing left
        const auto files = checkpoint_files(directory);
        for (unsigned int i = 2; i < files.size(); ++i)
          fs::remove(files[i], ec);
        for (const auto &entry : fs::directory_iterator(dir, ec))
          {
            const std::string n = entry.path().filename().string();
            if (n.size() > 9 && n[0] == '.' && n.compare(n.size() - 9, 9, ".ckpt.tmp") == 0)
              fs::remove(entry.path(), ec);
          }
      }
    MPI_Barrier(comm);
    return file.string();
  }

  Checkpoint
  read_checkpoint(const std::string &directory, const CheckpointIdentity &id,
                  const ParameterList &parameters, const MPI_Comm comm)
  {
    const bool  root = Utilities::MPI::this_mpi_process(comm) == 0;
    Checkpoint  c;
    std::string error;
    if (root)
      {
        std::string skipped;
        for (const auto &file : checkpoint_files(directory))
          {
            ParsedFile f;
            try
              {
                f = parse_file(file);
              }
            catch (const RunError &e)
              {
                // a damaged newer checkpoint: the older one may be fine
                std::cerr << "granular_dg: warning: checkpoint " << file.string()
                          << " is unusable (" << e.what() << "); trying an older one"
                          << std::endl;
                skipped += (skipped.empty() ? "" : "; ") + file.filename().string() + ": " +
                           e.what();
                continue;
              }
            // a readable checkpoint of another run is an error, not a fallback
            const std::string why = mismatch(f, id);
            if (!why.empty())
              {
                error = "checkpoint " + file.string() + " does not belong to this run: " + why;
                break;
              }
            try
              {
                require_same_parameters(f.parameters, parameters,
                                        "from checkpoint " + file.string());
              }
            catch (const InputError &e)
              {
                error = e.what();
                break;
              }
            c.file    = file.string();
            c.step    = std::stoul(f.header["step"]);
            c.time    = std::stod(f.header["time"]);
            c.payload = std::move(f.payload);
            break;
          }
        if (error.empty() && c.file.empty())
          error = "parameter 'Checkpoint/resume' = 'true' is not allowed: there is no usable "
                  "checkpoint in " +
                  checkpoint_directory(directory) +
                  (skipped.empty() ? " (none was written" : " (" + skipped) +
                  (has_incomplete_checkpoint(directory) ?
                     "; an incomplete checkpoint of an interrupted write was ignored)" :
                     ")");
      }
    error = Utilities::MPI::broadcast(comm, error, 0);
    if (!error.empty())
      throw InputError(error);
    c.file = Utilities::MPI::broadcast(comm, c.file, 0);
    c.step = Utilities::MPI::broadcast(comm, c.step, 0);
    c.time = Utilities::MPI::broadcast(comm, c.time, 0);
    broadcast_bytes(comm, c.payload);
    return c;
  }

  InterruptHandlers::InterruptHandlers()
  {
    received_signal      = 0;
    struct sigaction action = {};
    action.sa_handler       = on_interrupt;
    sigemptyset(&action.sa_mask);
    // (no SA_RESETHAND: a second Ctrl-C while the run writes its final
    // checkpoint must not kill it half-way; kill -9 ends a run at once)
    action.sa_flags = 0;
    sigaction(SIGINT, &action, &previous_int);
    sigaction(SIGTERM, &action, &previous_term);
  }

  InterruptHandlers::~InterruptHandlers()
  {
    if (received_signal != 0)
      {
        // the run stops on that signal: what follows (summary, message,
        // exit 128 + signal) is not to be cut short by another one
        std::signal(SIGINT, SIG_IGN);
        std::signal(SIGTERM, SIG_IGN);
        return;
      }
    sigaction(SIGINT, &previous_int, nullptr);
    sigaction(SIGTERM, &previous_term, nullptr);
  }

  int
  interrupt_signal()
  {
    return received_signal;
  }

  std::string
  signal_name(const int signal)
  {
    switch (signal)
      {
        case SIGINT:
          return "SIGINT";
        case SIGTERM:
          return "SIGTERM";
        default:
          return "signal " + std::to_string(signal);
      }
  }

  std::string
  stop_status(const CheckpointSchedule::Decision &d, const std::string &time_name,
              const double t, const unsigned long step, const std::string &file)
  {
    std::string s = d.signal != 0 ?
                      "interrupted by " + signal_name(d.signal) + " at " + time_name + " = " +
                        format_number(t) + " (step " + std::to_string(step) + ")" :
                      "stopped at Time stepping/max steps = " + std::to_string(step) + " (" +
                        time_name + " = " + format_number(t) + ")";
    if (!file.empty())
      s += "; checkpoint " + file + "; continue with --resume";
    return s;
  }

  CheckpointSchedule::CheckpointSchedule(const unsigned long every_steps,
                                         const double        every_seconds,
                                         const unsigned long max_steps, const bool enabled,
                                         const MPI_Comm comm)
    : every_steps(every_steps)
    , max_steps(max_steps)
    , every_seconds(every_seconds)
    , enabled(enabled)
    , comm(comm)
    , last(Clock::now())
  {}

  CheckpointSchedule::Decision
  CheckpointSchedule::poll(const unsigned long step)
  {
    Decision d;
    d.max_steps = max_steps > 0 && step >= max_steps;
    int write   = enabled && every_steps > 0 && step % every_steps == 0;
    // the wall clock of rank 0 decides for all
    if (enabled && every_seconds > 0 && Utilities::MPI::this_mpi_process(comm) == 0 &&
        std::chrono::duration<double>(Clock::now() - last).count() >= every_seconds)
      write = 1;
    int signal = interrupt_signal();
    if (Utilities::MPI::n_mpi_processes(comm) > 1)
      {
        int local[2] = {write, signal}, global[2];
        MPI_Allreduce(local, global, 2, MPI_INT, MPI_MAX, comm);
        write  = global[0];
        signal = global[1];
      }
    d.signal    = signal;
    d.scheduled = enabled && write != 0;
    // a run that stops writes a checkpoint to continue from
    d.write = enabled && (write != 0 || d.stop());
    return d;
  }

  void
  CheckpointSchedule::written()
  {
    last = Clock::now();
  }
} // namespace granular_dg
