#include <deal.II/base/mpi.h>

#include <granular_dg/base/parameters.h>
#include <granular_dg/base/simulation.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

namespace granular_dg
{
  namespace
  {
    const EnumNames<dg::NumericalFlux> flux_names(
      {{dg::NumericalFlux::local_lax_friedrichs, "local_lax_friedrichs"},
       {dg::NumericalFlux::impedance, "impedance"},
       {dg::NumericalFlux::roe_lax_friedrichs, "roe_lax_friedrichs"},
       {dg::NumericalFlux::upwind, "upwind"},
       {dg::NumericalFlux::godunov, "godunov"}});
    const EnumNames<dg::Engine> engine_names({{dg::Engine::automatic, "auto"},
                                              {dg::Engine::matrix_free, "matrix_free"},
                                              {dg::Engine::line, "line"}});
    const EnumNames<dg::LimiterType> limiter_names(
      {{dg::LimiterType::none, "none"},
       {dg::LimiterType::componentwise, "componentwise"},
       {dg::LimiterType::characteristic, "characteristic"},
       {dg::LimiterType::flux_variables, "flux_variables"}});

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

    /// Whether the scene declares Convergence/CFL numbers (then it checks them).
    bool
    convergence_has_own_cfl(ParameterHandler &prm)
    {
      prm.enter_subsection("Convergence");
      bool declared = true;
      try
        {
          prm.get("CFL numbers");
        }
      catch (...)
        {
          declared = false;
        }
      prm.leave_subsection();
      return declared;
    }
  } // namespace

  double
  ssprk3_cfl_limit(const unsigned int degree)
  {
    // max nu = a dt/h with |R(nu z)| <= 1 for every eigenvalue z of the
    // upwind DG operator of u_t + u_x = 0 (Fourier analysis; R the SSP-RK3
    // stability polynomial), rounded down; contrib/dg_cfl_limits.py
    // computes them
    static const double limit[] = {1.2563, 0.4095, 0.2097, 0.1300, 0.0896};
    return limit[std::min(degree, 4u)];
  }

  void
  require_stable_cfl(const double cfl, const unsigned int degree, const std::string &parameter)
  {
    const double limit = ssprk3_cfl_limit(degree);
    require(cfl <= limit, parameter, cfl,
            "at most " + format_number(limit) + " at degree " + std::to_string(degree) +
              " (the linear stability limit of SSP-RK3 with DG of degree p = 0..4: "
              "1.2563, 0.4095, 0.2097, 0.13, 0.0896)");
  }

