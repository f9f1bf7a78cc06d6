/**
 * granular_dg: explicit discontinuous Galerkin solvers for the conservation
 * laws of granular and layered media. See README.md and doc/.
 */

#include <deal.II/base/mpi.h>
#include <deal.II/base/revision.h>

#include <granular_dg/base/checkpoint.h>
#include <granular_dg/base/errors.h>
#include <granular_dg/base/output.h>
#include <granular_dg/base/parameters.h>
#include <granular_dg/base/scene.h>
#include <granular_dg/version.h>

#include <filesystem>
#include <cstdlib>
#include <iostream>
#include <optional>

using namespace granular_dg;

namespace
{
  const Scene &
  find_scene(const std::string &name, const std::string &where)
  {
    const Scene *scene = find_registered_scene(name);
    require(scene != nullptr, where, name, "one of " + scene_names());
    return *scene;
  }

  void
  declare_all(ParameterHandler &prm, const Scene &scene)
  {
    prm.declare_entry("scene", scene.name, Patterns::Selection(scene_names()),
                      "The scene to run: " + scene_names() + ".");
    scene.declare(prm);
  }

  /// The scene named by the top-level `set scene = NAME` of a prm file (or of
  /// a file it includes), or by a --set scene=NAME override, found before the
  /// parameters are declared, since what is declared depends on it.
  std::string
  find_scene_name(const std::string &filename, const std::vector<std::string> &overrides)
  {
    std::string name, override_name, where;
    for (const auto &o : overrides)
      if (o.rfind("scene=", 0) == 0)
        override_name = Utilities::trim(o.substr(6));
    require_readable_parameter_file(filename);
    for (const auto &[value, at] : top_level_settings(filename, "scene"))
      {
        if (!name.empty() && name != value) // (require()'s form, with the origin)
          throw InputError("parameter 'scene' = '" + value + "' (" + at +
                           ") is not allowed: one scene per case: " + where + " sets scene = " + name);
        name  = value;
        where = at;
      }
    if (!override_name.empty())
      {
        // the file's parameters belong to its scene
        require(name.empty() || name == override_name, "scene", override_name,
                "the scene of " + filename + ", " + name + " (--set scene only names the "
                "scene of a file that does not)");
        return override_name;
      }
    if (name.empty())
      throw InputError("parameter file '" + filename +
                       "' does not say which scene to run: add 'set scene = NAME' "
                       "with NAME one of " + scene_names());
    return name;
  }

  void
  print_help()
  {
    std::cout
      << "granular_dg " << GRANULAR_DG_VERSION
      << " - explicit DG for granular and layered media\n\n"
         "Usage:\n"
         "  granular_dg CASE.prm [--set Section/name=value ...]   run a case\n"
         "  granular_dg --benchmark CASE.prm [--set ...]           time the steps of a case\n"
         "                                                         (benchmark.json; doc/performance.md)\n"
         "  granular_dg --resume CASE.prm [--set ...]              continue the run in the case's\n"
         "                                                         output directory from its newest\n"
         "                                                         checkpoint (Checkpoint/ parameters)\n"
         "  granular_dg --print-parameters SCENE                   all parameters of a scene,\n"
         "                                                         with defaults and documentation\n"
         "  granular_dg --list-scenes                              the scenes, one per line\n"
         "  granular_dg --version | --help\n\n"
         "Scenes:\n";
    for (const auto &scene : registered_scenes())
      std::cout << "  " << scene.name << ": " << scene.description << '\n';
    std::cout
      << "\nA run writes to Output/directory: solution.pvd + solution-NNNN.vtu (ParaView),\n"
         "profile-NNNN.csv (1D), timeseries.csv, summary.json and parameters.prm.\n"
         "Checkpoints: Output/directory/checkpoints/ every Checkpoint/every seconds\n"
         "(600) or every steps, and on SIGINT/SIGTERM; continue with --resume.\n"
         "Exit codes: 0 completed (or stopped at Time stepping/max steps), 2 bad input,\n"
         "3 run failed (inadmissible state; the last good state is written), 4 internal\n"
         "error, 130/143 interrupted by SIGINT/SIGTERM (a checkpoint is written).\n"
         "Examples are in prm/; documentation in doc/.\n";
  }

