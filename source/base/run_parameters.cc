#include <deal.II/base/mpi.h>

#include <granular_dg/base/errors.h>
#include <granular_dg/base/input_path.h>
#include <granular_dg/base/output.h>
#include <granular_dg/base/parameter_binding.h>
#include <granular_dg/base/run_parameters.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <sched.h>

namespace granular_dg
{
  std::vector<double>
  parse_doubles(const std::string &text, const std::string &parameter)
  {
    std::vector<double> out;
    for (const auto &s : Utilities::split_string_list(text, ','))
      {
        try
          {
            out.push_back(Utilities::string_to_double(s));
          }
        catch (...)
          {
            require(false, parameter, text, "a comma-separated list of numbers");
          }
      }
    return out;
  }

  namespace
  {
    /// Unsigned integers of a comma-separated list (checked by its pattern).
    std::vector<unsigned int>
    unsigned_list(const std::string &text)
    {
      std::vector<unsigned int> out;
      for (const auto &s : Utilities::split_string_list(text))
        out.push_back(Utilities::string_to_int(s));
      return out;
    }

    /// The MPI ranks on this machine (1 without MPI): collective on its
    /// first call, which splits MPI_COMM_WORLD by node, then remembered.
    unsigned int
    ranks_on_this_machine()
    {
      static const unsigned int ranks = [] {
        int ranks_here = 1;
        if (Utilities::MPI::job_supports_mpi())
          {
            MPI_Comm node;
            MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
            MPI_Comm_size(node, &ranks_here);
            MPI_Comm_free(&node);
          }
        return unsigned(ranks_here);
      }();
      return ranks;
    }
  } // namespace

  void
  RunParameters::declare(ParameterHandler &prm)
  {
    ParameterBinding b(prm, ParameterBinding::Mode::declare);
    RunParameters().bind(b);
  }

  void
  RunParameters::parse(ParameterHandler &prm)
  {
    {
      ParameterBinding b(prm, ParameterBinding::Mode::read);
      bind(b);
    }
    record_parameters(prm);
  }

  void
  RunParameters::bind(ParameterBinding &b)
  {
    b.section("Time stepping");
    b.add("final time", final_time, Patterns::Double(), "End of the simulation. Must be > 0.")
      .check([](const double t) { return t > 0; }, "must be > 0");
    b.add("max steps", max_steps, Patterns::Integer(0),
          "Stop when the step counter reaches this number, writing a checkpoint and "
          "summary.json (status 'stopped at max steps'); continue with --resume. For runs "
          "split into jobs, and restart tests. 0: no limit.");
    bind_output(b);
    bind_modes(b);
    bind_checkpoint(b);
  }

  void
  RunParameters::bind_output(ParameterBinding &b)
  {
    b.section("Output");
    b.add("directory", directory, Patterns::Anything(),
          "Where everything of the run goes (created if missing).");
    b.add("overwrite", overwrite, Patterns::Bool(),
          "Replace the results of a previous run in the directory (the files its manifest "
          "lists); without it such a directory is refused.");
    b.add("output times", "", Patterns::Anything(),
          "Comma-separated times of the snapshots (besides t = 0 and the final time). Empty: "
          "use the output interval.",
          [this](const std::string &text) {
            output_times = parse_doubles(text, "Output/output times");
            for (const double t : output_times)
              require(t > 0 && t <= final_time, "Output/output times", text,
                      "times in (0, final time = " + format_number(final_time) + "]");
          });
    b.add("output interval", output_interval, Patterns::Double(0),
          "Snapshot every this much time when no output times are given (0: only the initial "
          "and final state).");
    b.add("write vtu", write_vtu, Patterns::Bool(),
          "Write field snapshots (in Output/format) and their index; false: CSV/JSON output "
          "only.");
    b.add("format", "vtu", Patterns::Selection("vtu|hdf5"),
          "Snapshot format: vtu (solution-NNNN.vtu, one .vtu per rank and a .pvtu under MPI, "
          "indexed by solution.pvd) or hdf5 (2D only: solution-NNNN.h5 written by all ranks "
          "into one file through parallel HDF5, indexed by solution.xdmf; doc/program.md).",
          [this](const std::string &text) { hdf5 = text == "hdf5"; });
    b.add("progress interval", progress_interval, Patterns::Double(0),
          "Seconds of wall time between progress lines (0: none).");
  }

