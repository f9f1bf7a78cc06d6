#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <granular_dg/base/checkpoint.h>
#include <granular_dg/base/output.h>

#include <zlib.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include <unistd.h>

namespace granular_dg
{
  namespace fs = std::filesystem;
  using namespace dealii;

  namespace
  {
    const char *const magic = "granular_dg checkpoint 5";

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

    /// handle_interrupts_outside_time_loops(): whether this process reports,
    /// and whether a time loop has begun
    volatile std::sig_atomic_t report_outside = 0, loop_begun = 0;

    void
    on_interrupt_outside_loop(const int signal)
    {
      // (write and _exit only: nothing else is safe in a signal handler)
      static constexpr char set_up[] =
        " during set-up, before the first step: no results and no checkpoint were written (to "
        "run again into the same output directory, set Output/overwrite = true)\n";
      static constexpr char after[] =
        " outside a time loop: no checkpoint was written and the run's last files may be "
        "incomplete\n";
      if (report_outside)
        {
          const bool term = signal == SIGTERM;
          ssize_t    ok   = write(2, "granular_dg: interrupted by ", 28);
          ok = write(2, term ? "SIGTERM" : "SIGINT", term ? 7 : 6);
          ok = loop_begun ? write(2, after, sizeof(after) - 1) : write(2, set_up, sizeof(set_up) - 1);
          (void)ok;
        }
      _exit(128 + signal);
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

    /// Whether `name` is what a checkpoint write cut short leaves behind:
    /// .step-NNNNNNNNNN.ckpt.tmp, and the files Open MPI's MPI-IO keeps beside
    /// it while it writes, named after it (its lock file
    /// .step-NNNNNNNNNN.ckpt.tmp-JOB-PID.lock, its test of file locking
    /// .step-NNNNNNNNNN.ckpt.tmp.locktest.R)
    bool
    is_partial_checkpoint(const std::string &name)
    {
      return name.size() >= 25 && name[0] == '.' && step_of(name.substr(1, 20)) >= 0 &&
             name.compare(21, 4, ".tmp") == 0 &&
             (name.size() == 25 || name[25] == '-' || name[25] == '.');
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

    /// A checkpoint file parsed: its header entries, parameters, payload,
    /// where its shared blocks lie and their checksums (not yet checked).
    struct ParsedFile
    {
      std::map<std::string, std::string> header;
      ParameterList                      parameters;
      std::string                        payload;
      SharedBlocks                       blocks;
      std::vector<std::uint32_t>         crcs;
    };

    /// "blocks = 12 34" -> {12, 34}
    std::vector<std::uint64_t>
    block_sizes(const std::string &list)
    {
      std::vector<std::uint64_t> sizes;
      std::istringstream         s(list);
      std::uint64_t              n;
      while (s >> n)
        sizes.push_back(n);
      if (!s.eof())
        throw RunError("garbled blocks line");
      return sizes;
    }

    /// After the payload: the shared blocks and the line of their checksums
    /// that ends the file.
    void
    parse_blocks(std::ifstream &in, const fs::path &file, ParsedFile &f)
    {
      const auto it = f.header.find("blocks");
      if (it == f.header.end())
        throw RunError("garbled header (no blocks line)");
      f.blocks.file  = file.string();
      f.blocks.sizes = block_sizes(it->second);
      std::uint64_t position = static_cast<std::uint64_t>(in.tellg()), total = 0;
      for (const auto s : f.blocks.sizes)
        {
          f.blocks.offsets.push_back(position + total);
          total += s;
        }
      std::error_code     ec;
      const std::uint64_t file_size = fs::file_size(file, ec);
      if (ec || file_size < position + total)
        throw RunError("truncated: the shared blocks have " +
                       std::to_string(ec ? 0 : file_size - std::min(file_size, position)) +
                       " of " + std::to_string(total) + " bytes");
      in.seekg(static_cast<std::streamoff>(position + total));
      std::string line;
      if (!std::getline(in, line) || in.eof() || line.rfind("checksums", 0) != 0)
        throw RunError("truncated: the checksums at its end are missing");
      std::istringstream s(line.substr(9));
      std::string        sum;
      while (s >> sum)
        f.crcs.push_back(static_cast<std::uint32_t>(std::stoul(sum, nullptr, 16)));
      if (f.crcs.size() != f.blocks.sizes.size())
        throw RunError("garbled checksums line");
      if (in.peek() != std::char_traits<char>::eof())
        throw RunError("bytes after the checksums");
    }

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
              if (hex(fnv1a(f.payload)) != sum)
                throw RunError("checksum mismatch (the file is corrupt)");
              parse_blocks(in, file, f);
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

  std::uint32_t
  combined_crc32(const MPI_Comm comm, const std::uint32_t crc, const std::uint64_t size)
  {
    const unsigned int n = Utilities::MPI::n_mpi_processes(comm);
    if (n == 1)
      return crc;
    const std::uint64_t        mine[2] = {crc, size};
    std::vector<std::uint64_t> all(2 * n);
    MPI_Gather(mine, 2, MPI_UINT64_T, all.data(), 2, MPI_UINT64_T, 0, comm);
    if (Utilities::MPI::this_mpi_process(comm) != 0)
      return 0;
    uLong combined = crc32(0L, Z_NULL, 0);
    for (unsigned int r = 0; r < n; ++r)
      combined = crc32_combine(combined, all[2 * r], static_cast<z_off_t>(all[2 * r + 1]));
    return static_cast<std::uint32_t>(combined);
  }

  std::string
  SharedBlocks::read(const unsigned int block, const std::uint64_t offset,
                     const std::uint64_t size) const
  {
    std::string   bytes(size, '\0');
    std::ifstream in(file, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(offsets.at(block) + offset));
    in.read(bytes.data(), static_cast<std::streamsize>(size));
    if (!in || static_cast<std::uint64_t>(in.gcount()) != size)
      throw RunError("checkpoint " + file + " cannot be read (bytes " +
                     std::to_string(offsets.at(block) + offset) + " to " +
                     std::to_string(offsets.at(block) + offset + size) + ")");
    return bytes;
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
    /// s (trimmed) as a number, if all of it is one (strtod's syntax)
    std::optional<double>
    number_in(const std::string &s)
    {
      const std::string text = Utilities::trim(s);
      char             *end  = nullptr;
      const double      x    = std::strtod(text.c_str(), &end);
      return !text.empty() && *end == '\0' ? std::optional<double>(x) : std::nullopt;
    }

    /// A parameter's value as resume compares it: the output directory as a
    /// canonical path (rel, ./rel/ and /abs/rel are one directory), the
    /// output times as a sorted list of numbers, and a number as its value
    /// (0.1, 0.10 and 1e-1 are one number).
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
              const auto t = number_in(s);
              if (!t)
                return value;
              times.push_back(*t);
            }
          std::sort(times.begin(), times.end());
          std::ostringstream out;
          for (const double t : times)
            out << t << ',';
          return out.str();
        }
      if (const auto x = number_in(value))
        {
          std::ostringstream out;
          out << std::setprecision(17) << *x;
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
        if (is_partial_checkpoint(entry.path().filename().string()))
          return true;
    return false;
  }

  std::string
  checkpoint_directory(const std::string &directory)
  {
    return (fs::path(directory) / "checkpoints").string();
  }

  void
  remove_checkpoints(const std::string &directory)
  {
    std::error_code ec;
    const fs::path  dir = checkpoint_directory(directory);
    if (!fs::is_directory(dir, ec))
      return;
    for (const auto &file : checkpoint_files(directory))
      fs::remove(file, ec);
    for (const auto &entry : fs::directory_iterator(dir, ec))
      if (is_partial_checkpoint(entry.path().filename().string()))
        fs::remove(entry.path(), ec);
    // removes the folder only if nothing else is in it
    fs::remove(dir, ec);
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

  namespace
  {
    /// Rank 0: the header and the payload into a new file; returns where the
    /// shared blocks begin.
    std::uint64_t
    write_head(const fs::path &tmp, const CheckpointIdentity &id, const ParameterList &parameters,
               const unsigned long step, const double time, const ByteWriter &payload,
               const std::vector<std::uint64_t> &block_sizes, const unsigned int n_ranks)
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
          << "n_mpi_ranks = " << n_ranks << '\n'
          << "step = " << step << '\n'
          << "time = " << t << '\n';
      for (const auto &[key, value] : parameters)
        out << "parameter " << key << " = " << value << '\n';
      out << "blocks = ";
      for (unsigned int b = 0; b < block_sizes.size(); ++b)
        out << (b > 0 ? " " : "") << block_sizes[b];
      out << '\n' << "payload " << payload.bytes.size() << ' ' << hex(fnv1a(payload.bytes)) << '\n';
      out.write(payload.bytes.data(), payload.bytes.size());
      out.flush();
      require_written(out, tmp.string());
      return static_cast<std::uint64_t>(out.tellp());
    }

    /// A piece through `write(data, n)` in chunks of 4 MB (its bytes never
    /// exist whole: the chunk is all a checkpoint adds to the run's memory);
    /// returns the piece's CRC-32, 0 if a write failed.
    template <typename Write>
    std::uint32_t
    write_piece(const SharedPiece &piece, const Write &write)
    {
      const std::uint64_t chunk = std::uint64_t(1) << 22;
      std::string         buffer(std::min(chunk, piece.size), '\0');
      uLong               crc = crc32(0L, Z_NULL, 0);
      for (std::uint64_t o = 0; o < piece.size; o += chunk)
        {
          const std::uint64_t n = std::min(chunk, piece.size - o);
          piece.fill(o, n, buffer.data());
          crc = crc32(crc, reinterpret_cast<const Bytef *>(buffer.data()), n);
          if (!write(buffer.data(), n))
            return 0;
        }
      return static_cast<std::uint32_t>(crc);
    }

    /// Every rank: its pieces of the shared blocks into the file at
    /// `start` + the block's offset + the pieces of the ranks before it
    /// (MPI-IO, independent writes), and their CRC-32s; false on an error.
    bool
    write_pieces(const fs::path &tmp, const std::uint64_t start, const ByteWriter &payload,
                 const std::vector<std::uint64_t> &block_starts,
                 const std::vector<std::uint64_t> &before, std::vector<std::uint32_t> &crcs,
                 const MPI_Comm comm)
    {
      MPI_File file;
      if (MPI_File_open(comm, tmp.c_str(), MPI_MODE_WRONLY, MPI_INFO_NULL, &file) != MPI_SUCCESS)
        return false;
      bool ok = true;
      for (unsigned int b = 0; b < payload.blocks.size(); ++b)
        {
          MPI_Offset at = static_cast<MPI_Offset>(start + block_starts[b] + before[b]);
          crcs[b] = write_piece(payload.blocks[b], [&](const char *data, const std::uint64_t n) {
            ok = ok && MPI_File_write_at(file, at, data, static_cast<int>(n), MPI_CHAR,
                                         MPI_STATUS_IGNORE) == MPI_SUCCESS;
            at += static_cast<MPI_Offset>(n);
            return ok;
          });
        }
      return MPI_File_close(&file) == MPI_SUCCESS && ok;
    }

    /// Rank 0: the checksums line, the rename and the rotation.
    void
    finish_file(const fs::path &tmp, const fs::path &file, const std::string &directory,
                const std::vector<std::uint32_t> &crcs)
    {
      {
        std::ofstream out(tmp, std::ios::binary | std::ios::app);
        out << "checksums";
        for (const auto crc : crcs)
          {
            char buffer[9];
            std::snprintf(buffer, sizeof(buffer), "%08x", static_cast<unsigned int>(crc));
            out << ' ' << buffer;
          }
        out << '\n';
        out.flush();
        require_written(out, tmp.string());
      }
      std::error_code ec;
      fs::rename(tmp, file);
      // keep the newest two; drop what a run killed while writing left
      const auto files = checkpoint_files(directory);
      for (unsigned int i = 2; i < files.size(); ++i)
        fs::remove(files[i], ec);
      for (const auto &entry : fs::directory_iterator(file.parent_path(), ec))
        if (is_partial_checkpoint(entry.path().filename().string()))
          fs::remove(entry.path(), ec);
    }
  } // namespace

  std::string
  write_checkpoint(const std::string &directory, const CheckpointIdentity &id,
                   const ParameterList &parameters, const unsigned long step, const double time,
                   const ByteWriter &payload, const MPI_Comm comm)
  {
    const unsigned int n_ranks  = Utilities::MPI::n_mpi_processes(comm);
    const bool         root     = Utilities::MPI::this_mpi_process(comm) == 0;
    const unsigned int n_blocks = payload.blocks.size();
    const fs::path     dir      = checkpoint_directory(directory);
    char               name[32];
    std::snprintf(name, sizeof(name), "step-%010lu.ckpt", step);
    const fs::path file = dir / name, tmp = dir / (std::string(".") + name + ".tmp");
    // a second Ctrl-C must not cut the checkpoint in half: SIGINT and SIGTERM
    // wait until it is renamed into place
    const SignalBlock block;

    // where each block starts and where this rank's pieces go in them
    std::vector<std::uint64_t> mine(n_blocks), before(n_blocks, 0), starts(n_blocks, 0);
    for (unsigned int b = 0; b < n_blocks; ++b)
      mine[b] = payload.blocks[b].size;
    std::vector<std::uint64_t> sizes = mine;
    if (n_ranks > 1 && n_blocks > 0)
      {
        MPI_Exscan(mine.data(), before.data(), n_blocks, MPI_UINT64_T, MPI_SUM, comm);
        if (root)
          std::fill(before.begin(), before.end(), 0);
        MPI_Allreduce(mine.data(), sizes.data(), n_blocks, MPI_UINT64_T, MPI_SUM, comm);
      }
    for (unsigned int b = 1; b < n_blocks; ++b)
      starts[b] = starts[b - 1] + sizes[b - 1];

    std::uint64_t              start = 0;
    std::vector<std::uint32_t> crcs(n_blocks); // of this rank's pieces
    agree_on_run_error(comm, [&] {
      if (!root)
        return;
      std::error_code ec;
      fs::create_directories(dir, ec);
      start = write_head(tmp, id, parameters, step, time, payload, sizes, n_ranks);
    });
    if (n_ranks > 1)
      start = Utilities::MPI::broadcast(comm, start, 0);
    agree_on_run_error(comm, [&] {
      if (!write_pieces(tmp, start, payload, starts, before, crcs, comm))
        throw RunError("cannot write checkpoint " + tmp.string() + " through MPI-IO");
    });

    for (unsigned int b = 0; b < n_blocks; ++b)
      crcs[b] = combined_crc32(comm, crcs[b], mine[b]);
    agree_on_run_error(comm, [&] {
      if (root)
        finish_file(tmp, file, directory, crcs);
    });
    return file.string();
  }

  namespace
  {
    /// Whether the shared blocks of a parsed checkpoint pass their checksums:
    /// each rank reads an equal share of every block. Collective.
    bool
    blocks_intact(const SharedBlocks &blocks, const std::vector<std::uint32_t> &crcs,
                  const MPI_Comm comm)
    {
      const std::uint64_t n    = Utilities::MPI::n_mpi_processes(comm);
      const std::uint64_t rank = Utilities::MPI::this_mpi_process(comm);
      const std::uint64_t step = std::uint64_t(1) << 26;
      int                 ok   = 1;
      for (unsigned int b = 0; b < blocks.sizes.size(); ++b)
        {
          const std::uint64_t size  = blocks.sizes[b] / n + (rank < blocks.sizes[b] % n ? 1 : 0);
          const std::uint64_t first = blocks.sizes[b] / n * rank + std::min(rank, blocks.sizes[b] % n);
          uLong               crc   = crc32(0L, Z_NULL, 0);
          try
            {
              for (std::uint64_t o = 0; o < size; o += step)
                {
                  const std::string part = blocks.read(b, first + o, std::min(step, size - o));
                  crc = crc32(crc, reinterpret_cast<const Bytef *>(part.data()), part.size());
                }
            }
          catch (const RunError &)
            {
              ok = 0;
            }
          const std::uint32_t all = combined_crc32(comm, static_cast<std::uint32_t>(crc), size);
          if (rank == 0 && all != crcs[b])
            ok = 0;
        }
      return n == 1 ? ok == 1 : Utilities::MPI::min(ok, comm) == 1;
    }
  } // namespace

  Checkpoint
  read_checkpoint(const std::string &directory, const CheckpointIdentity &id,
                  const ParameterList &parameters, const MPI_Comm comm)
  {
    const bool root     = Utilities::MPI::this_mpi_process(comm) == 0;
    const bool parallel = Utilities::MPI::n_mpi_processes(comm) > 1;
    const auto share    = [&](auto x) { return parallel ? Utilities::MPI::broadcast(comm, x, 0) : x; };
    const std::vector<fs::path> files   = root ? checkpoint_files(directory) : std::vector<fs::path>();
    const unsigned int          n_files = share(static_cast<unsigned int>(root ? files.size() : 0));
    Checkpoint                  c;
    std::string                 error, skipped;
    for (unsigned int i = 0; i < n_files; ++i)
      {
        ParsedFile  f;
        std::string unusable;
        if (root)
          {
            try
              {
                f = parse_file(files[i]);
                // a readable checkpoint of another run is an error, not a fallback
                if (const std::string why = mismatch(f, id); !why.empty())
                  error = "checkpoint " + files[i].string() + " does not belong to this run: " + why;
                else
                  require_same_parameters(f.parameters, parameters,
                                          "from checkpoint " + files[i].string());
              }
            catch (const RunError &e)
              {
                unusable = e.what();
              }
            catch (const InputError &e)
              {
                error = e.what();
              }
          }
        if (!(error = share(error)).empty())
          break;
        if ((unusable = share(unusable)).empty())
          {
            f.blocks.file    = share(f.blocks.file);
            f.blocks.offsets = share(f.blocks.offsets);
            f.blocks.sizes   = share(f.blocks.sizes);
            if (!blocks_intact(f.blocks, f.crcs, comm))
              unusable = "checksum mismatch (the file is corrupt)";
          }
        if (!unusable.empty())
          {
            // a damaged newer checkpoint: the older one may be fine
            if (root)
              {
                std::cerr << "granular_dg: warning: checkpoint " << files[i].string()
                          << " is unusable (" << unusable << "); trying an older one"
                          << std::endl;
                skipped += (skipped.empty() ? "" : "; ") + files[i].filename().string() + ": " +
                           unusable;
              }
            continue;
          }
        if (root)
          {
            c.file    = files[i].string();
            c.step    = std::stoul(f.header["step"]);
            c.time    = std::stod(f.header["time"]);
            c.payload = std::move(f.payload);
          }
        c.blocks = std::move(f.blocks);
        break;
      }
    if (error.empty() && share(c.file).empty())
      error = "parameter 'Checkpoint/resume' = 'true' is not allowed: there is no usable "
              "checkpoint in " +
              checkpoint_directory(directory) +
              (skipped.empty() ? " (none was written" : " (" + skipped) +
              (has_incomplete_checkpoint(directory) ?
                 "; an incomplete checkpoint of an interrupted write was ignored)" :
                 ")");
    if (!(error = share(error)).empty())
      throw InputError(error);
    c.file = share(c.file);
    c.step = share(c.step);
    c.time = share(c.time);
    if (parallel)
      broadcast_bytes(comm, c.payload);
    return c;
  }

  void
  handle_interrupts_outside_time_loops(const bool report)
  {
    report_outside          = report;
    struct sigaction action = {};
    action.sa_handler       = on_interrupt_outside_loop;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
  }

  InterruptHandlers::InterruptHandlers()
  {
    loop_begun           = 1;
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
