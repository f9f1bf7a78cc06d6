#pragma once

#include <deal.II/base/mpi.h>

#include <granular_dg/base/errors.h>

#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

/**
 * Checkpoint and resume (doc/program.md, "Checkpoints").
 *
 * A checkpoint is one file OUTPUT/checkpoints/step-NNNNNNNNNN.ckpt: a text
 * header (what run it belongs to: scene, physics, dim, degree, mesh size,
 * time, step, every parameter of the run) and a binary payload with an
 * FNV-1a checksum, then shared blocks with CRC-32 checksums. It is written
 * to a temporary file and renamed, so a reader never sees half of one; the
 * newest two are kept. The payload holds the time loop's state and the
 * scene's running state (SceneHooks::save/load), written and read with the
 * same io() calls, rank 0's. A shared block (the solution, cell by cell in a
 * partition-independent order) is written by every MPI rank at its own
 * offset, each its own cells, and read the same way, so no rank holds more
 * than its part and a resume may use another number of ranks.
 */
namespace granular_dg
{
  /// This rank's piece of a shared block of a checkpoint: its size, and
  /// what writes bytes [offset, offset + n) of it to out (called while the
  /// checkpoint is written, in chunks, so the piece need not exist whole).
  struct SharedPiece
  {
    std::uint64_t                                                     size = 0;
    std::function<void(std::uint64_t offset, std::uint64_t n, char *out)> fill;
  };

  /// The payload of a checkpoint, written with io(x) for each member; a
  /// ByteReader reads it back with the same sequence of io() calls.
  class ByteWriter
  {
  public:
    template <typename T>
    void
    io(const T &x)
    {
      static_assert(std::is_trivially_copyable_v<T>, "no serialisation for this type");
      bytes.append(reinterpret_cast<const char *>(&x), sizeof(T));
    }
    void
    io(const std::string &s)
    {
      io(static_cast<std::uint64_t>(s.size()));
      bytes.append(s);
    }
    template <typename A, typename B>
    void
    io(const std::pair<A, B> &p)
    {
      io(p.first);
      io(p.second);
    }
    template <typename T>
    void
    io(const std::vector<T> &v)
    {
      io(static_cast<std::uint64_t>(v.size()));
      if constexpr (std::is_trivially_copyable_v<T>)
        bytes.append(reinterpret_cast<const char *>(v.data()), v.size() * sizeof(T));
      else
        for (const auto &x : v)
          io(x);
    }

    /// This rank's piece of the next shared block. Every rank calls it for
    /// the same blocks in the same order; in the file, rank r's piece follows
    /// rank r - 1's.
    void
    shared(SharedPiece mine)
    {
      blocks.push_back(std::move(mine));
    }

    /// shared() of bytes at hand
    void
    shared(std::string mine)
    {
      auto bytes = std::make_shared<const std::string>(std::move(mine));
      shared({bytes->size(), [bytes](const std::uint64_t offset, const std::uint64_t n,
                                     char *out) { std::memcpy(out, bytes->data() + offset, n); }});
    }

    /// Append what `inner` wrote: its bytes as one string, its shared blocks.
    void
    io(ByteWriter &&inner)
    {
      io(inner.bytes);
      for (auto &b : inner.blocks)
        blocks.push_back(std::move(b));
    }

    std::string              bytes;
    std::vector<SharedPiece> blocks; ///< this rank's piece of each shared block
  };

  /// Where the shared blocks of a checkpoint file lie; a ByteReader reads a
  /// rank's piece of them from the file.
  struct SharedBlocks
  {
    std::string                file;
    std::vector<std::uint64_t> offsets, sizes; ///< in the file, in bytes

    /// Bytes [offset, offset + size) of block `block` (any rank, no
    /// communication); a RunError if the file cannot give them.
    std::string
    read(unsigned int block, std::uint64_t offset, std::uint64_t size) const;
  };

  /// Reads what a ByteWriter wrote; a short or garbled payload throws a
  /// RunError.
  class ByteReader
  {
  public:
    /// blocks: where the shared blocks are (none: a payload without them)
    explicit ByteReader(const std::string &bytes, const SharedBlocks *blocks = nullptr)
      : bytes(bytes)
      , blocks(blocks)
    {}

    /// Size in bytes of the next shared block (all ranks' pieces).
    std::uint64_t
    shared_size() const
    {
      if (blocks == nullptr || next_block >= blocks->sizes.size())
        throw RunError("checkpoint payload garbled (a shared block is missing)");
      return blocks->sizes[next_block];
    }

    /// Bytes [offset, offset + size) of the next shared block; the reader
    /// then moves on to the block after it.
    std::string
    shared(const std::uint64_t offset, const std::uint64_t size)
    {
      if (offset + size > shared_size())
        throw RunError("checkpoint payload garbled (beyond the end of a shared block)");
      return blocks->read(next_block++, offset, size);
    }