  /// Whether an MPI launcher (mpirun, srun) started this process: its rank
  /// in the launcher's environment, "" if there is none.
  std::string
  mpi_launcher_rank()
  {
    for (const char *name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
      if (const char *rank = std::getenv(name))
        return rank;
    return "";
  }

  /// The command line: a run (a parameter file and its --set overrides), or
  /// a request that needs no MPI (--help, --version, --list-scenes,
  /// --print-parameters), answered here; then its exit code is returned,
  /// -1 for a run. root: whether this process prints.
  int
  parse_command_line(const std::vector<std::string> &args, const bool root,
                     std::string &filename, std::vector<std::string> &overrides)
  {
    for (unsigned int i = 0; i < args.size(); ++i)
      {
        const std::string &a = args[i];
        if (a == "--help" || a == "-h")
          {
            if (root)
              print_help();
            return 0;
          }
        else if (a == "--list-scenes")
          {
            if (root)
              for (const auto &scene : registered_scenes())
                std::cout << scene.name << '\n';
            return 0;
          }
        else if (a == "--version")
          {
            if (root)
              std::cout << "granular_dg " << GRANULAR_DG_VERSION << " (git "
                        << git_revision() << "), deal.II " << DEAL_II_PACKAGE_VERSION
                        << std::endl;
            return 0;
          }
        else if (a == "--print-parameters")
          {
            const std::string name = i + 1 < args.size() ? args[i + 1] : "";
            if (name.empty())
              throw InputError("--print-parameters needs a scene: one of " + scene_names());
            // (options after it are ignored, as --print-parameters answers at once)
            if (i + 2 < args.size() && args[i + 2].rfind("-", 0) != 0)
              throw InputError("--print-parameters takes one scene ('" + args[i + 2] +
                               "' after it is not one of its arguments)");
            ParameterHandler prm;
            declare_all(prm, find_scene(name, "--print-parameters"));
            prm.set("scene", name);
            if (root)
              prm.print_parameters(std::cout, ParameterHandler::PRM);
            return 0;
          }
        else if (a == "--set")
          {
            if (i + 1 >= args.size())
              throw InputError("--set needs an argument Section/name=value");
            overrides.push_back(args[++i]);
          }
        else if (a == "--benchmark")
          overrides.push_back("Benchmark/enabled=true");
        else if (a == "--resume")
          overrides.push_back("Checkpoint/resume=true");
        else if (a.rfind("--set=", 0) == 0)
          overrides.push_back(a.substr(6));
        else if (a.rfind("-", 0) == 0)
          throw InputError("unknown option '" + a + "' (see granular_dg --help)");
        else if (filename.empty())
          filename = a;
        else
          throw InputError("more than one parameter file given ('" + filename + "' and '" + a +
                           "')");
      }
    if (!filename.empty())
      return -1;
    if (!args.empty())
      throw InputError("no parameter file given: granular_dg [--resume] CASE.prm [--set ...] "
                       "(see granular_dg --help)");
    if (root)
      print_help();
    return 2;
  }
} // namespace

int
main(int argc, char **argv)
{
  // MPI starts only for a run. (A run that no process manager started is an
  // Open MPI singleton; the launcher, granular_dg, sets it up to start in
  // 0.05 s instead of 0.4 s: source/launcher.cc.)
  const std::string                               rank = mpi_launcher_rank();
  bool                                            root = rank.empty() || rank == "0";
  std::optional<Utilities::MPI::MPI_InitFinalize> mpi;
  try
    {
      const std::vector<std::string> args(argv + 1, argv + argc);
      std::vector<std::string>       overrides;
      std::string                    filename;
      if (const int code = parse_command_line(args, root, filename, overrides); code >= 0)
        return code;

      mpi.emplace(argc, argv, 1);
      root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
      handle_interrupts_outside_time_loops(root);
      const Scene     &scene = find_scene(find_scene_name(filename, overrides), "scene");
      ParameterHandler prm;
      declare_all(prm, scene);
      parse_parameters(prm, filename, overrides);
      if (root)
        std::cout << "granular_dg " << GRANULAR_DG_VERSION << ": scene '" << scene.name
                  << "' from " << filename << std::endl;
      scene.run(prm);
    }
  catch (const InputError &e)
    {
      if (root)
        {
          std::cerr << "granular_dg: error: " << e.what() << std::endl;
          abandon_new_output();
        }
      return 2;
    }
  catch (const RunError &e)
    {
      if (root)
        {
          std::cerr << "granular_dg: run failed: " << e.what() << std::endl;
          abandon_new_output(); // (a benchmark that wrote nothing)
        }
      return 3;
    }
  catch (const Interrupted &e)
    {
      if (root)
        std::cerr << "granular_dg: " << e.what() << std::endl;
      return 128 + e.signal;
    }
  catch (const std::exception &e)
    {
      std::cerr << "granular_dg: internal error: " << one_line_message(e) << std::endl;
      return 4;
    }
  return 0;
}
