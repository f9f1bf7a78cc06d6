#pragma once

#include <deal.II/base/parameter_handler.h>

#include <granular_dg/base/parameter_binding.h>
#include <granular_dg/base/run_parameters.h>
#include <granular_dg/dg/limiter.h>
#include <granular_dg/dg/operator.h>

#include <string>

namespace granular_dg::dg
{
  using namespace dealii;

  /**
   * The DG method of a run: degree, numerical flux (by the name the physics
   * gives it), engine, CFL number, limiter, and the 1D output of the modal
   * field (subsections Discretization, Time stepping, Limiter, Output).
   * What the physics offers comes in as names: its numerical fluxes
   * ("local_lax_friedrichs|impedance") and, if it has limiting variables of
   * its own, their name in Limiter/scheme ("flux_variables").
   */
  struct DiscretizationParameters
  {
    unsigned int degree = 2;
    std::string  flux   = "local_lax_friedrichs";
    Engine       engine = Engine::automatic;
    double       cfl    = 0.2;
    TimeScheme   scheme = TimeScheme::ssp_rk3;
    bool         check_stability_limit = true;
    /// Time stepping/skip tolerance (ActiveCells); 0: compute every cell
    double       skip_tolerance        = 0.;
    /// the largest skip tolerance allowed: up to it the results agree with
    /// the full computation to 1e-12 of each component's largest value
    /// (doc/engine.md, "Skipping quiet cells")
    static constexpr double max_skip_tolerance = 1e-14;
    /// Time stepping/skip cells at rest (CellsAtRest: the 2D engine leaves
    /// out the cells at the physics' rest state, within rest_tolerance)
    bool         skip_at_rest   = false;
    double       rest_tolerance = 0.;
    LimiterType  limiter      = LimiterType::none;
    std::string  limiter_name = "none";
    double       tvb_M        = 0.;
    /// which cells the limiter examines, and the indicator's threshold
    /// (0: the automatic one of the degree)
    TroubleIndicator indicator           = TroubleIndicator::everywhere;
    double           indicator_threshold = 0.;
    /// Limiter/subcell blending and Limiter/blending maximum
    bool             subcell_blending    = false;
    double           blending_maximum    = 0.5;
    /// the largest blending factor of subcell blending (0: off)
    double
    blending_max() const
    {
      return subcell_blending ? blending_maximum : 0.;
    }
    unsigned int profile_points = 0;
    bool         write_modes    = false;

    /// Every entry of the method, declared once (bind()).
    static void
    declare(ParameterHandler &prm, const std::string &fluxes,
            const std::string &physics_variables = "");

    /// Read and check every entry (bind(); the CFL number against the
    /// stability limit of every degree the run or its convergence study uses).
    void
    parse(ParameterHandler &prm, const RunParameters &run,
          const std::string &physics_variables = "");

    /// The entries, each with its field, pattern, documentation and checks
    /// (ParameterBinding): sections Discretization, Time stepping, Limiter
    /// and Output.
    void
    bind(ParameterBinding &b, const RunParameters &run, const std::string &fluxes,
         const std::string &physics_variables);

    /// The method of the i-th degree of a convergence study (its CFL number).
    DiscretizationParameters
    for_study(const RunParameters &run, unsigned int i) const;

    /// The time step CFL number / max_speed_over_h (the largest wave speed
    /// over the cell size); a RunError at (time_name =) t if it is not a
    /// positive finite number.
    double
    time_step(double max_speed_over_h, const std::string &time_name, double t) const;

  private:
    void
    bind_time_stepping(ParameterBinding &b, const RunParameters &run);
    void
    bind_limiter(ParameterBinding &b, const RunParameters &run,
                 const std::string &physics_variables);
  };

  /// The size of one snapshot of a DG field (the VTU and, in 1D, the CSV
  /// profile) of n_cells cells of degree p with n_fields values per point:
  /// what the refusal of snapshot counts that cannot be meant quotes.
  double
  snapshot_bytes(double n_cells, unsigned int degree, int dim, unsigned int n_fields,
                 bool vtu);

  /// An InputError naming parameter (= value) when a mesh of n_cells cells
  /// of degree p with n_components unknowns needs more memory than this MPI
  /// rank has (available_memory_per_rank()), writing snapshots (Output/write
  /// vtu, Output/format of run) included: refused before anything is
  /// allocated; change says what to change. The bytes per DoF are measured
  /// (doc/program.md, "Memory").
  void
  require_memory_fits(const RunParameters &run, double n_cells, unsigned int degree, int dim,
                      unsigned int n_components, const std::string &parameter,
                      const std::string &value, const std::string &change);

  /// The name of a scheme in Time stepping/scheme.
  std::string
  time_scheme_name(TimeScheme scheme);

  /// The linear stability limit of the CFL number of a Runge-Kutta scheme
  /// with upwind DG of degree p (1D Fourier analysis, rounded down;
  /// tests/unit/rk_stability_limits computes them), e.g. SSP-RK3: 1.2563,
  /// 0.4095, 0.2097, 0.13, 0.0896.
  double
  cfl_limit(TimeScheme scheme, unsigned int degree);

  /// An InputError naming parameter unless cfl <= cfl_limit(scheme, degree).
  void
  require_stable_cfl(double cfl, TimeScheme scheme, unsigned int degree,
                     const std::string &parameter);
} // namespace granular_dg::dg