    /// A reader of the string `inner` (read from this one) that finds the
    /// shared blocks where this one does.
    ByteReader
    nested(const std::string &inner) const
    {
      return ByteReader(inner, blocks);
    }

    template <typename T>
    void
    io(T &x)
    {
      static_assert(std::is_trivially_copyable_v<T>, "no serialisation for this type");
      std::memcpy(&x, take(sizeof(T)), sizeof(T));
    }
    void
    io(std::string &s)
    {
      const std::size_t n = size();
      s.assign(take(n), n);
    }
    template <typename A, typename B>
    void
    io(std::pair<A, B> &p)
    {
      io(p.first);
      io(p.second);
    }
    template <typename T>
    void
    io(std::vector<T> &v)
    {
      const std::size_t n = size();
      if constexpr (std::is_trivially_copyable_v<T>)
        {
          const char *p = take(n * sizeof(T));
          v.resize(n);
          if (n > 0)
            std::memcpy(static_cast<void *>(v.data()), p, n * sizeof(T));
        }
      else
        {
          v.resize(n);
          for (auto &x : v)
            io(x);
        }
    }

    bool
    at_end() const
    {
      return position == bytes.size();
    }

  private:
    std::size_t
    size()
    {
      std::uint64_t n = 0;
      io(n);
      if (n > bytes.size() - position)
        throw RunError("checkpoint payload garbled (a length beyond its end)");
      return n;
    }

    const char *
    take(const std::size_t n)
    {
      if (n > bytes.size() - position)
        throw RunError("checkpoint payload ends early");
      const char *p = bytes.data() + position;
      position += n;
      return p;
    }

    const std::string  &bytes;
    std::size_t         position = 0;
    const SharedBlocks *blocks;
    unsigned int        next_block = 0;
  };

  /// A flat list of "Section/name" = value pairs (the parameters of a run).
  using ParameterList = std::vector<std::pair<std::string, std::string>>;

  /// The parameters of deal.II's ShortPRM text as a flat list.
  ParameterList
  flatten_parameters(const std::string &short_prm_text);

  /// The parameters a resumed run may change: the final time, the stop after
  /// max steps, the checkpoint schedule, progress and overwrite. Everything
  /// else must equal the checkpointed run's.
  bool
  may_change_on_resume(const std::string &parameter);

  /// An InputError naming the first parameter (not allowed to change) whose
  /// value differs; `what` names the other side ("the run in out/").
  void
  require_same_parameters(const ParameterList &before, const ParameterList &now,
                          const std::string &what);

  /// What a checkpoint must match to be resumed by a run.
  struct CheckpointIdentity
  {
    std::string   scene, physics;
    int           dim    = 1;
    unsigned int  degree = 0;
    unsigned long n_cells = 0, n_dofs = 0;
  };

  /// A checkpoint read back: where it stands, its payload and where its
  /// shared blocks are (read them through ByteReader(payload, &blocks)).
  struct Checkpoint
  {
    std::string   file;
    unsigned long step = 0;
    double        time = 0;
    std::string   payload;
    SharedBlocks  blocks;
  };

  /// The directory holding the checkpoints of a run writing to directory.
  std::string
  checkpoint_directory(const std::string &directory);

  /// Remove the checkpoint files of a run writing to directory (its
  /// step-NNNNNNNNNN.ckpt files and their temporary files), and the folder
  /// DIRECTORY/checkpoints if nothing else is in it: files a user put there
  /// are kept.
  void
  remove_checkpoints(const std::string &directory);

  /// Whether DIRECTORY/checkpoints holds the temporary file of a checkpoint
  /// whose writing was cut off (ignored by resume and removed by the next
  /// checkpoint or an overwrite).
  bool
  has_incomplete_checkpoint(const std::string &directory);

  /// Whether directory, or a subdirectory of it (a scene's part run), holds
  /// a checkpoint file.
  bool
  has_checkpoints(const std::string &directory, bool search_subdirectories = false);

  /// Write DIRECTORY/checkpoints/step-NNNNNNNNNN.ckpt via a temporary file
  /// and a rename, then remove all but the newest two. Collective: rank 0
  /// writes the header and its payload.bytes, every rank its pieces of the
  /// shared blocks (payload.blocks, MPI-IO at offsets from an exclusive scan
  /// of the piece sizes; CRC-32s combined on rank 0). Returns the file name.
  std::string
  write_checkpoint(const std::string &directory, const CheckpointIdentity &id,
                   const ParameterList &parameters, unsigned long step, double time,
                   const ByteWriter &payload, MPI_Comm comm);

