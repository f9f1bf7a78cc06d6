/**
 * granular_dg: the command a user runs. It answers what needs no solver
 * (--help, --version, --list-scenes) from text the engine printed when it
 * was built, and hands everything else to the engine, granular_dg_engine
 * beside it, by exec (same process, arguments and environment, so mpirun and
 * signals see the engine itself). Loading deal.II and its ~200 shared
 * libraries takes about 0.4 s before main(); the answers here take none of it
 * (doc/performance.md, "Build and start-up").
 */

#include <granular_dg/engine_information.h>

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <utility>

namespace
{
  /// The engine: granular_dg_engine in the directory of this program.
  std::string
  engine_path(const char *argv0)
  {
    char      buffer[4096];
    const int n    = ::readlink("/proc/self/exe", buffer, sizeof(buffer) - 1);
    std::string self = n > 0 ? std::string(buffer, n) : std::string(argv0);
    const auto  slash = self.rfind('/');
    return (slash == std::string::npos ? std::string(".") : self.substr(0, slash)) +
           "/granular_dg_engine";
  }

  /// True when a process manager (mpirun, srun, a PMIx server) started us.
  bool
  started_by_process_manager()
  {
    for (const char *name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE",
                             "SLURM_STEP_ID", "HYDRA_CONTROL_FD"})
      if (std::getenv(name) != nullptr)
        return true;
    return false;
  }

  /**
   * A run without mpirun is an MPI singleton. Open MPI 4.1 then starts a
   * daemon (orted) for it and probes every point-to-point layer, UCX among
   * them: 0.40 s of a bare MPI_Init + MPI_Finalize on this project's machines,
   * against 0.05 s as an isolated singleton with the ob1 layer (doc/
   * performance.md, "Build and start-up"). Isolated singletons all take the
   * same job id and so the same session directory (/tmp/ompi.HOST.UID/jf.0/1):
   * one run ending removes it while another creates it, and the other's
   * MPI_Init fails (8 of 1200 bare starts, four at a time). So no session
   * directory is made at all (0 of 4000): one rank needs only the self
   * transport, and MPI-IO's "sm" component, the one that keeps files there,
   * is off for every run (keep_mpi_io_off_named_semaphores()).
   * A setting the user made wins; other MPI implementations ignore the names.
   */
  void
  start_singleton_quickly()
  {
    if (started_by_process_manager())
      return;
    for (const auto &[name, value] : {std::pair{"OMPI_MCA_ess_singleton_isolated", "1"},
                                      std::pair{"OMPI_MCA_pml", "ob1"},
                                      std::pair{"OMPI_MCA_btl", "self"},
                                      std::pair{"OMPI_MCA_orte_create_session_dirs", "0"}})
      ::setenv(name, value, /*overwrite=*/0);
  }

  /**
   * MPI-IO (the checkpoints, HDF5 output) never uses shared file pointers,
   * yet Open MPI 4.1's MPI-IO (OMPIO) sets one up at every MPI_File_open, on
   * one node with its "sm" component: rank 0 takes and releases a POSIX
   * semaphore named after the file's base name alone
   * (/dev/shm/sem.OMPIO_.step-0000000040.ckpt.tmp). A run killed while it
   * holds it (a batch system's time limit, kill -9) leaves it taken, and from
   * then on every MPI run on that machine that writes a file of that name,
   * the checkpoint of the same step in any directory, waits in MPI_File_open
   * forever, until someone deletes the semaphore by hand. Without "sm" Open
   * MPI takes its file-lock component, whose locks end with the process.
   * Every run, with or without mpirun; a setting the user made wins.
   * (tests/checkpoint/killed_write_leftovers)
   */
  void
  keep_mpi_io_off_named_semaphores()
  {
    ::setenv("OMPI_MCA_sharedfp", "^sm", /*overwrite=*/0);
  }

} // namespace

int
main(int argc, char **argv)
{
  // the first argument decides, as in the engine (which also answers these
  // when it meets them after other arguments)
  const std::string first = argc > 1 ? argv[1] : "";
  if (argc == 1)
    {
      std::cout << granular_dg::engine_information::help;
      return 2;
    }
  if (first == "--help" || first == "-h")
    {
      std::cout << granular_dg::engine_information::help;
      return 0;
    }
  if (first == "--version")
    {
      std::cout << granular_dg::engine_information::version;
      return 0;
    }
  if (first == "--list-scenes")
    {
      std::cout << granular_dg::engine_information::scenes;
      return 0;
    }
  const std::string engine = engine_path(argv[0]);
  start_singleton_quickly();
  keep_mpi_io_off_named_semaphores();
  ::execv(engine.c_str(), argv);
  std::cerr << "granular_dg: internal error: cannot start the engine " << engine << ": "
            << std::strerror(errno) << std::endl;
  return 4;
}