  void
  CommonParameters::declare(ParameterHandler &prm, const std::string &fluxes)
  {
    prm.enter_subsection("Discretization");
    prm.declare_entry("degree", "2", Patterns::Integer(0, 4),
                      "Polynomial degree of the FE_DGQLegendre space (0 = finite "
                      "volumes). Allowed: 0 to 4.");
    prm.declare_entry("numerical flux", "local_lax_friedrichs",
                      Patterns::Selection(fluxes),
                      "Numerical flux on faces: local_lax_friedrichs (Rusanov) or a "
                      "physics-specific one: impedance (elasticity: linearised Godunov "
                      "state with continuous velocity and stress), roe_lax_friedrichs "
                      "(Lax-Friedrichs with the Roe-matrix speed), upwind "
                      "(Engquist-Osher for scalar laws), godunov. Allowed: " + fluxes + ".");
    prm.declare_entry("engine", "auto", engine_names.pattern(),
                      "The operator: matrix_free (deal.II MatrixFree cell/face kernels, "
                      "any dimension, MPI) or line (a lean 1D kernel of the same "
                      "discretisation, serial, several times faster in 1D); auto: line "
                      "for serial 1D runs, matrix_free otherwise.");
    prm.leave_subsection();

    prm.enter_subsection("Time stepping");
    prm.declare_entry("final time", "1", Patterns::Double(),
                      "End of the simulation. Must be > 0.");
    prm.declare_entry("CFL number", "0.2", Patterns::Double(),
                      "Courant number dt * sum_d(lambda_max / h_d). SSP-RK3 with DG "
                      "of degree p is stable up to about 1/(2p+1). Allowed: (0, 1].");
    prm.declare_entry("max steps", "0", Patterns::Integer(0),
                      "Stop when the step counter reaches this number, writing a "
                      "checkpoint and summary.json (status 'stopped at max steps'); "
                      "continue with --resume. For runs split into jobs, and restart "
                      "tests. 0: no limit.");
    prm.declare_entry("check stability limit", "true", Patterns::Bool(),
                      "Refuse a CFL number above SSP-RK3's linear stability limit for the "
                      "degree (1.256, 0.4095, 0.2097, 0.13, 0.0896 for p = 0-4). false: "
                      "run anyway, for stability studies of where the method fails.");
    prm.leave_subsection();

    prm.enter_subsection("Limiter");
    prm.declare_entry("scheme", "none", limiter_names.pattern(),
                      "TVB minmod limiter on the Legendre modes after every stage: "
                      "none, componentwise (conserved variables), characteristic "
                      "(eigenvectors of the flux Jacobian at the cell average) or "
                      "flux_variables (variables continuous across material interfaces, "
                      "layered elasticity: stress and velocity).");
    prm.declare_entry("TVB constant", "0", Patterns::Double(0),
                      "M of the TVB minmod: slopes with |slope| <= M h^2 are not "
                      "limited (0 = TVD minmod).");
    prm.leave_subsection();

    prm.enter_subsection("Output");
    prm.declare_entry("directory", "output", Patterns::Anything(),
                      "Where everything of the run goes (created if missing).");
    prm.declare_entry("overwrite", "false", Patterns::Bool(),
                      "Replace the results of a previous run in the directory; "
                      "without it such a directory is refused.");
    prm.declare_entry("output times", "", Patterns::Anything(),
                      "Comma-separated times of the snapshots (besides t = 0 and the "
                      "final time). Empty: use the output interval.");
    prm.declare_entry("output interval", "0", Patterns::Double(0),
                      "Snapshot every this much time when no output times are "
                      "given (0: only the initial and final state).");
    prm.declare_entry("profile points per cell", "0", Patterns::Integer(0, 20),
                      "Sample points per cell in the 1D profile-NNNN.csv, equally "
                      "spaced with both end points (1: the cell centre; 0: degree+1, "
                      "at least 2).");
    prm.declare_entry("write modes", "false", Patterns::Bool(),
                      "1D: also write modes-NNNN.csv, the Legendre coefficients of every "
                      "cell (x_left, h, then per component the modes 0..p): the exact "
                      "discrete solution, usable as a reference solution of another run "
                      "(Exact solution/reference file of the scenes that offer it).");
    prm.declare_entry("write vtu", "true", Patterns::Bool(),
                      "Write solution-NNNN.vtu snapshots and solution.pvd.");
    prm.declare_entry("progress interval", "5", Patterns::Double(0),
                      "Seconds of wall time between progress lines (0: none).");
    prm.leave_subsection();

    prm.enter_subsection("Checkpoint");
    prm.declare_entry("every steps", "0", Patterns::Integer(0),
                      "Write a checkpoint (Output/directory/checkpoints/step-N.ckpt, the "
                      "newest two are kept) every this many steps (0: not by steps).");
    prm.declare_entry("every seconds", "600", Patterns::Double(0),
                      "Write a checkpoint every this many seconds of wall time (0: not by "
                      "time). A SIGINT or SIGTERM always writes one before the run stops.");
    prm.declare_entry("resume", "false", Patterns::Bool(),
                      "Continue the run in Output/directory from its newest valid "
                      "checkpoint (also granular_dg --resume CASE.prm), appending to its "
                      "solution.pvd and timeseries.csv. The parameters must be those of "
                      "that run, except Time stepping/final time and max steps, "
                      "Checkpoint/* and Output/progress interval.");
    prm.leave_subsection();

    prm.enter_subsection("Convergence");
    prm.declare_entry("enabled", "false", Patterns::Bool(),
                      "Run a convergence study against the exact solution instead "
                      "of a single run.");
    prm.declare_entry("degrees", "0,1,2,3,4", Patterns::List(Patterns::Integer(0, 4)),
                      "Degrees of the study.");
    prm.declare_entry("cells", "16,32,64,128", Patterns::List(Patterns::Integer(1)),
                      "Numbers of cells (per direction) of the study, coarse to fine.");
    prm.leave_subsection();

    prm.enter_subsection("Benchmark");
    prm.declare_entry("enabled", "false", Patterns::Bool(),
                      "Time the steps instead of running to the final time (also "
                      "granular_dg --benchmark CASE.prm): warm-up steps, then repetitions "
                      "of a block of steps; writes benchmark.json (CPU time per step, "
                      "DoF-stage updates per second per core, the phases of a step) and "
                      "no snapshots. doc/performance.md.");
    prm.declare_entry("repetitions", "5", Patterns::Integer(1),
                      "Number of timed blocks (min and median are reported).");
    prm.declare_entry("steps", "0", Patterns::Integer(0),
                      "Steps per block; 0: doubled from 1 until a block takes the "
                      "minimum time.");
    prm.declare_entry("minimum time", "0.3", Patterns::Double(0),
                      "CPU seconds a calibrated block lasts at least.");
    prm.declare_entry("warm-up steps", "2", Patterns::Integer(0),
                      "Untimed steps before the calibration.");
    prm.leave_subsection();
  }

