#pragma once

#include <deal.II/base/function.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/tria.h>

#include <granular_dg/base/benchmark.h>
#include <granular_dg/base/checkpoint.h>
#include <granular_dg/base/output.h>
#include <granular_dg/dg/boundary.h>
#include <granular_dg/dg/dg_operator.h>
#include <granular_dg/dg/limiter.h>
#include <granular_dg/dg/modal_layout.h>
#include <granular_dg/dg/time_integrator.h>
#include <granular_dg/dg/numerical_flux.h>

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace granular_dg
{
  using namespace dealii;

  /// Parameters every scene shares: discretisation, time stepping, limiter,
  /// output, convergence study. Scenes add their own sections.
  struct CommonParameters
  {
    unsigned int      degree = 2;
    dg::NumericalFlux flux   = dg::NumericalFlux::local_lax_friedrichs;
    dg::Engine        engine = dg::Engine::automatic;

    double        final_time = 1.;
    double        cfl        = 0.2;
    /// stop (with a checkpoint) when the step counter reaches this (0: never)
    unsigned long max_steps  = 0;

    /// Checkpoint/: every so many steps and wall seconds (0: not), resume
    unsigned long checkpoint_steps   = 0;
    double        checkpoint_seconds = 0.;
    bool          resume             = false;
    /// the parameters of the run (parameters.prm, and what a checkpoint
    /// must match when resumed)
    std::string   parameters_text;
    ParameterList parameters;

    dg::LimiterType limiter = dg::LimiterType::none;
    double          tvb_M   = 0.;

    std::string         directory = "output";
    bool                overwrite = false;
    std::vector<double> output_times;
    double              output_interval    = 0.;
    unsigned int        profile_points     = 0;
    bool                write_modes        = false;
    bool                write_vtu          = true;
    double              progress_interval  = 5.;

    bool                      convergence = false;
    std::vector<unsigned int> convergence_degrees;
    std::vector<unsigned int> convergence_cells;

    BenchmarkParameters benchmark;

    /// Declare the shared sections; fluxes lists the numerical fluxes the
    /// scene's physics offers.
    static void
    declare(ParameterHandler &prm, const std::string &fluxes);
    void
    parse(ParameterHandler &prm);
  };

  /**
   * What a scene adds to the generic time loop of run_simulation(): implicit
   * stage operations, diagnostics and end-of-run analysis. Every method has
   * an empty default, so a scene overrides only what it needs.
   */
  template <int dim>
  class SceneHooks
  {
  public:
    virtual ~SceneHooks() = default;

    /// Set before initialize(): the run continues from a checkpoint, whose
    /// state load() brings (files the hooks append to must not be started
    /// anew in initialize()).
    void
    set_resuming(const bool r)
    {
      resuming_run = r;
    }
    bool
    resuming() const
    {
      return resuming_run;
    }

    /// Once the discretisation exists (the layout gives cell-wise access to
    /// the Legendre modes of the solution vector: local indices, to be used
    /// with local_element()).
    virtual void
    initialize(const DoFHandler<dim> &, const Mapping<dim> &, const dg::ModalLayout<dim> &)
    {}

    /// After every Runge-Kutta stage, before the limiter: implicit stage
    /// operations (e.g. a friction projection). weight is the effective time
    /// step of the explicit update in the stage (SSPRK3: dt, dt/4, 2dt/3).
    virtual void
    post_stage(dg::VectorType &, double /*stage_time*/, double /*weight*/)
    {}

    /// After the limiter of every stage (constraints the limiter must not
    /// break, e.g. v = 0 in cells the friction holds at rest).
    virtual void
    post_limiter(dg::VectorType &, double /*stage_time*/)
    {}

    /// After the operator's own check of every stage (finite, hyperbolic):
    /// what else the scene's model requires of the state (e.g. strain >= 0
    /// with the positivity option). A report that is not ok stops the run
    /// like the operator's.
    virtual dg::AdmissibilityReport
    check_admissibility(const dg::VectorType &) const
    {
      return {};
    }

    /// After every completed step (cheap per-step diagnostics).
    virtual void
    end_of_step(const dg::VectorType &, double /*t*/, double /*dt*/, unsigned long /*step*/)
    {}

    /// Extra columns of timeseries.csv, and their values at an output time.
    virtual std::vector<std::string>
    timeseries_names() const
    {
      return {};
    }
    virtual std::vector<double>
    timeseries_values(const dg::VectorType &, double /*t*/)
    {
      return {};
    }

    /// The scene's running state for a checkpoint (counters, histories, the
    /// sizes of the files it appends to), written with w.io(x) per member.
    /// Called on every MPI rank (it may be collective); rank 0's bytes are
    /// stored, so the state must not depend on the partition (sum counters
    /// over the ranks here).
    virtual void
    save(ByteWriter & /*w*/)
    {}

    /// Restore what save() wrote, on every rank (all get rank 0's bytes), at
    /// the start of a resumed run, after initialize(); reopen appended files
    /// cut to their checkpointed sizes.
    virtual void
    load(ByteReader & /*r*/)
    {}

    /// At the end of a run (also of a failed one, with the last good state):
    /// scene diagnostics for summary.json and, when write_files, extra files
    /// in directory.
    virtual void
    finish(const dg::VectorType &, double /*t*/, JsonObject & /*diagnostics*/,
           const std::string & /*directory*/, bool /*write_files*/)
    {}

  private:
    bool resuming_run = false;
  };

  /// What a scene hands to the solver: its physics, mesh, boundary and
  /// initial data and, where known, the exact solution (conserved variables).
  template <int dim, typename Physics>
  struct SceneData
  {
    std::string                          scene;
    Physics                              physics;
    std::shared_ptr<Triangulation<dim>>  triangulation;
    dg::BoundaryMap<dim>                 boundary;
    std::shared_ptr<Function<dim>>       initial;
    std::shared_ptr<Function<dim>>       exact;
    /// optional: stage operations and diagnostics of the scene
    std::shared_ptr<SceneHooks<dim>>     hooks;
    /// the time step uses max(lambda_max(U), this) as wave speed: for states
    /// at rest whose speed is 0 (sigma'(0) = 0), the speed the scene will reach
    double                               min_wave_speed = 0.;
    /// the name of the evolution variable in messages ("t"; the hopper: "tau")
    std::string                          time_name = "t";
    /// where the run starts: time and, optionally, the state itself (a vector
    /// of the same discretisation, e.g. the final state of an earlier run,
    /// RunResult::final_solution); without it the initial Function is projected
    double                                 start_time = 0.;
    std::shared_ptr<const dg::VectorType>  initial_vector;
  };

  /// The outcome of one run, for summary.json and the convergence table.
  struct RunResult
  {
    std::string                      status = "completed";
    unsigned long                    n_steps = 0;
    double                           final_time = 0;
    double                           wall_time_s = 0;
    double                           time_loop_s = 0;     ///< wall time of the steps
    double                           time_loop_cpu_s = 0; ///< CPU time of the steps (rank 0)
    double                           dof_updates_per_cpu_s_per_rank = 0;
    double                           dof_updates_per_s = 0;
    unsigned long                    n_dofs = 0, n_cells = 0;
    double                           h_min = 0;
    /// per component (L1, L2, Linf) against the exact solution, if any
    std::vector<std::array<double, 3>> errors;
    double                           l2_error = -1; ///< all components
    double                           l1_error = -1; ///< sum over the components
    /// the step a resumed run started from (0: not resumed)
    unsigned long                    resumed_from_step = 0;
    /// the state at the end (the last good one of a failed run)
    std::shared_ptr<dg::VectorType>  final_solution;
    JsonObject                       diagnostics;
  };

  /// Run one scene: time loop, output, diagnostics. When write_files is
  /// false (convergence studies) nothing is written. dt_factor scales the
  /// CFL time step.
  template <int dim, typename Physics>
  RunResult
  run_simulation(const SceneData<dim, Physics> &scene,
                 const CommonParameters        &params,
                 unsigned int                   degree,
                 bool                           write_files,
                 double                         dt_factor = 1.);

  /// The convergence study of Convergence/degrees x Convergence/cells: one run
  /// per pair (the scene factory builds the mesh with the given number of
  /// cells), errors against the exact solution, EOC, written to
  /// convergence.csv and convergence-rates.csv. For degree p the time step
  /// is scaled with (h/h_0)^(max(1,(p+1)/3) - 1) so that SSP-RK3's O(dt^3)
  /// error stays below the spatial O(h^(p+1)) one.
  template <int dim, typename Physics>
  void
  run_convergence_study(
    const std::function<SceneData<dim, Physics>(unsigned int)> &make_scene,
    const CommonParameters                                     &params);

  /// The linear stability limit of the CFL number of SSP-RK3 with upwind DG
  /// of degree p (1D Fourier analysis): 1.2563, 0.4095, 0.2097, 0.13, 0.0896.
  double
  ssprk3_cfl_limit(unsigned int degree);

  /// An InputError naming parameter unless cfl <= ssprk3_cfl_limit(degree).
  void
  require_stable_cfl(double cfl, unsigned int degree, const std::string &parameter);

  /// Create (or, with Output/overwrite, clear) the output directory and write
  /// parameters.prm, the parameters actually used. Call after all input has
  /// been validated, so that bad input leaves nothing behind. With
  /// Checkpoint/resume: check_resumable() instead of creating.
  void
  begin_output(const CommonParameters &params);

  /// An InputError unless Output/directory holds a run that wrote a
  /// checkpoint and had the same parameters (but those a resume may change).
  void
  check_resumable(const CommonParameters &params);

  /// An InputError unless the final time and max steps lie beyond the
  /// checkpoint a run resumes from.
  void
  require_beyond_checkpoint(const CommonParameters &params, const Checkpoint &checkpoint,
                            const std::string &time_name);

  /// Write summary.json of a run.
  void
  write_summary(const std::string &directory, const std::string &scene, int dim,
                unsigned int degree, const RunResult &result);
} // namespace granular_dg