  void
  RunParameters::bind_modes(ParameterBinding &b)
  {
    b.section("Convergence");
    b.add("enabled", convergence, Patterns::Bool(),
          "Run a convergence study against the exact solution instead of a single run.")
      .check([this](const bool on) { return !(on && max_steps > 0); },
             "false when Time stepping/max steps is set (a study runs every mesh to the final "
             "time; max steps stops a single run, to be continued with --resume)");
    b.add("degrees", "0,1,2,3,4", Patterns::List(Patterns::Integer(0, 4)),
          "Degrees of the study, each once.",
          [this](const std::string &text) {
            convergence_degrees = unsigned_list(text);
            auto sorted         = convergence_degrees;
            std::sort(sorted.begin(), sorted.end());
            require(!convergence || !sorted.empty(), "Convergence/degrees", text,
                    "at least one degree for a study");
            require(!convergence || std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end(),
                    "Convergence/degrees", text, "each degree once");
          });
    b.add("cells", "16,32,64,128", Patterns::List(Patterns::Integer(1)),
          "Numbers of cells of the study, coarse to fine, per direction of the mesh (every "
          "direction is refined) or as the scene's doc/ page defines them.",
          [this](const std::string &text) {
            convergence_cells = unsigned_list(text);
            require(!convergence || convergence_cells.size() >= 2, "Convergence/cells", text,
                    "at least two mesh sizes for a study");
            // the rates of the two finest meshes are those of the last two
            require(!convergence ||
                      std::adjacent_find(convergence_cells.begin(), convergence_cells.end(),
                                         std::greater_equal<>()) == convergence_cells.end(),
                    "Convergence/cells", text, "increasing mesh sizes, coarse to fine");
          });
    b.add("CFL numbers", "", Patterns::Anything(),
          "One CFL number per entry of Convergence/degrees (comma-separated); empty: Time "
          "stepping/CFL number for all.",
          [this](const std::string &text) { read_convergence_cfl(text); });

    b.section("Benchmark");
    b.add("enabled", benchmark.enabled, Patterns::Bool(),
          "Time the steps instead of running to the final time (also granular_dg --benchmark "
          "CASE.prm): warm-up steps, then repetitions of a block of steps, restarted from the "
          "initial state before they would pass the final time; writes benchmark.json (CPU "
          "time per step, DoF-stage updates per second per core, the phases of a step) and "
          "nothing else. doc/performance.md.")
      .check([this](const bool on) { return !(on && convergence); },
             "false when Convergence/enabled is true");
    b.add("repetitions", benchmark.repetitions, Patterns::Integer(1),
          "Number of timed blocks (min and median are reported).");
    b.add("steps", benchmark.steps, Patterns::Integer(0),
          "Steps per block; 0: doubled from 1 until a block takes the minimum time.");
    b.add("minimum time", benchmark.min_time, Patterns::Double(0),
          "CPU seconds a calibrated block lasts at least.");
    b.add("warm-up steps", benchmark.warmup_steps, Patterns::Integer(0),
          "Untimed steps before the calibration.");
  }

  void
  RunParameters::read_convergence_cfl(const std::string &text)
  {
    convergence_cfl = parse_doubles(text, "Convergence/CFL numbers");
    for (const double v : convergence_cfl)
      require(v > 0 && v <= 1, "Convergence/CFL numbers", text, "numbers in (0, 1]");
    require(!convergence || convergence_cfl.empty() ||
              convergence_cfl.size() == convergence_degrees.size(),
            "Convergence/CFL numbers", text,
            "one number per entry of Convergence/degrees (" +
              std::to_string(convergence_degrees.size()) + ")");
  }