  void
  CommonParameters::parse(ParameterHandler &prm)
  {
    prm.enter_subsection("Discretization");
    degree = prm.get_integer("degree");
    flux   = flux_names.parse("Discretization/numerical flux", prm.get("numerical flux"));
    engine = engine_names.parse("Discretization/engine", prm.get("engine"));
    prm.leave_subsection();

    prm.enter_subsection("Time stepping");
    final_time = prm.get_double("final time");
    cfl        = prm.get_double("CFL number");
    max_steps  = prm.get_integer("max steps");
    const bool check_stability_limit = prm.get_bool("check stability limit");
    prm.leave_subsection();
    require(final_time > 0, "Time stepping/final time", final_time, "must be > 0");
    // (a stability study, check stability limit = false, may go beyond 1)
    require(cfl > 0 && (cfl <= 1 || !check_stability_limit), "Time stepping/CFL number", cfl,
            "must be in (0, 1] (SSP-RK3 DG of degree p is stable up to about 1/(2p+1))");

    prm.enter_subsection("Limiter");
    limiter = limiter_names.parse("Limiter/scheme", prm.get("scheme"));
    tvb_M   = prm.get_double("TVB constant");
    prm.leave_subsection();

    prm.enter_subsection("Output");
    directory         = prm.get("directory");
    overwrite         = prm.get_bool("overwrite");
    const std::string output_times_text = prm.get("output times");
    output_times      = parse_doubles(output_times_text, "Output/output times");
    output_interval   = prm.get_double("output interval");
    profile_points    = prm.get_integer("profile points per cell");
    write_vtu         = prm.get_bool("write vtu");
    write_modes       = prm.get_bool("write modes");
    progress_interval = prm.get_double("progress interval");
    prm.leave_subsection();
    for (const double t : output_times)
      require(t > 0 && t <= final_time, "Output/output times", output_times_text,
              "times in (0, final time = " + format_number(final_time) + "]");

    prm.enter_subsection("Convergence");
    convergence = prm.get_bool("enabled");
    for (const auto &s : Utilities::split_string_list(prm.get("degrees")))
      convergence_degrees.push_back(Utilities::string_to_int(s));
    for (const auto &s : Utilities::split_string_list(prm.get("cells")))
      convergence_cells.push_back(Utilities::string_to_int(s));
    prm.leave_subsection();
    if (convergence)
      require(convergence_cells.size() >= 2 && !convergence_degrees.empty(),
              "Convergence/cells", convergence_cells.size(),
              "at least two mesh sizes and one degree for a study");
    // above the linear stability limit the run would blow up after a few
    // hundred steps (or, with a limiter, silently lose accuracy); a
    // convergence study needs it for every degree of the study, unless the
    // scene takes one CFL number per degree (Convergence/CFL numbers)
    if (check_stability_limit && !(convergence && convergence_has_own_cfl(prm)))
      for (const unsigned int p : convergence ? convergence_degrees :
                                                std::vector<unsigned int>{degree})
        require_stable_cfl(cfl, p, "Time stepping/CFL number");

    prm.enter_subsection("Benchmark");
    benchmark.enabled      = prm.get_bool("enabled");
    benchmark.repetitions  = prm.get_integer("repetitions");
    benchmark.steps        = prm.get_integer("steps");
    benchmark.min_time     = prm.get_double("minimum time");
    benchmark.warmup_steps = prm.get_integer("warm-up steps");
    prm.leave_subsection();
    require(!(benchmark.enabled && convergence), "Benchmark/enabled", "true",
            "false when Convergence/enabled is true");

    prm.enter_subsection("Checkpoint");
    checkpoint_steps   = prm.get_integer("every steps");
    checkpoint_seconds = prm.get_double("every seconds");
    resume             = prm.get_bool("resume");
    prm.leave_subsection();
    require(!(resume && overwrite), "Checkpoint/resume", "true",
            "false when Output/overwrite is true (resume continues the run in the "
            "directory, overwrite discards it)");
    require(!(resume && convergence), "Checkpoint/resume", "true",
            "false when Convergence/enabled is true (a study has no checkpoints)");
    require(!(resume && benchmark.enabled), "Checkpoint/resume", "true",
            "false in benchmark mode");

    std::ostringstream text;
    prm.print_parameters(text, ParameterHandler::ShortPRM);
    parameters_text = text.str();
    parameters      = flatten_parameters(parameters_text);
  }

