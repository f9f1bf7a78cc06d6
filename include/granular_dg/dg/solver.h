#pragma once

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/numerics/data_out.h>

#include <granular_dg/base/evolution.h>
#include <granular_dg/base/run_parameters.h>
#include <granular_dg/dg/cell_quadrature.h>
#include <granular_dg/dg/limiter.h>
#include <granular_dg/dg/operator.h>
#include <granular_dg/dg/parameters.h>
#include <granular_dg/dg/scene_data.h>
#include <granular_dg/dg/time_integrator.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace granular_dg::dg
{
  /**
   * The DG discretisation of one scene as the TimeLoop drives it: the
   * DoFHandler of FE_DGQLegendre on the scene's mesh, an Operator of the
   * chosen engine, the limiter, SSP-RK3 and the scene's hooks, and the
   * output of the modal field (VTU through DataOut, 1D profiles and modes).
   * After every stage: the scene's post-stage hook, the limiter, the
   * post-limiter hook, then the admissibility checks of the operator and of
   * the scene.
   */
  template <int dim, typename Physics>
  class Solver : public Evolution
  {
  public:
    Solver(const SceneData<dim, Physics> &scene, const DiscretizationParameters &method,
           const RunParameters &run, bool write_files);
    ~Solver() override;

    EvolutionInfo
    info() const override;
    double
    initialize() override;
    void
    check_initial_state(double t) override;
    double
    time_step(double t) override;
    void
    advance(double t, double dt) override;
    void
    end_of_step(double t, double dt, unsigned long step) override;
    void
    store(Slot slot) override;
    void
    restore(Slot slot) override;
    SnapshotFiles
    write_snapshot(const std::string &directory, unsigned int index, double t) override;
    std::vector<std::string>
    timeseries_names() const override;
    std::vector<double>
    timeseries_values(double t) override;
    void
    save(ByteWriter &w) override;
    void
    load(ByteReader &r) override;
    void
    finish(double t, RunResult &result, bool write_files) override;
    bool
    at_rest() const override;
    bool
    skip_step(double dt) override;
    void
    set_phases(StepPhases *p) override
    {
      phases = p;
    }

    /// The current state (the final one after a run).
    const VectorType &
    state() const
    {
      return solution;
    }

    /// Whether a step swaps solution and last_good instead of copying.
    bool
    swaps_last_good() const
    {
      return !low_storage && !active;
    }

  private:
    void
    post_stage(VectorType &u, double stage_time, double weight);
    Inadmissible
    inadmissible(const AdmissibilityReport &report, double t, bool initial) const;
    /// Inadmissible unless u passes the operator's and the scene's checks.
    void
    check(const VectorType &u, double t, bool initial) const;
    /// L1, L2, Linf per component against the exact solution at t
    std::vector<std::array<double, 3>>
    errors(double t) const;
    double
    energy() const;
    /// The fields of a snapshot: components, derived quantities and, with a
    /// limiter, the cell field `troubled`, with subcell blending the cell
    /// field `blending` (the factors of the last stage); cell_fields holds
    /// their values.
    void
    fill_data_out(DataOut<dim> &data_out, std::array<Vector<float>, 2> &cell_fields) const;
    std::string
    write_vtu(const std::string &directory, unsigned int index, double t) const;
    /// solution-NNNN.h5 by all ranks (parallel HDF5); returns its <Grid>
    /// element for solution.xdmf, the same on every rank.
    std::string
    write_hdf5(const std::string &directory, const std::string &name, double t) const;
    std::string
    write_profile(const std::string &directory, unsigned int index, double t) const;
    /// Bytes per owned DoF of the solution, Runge-Kutta stages, last-good
    /// and benchmark copies, operator (MatrixFree data), limiter (with its
    /// ghosted copy), DoFHandler and triangulation, their sum and the peak
    /// resident set size (summary.json diagnostics/memory; printed with
    /// print); the largest over the ranks.
    JsonObject
    memory_report(bool print) const;
    void
    write_modes(const std::string &directory, unsigned int index, double t) const;

    SceneData<dim, Physics>          scene;
    const DiscretizationParameters   method;
    const bool                       write_vtu_files;
    const bool                       hdf5_files;
    const std::string                directory;
    FESystem<dim>                    fe;
    DoFHandler<dim>                  dof_handler;
    MappingQ1<dim>                   mapping;
    std::unique_ptr<Operator<dim>>   op;
    ModalLimiter<dim, Physics>       limiter;
    CellQuadrature<dim>              quadrature;
    SSPRK3<>                         integrator;
    std::unique_ptr<LowStorageRK>    low_storage; ///< when method.scheme is one
    HookList<dim>                    hooks;
    /// the cells a step computes, with Time stepping/skip tolerance > 0
    std::unique_ptr<ActiveCells>     active;
    /// whether the operator's cells at rest (Time stepping/skip cells at
    /// rest) are those of the present state (time_step() found them)
    bool                             rest_found = false;
    /// the last CFL step time_step() gave
    double                           cfl_step = 0;
    VectorType                       solution, last_good, benchmark_start;
    /// SSP-RK3 without skipped cells writes a step's new state to last_good
    /// and swaps (SSPRK3::step's spare): storing the last good state is then
    /// free, and this says whether the swap of the last step has happened
    /// since (restore swaps back)
    bool                             last_good_swapped = false;
    unsigned int                     troubled = 0;
    StepPhases                      *phases   = nullptr;
  };

  /// An InputError naming Time stepping/scheme when the scene has a stage
  /// operation (SceneHooks::stage_operation) the scheme cannot carry: only
  /// SSP-RK3 can; and one naming Time stepping/skip tolerance when the run
  /// cannot skip cells; and one naming the MPI ranks when there are several
  /// and the mesh is not spread over them (the 1D scenes). The one check of
  /// the method against the scene: a
  /// scene calls it once its scene data is built, before it writes anything.
  template <int dim, typename Physics>
  void
  require_scheme_fits(const DiscretizationParameters &method, const SceneData<dim, Physics> &scene);

  /// Why a run of this scene with this method cannot skip quiet cells
  /// (Time stepping/skip tolerance > 0), "" when it can: the line engine,
  /// SSP-RK3, an autonomous scene, and stage operations that honour active
  /// cells.
  template <int dim, typename Physics>
  std::string
  why_cells_cannot_be_skipped(const DiscretizationParameters &method,
                              const SceneData<dim, Physics>  &scene);

  /// One run of a scene: a Solver driven by the TimeLoop. final_state, if
  /// given, gets the state at the end.
  template <int dim, typename Physics>
  RunResult
  run_simulation(const SceneData<dim, Physics> &scene, const RunParameters &run,
                 const DiscretizationParameters &method, bool write_files = true,
                 double dt_factor = 1., VectorType *final_state = nullptr);

  /// The convergence study of Convergence/degrees x Convergence/cells: one run
  /// per pair (the factory builds the mesh with that many cells per
  /// direction), errors against the exact solution, EOC from the smallest
  /// cell diameters, written to convergence.csv and convergence-rates.csv.
  /// For degree p the time step is scaled with (h/h_0)^(max(1,(p+1)/3) - 1)
  /// so that SSP-RK3's O(dt^3) error stays below the spatial O(h^(p+1)) one.
  template <int dim, typename Physics>
  void
  run_convergence_study(
    const std::function<SceneData<dim, Physics>(unsigned int)> &make_scene,
    const RunParameters &run, const DiscretizationParameters &method);
} // namespace granular_dg::dg
