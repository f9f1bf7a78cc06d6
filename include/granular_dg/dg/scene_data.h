#pragma once

#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/tria.h>

#include <granular_dg/base/checkpoint.h>
#include <granular_dg/base/output.h>
#include <granular_dg/dg/boundary.h>
#include <granular_dg/dg/modal_layout.h>
#include <granular_dg/dg/operator.h>

#include <memory>
#include <string>
#include <vector>

namespace granular_dg::dg
{
  using namespace dealii;

  /**
   * What a scene adds to the DG solver's steps: implicit stage operations,
   * diagnostics and end-of-run analysis. Every method has an empty default,
   * so a scene overrides only what it needs (doc/engine.md has the table).
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
    initialize(const DoFHandler<dim> &, const Mapping<dim> &, const ModalLayout<dim> &)
    {}

    /// After every Runge-Kutta stage, before the limiter: implicit stage
    /// operations (e.g. a friction projection). weight is the effective time
    /// step of the explicit update in the stage (SSPRK3: dt, dt/4, 2dt/3).
    virtual void
    post_stage(VectorType &, double /*stage_time*/, double /*weight*/)
    {}

    /// After the limiter of every stage (constraints the limiter must not
    /// break, e.g. v = 0 in cells the friction holds at rest).
    virtual void
    post_limiter(VectorType &, double /*stage_time*/)
    {}

    /// After the operator's own check of every stage (finite, hyperbolic):
    /// what else the scene's model requires of the state. A report that is
    /// not ok stops the run like the operator's.
    virtual AdmissibilityReport
    check_admissibility(const VectorType &) const
    {
      return {};
    }

    /// After every completed step (cheap per-step diagnostics).
    virtual void
    end_of_step(const VectorType &, double /*t*/, double /*dt*/, unsigned long /*step*/)
    {}

    /// Extra columns of timeseries.csv, and their values at an output time.
    virtual std::vector<std::string>
    timeseries_names() const
    {
      return {};
    }
    virtual std::vector<double>
    timeseries_values(const VectorType &, double /*t*/)
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
    finish(const VectorType &, double /*t*/, JsonObject & /*diagnostics*/,
           const std::string & /*directory*/, bool /*write_files*/)
    {}

  private:
    bool resuming_run = false;
  };

  /// What a scene hands to the solver: its physics (with its numerical flux),
  /// mesh, boundary and initial data and, where known, the exact solution
  /// (conserved variables).
  template <int dim, typename Physics>
  struct SceneData
  {
    std::string                         scene;
    Physics                             physics;
    std::shared_ptr<Triangulation<dim>> triangulation;
    BoundaryMap<dim>                    boundary;
    std::shared_ptr<Function<dim>>      initial;
    std::shared_ptr<Function<dim>>      exact;
    /// optional: stage operations and diagnostics of the scene
    std::shared_ptr<SceneHooks<dim>>    hooks;
    /// the time step uses max(lambda_max(U), this) as wave speed: for states
    /// at rest whose speed is 0 (sigma'(0) = 0), the speed the scene will reach
    double                              min_wave_speed = 0.;
    /// the name of the evolution variable in messages ("t"; the hopper: "tau")
    std::string                         time_name = "t";
    /// where the run starts: time and, optionally, the state itself (a vector
    /// of the same discretisation, e.g. the final state of an earlier run);
    /// without it the initial Function is projected
    double                              start_time = 0.;
    std::shared_ptr<const VectorType>   initial_vector;
  };
} // namespace granular_dg::dg