  void
  begin_output(const CommonParameters &params)
  {
    std::string error;
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      {
        try
          {
            if (params.resume)
              check_resumable(params);
            else
              prepare_output_directory(params.directory, params.overwrite);
          }
        catch (const InputError &e)
          {
            error = e.what();
          }
        if (error.empty())
          {
            std::ofstream out(params.directory + "/parameters.prm");
            out << params.parameters_text;
          }
      }
    // the other ranks write into the directory only after it exists
    error = Utilities::MPI::broadcast(MPI_COMM_WORLD, error, 0);
    if (!error.empty())
      throw InputError(error);
  }

  void
  require_beyond_checkpoint(const CommonParameters &params, const Checkpoint &checkpoint,
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
  check_resumable(const CommonParameters &params)
  {
    const std::string &dir = params.directory;
    require(std::filesystem::is_directory(dir), "Checkpoint/resume", "true",
            "Output/directory = '" + dir + "' does not exist: there is no run to resume");
    std::ifstream in(dir + "/parameters.prm");
    require(static_cast<bool>(in), "Checkpoint/resume", "true",
            "Output/directory = '" + dir + "' holds no run (no parameters.prm)");
    require(has_checkpoints(dir, true), "Checkpoint/resume", "true",
            "the run in '" + dir + "' wrote no checkpoint (" +
              checkpoint_directory(dir) + " is empty or missing), it cannot be resumed");
    std::ostringstream before;
    before << in.rdbuf();
    require_same_parameters(flatten_parameters(before.str()), params.parameters,
                            "the run in '" + dir + "'");

    // a completed run has nothing to continue, unless the final time grows
    std::ifstream summary(dir + "/summary.json");
    std::ostringstream text;
    text << summary.rdbuf();
    const std::regex status(R"re("status": "completed")re"),
      final_time(R"re("final_time": ([-+0-9.eE]+))re");
    std::smatch match;
    const std::string json = text.str();
    if (std::regex_search(json, status) && std::regex_search(json, match, final_time) &&
        std::stod(match[1]) >= params.final_time * (1 - 1e-12))
      require(false, "Checkpoint/resume", "true",
              "the run in '" + dir + "' completed (final time " +
                std::string(match[1]) +
                "); nothing to resume (raise Time stepping/final time to continue it)");
  }

  void
  write_summary(const std::string &directory, const std::string &scene, const int dim,
                const unsigned int degree, const RunResult &r)
  {
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
      return;
    JsonObject s;
    s.add("scene", scene);
    s.add("dim", static_cast<long long>(dim));
    s.add("degree", degree);
    s.add("n_cells", static_cast<long long>(r.n_cells));
    s.add("n_dofs", static_cast<long long>(r.n_dofs));
    s.add("n_time_steps", static_cast<long long>(r.n_steps));
    s.add("final_time", r.final_time);
    s.add("wall_time_s", r.wall_time_s);
    s.add("time_loop_s", r.time_loop_s);
    s.add("time_loop_cpu_s", r.time_loop_cpu_s);
    s.add("dof_updates_per_s", r.dof_updates_per_s);
    s.add("dof_updates_per_cpu_s_per_rank", r.dof_updates_per_cpu_s_per_rank);
    s.add("n_mpi_ranks", static_cast<long long>(Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD)));
    s.add("status", r.status);
    if (r.resumed_from_step > 0)
      s.add("resumed_from_step", static_cast<long long>(r.resumed_from_step));
    if (!r.errors.empty())
      {
        JsonObject e;
        e.add("l2_all_components", r.l2_error);
        for (unsigned int c = 0; c < r.errors.size(); ++c)
          e.add("component_" + std::to_string(c) + "_l1_l2_linf",
                std::vector<double>(r.errors[c].begin(), r.errors[c].end()));
        s.add_object("errors", e);
      }
    s.add_object("diagnostics", r.diagnostics);
    s.write(directory + "/summary.json");
  }
} // namespace granular_dg
