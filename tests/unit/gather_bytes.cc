// gather_bytes and broadcast_bytes (base/checkpoint.h), the transport of a
// checkpoint's payload that must not stop at MPI's int counts (2 GB): run on
// 3 ranks with a chunk of 7 bytes, so that every message is split and the
// last chunk is short. Rank r sends 13 r + 5 bytes of a pattern of its own
// (rank 1 of 3: also an empty string in a second round); rank 0 checks every
// byte; a 1000-byte string of rank 0 is broadcast and checked on every rank.
// Prints from rank 0; exits 1 when a byte is wrong (on any rank).
#include <deal.II/base/mpi.h>

#include <granular_dg/base/checkpoint.h>

#include <cstdio>
#include <string>

namespace
{
  std::string
  pattern(const unsigned int rank, const std::size_t size)
  {
    std::string s(size, '\0');
    for (std::size_t i = 0; i < size; ++i)
      s[i] = static_cast<char>((31 * rank + 7 * i) % 251);
    return s;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm     comm  = MPI_COMM_WORLD;
  const unsigned int rank  = dealii::Utilities::MPI::this_mpi_process(comm);
  const unsigned int n     = dealii::Utilities::MPI::n_mpi_processes(comm);
  const std::size_t  chunk = 7;

  bool ok = true;
  for (const bool empty_middle : {false, true})
    {
      const std::size_t size = empty_middle && rank == 1 ? 0 : 13 * rank + 5;
      const auto        all  = granular_dg::gather_bytes(comm, pattern(rank, size), chunk);
      if (rank == 0)
        {
          ok = ok && all.size() == n;
          for (unsigned int r = 0; r < all.size(); ++r)
            ok = ok && all[r] == pattern(r, empty_middle && r == 1 ? 0 : 13 * r + 5);
        }
      else
        ok = ok && all.empty();
    }
  if (rank == 0)
    std::printf("gather of %u ranks' bytes in chunks of %zu: %s\n", n, chunk, ok ? "ok" : "WRONG");

  std::string bytes = rank == 0 ? pattern(99, 1000) : std::string("stale");
  granular_dg::broadcast_bytes(comm, bytes, chunk);
  const bool same = dealii::Utilities::MPI::min(bytes == pattern(99, 1000) ? 1 : 0, comm) == 1;
  if (rank == 0)
    std::printf("broadcast of 1000 bytes in chunks of %zu: %s\n", chunk, same ? "ok" : "WRONG");
  return dealii::Utilities::MPI::min(ok && same ? 1 : 0, comm) == 1 ? 0 : 1;
}