  void
  RunParameters::bind_checkpoint(ParameterBinding &b)
  {
    b.section("Checkpoint");
    b.add("every steps", checkpoint_steps, Patterns::Integer(0),
          "Write a checkpoint (Output/directory/checkpoints/step-N.ckpt, the newest two are "
          "kept) every this many steps (0: not by steps).")
      .check([this](const unsigned long n) { return !(n > 0 && convergence); },
             "0 when Convergence/enabled is true (a study writes no checkpoints)");
    b.add("every seconds", checkpoint_seconds, Patterns::Double(0),
          "Write a checkpoint every this many seconds of wall time (0: not by time). A SIGINT "
          "or SIGTERM always writes one before the run stops.");
    b.add("resume", resume, Patterns::Bool(),
          "Continue the run in Output/directory from its newest valid checkpoint (also "
          "granular_dg --resume CASE.prm), appending to its solution.pvd and timeseries.csv. "
          "The parameters must be those of that run, except Time stepping/final time and max "
          "steps, Checkpoint/* and Output/progress interval.")
      .check([this](const bool r) { return !(r && overwrite); },
             "false when Output/overwrite is true (resume continues the run in the directory, "
             "overwrite discards it)")
      .check([this](const bool r) { return !(r && convergence); },
             "false when Convergence/enabled is true (a study has no checkpoints)")
      .check([this](const bool r) { return !(r && benchmark.enabled); },
             "false in benchmark mode");
  }

  void
  RunParameters::record_parameters(ParameterHandler &prm)
  {
    // the parameters of the run, without the switch that resumes it: a
    // resumed run's parameters.prm is the uninterrupted run's
    prm.enter_subsection("Checkpoint");
    prm.set("resume", false);
    prm.leave_subsection();
    std::ostringstream text;
    prm.print_parameters(text, ParameterHandler::ShortPRM);
    prm.enter_subsection("Checkpoint");
    prm.set("resume", resume);
    prm.leave_subsection();
    parameters_text = text.str();
    parameters      = flatten_parameters(parameters_text);
  }

