#pragma once

#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/tria.h>

#include <granular_dg/base/checkpoint.h>
#include <granular_dg/base/output.h>
#include <granular_dg/dg/active_cells.h>
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

    /// Set before initialize() when the run skips quiet cells (ActiveCells;
    /// null otherwise): post_stage() and post_limiter() then work on the
    /// cells of active_cells()->ranges() only, and end_of_step() may look at
    /// those only, since no other cell changed. At rest, end_of_step() also
    /// follows the steps that are counted but not computed (no cell in
    /// ranges()), so that per-step diagnostics see every step.
    void
    set_active_cells(const ActiveCells *cells)
    {
      active = cells;
    }
    const ActiveCells *
    active_cells() const
    {
      return active;
    }

    /// Whether post_stage() and post_limiter() honour active_cells() and act
    /// on each cell alone (a friction projection does; a stage operation
    /// that couples cells cannot). A run skips quiet cells only when every
    /// hook with a stage_operation() says so.
    virtual bool
    honours_active_cells() const
    {
      return false;
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

    /// The name of what post_stage() or post_limiter() do to a stage value
    /// ("" if nothing): such operations need SSP-RK3's stages (convex
    /// combinations of Euler steps), so Solver refuses the low-storage
    /// schemes with them, naming this.
    virtual std::string
    stage_operation() const
    {
      return "";
    }

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
    bool               resuming_run = false;
    const ActiveCells *active       = nullptr;
  };

  /// The hooks of a scene called one after the other (the first failing
  /// admissibility report wins; save/load in order).
  template <int dim>
  class HookList : public SceneHooks<dim>
  {
  public:
    explicit HookList(std::vector<std::shared_ptr<SceneHooks<dim>>> list)
      : list(std::move(list))
    {}

    void
    set_all_resuming(const bool r)
    {
      this->set_resuming(r);
      for (auto &h : list)
        h->set_resuming(r);
    }
    void
    set_all_active_cells(const ActiveCells *cells)
    {
      this->set_active_cells(cells);
      for (auto &h : list)
        h->set_active_cells(cells);
    }
    /// the stage operation of a hook that does not honour active cells ("": none)
    std::string
    stage_operation_on_all_cells() const
    {
      for (const auto &h : list)
        if (const auto name = h->stage_operation(); !name.empty() && !h->honours_active_cells())
          return name;
      return "";
    }
    void
    initialize(const DoFHandler<dim> &d, const Mapping<dim> &m,
               const ModalLayout<dim> &l) override
    {
      for (auto &h : list)
        h->initialize(d, m, l);
    }
    void
    post_stage(VectorType &u, const double t, const double w) override
    {
      for (auto &h : list)
        h->post_stage(u, t, w);
    }
    void
    post_limiter(VectorType &u, const double t) override
    {
      for (auto &h : list)
        h->post_limiter(u, t);
    }
    std::string
    stage_operation() const override
    {
      for (const auto &h : list)
        if (const auto name = h->stage_operation(); !name.empty())
          return name;
      return "";
    }
    AdmissibilityReport
    check_admissibility(const VectorType &u) const override
    {
      for (const auto &h : list)
        if (auto r = h->check_admissibility(u); !r.ok)
          return r;
      return {};
    }
    void
    end_of_step(const VectorType &u, const double t, const double dt,
                const unsigned long step) override
    {
      for (auto &h : list)
        h->end_of_step(u, t, dt, step);
    }
    std::vector<std::string>
    timeseries_names() const override
    {
      std::vector<std::string> names;
      for (const auto &h : list)
        for (const auto &n : h->timeseries_names())
          names.push_back(n);
      return names;
    }
    std::vector<double>
    timeseries_values(const VectorType &u, const double t) override
    {
      std::vector<double> values;
      for (auto &h : list)
        for (const double v : h->timeseries_values(u, t))
          values.push_back(v);
      return values;
    }
    void
    save(ByteWriter &w) override
    {
      for (auto &h : list)
        h->save(w);
    }
    void
    load(ByteReader &r) override
    {
      for (auto &h : list)
        h->load(r);
    }
    void
    finish(const VectorType &u, const double t, JsonObject &diagnostics,
           const std::string &directory, const bool write_files) override
    {
      for (auto &h : list)
        h->finish(u, t, diagnostics, directory, write_files);
    }

  private:
    std::vector<std::shared_ptr<SceneHooks<dim>>> list;
  };

  /// What a scene hands to the solver: its physics (with its numerical flux),
  /// mesh, boundary and initial data and, where known, the exact solution
  /// (conserved variables).
  template <int dim, typename Physics>
  struct SceneData
  {
    // (every member but the physics has a default: a scene names what it sets)
    std::string                         scene = {};
    Physics                             physics;
    std::shared_ptr<Triangulation<dim>> triangulation = {};
    BoundaryMap<dim>                    boundary      = {};
    std::shared_ptr<Function<dim>>      initial       = {};
    std::shared_ptr<Function<dim>>      exact         = {};
    /// the scene's stage operations and diagnostics, called in this order
    /// (e.g. a friction projection, then the diagnostics that read it)
    std::vector<std::shared_ptr<SceneHooks<dim>>> hooks = {};
    /// the time step uses max(lambda_max(U), this) as wave speed: for states
    /// at rest whose speed is 0 (sigma'(0) = 0), the speed the scene will reach
    double                              min_wave_speed = 0.;
    /// whether the operator, its boundary data and sources and the hooks'
    /// stage operations are the same at every time (a run may then skip
    /// quiet cells: Time stepping/skip tolerance)
    bool                                autonomous = false;
    /// the name of the evolution variable in messages ("t"; the hopper: "tau")
    std::string                         time_name = "t";
    /// where the run starts: time and, optionally, the state itself (a vector
    /// of the same discretisation, e.g. the final state of an earlier run);
    /// without it the initial Function is projected
    double                              start_time = 0.;
    std::shared_ptr<const VectorType>   initial_vector = {};
  };
} // namespace granular_dg::dg
