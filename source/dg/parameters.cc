#include <granular_dg/base/errors.h>
#include <granular_dg/base/output.h>
#include <granular_dg/base/parameter_binding.h>
#include <granular_dg/base/parameters.h>
#include <granular_dg/dg/parameters.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace granular_dg::dg
{
  namespace
  {
    const EnumNames<Engine> engine_names({{Engine::automatic, "auto"},
                                          {Engine::matrix_free, "matrix_free"},
                                          {Engine::line, "line"}});

    const EnumNames<TimeScheme> time_scheme_names({{TimeScheme::ssp_rk3, "ssp_rk3"},
                                                   {TimeScheme::lsrk_3_3, "lsrk_3_3"},
                                                   {TimeScheme::lsrk_5_4, "lsrk_5_4"},
                                                   {TimeScheme::lsrk_7_4, "lsrk_7_4"},
                                                   {TimeScheme::lsrk_9_5, "lsrk_9_5"}});

    std::string
    limiter_selection(const std::string &physics_variables)
    {
      return "none|componentwise|characteristic" +
             (physics_variables.empty() ? "" : "|" + physics_variables);
    }
  } // namespace

  double
  snapshot_bytes(const double n_cells, const unsigned int degree, const int dim,
                 const unsigned int n_fields, const bool vtu)
  {
    // VTU: Float32 values at (p+1)^dim points per cell, the points and the
    // connectivity; CSV: about 16 characters a number
    const double points = n_cells * std::pow(std::max(2u, degree + 1), dim);
    return (vtu ? points * (4. * n_fields + 12. + 8.) : 0.) +
           (dim == 1 ? points * 16. * (n_fields + 1) : 0.);
  }

  namespace
  {
    /// Peak bytes per DoF of a DG run, measured on the 2D strip at 2000 x 200
    /// cells, P2 (10.8 M DoFs, one rank): 95 without snapshots, 185 writing
    /// VTU, 230 writing HDF5 (doc/program.md, "Memory"). The estimate is the
    /// solver's 134 (its 95 and a margin for other meshes, ranks and
    /// checkpoints) and what a snapshot adds at its peak (DataOut's patches
    /// and the file's buffers).
    constexpr double bytes_per_dof               = 134.;
    constexpr double vtu_snapshot_bytes_per_dof  = 90.;
    constexpr double hdf5_snapshot_bytes_per_dof = 136.;
  } // namespace

  void
  require_memory_fits(const RunParameters &run, const double n_cells, const unsigned int degree,
                      const int dim, const unsigned int n_components, const std::string &parameter,
                      const std::string &value, const std::string &change)
  {
    const bool   snapshots = run.write_vtu && !run.convergence && !run.benchmark.enabled;
    const double per_dof =
      bytes_per_dof +
      (snapshots ? (run.hdf5 ? hdf5_snapshot_bytes_per_dof : vtu_snapshot_bytes_per_dof) : 0.);
    const double n_dofs    = n_cells * std::pow(degree + 1., dim) * n_components;
    const double ranks     = Utilities::MPI::job_supports_mpi() ?
                               Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) :
                               1.;
    const double needed    = n_dofs * per_dof / ranks;
    const double available = available_memory_per_rank();
    require(available <= 0. || needed <= available, parameter, value,
            "the run needs about " + format_bytes(needed) + " per MPI rank (" +
              format_number(n_dofs) + " DoFs at ~" + format_number(per_dof) + " bytes each" +
              (snapshots ? std::string(", writing ") + (run.hdf5 ? "HDF5" : "VTU") +
                             " snapshots included" :
                           std::string()) +
              "), more than the " + format_bytes(available) + " available (MemAvailable): " +
              change + (snapshots ? ", or write no snapshots (Output/write vtu = false)" : ""));
  }

  std::string
  time_scheme_name(const TimeScheme scheme)
  {
    return time_scheme_names.name(scheme);
  }

  double
  cfl_limit(const TimeScheme scheme, const unsigned int degree)
  {
    // max nu = a dt/h with |R(nu z)| <= 1 for every eigenvalue z of the
    // upwind DG operator of u_t + u_x = 0 (Fourier analysis; R the scheme's
    // stability function), rounded down; tests/unit/rk_stability_limits
    // computes them from the integrators and checks this table
    static const double limit[][5] = {
      {1.2563, 0.4095, 0.2097, 0.1300, 0.0896},  // ssp_rk3
      {1.2563, 0.4095, 0.2097, 0.1300, 0.0896},  // lsrk_3_3 (the same R(z))
      {2.2294, 0.6754, 0.3505, 0.2193, 0.1519},  // lsrk_5_4
      {2.5081, 0.8360, 0.4235, 0.2618, 0.1801},  // lsrk_7_4
      {2.6026, 0.8332, 0.4270, 0.2649, 0.1827}}; // lsrk_9_5
    return limit[static_cast<unsigned int>(scheme)][std::min(degree, 4u)];
  }

  void
  require_stable_cfl(const double cfl, const TimeScheme scheme, const unsigned int degree,
                     const std::string &parameter)
  {
    const double limit = cfl_limit(scheme, degree);
    std::string  table;
    for (unsigned int p = 0; p <= 4; ++p)
      table += (p ? ", " : "") + format_number(cfl_limit(scheme, p));
    require(cfl <= limit, parameter, cfl,
            "at most " + format_number(limit) + " at degree " + std::to_string(degree) +
              " (the linear stability limit of " +
              (scheme == TimeScheme::ssp_rk3 ? std::string("SSP-RK3") : time_scheme_name(scheme)) +
              " with DG of degree p = 0..4: " + table + ")");
  }

  namespace
  {
    const EnumNames<TroubleIndicator> indicator_names(
      {{TroubleIndicator::everywhere, "everywhere"},
       {TroubleIndicator::modal_energy, "modal_energy"},
       {TroubleIndicator::kxrcf, "kxrcf"},
       {TroubleIndicator::modal_energy_neighbours, "modal_energy_neighbours"}});

    EnumNames<LimiterType>
    limiter_names(const std::string &physics_variables)
    {
      return EnumNames<LimiterType>(
        {{LimiterType::none, "none"},
         {LimiterType::componentwise, "componentwise"},
         {LimiterType::characteristic, "characteristic"},
         {LimiterType::physics_variables,
          physics_variables.empty() ? std::string("(none)") : physics_variables}});
    }

    /// a warning, not a refusal: --set Limiter/indicator=everywhere on a case
    /// that sets a threshold is how the limiter in every cell is compared
    void
    warn_unused_threshold(const double threshold)
    {
      static bool warned = false;
      if (warned || (Utilities::MPI::job_supports_mpi() &&
                     Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0))
        return;
      std::cerr << "granular_dg: warning: Limiter/indicator threshold = "
                << format_number(threshold)
                << " has no effect with Limiter/indicator = everywhere (every cell is "
                   "examined; a threshold selects the cells an indicator flags)"
                << std::endl;
      warned = true;
    }
  } // namespace

  void
  DiscretizationParameters::declare(ParameterHandler &prm, const std::string &fluxes,
                                    const std::string &physics_variables)
  {
    ParameterBinding         b(prm, ParameterBinding::Mode::declare);
    DiscretizationParameters defaults;
    defaults.bind(b, RunParameters(), fluxes, physics_variables);
  }

  void
  DiscretizationParameters::parse(ParameterHandler &prm, const RunParameters &run,
                                  const std::string &physics_variables)
  {
    ParameterBinding b(prm, ParameterBinding::Mode::read);
    bind(b, run, "", physics_variables);
  }

  void
  DiscretizationParameters::bind(ParameterBinding &b, const RunParameters &run,
                                 const std::string &fluxes, const std::string &physics_variables)
  {
    b.section("Discretization");
    b.add("degree", degree, Patterns::Integer(0, 4),
          "Polynomial degree of the FE_DGQLegendre space (0 = finite volumes). Allowed: 0 to 4.");
    b.add("numerical flux", flux, Patterns::Selection(fluxes),
          "Numerical flux on faces: local_lax_friedrichs (Rusanov) or one the physics offers "
          "(doc/ of the scene). Allowed: " + fluxes + ".");
    b.add("engine", engine, engine_names,
          "The operator: matrix_free (deal.II MatrixFree cell/face kernels, any dimension, "
          "MPI) or line (a lean 1D kernel of the same discretisation, serial, several times "
          "faster in 1D); auto: line for serial 1D runs, matrix_free otherwise.");
    bind_time_stepping(b, run);
    bind_limiter(b, run, physics_variables);

    b.section("Output");
    b.add("profile points per cell", profile_points, Patterns::Integer(0, 20),
          "Sample points per cell in the 1D profile-NNNN.csv, equally spaced with both end "
          "points (1: the cell centre; 0: degree+1, at least 2).");
    b.add("write modes", write_modes, Patterns::Bool(),
          "1D: also write modes-NNNN.csv, the Legendre coefficients of every cell (x_left, h, "
          "then per component the modes 0..p): the exact discrete solution, usable as a "
          "reference solution of another run (Exact solution/reference file of the scenes "
          "that offer it).");
  }

  void
  DiscretizationParameters::bind_time_stepping(ParameterBinding &b, const RunParameters &run)
  {
    b.section("Time stepping");
    b.add("scheme", scheme, time_scheme_names,
          "Explicit Runge-Kutta scheme: ssp_rk3 (Shu-Osher, 3 stages, order 3; the only one "
          "with limiters and stage operations) or deal.II's low-storage schemes lsrk_S_O (S "
          "stages, order O), more stable per stage, for unlimited runs. Allowed: " +
            time_scheme_names.selection() + ".");
    b.add("check stability limit", check_stability_limit, Patterns::Bool(),
          "Refuse a CFL number above the scheme's linear stability limit for the degree "
          "(SSP-RK3: 1.256, 0.4095, 0.2097, 0.13, 0.0896 for p = 0-4). false: run anyway, for "
          "stability studies of where the method fails.");
    // (a stability study, check stability limit = false, may go beyond 1;
    // SSP-RK3: at most 1, also for the network's forward Euler at degree 0)
    const double largest = scheme == TimeScheme::ssp_rk3 ? 1. : std::max(1., cfl_limit(scheme, 0));
    b.add("CFL number", cfl, Patterns::Double(),
          "Courant number dt * sum_d(lambda_max / h_d). SSP-RK3 with DG of degree p is stable "
          "up to about 1/(2p+1). Allowed: (0, 1].")
      .check([&](const double c) { return c > 0 && (c <= largest || !check_stability_limit); },
             scheme == TimeScheme::ssp_rk3 ?
               "must be in (0, 1] (SSP-RK3 DG of degree p is stable up to about 1/(2p+1))" :
               "must be in (0, " + format_number(largest) + "] (the stability limits of " +
                 time_scheme_name(scheme) + " are in doc/program.md)");
    // above the linear stability limit the run would blow up after a few
    // hundred steps (or, with a limiter, silently lose accuracy); a
    // convergence study needs it for every degree of the study
    if (b.reading() && check_stability_limit && !run.convergence)
      require_stable_cfl(cfl, scheme, degree, "Time stepping/CFL number");
    if (b.reading() && check_stability_limit && run.convergence)
      for (unsigned int i = 0; i < run.convergence_degrees.size(); ++i)
        require_stable_cfl(for_study(run, i).cfl, scheme, run.convergence_degrees[i],
                           run.convergence_cfl.empty() ? "Time stepping/CFL number" :
                                                         "Convergence/CFL numbers");
    b.add("skip tolerance", skip_tolerance, Patterns::Double(0),
          "Skip the cells that cannot change: after a step, a cell whose values all moved by "
          "at most this times the largest |value| of their component so far is quiet, and the "
          "next step (of the same size) computes only the cells within reach of a cell that "
          "was not; when all are quiet, the run is at rest and steps of that size are not "
          "computed (steps of another size, such as those that land on output times, are). "
          "The results differ from the full computation by about 10 times this, of each "
          "component's largest value (doc/engine.md). For scenes whose operator does not "
          "depend on time, 1D, line engine, ssp_rk3. 0: compute every cell. Allowed: [0, "
          "1e-14].")
      .check([](const double t) { return t <= max_skip_tolerance; },
             "must be in [0, " + format_number(max_skip_tolerance) +
               "]: a larger tolerance takes slowly moving cells for quiet ones, and the "
               "results no longer agree with the full computation to 1e-12 (doc/engine.md, "
               "\"Skipping quiet cells\")");
    b.add("skip cells at rest", skip_at_rest, Patterns::Bool(),
          "2D engine: leave out the cells at the physics' rest state and out of a step's "
          "reach of the others, and the faces between them (doc/engine.md, \"Cells at "
          "rest\"). Cells on a boundary with data are always computed. For physics with a "
          "rest state (nonlinear elasticity), without subcell blending.");
    // a cell left out is within the tolerance of rest (no drift adds up)
    b.add("rest tolerance", rest_tolerance, Patterns::Double(0),
          "With skip cells at rest: a cell is at rest when every Legendre coefficient of each "
          "component i is at most this times the largest |coefficient| of i in the domain "
          "now. The results agree with the full computation to about this, of each "
          "component's largest value; bit for bit at 0 (exactly at rest). Allowed: [0, "
          "1e-10].")
      .check([](const double t) { return t <= 1e-10; },
             "must be in [0, 1e-10]: the results agree with the full computation to about the "
             "tolerance (doc/engine.md, \"Cells at rest\")");
  }

  void
  DiscretizationParameters::bind_limiter(ParameterBinding &b, const RunParameters &run,
                                         const std::string &physics_variables)
  {
    const auto limiters = limiter_names(physics_variables);
    b.section("Limiter");
    b.add("scheme", limiter_name, Patterns::Selection(limiter_selection(physics_variables)),
          "TVB minmod limiter on the Legendre modes after every stage: none, componentwise "
          "(conserved variables), characteristic (eigenvectors of the flux Jacobian at the "
          "cell average)" +
            (physics_variables.empty() ?
               std::string(".") :
               " or " + physics_variables +
                 " (variables the physics names, continuous across material interfaces)."));
    if (b.reading())
      limiter = limiters.parse("Limiter/scheme", limiter_name);
    if (b.reading())
      require(scheme == TimeScheme::ssp_rk3 || limiter == LimiterType::none,
              "Time stepping/scheme", time_scheme_name(scheme),
              "ssp_rk3 only with Limiter/scheme = " + limiter_name +
                " (a limiter needs a scheme of convex combinations of Euler steps; the lsrk "
                "schemes run without limiter)");
    b.add("TVB constant", tvb_M, Patterns::Double(0),
          "M of the TVB minmod: slopes with |slope| <= M h^2 are not limited (0 = TVD "
          "minmod).");
    b.add("indicator", indicator, indicator_names,
          "Which cells the limiter examines: everywhere (every cell), modal_energy (only the "
          "cells whose indicator variable, named by the physics, has too much energy in its "
          "highest Legendre modes: the indicator of Hennemann et al. 2021), kxrcf (only the "
          "cells with large jumps of the indicator variable across their faces: Krivodonova "
          "et al. 2004), or modal_energy_neighbours (the cells modal_energy flags and their "
          "face neighbours: a shock flagged at its foot is limited above it too); "
          "doc/engine.md.");
    const bool share = indicator == TroubleIndicator::modal_energy ||
                       indicator == TroubleIndicator::modal_energy_neighbours;
    b.add("indicator threshold", indicator_threshold, Patterns::Double(0),
          "modal_energy(_neighbours): the share of the energy in the highest modes above "
          "which a cell is flagged, in (0, 1); kxrcf: the bound on the normalised face jumps; "
          "0: automatic (0.5 10^(-1.8 (p+1)^(1/4)) for degree p, 1 for kxrcf).")
      .check([&](const double t) { return !share || t < 1; },
             "must be in [0, 1) with indicator = modal_energy or modal_energy_neighbours (a "
             "share of the energy; 0 = automatic)");
    if (b.reading() && indicator == TroubleIndicator::everywhere && indicator_threshold != 0)
      warn_unused_threshold(indicator_threshold);
    b.add("subcell blending", subcell_blending, Patterns::Bool(),
          "Blend the DG update of every stage with a first-order finite-volume update on the "
          "(p + 1)^dim subcells of each cell, by a factor alpha from the modal energy of the "
          "indicator variable (Hennemann et al. 2021; 0 in smooth cells); conservative. "
          "Independent of Limiter/scheme (both may act). Line engine (serial 1D runs and the "
          "edges of networks) and the 2D engine (Cartesian meshes); doc/engine.md.")
      .check([&](const bool on) { return !on || degree > 0 || run.convergence; },
             "false at Discretization/degree = 0 (a cell of degree 0 is its own only subcell: "
             "blending would change nothing)");
    b.add("blending maximum", blending_maximum, Patterns::Double(0, 1),
          "The largest blending factor alpha_max, in (0, 1] (1: pure finite volumes in the "
          "cells the indicator flags most).")
      .check([&](const double a) { return !subcell_blending || a > 0; },
             "must be in (0, 1] with subcell blending = true");
  }

  double
  DiscretizationParameters::time_step(const double       max_speed_over_h,
                                      const std::string &time_name, const double t) const
  {
    const double dt = cfl / max_speed_over_h;
    if (!(std::isfinite(dt) && dt > 0))
      throw RunError("time step is " + format_number(dt) + " at " + time_name + " = " +
                     format_number(t) + " (max wave speed/h = " +
                     format_number(max_speed_over_h) + ")");
    return dt;
  }

  DiscretizationParameters
  DiscretizationParameters::for_study(const RunParameters &run, const unsigned int i) const
  {
    DiscretizationParameters m = *this;
    m.degree                   = run.convergence_degrees[i];
    if (!run.convergence_cfl.empty())
      m.cfl = run.convergence_cfl[i];
    return m;
  }
} // namespace granular_dg::dg