  /// The newest checkpoint in DIRECTORY/checkpoints that is complete, passes
  /// its checksum and belongs to this run (same scene, physics, dimension,
  /// degree, mesh and parameters, but those of may_change_on_resume());
  /// unusable newer ones are skipped with a warning on stderr. An InputError
  /// when there is none (naming what differs, or why each one is unusable).
  /// Collective: rank 0 reads the header and payload, which are broadcast;
  /// every rank checks a share of the shared blocks' checksums.
  Checkpoint
  read_checkpoint(const std::string &directory, const CheckpointIdentity &id,
                  const ParameterList &parameters, MPI_Comm comm);

  /// Every rank's bytes on rank 0, in rank order (an empty list elsewhere),
  /// of any size: point-to-point messages of at most `chunk` bytes. (MPI
  /// counts are int: deal.II's gather and one MPI_Bcast stop at 2 GB, the
  /// checkpoint of ~2.5 10^8 DoFs.)
  std::vector<std::string>
  gather_bytes(MPI_Comm comm, const std::string &mine, std::size_t chunk = std::size_t(1) << 30);

  /// Rank 0's bytes on every rank, of any size (broadcasts of at most
  /// `chunk` bytes).
  void
  broadcast_bytes(MPI_Comm comm, std::string &bytes, std::size_t chunk = std::size_t(1) << 30);

  /// FNV-1a, 64 bit, of a byte string (the payload checksum).
  std::uint64_t
  fnv1a(const std::string &bytes);

  /// CRC-32 (zlib) of the bytes all ranks hold in rank order, given each
  /// rank's: one gather to rank 0, which combines them (crc32_combine) and
  /// returns the checksum (other ranks: 0). `size` is this rank's byte count.
  std::uint32_t
  combined_crc32(MPI_Comm comm, std::uint32_t crc, std::uint64_t size);

  /// While it lives, SIGINT and SIGTERM set a flag that the time loop polls
  /// after every step (CheckpointSchedule): the run writes a checkpoint and
  /// stops. Further signals change nothing (the final checkpoint and summary
  /// are always complete, and after a stop by a signal they are ignored
  /// until the process exits); kill -9 ends a run at once. Outside time
  /// loops: handle_interrupts_outside_time_loops().
  class InterruptHandlers
  {
  public:
    InterruptHandlers();
    ~InterruptHandlers();
    InterruptHandlers(const InterruptHandlers &) = delete;
    InterruptHandlers &
    operator=(const InterruptHandlers &) = delete;

  private:
    struct sigaction previous_int, previous_term;
  };

  /// Outside time loops (set-up, final output), SIGINT and SIGTERM end the
  /// process at once with exit 128 + signal, and (report: the MPI root) one
  /// line on stderr saying when: "interrupted by SIGINT during set-up ...".
  void
  handle_interrupts_outside_time_loops(bool report);

  /// The signal received so far (0: none).
  int
  interrupt_signal();

  /// "SIGINT", "SIGTERM", ...
  std::string
  signal_name(int signal);

  /**
   * When a time loop writes a checkpoint or stops: every `every_steps`
   * steps, every `every_seconds` of wall time, when a SIGINT/SIGTERM arrived
   * (then it stops), and when the step counter reaches `max_steps` (then it
   * stops). The decision is collective: under MPI every rank gets rank 0's
   * wall clock and any rank's signal.
   */
  class CheckpointSchedule
  {
  public:
    struct Decision
    {
      bool write     = false; ///< write a checkpoint now
      int  signal    = 0;     ///< stop: this signal arrived
      bool max_steps = false; ///< stop: the step counter reached max steps
      bool scheduled = false; ///< a checkpoint is due by steps or wall time
      bool
      stop() const
      {
        return signal != 0 || max_steps;
      }
    };

    /// enabled false (no output directory): never write, still stop.
    CheckpointSchedule(unsigned long every_steps, double every_seconds,
                       unsigned long max_steps, bool enabled, MPI_Comm comm);

    /// After completed step `step`.
    Decision
    poll(unsigned long step);

    /// A checkpoint was written: restart the wall clock.
    void
    written();

  private:
    using Clock = std::chrono::steady_clock;
    unsigned long     every_steps, max_steps;
    double            every_seconds;
    bool              enabled;
    MPI_Comm          comm;
    Clock::time_point last;
  };

  /// The status of a run that stopped early (d.stop()): "interrupted by
  /// SIGINT at t = 1.5 (step 120); checkpoint FILE; continue with --resume",
  /// or "stopped at Time stepping/max steps = 120 (t = 1.5); ...".
  std::string
  stop_status(const CheckpointSchedule::Decision &d, const std::string &time_name, double t,
              unsigned long step, const std::string &checkpoint_file);

  /// A run stopped by a signal (after writing a checkpoint): main() prints
  /// what() and exits with 128 + signal.
  class Interrupted : public std::runtime_error
  {
  public:
    Interrupted(const int signal, const std::string &what)
      : std::runtime_error(what)
      , signal(signal)
    {}
    const int signal;
  };
} // namespace granular_dg