  std::vector<double>
  RunParameters::output_schedule(const double start_time) const
  {
    std::vector<double> times;
    if (!output_times.empty())
      times = output_times;
    else if (output_interval > 0)
      for (unsigned long k = 1; k * output_interval < final_time * (1 - 1e-12); ++k)
        times.push_back(k * output_interval);
    times.erase(std::remove_if(times.begin(), times.end(),
                               [&](const double t) { return t <= start_time * (1 + 1e-12); }),
                times.end());
    times.push_back(final_time);
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end(),
                            [&](double a, double b) {
                              return std::abs(a - b) <= 1e-12 * final_time;
                            }),
                times.end());
    return times;
  }

  double
  peak_resident_bytes()
  {
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
      if (line.rfind("VmHWM:", 0) == 0)
        return 1024. * std::atof(line.c_str() + 6);
    return 0.;
  }

  double
  available_memory_per_rank()
  {
    std::ifstream meminfo("/proc/meminfo");
    std::string   key, unit;
    double        kb = 0.;
    while (meminfo >> key >> kb >> unit)
      if (key == "MemAvailable:")
        break;
    if (key != "MemAvailable:")
      return 0.;
    return 1024. * kb / ranks_on_this_machine();
  }

  unsigned int
  cores_per_rank()
  {
    cpu_set_t allowed;
    const int cores = sched_getaffinity(0, sizeof(allowed), &allowed) == 0 ? CPU_COUNT(&allowed) : 1;
    return std::max(1u, unsigned(cores) / ranks_on_this_machine());
  }

  void
  require_reasonable_snapshot_count(const RunParameters &p, const double bytes_per_snapshot,
                                    const unsigned long max_snapshots)
  {
    if (p.benchmark.enabled || p.convergence)
      return;
    // counted without building the list (an interval of 1e-9 would be 3e10 times)
    const double n = 2. + (p.output_times.empty() && p.output_interval > 0 ?
                             std::floor(p.final_time / p.output_interval) :
                             double(p.output_times.size()));
    if (n <= max_snapshots)
      return;
    const std::string parameter =
      p.output_times.empty() ? "Output/output interval" : "Output/output times";
    const std::string value = p.output_times.empty() ? format_number(p.output_interval) :
                                                       std::to_string(p.output_times.size()) +
                                                         " times";
    require(false, parameter, value,
            "at most " + std::to_string(max_snapshots) + " snapshots per run: this asks for " +
              format_number(n) + " snapshots of about " + format_bytes(bytes_per_snapshot) +
              " each (" + format_bytes(n * bytes_per_snapshot) + " in all)");
  }

  void
  begin_output(const RunParameters &params)
  {
    std::string error;
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      {
        try
          {
            const std::string dump = params.directory + "/parameters.prm";
            require(params.benchmark.enabled || !is_parameter_file(dump), "Output/directory",
                    params.directory,
                    "a directory whose parameters.prm is not this run's parameter file: the run "
                    "writes the parameters it used there and would overwrite " +
                      dump + "; rename the case file or choose another directory");
            if (params.benchmark.enabled)
              prepare_benchmark_directory(params.directory);
            else if (params.resume)
              {
                if (std::filesystem::is_directory(params.directory))
                  lock_output_directory(params.directory);
                check_resumable(params);
                begin_manifest(params.directory, true);
              }
            else
              prepare_output_directory(params.directory, params.overwrite);
          }
        catch (const InputError &e)
          {
            error = e.what();
          }
        if (error.empty() && !params.benchmark.enabled)
          try
            {
              write_to_file(params.directory + "/parameters.prm",
                            [&](std::ostream &out) { out << params.parameters_text; });
            }
          catch (const RunError &e)
            {
              error = e.what();
            }
      }
    // the other ranks write into the directory only after it exists
    error = Utilities::MPI::broadcast(MPI_COMM_WORLD, error, 0);
    if (!error.empty())
      throw InputError(error);
  }

  void
  require_beyond_checkpoint(const RunParameters &params, const Checkpoint &checkpoint,
                            const std::string &time_name)
  {
    require(checkpoint.time < params.final_time * (1 - 1e-14), "Time stepping/final time",
            params.final_time,
            "after the time of the checkpoint, " + time_name + " = " +
              format_number(checkpoint.time) + " (" + checkpoint.file +
              "): raise it to continue the run");
    require(params.max_steps == 0 || checkpoint.step < params.max_steps,
            "Time stepping/max steps", params.max_steps,
            "0 or above the step of the checkpoint, " + std::to_string(checkpoint.step) + " (" +
              checkpoint.file + ")");
  }

  void
  check_resumable(const RunParameters &params)
  {
    const std::string &dir = params.directory;
    require(std::filesystem::is_directory(dir), "Checkpoint/resume", "true",
            "Output/directory = '" + dir + "' does not exist: there is no run to resume");
    std::ifstream in(dir + "/parameters.prm");
    require(static_cast<bool>(in), "Checkpoint/resume", "true",
            "Output/directory = '" + dir + "' holds no run (no parameters.prm)");
    require(has_checkpoints(dir, true), "Checkpoint/resume", "true",
            "the run in '" + dir + "' wrote no checkpoint (" + checkpoint_directory(dir) +
              " is empty or missing" +
              (has_incomplete_checkpoint(dir) ?
                 "; an incomplete checkpoint of an interrupted write was ignored" :
                 "") +
              "), it cannot be resumed");
    std::ostringstream before;
    before << in.rdbuf();
    require_same_parameters(flatten_parameters(before.str()), params.parameters,
                            "the run in '" + dir + "'");

    // a completed run has nothing to continue, unless the final time grows
    std::ifstream      summary(dir + "/summary.json");
    std::ostringstream text;
    text << summary.rdbuf();
    const std::regex status(R"re("status": "completed)re"),
      final_time(R"re("final_time": ([-+0-9.eE]+))re");
    std::smatch       match;
    const std::string json = text.str();
    if (std::regex_search(json, status) && std::regex_search(json, match, final_time) &&
        std::stod(match[1]) >= params.final_time * (1 - 1e-12))
      require(false, "Checkpoint/resume", "true",
              "the run in '" + dir + "' completed (final time " + std::string(match[1]) +
                "); nothing to resume (raise Time stepping/final time to continue it)");
  }

  void
  RunParameters::require_format_fits(const unsigned int dim) const
  {
    require(dim > 1 || !hdf5, "Output/format", "hdf5",
            "vtu in 1D (deal.II writes HDF5/XDMF for dim >= 2 only; 1D runs also write CSV "
            "profiles)");
  }
} // namespace granular_dg
