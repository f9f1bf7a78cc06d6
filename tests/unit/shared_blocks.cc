// Checkpoints written and read per rank (base/checkpoint.h): on 3 ranks each
// rank writes its own pieces of two shared blocks (uneven sizes, rank 1's
// piece of the second block empty) through MPI-IO next to rank 0's payload.
// Checked: the payload reads back; each block is the ranks' pieces in rank
// order (rank 0 reads each whole block, every rank its own piece); the
// checksums, computed from the written pieces and checked over other shares,
// agree; a flipped byte in a block of the newest checkpoint makes resume fall
// back to the older one, and with both damaged there is none.
// Prints from rank 0; exits 1 when anything is wrong (on any rank).
#include <deal.II/base/mpi.h>

#include <granular_dg/base/checkpoint.h>
#include <granular_dg/base/errors.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>

namespace
{
  using namespace granular_dg;

  std::string
  pattern(const unsigned int block, const unsigned int rank, const std::size_t size)
  {
    std::string s(size, '\0');
    for (std::size_t i = 0; i < size; ++i)
      s[i] = static_cast<char>((31 * rank + 7 * i + 101 * block) % 251);
    return s;
  }

  std::size_t
  piece_size(const unsigned int block, const unsigned int rank)
  {
    return block == 1 && rank == 1 ? 0 : 1000 * (block + 1) + 37 * rank;
  }

  void
  flip_byte(const std::string &file, const std::uint64_t offset)
  {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(offset);
    const char c = static_cast<char>(f.get() ^ 0x20);
    f.seekp(offset);
    f.put(c);
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm     comm = MPI_COMM_WORLD;
  const unsigned int rank = dealii::Utilities::MPI::this_mpi_process(comm);
  const unsigned int n    = dealii::Utilities::MPI::n_mpi_processes(comm);
  if (rank == 0)
    std::filesystem::remove_all("out");
  MPI_Barrier(comm);

  const CheckpointIdentity id{"unit", "none", 2, 1, 3, 3 * n};
  const ParameterList      parameters{{"Time stepping/final time", "1"}};
  std::string              files[2];
  for (const unsigned long step : {7ul, 9ul})
    {
      ByteWriter w;
      w.io(step);
      w.shared(pattern(0, rank, piece_size(0, rank)));
      w.io(std::string("between"));
      w.shared(pattern(1, rank, piece_size(1, rank)));
      files[step == 9] = write_checkpoint("out", id, parameters, step, 0.5 * step, w, comm);
    }

  bool ok = true;
  auto check_read = [&](const unsigned long expected_step) {
    const Checkpoint c = read_checkpoint("out", id, parameters, comm);
    ByteReader       r(c.payload, &c.blocks);
    unsigned long    step = 0;
    std::string      between;
    r.io(step);
    ok = ok && step == expected_step && c.step == expected_step;
    for (const unsigned int b : {0u, 1u})
      {
        std::string whole;
        std::size_t before = 0;
        for (unsigned int q = 0; q < n; ++q)
          {
            whole += pattern(b, q, piece_size(b, q));
            before += q < rank ? piece_size(b, q) : 0;
          }
        ok = ok && r.shared_size() == whole.size();
        if (rank == 0)
          ok = ok && c.blocks.read(b, 0, whole.size()) == whole;
        ok = ok && r.shared(before, piece_size(b, rank)) == pattern(b, rank, piece_size(b, rank));
        if (b == 0)
          {
            r.io(between);
            ok = ok && between == "between";
          }
      }
    ok = ok && r.at_end();
    return c;
  };

  const Checkpoint newest = check_read(9);
  if (rank == 0)
    std::printf("%u ranks wrote 2 shared blocks; read back: %s\n", n, ok ? "ok" : "WRONG");

  // a flipped byte in the second block of the newest checkpoint: the older one
  if (rank == 0)
    flip_byte(files[1], newest.blocks.offsets[1] + 1500);
  MPI_Barrier(comm);
  check_read(7);
  if (rank == 0)
    std::printf("newest damaged: resumed from step 7: %s\n", ok ? "ok" : "WRONG");

  // both damaged: none is usable
  if (rank == 0)
    flip_byte(files[0], newest.blocks.offsets[0] + 10);
  MPI_Barrier(comm);
  try
    {
      read_checkpoint("out", id, parameters, comm);
      ok = false;
    }
  catch (const InputError &e)
    {
      if (rank == 0)
        std::printf("both damaged: %s\n", e.what());
    }
  return dealii::Utilities::MPI::min(ok ? 1 : 0, comm) == 1 ? 0 : 1;
}
