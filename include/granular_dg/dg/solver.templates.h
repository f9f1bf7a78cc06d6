#pragma once

#include <deal.II/base/quadrature.h>
#include <deal.II/base/utilities.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <granular_dg/base/convergence_study.h>
#include <granular_dg/base/errors.h>
#include <granular_dg/base/run_parameters.h>
#include <granular_dg/base/time_loop.h>
#include <granular_dg/dg/dg_operator.h>
#include <granular_dg/dg/line_operator.h>
#include <granular_dg/dg/make_operator.h>
#include <granular_dg/dg/solution_transfer.h>
#include <granular_dg/dg/solver.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <sstream>

namespace granular_dg::dg
{
  namespace internal
  {
    /// Derived quantities of the Physics (velocity, stress, ...) as VTU fields.
    template <int dim, typename Physics>
    class DerivedFields : public DataPostprocessor<dim>
    {
    public:
      explicit DerivedFields(const Physics &physics)
        : physics(physics)
      {}

      void
      evaluate_vector_field(const DataPostprocessorInputs::Vector<dim> &inputs,
                            std::vector<Vector<double>> &computed) const override
      {
        evaluate(inputs, computed);
      }

      /// (deal.II calls this one for a system of one component)
      void
      evaluate_scalar_field(const DataPostprocessorInputs::Scalar<dim> &inputs,
                            std::vector<Vector<double>> &computed) const override
      {
        evaluate(inputs, computed);
      }

      std::vector<std::string>
      get_names() const override
      {
        return Physics::derived_names();
      }

      UpdateFlags
      get_needed_update_flags() const override
      {
        return update_values;
      }

    private:
      /// The derived fields at the points of inputs (their solution_values:
      /// a value per point for one component, else a vector per point).
      template <typename Inputs>
      void
      evaluate(const Inputs &inputs, std::vector<Vector<double>> &computed) const
      {
        const auto coefficients =
          physics.coefficients(inputs.template get_cell<dim>()->material_id());
        for (unsigned int q = 0; q < inputs.solution_values.size(); ++q)
          {
            Tensor<1, Physics::n_components> U;
            for (unsigned int c = 0; c < Physics::n_components; ++c)
              U[c] = component(inputs.solution_values[q], c);
            const auto d = physics.derived(U, coefficients);
            for (unsigned int i = 0; i < d.size(); ++i)
              computed[q][i] = d[i];
          }
      }

      static double
      component(const double value, const unsigned int)
      {
        return value;
      }

      static double
      component(const Vector<double> &values, const unsigned int c)
      {
        return values[c];
      }

      const Physics physics;
    };

    /// The operator with its apply calls charged to the operator phase
    /// (nothing when phases is null).
    template <int dim>
    struct TimedOperator
    {
      const Operator<dim> &op;
      StepPhases *const   &phases;

      void
      apply_stage(const double t, const VectorType &src, VectorType &dst,
                  const StageUpdate<> &s) const
      {
        StepPhases::Scope scope(phases, StepPhases::operator_apply);
        op.apply_stage(t, src, dst, s);
      }

      void
      apply(const double t, const VectorType &src, VectorType &dst) const
      {
        StepPhases::Scope scope(phases, StepPhases::operator_apply);
        op.apply(t, src, dst);
      }
    };

    inline std::string
    snapshot_name(const std::string &prefix, const unsigned int index,
                  const std::string &suffix)
    {
      return prefix + Utilities::int_to_string(index, 4) + suffix;
    }
  } // namespace internal

  template <int dim, typename Physics>
  Solver<dim, Physics>::Solver(const SceneData<dim, Physics> &scene_data,
                               const DiscretizationParameters &method,
                               const RunParameters &run, const bool write_files)
    : scene(scene_data)
    , method(method)
    , write_vtu_files(run.write_vtu)
    , hdf5_files(run.hdf5)
    , directory(run.directory)
    , fe(FE_DGQLegendre<dim>(method.degree), Physics::n_components)
    , dof_handler(*scene_data.triangulation)
    , op(make_operator<dim>(method.engine, scene_data.physics, scene_data.boundary))
    , limiter(scene_data.physics, method.limiter, method.tvb_M, scene_data.boundary)
    , hooks(scene_data.hooks)
  {
    run.require_format_fits(dim);
    dof_handler.distribute_dofs(fe);
    op->reinit(mapping, dof_handler);
    op->initialize_vector(solution);
    op->initialize_vector(last_good);
    limiter.reinit(dof_handler, solution);
    limiter.set_indicator(method.indicator, method.indicator_threshold);
    if (method.blending_max() > 0)
      AssertThrow(op->set_subcell_blending(method.blending_max()), ExcInternalError());
    quadrature.reinit(limiter.layout());
    hooks.set_all_resuming(run.resume && write_files);
    if (method.scheme != TimeScheme::ssp_rk3)
      low_storage = std::make_unique<LowStorageRK>(method.scheme);
    if (method.skip_at_rest)
      {
        // a stage reaches one face neighbour (two with a limiter)
        const unsigned int stages = low_storage ? low_storage->n_stages() : SSPRK3<>::n_stages;
        const unsigned int reach  = stages * (method.limiter == LimiterType::none ? 1 : 2);
        AssertThrow(op->skip_cells_at_rest(method.rest_tolerance, reach), ExcInternalError());
      }
    else if (method.skip_tolerance > 0)
      {
        // a step reaches (1 + 1 with a limiter) cells per stage
        const unsigned int reach =
          SSPRK3<>::n_stages * (method.limiter == LimiterType::none ? 1 : 2);
        const auto        &layout = limiter.layout();
        active = std::make_unique<ActiveCells>(layout.n_owned(), Physics::n_components,
                                               layout.n_modes(), reach,
                                               layout.n_owned() > 1 && layout.neighbor(0, 0) >= 0,
                                               method.skip_tolerance);
        AssertThrow(op->restrict_to(active.get()), ExcInternalError());
        hooks.set_all_active_cells(active.get());
      }
    hooks.initialize(dof_handler, mapping, limiter.layout());
  }

  template <int dim, typename Physics>
  std::string
  why_cells_cannot_be_skipped(const DiscretizationParameters &method,
                              const SceneData<dim, Physics>  &scene)
  {
    const bool serial = !Utilities::MPI::job_supports_mpi() ||
                        Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1;
    if (dim != 1 || method.engine == Engine::matrix_free || !serial)
      return "the line engine (serial 1D runs)";
    if (method.scheme != TimeScheme::ssp_rk3)
      return "Time stepping/scheme = ssp_rk3";
    if (!scene.autonomous)
      return "a scene whose operator does not depend on time (the " + scene.scene +
             " scene's boundary data or sources may)";
    if (const auto op = HookList<dim>(scene.hooks).stage_operation_on_all_cells(); !op.empty())
      return "stage operations that act cell by cell (this run has " + op + ")";
    return "";
  }

  template <int dim, typename Physics>
  std::string
  why_cells_at_rest_cannot_be_skipped(const DiscretizationParameters &method,
                                      const SceneData<dim, Physics>  &scene)
  {
    if (dim == 1)
      return "the 2D engine (in 1D, skip tolerance > 0 alone leaves out the quiet cells "
             "of the line engine)";
    if (!internal::zero_is_rest_state<Physics>)
      return std::string("a physics with a rest state (") + Physics::name + " declares none)";
    if (method.blending_max() > 0)
      return "Limiter/subcell blending = false";
    if (const auto op = HookList<dim>(scene.hooks).stage_operation_on_all_cells(); !op.empty())
      return "stage operations that act cell by cell (this run has " + op + ")";
    return "";
  }

  template <int dim, typename Physics>
  void
  require_scheme_fits(const DiscretizationParameters &method, const SceneData<dim, Physics> &scene)
  {
    // a mesh not spread over the ranks would be computed and written by each
    const unsigned int ranks = Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
    require(ranks == 1 || dynamic_cast<const parallel::TriangulationBase<dim> *>(
                            scene.triangulation.get()) != nullptr,
            "MPI ranks", ranks,
            "1 (the mesh of the " + scene.scene + " scene in " + std::to_string(dim) +
              "D is not spread over ranks: run it without mpirun)");
    require(dim == 1 || method.engine != Engine::line, "Discretization/engine", "line",
            "auto or matrix_free in " + std::to_string(dim) +
              "D (the line engine is one-dimensional)");
    require(dim == 1 || !method.write_modes, "Output/write modes", "true",
            "false in " + std::to_string(dim) + "D (modes-NNNN.csv, the cells' Legendre "
              "coefficients, is written in 1D)");
    if (method.skip_at_rest)
      {
        if (const std::string why = why_cells_at_rest_cannot_be_skipped(method, scene);
            !why.empty())
          require(false, "Time stepping/skip cells at rest", "true",
                  "false here: skipping cells at rest needs " + why);
      }
    else if (method.skip_tolerance > 0)
      if (const std::string why = why_cells_cannot_be_skipped(method, scene); !why.empty())
        require(false, "Time stepping/skip tolerance", method.skip_tolerance,
                "0 here: skipping quiet cells needs " + why);
    require(method.blending_max() == 0 || runs_line_engine(dim, method.engine) || dim == 2,
            "Limiter/subcell blending", "true",
            "false here: subcell blending is built in the line engine (serial 1D runs) and the "
            "2D engine");
    if (method.scheme == TimeScheme::ssp_rk3)
      return;
    const std::string operation = HookList<dim>(scene.hooks).stage_operation();
    require(operation.empty(), "Time stepping/scheme", time_scheme_name(method.scheme),
            "ssp_rk3 only: this run has " + operation +
              ", which needs a scheme of convex combinations of Euler steps");
  }

  template <int dim, typename Physics>
  Solver<dim, Physics>::~Solver() = default;

  template <int dim, typename Physics>
  EvolutionInfo
  Solver<dim, Physics>::info() const
  {
    EvolutionInfo i;
    i.scene     = scene.scene;
    i.physics   = Physics::name;
    i.dim       = dim;
    i.degree    = method.degree;
    i.n_cells   = scene.triangulation->n_global_active_cells();
    i.n_dofs    = dof_handler.n_dofs();
    i.h_min     = GridTools::minimal_cell_diameter(*scene.triangulation);
    i.n_stages  = low_storage ? low_storage->n_stages() : SSPRK3<>::n_stages;
    i.time_name = scene.time_name;
    i.snapshot_files = !write_vtu_files ? "" : hdf5_files ? "solution.xdmf, solution-NNNN.h5" :
                                                            "solution.pvd";
    if (dim == 1)
      i.snapshot_files += std::string(i.snapshot_files.empty() ? "" : ", ") + "profile-NNNN.csv";
    i.description    = std::to_string(i.n_cells) + " cells, " + std::to_string(i.n_dofs) +
                    " DoFs, degree " + std::to_string(method.degree) + ", " + Physics::name;
    i.method.add("engine", op->engine_name());
    i.method.add("numerical_flux", method.flux);
    i.method.add("limiter", method.limiter_name);
    if (method.blending_max() > 0)
      i.method.add("subcell_blending", method.blending_max());
    i.method.add("scheme", time_scheme_name(method.scheme));
    i.bytes_per_snapshot =
      snapshot_bytes(i.n_cells, method.degree, dim,
                     Physics::n_components + Physics::derived_names().size(), write_vtu_files);
    return i;
  }

  template <int dim, typename Physics>
  double
  Solver<dim, Physics>::initialize()
  {
    if (scene.initial_vector)
      {
        AssertThrow(scene.initial_vector->size() == solution.size(),
                    ExcMessage("the initial vector belongs to another discretisation"));
        solution.copy_locally_owned_data_from(*scene.initial_vector);
      }
    else
      {
        scene.initial->set_time(scene.start_time);
        quadrature.project(*scene.initial, solution);
        limiter.apply(solution, scene.start_time);
      }
    if (active)
      active->reset();
    rest_found = false;
    return scene.start_time;
  }

  template <int dim, typename Physics>
  Inadmissible
  Solver<dim, Physics>::inadmissible(const AdmissibilityReport &report, const double t,
                                     const bool initial) const
  {
    Inadmissible f;
    f.time    = t;
    f.initial = initial;
    std::ostringstream where;
    where << "x = (";
    for (int d = 0; d < dim; ++d)
      where << (d ? ", " : "") << format_number(report.position[d]);
    where << ")";
    f.where  = where.str();
    f.names  = Physics::component_names();
    f.state  = report.state;
    f.reason = report.reason;
    return f;
  }

  template <int dim, typename Physics>
  void
  Solver<dim, Physics>::check(const VectorType &u, const double t, const bool initial) const
  {
    auto report = op->check_admissibility(u);
    if (report.ok)
      report = first_failure(hooks.check_admissibility(u), u.get_mpi_communicator());
    if (!report.ok)
      throw inadmissible(report, t, initial);
  }

  template <int dim, typename Physics>
  void
  Solver<dim, Physics>::check_initial_state(const double t)
  {
    check(solution, t, true);
  }

  template <int dim, typename Physics>
  double
  Solver<dim, Physics>::time_step(const double t)
  {
    if (method.skip_at_rest)
      {
        op->find_cells_at_rest(solution);
        rest_found = true;
        op->use_cells_at_rest(Operator<dim>::RestUse::wave_speed_scan);
      }
    const double speed = op->max_speed_over_h(solution, scene.min_wave_speed);
    op->use_cells_at_rest(Operator<dim>::RestUse::off);
    cfl_step = method.time_step(speed, scene.time_name, t);
    return cfl_step;
  }

  template <int dim, typename Physics>
  void
  Solver<dim, Physics>::post_stage(VectorType &u, const double stage_time, const double weight)
  {
    {
      StepPhases::Scope scope(phases, StepPhases::post_stage_hook);
      hooks.post_stage(u, stage_time, weight);
    }
    {
      StepPhases::Scope scope(phases, StepPhases::limiter);
      troubled = limiter.apply(u, stage_time, active.get());
    }
    {
      StepPhases::Scope scope(phases, StepPhases::post_limiter_hook);
      hooks.post_limiter(u, stage_time);
    }
    StepPhases::Scope scope(phases, StepPhases::admissibility);
    check(u, stage_time, false);
  }

  template <int dim, typename Physics>
  void
  Solver<dim, Physics>::advance(const double t, const double dt)
  {
    const internal::TimedOperator<dim> timed{*op, phases};
    const auto stage = [&](VectorType &u, const double s, const double w) { post_stage(u, s, w); };
    if (active)
      active->begin_step(dt, dt == cfl_step, solution);
    // the cells at rest of this state (time_step() found them unless the
    // state changed since), left out by this step only
    if (method.skip_at_rest && !rest_found)
      op->find_cells_at_rest(solution);
    rest_found = false;
    struct RestScope
    {
      const Operator<dim> &op;
      ~RestScope()
      {
        op.use_cells_at_rest(Operator<dim>::RestUse::off);
      }
    } rest_scope{*op};
    if (method.skip_at_rest)
      op->use_cells_at_rest(Operator<dim>::RestUse::step);
    if (low_storage)
      low_storage->step(timed, solution, t, dt, stage);
    else if (swaps_last_good())
      {
        integrator.step(timed, solution, t, dt, stage, &last_good);
        solution.swap(last_good);
        last_good_swapped = true;
      }
    else
      integrator.step(timed, solution, t, dt, stage);
    if (active)
      active->end_step(solution);
  }

  template <int dim, typename Physics>
  bool
  Solver<dim, Physics>::at_rest() const
  {
    return active && active->at_rest();
  }

  template <int dim, typename Physics>
  bool
  Solver<dim, Physics>::skip_step(const double dt)
  {
    return active && dt == cfl_step && active->skip_step(dt);
  }

  template <int dim, typename Physics>
  void
  Solver<dim, Physics>::end_of_step(const double t, const double dt, const unsigned long step)
  {
    hooks.end_of_step(solution, t, dt, step);
  }

  template <int dim, typename Physics>
  void
  Solver<dim, Physics>::store(const Slot slot)
  {
    if (slot == Slot::benchmark_start)
      benchmark_start = solution;
    else if (swaps_last_good())
      last_good_swapped = false; // the solution is the last good state
    else
      last_good = solution;
  }

  template <int dim, typename Physics>
  void
  Solver<dim, Physics>::restore(const Slot slot)
  {
    if (slot == Slot::benchmark_start)
      {
        solution          = benchmark_start;
        last_good_swapped = false; // (a state restored is a good one)
      }
    else if (!swaps_last_good())
      solution = last_good;
    else if (last_good_swapped)
      {
        solution.swap(last_good);
        last_good_swapped = false;
      }
    if (active)
      active->reset();
    rest_found = false;
  }

  template <int dim, typename Physics>
  std::vector<std::array<double, 3>>
  Solver<dim, Physics>::errors(const double t) const
  {
    scene.exact->set_time(t);
    return quadrature.template errors<Physics::n_components>(solution, *scene.exact);
  }

  template <int dim, typename Physics>
  double
  Solver<dim, Physics>::energy() const
  {
    const auto &layout = limiter.layout();
    return quadrature.integrate(
      [&](const unsigned int c, const unsigned int q) {
        return scene.physics.energy(
          quadrature.template state<Physics::n_components>(solution, c, q),
          scene.physics.coefficients(layout.cell(c)->material_id()));
      },
      solution.get_mpi_communicator());
  }

  template <int dim, typename Physics>
  std::vector<std::string>
  Solver<dim, Physics>::timeseries_names() const
  {
    const auto               names = Physics::component_names();
    std::vector<std::string> header;
    for (const auto &n : names)
      header.push_back("integral_" + n);
    header.push_back("energy");
    header.push_back("troubled_cells");
    if (method.indicator != TroubleIndicator::everywhere)
      header.push_back("flagged_cells");
    if (method.blending_max() > 0)
      header.push_back("blended_cells");
    if (scene.exact)
      {
        header.push_back("l2_error");
        for (const auto &n : names)
          header.push_back("l1_error_" + n);
      }
    for (const auto &n : hooks.timeseries_names())
      header.push_back(n);
    return header;
  }

  template <int dim, typename Physics>
  std::vector<double>
  Solver<dim, Physics>::timeseries_values(const double t)
  {
    std::vector<double> row = quadrature.integrals(solution);
    row.push_back(energy());
    row.push_back(Utilities::MPI::sum(troubled, solution.get_mpi_communicator()));
    if (method.indicator != TroubleIndicator::everywhere)
      row.push_back(Utilities::MPI::sum(limiter.n_flagged(), solution.get_mpi_communicator()));
    if (method.blending_max() > 0)
      row.push_back(Utilities::MPI::sum(op->n_blended_cells(), solution.get_mpi_communicator()));
    if (scene.exact)
      {
        const auto e  = errors(t);
        double     l2 = 0;
        for (const auto &ei : e)
          l2 += ei[1] * ei[1];
        row.push_back(std::sqrt(l2));
        for (const auto &ei : e)
          row.push_back(ei[0]);
      }
    for (const double v : hooks.timeseries_values(solution, t))
      row.push_back(v);
    return row;
  }

  template <int dim, typename Physics>
  void
  Solver<dim, Physics>::save(ByteWriter &w)
  {
    w.io(troubled);
    save_cell_values(dof_handler, solution, w);
    ByteWriter h;
    hooks.save(h);
    w.io(std::move(h));
    if (active)
      {
        active->save(w);
        w.io(limiter.troubled_cells());
      }
    if (method.skip_at_rest)
      {
        auto counts = op->cell_updates_left_out();
        w.io(counts.first);
        w.io(counts.second);
      }
  }

  template <int dim, typename Physics>
  void
  Solver<dim, Physics>::load(ByteReader &r)
  {
    std::string hook_state;
    r.io(troubled);
    load_cell_values(dof_handler, r, solution);
    r.io(hook_state);
    ByteReader h = r.nested(hook_state);
    hooks.load(h);
    rest_found = false;
    if (active)
      {
        active->load(r);
        std::vector<unsigned char> flags;
        r.io(flags);
        limiter.set_troubled_cells(flags);
        op->restrict_to(active.get()); // forget the cached wave speeds
      }
    if (method.skip_at_rest)
      {
        std::pair<double, double> counts;
        r.io(counts.first);
        r.io(counts.second);
        op->set_cell_updates_left_out(counts);
      }
  }

  template <int dim, typename Physics>
  void
  Solver<dim, Physics>::finish(const double t, RunResult &result, const bool write_files)
  {
    // errors and integrals of a completed run; the scene's own diagnostics always
    if (result.status == "completed")
      {
        if (scene.exact)
          {
            result.errors   = errors(t);
            result.l1_error = 0;
            double l2       = 0;
            for (const auto &e : result.errors)
              {
                l2 += e[1] * e[1];
                result.l1_error += e[0];
              }
            result.l2_error = std::sqrt(l2);
          }
        const auto names     = Physics::component_names();
        const auto integrals = quadrature.integrals(solution);
        for (unsigned int c = 0; c < names.size(); ++c)
          result.diagnostics.add("integral_" + names[c], integrals[c]);
        result.diagnostics.add("energy", energy());
      }
    if (active)
      result.diagnostics.add("skipped_cell_updates", active->skipped_fraction());
    if (method.skip_at_rest)
      {
        const auto [left_out, all] = op->cell_updates_left_out();
        result.diagnostics.add("skipped_cell_updates", all > 0 ? left_out / all : 0.);
      }
    result.diagnostics.add_object("memory", memory_report(write_files));
    hooks.finish(solution, t, result.diagnostics, directory, write_files);
  }

  template <int dim, typename Physics>
  JsonObject
  Solver<dim, Physics>::memory_report(const bool print) const
  {
    // bytes on this rank per owned DoF, by what holds them; the largest over
    // the ranks of each
    const std::vector<std::pair<std::string, std::size_t>> parts = {
      {"solution", solution.memory_consumption()},
      {"rk_stages", integrator.memory_consumption() +
                      (low_storage ? low_storage->memory_consumption() : 0)},
      {"last_good", last_good.memory_consumption()},
      {"benchmark_copy", benchmark_start.memory_consumption()},
      {"operator", op->memory_consumption()},
      {"limiter", limiter.memory_consumption()},
      {"dof_handler", dof_handler.memory_consumption()},
      {"triangulation", scene.triangulation->memory_consumption()}};
    const MPI_Comm      comm = solution.get_mpi_communicator();
    const double        dofs = std::max<double>(1., solution.locally_owned_size());
    std::vector<double> per_dof;
    double              accounted = 0;
    for (const auto &[name, bytes] : parts)
      {
        per_dof.push_back(bytes / dofs);
        accounted += bytes / dofs;
      }
    per_dof.push_back(accounted);
    per_dof.push_back(peak_resident_bytes() / dofs);
    for (double &x : per_dof) // (deal.II 9.4 has the vector form of max() only for ArrayView)
      x = Utilities::MPI::max(x, comm);

    JsonObject  m;
    std::string line = "  memory per DoF (largest rank):";
    for (unsigned int i = 0; i < parts.size(); ++i)
      {
        m.add(parts[i].first + "_bytes_per_dof", per_dof[i]);
        line += " " + parts[i].first + " " + format_number(std::round(per_dof[i] * 10) / 10);
      }
    m.add("accounted_bytes_per_dof", per_dof[parts.size()]);
    m.add("peak_rss_bytes_per_dof", per_dof[parts.size() + 1]);
    line += "; accounted " + format_number(std::round(per_dof[parts.size()] * 10) / 10) +
            " of peak RSS " + format_number(std::round(per_dof[parts.size() + 1] * 10) / 10) +
            " B/DoF";
    if (print && Utilities::MPI::this_mpi_process(comm) == 0)
      std::cout << line << std::endl;
    return m;
  }

  template <int dim, typename Physics>
  SnapshotFiles
  Solver<dim, Physics>::write_snapshot(const std::string &dir, const unsigned int index,
                                       const double t)
  {
    solution.update_ghost_values();
    SnapshotFiles files;
    if (write_vtu_files && hdf5_files)
      {
        files.main_file  = internal::snapshot_name("solution-", index, ".h5");
        files.xdmf_entry = write_hdf5(dir, files.main_file, t);
      }
    else if (write_vtu_files)
      files.pvd_entry = files.main_file = write_vtu(dir, index, t);
    if constexpr (dim == 1)
      {
        const std::string profile = write_profile(dir, index, t);
        if (files.main_file.empty())
          files.main_file = profile;
        if (method.write_modes)
          write_modes(dir, index, t);
      }
    solution.zero_out_ghost_values();
    return files;
  }

  template <int dim, typename Physics>
  void
  Solver<dim, Physics>::fill_data_out(DataOut<dim>                 &data_out,
                                      std::array<Vector<float>, 2> &cell_fields) const
  {
    data_out.attach_dof_handler(dof_handler);
    const internal::DerivedFields<dim, Physics> derived(scene.physics);
    data_out.add_data_vector(solution, Physics::component_names());
    data_out.add_data_vector(solution, derived);
    // the cells the limiter modified in the last stage
    const auto add_cell_field = [&](Vector<float> &field, const auto &values,
                                    const std::string &name) {
      field.reinit(dof_handler.get_triangulation().n_active_cells());
      unsigned int k = 0;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          field[cell->active_cell_index()] = values[k++];
      data_out.add_data_vector(field, name, DataOut<dim>::type_cell_data);
    };
    if (limiter.get_type() != LimiterType::none)
      add_cell_field(cell_fields[0], limiter.troubled_cells(), "troubled");
    if (!op->blending_factors().empty())
      add_cell_field(cell_fields[1], op->blending_factors(), "blending");
    data_out.build_patches(mapping, std::max(1u, method.degree));
  }

  template <int dim, typename Physics>
  std::string
  Solver<dim, Physics>::write_hdf5(const std::string &directory, const std::string &name,
                                   const double t) const
  {
    const MPI_Comm comm = solution.get_mpi_communicator();
    DataOut<dim>   data_out;
    std::array<Vector<float>, 2> cell_fields;
    fill_data_out(data_out, cell_fields);
    // DG fields: vertices of neighbouring cells are not merged (the jumps
    // stay); the values are written as doubles
    DataOutBase::DataOutFilter filter(DataOutBase::DataOutFilterFlags(false, true));
    data_out.write_filtered_data(filter);
    data_out.write_hdf5_parallel(filter, directory + "/" + name, comm);
    const auto  entry = data_out.create_xdmf_entry(filter, name, t, comm);
    std::string grid;
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        grid = entry.get_xdmf_content(3, ReferenceCells::get_hypercube<dim>());
        record_output_file(directory, name);
      }
    return Utilities::MPI::broadcast(comm, grid, 0);
  }

  template <int dim, typename Physics>
  std::string
  Solver<dim, Physics>::write_vtu(const std::string &directory, const unsigned int index,
                                  const double t) const
  {
    const MPI_Comm        comm = solution.get_mpi_communicator();
    DataOut<dim>          data_out;
    DataOutBase::VtkFlags flags(t, index);
    // deterministic files: a resumed run writes the same bytes
    flags.print_date_and_time = false;
    // zlib's fastest level: deal.II's default (best_compression) took 0.9 s
    // of the 1.3 s start-up and output of a 100 x 10 2D strip
    flags.compression_level = DataOutBase::VtkFlags::best_speed;
    // deal.II 9.4.1 writes broken high-order cells in 1D: subdivided
    // linear patches there, Lagrange cells in 2D
    flags.write_higher_order_cells = (dim > 1);
    data_out.set_flags(flags);
    std::array<Vector<float>, 2> cell_fields;
    fill_data_out(data_out, cell_fields);

    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
    const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);
    if (n_ranks == 1)
      {
        const std::string name = internal::snapshot_name("solution-", index, ".vtu");
        write_to_file(directory + "/" + name, [&](std::ostream &out) { data_out.write_vtu(out); });
        return name;
      }
    const std::string base = internal::snapshot_name("solution-", index, "");
    write_to_file(directory + "/" + base + "." + Utilities::int_to_string(rank, 4) + ".vtu",
                  [&](std::ostream &out) { data_out.write_vtu(out); });
    if (rank == 0)
      {
        std::vector<std::string> pieces;
        for (unsigned int r = 0; r < n_ranks; ++r)
          {
            pieces.push_back(base + "." + Utilities::int_to_string(r, 4) + ".vtu");
            record_output_file(directory, pieces.back());
          }
        std::ostringstream record;
        data_out.write_pvtu_record(record, pieces);
        write_pvtu(directory + "/" + base + ".pvtu", record.str());
      }
    return base + ".pvtu";
  }

  template <int dim, typename Physics>
  std::string
  Solver<dim, Physics>::write_profile(const std::string &directory, const unsigned int index,
                                      const double t) const
  {
    const unsigned int n = method.profile_points > 0 ? method.profile_points :
                                                       std::max(2u, method.degree + 1);
    std::vector<Point<dim>> points;
    for (unsigned int i = 0; i < n; ++i)
      points.emplace_back(n == 1 ? 0.5 : double(i) / (n - 1));
    const Quadrature<dim> quad(points);
    FEValues<dim>         fe_values(mapping, fe, quad, update_values | update_quadrature_points);
    std::vector<Vector<double>> values(points.size(), Vector<double>(Physics::n_components));

    std::vector<std::string> header{"x"};
    for (const auto &name : Physics::component_names())
      header.push_back(name);
    for (const auto &name : Physics::derived_names())
      header.push_back(name);
    const std::string name = internal::snapshot_name("profile-", index, ".csv");
    CsvWriter         csv;
    csv.open(directory + "/" + name, header, "time = " + format_number(t));
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        fe_values.reinit(cell);
        fe_values.get_function_values(solution, values);
        const auto a = scene.physics.coefficients(cell->material_id());
        for (unsigned int q = 0; q < points.size(); ++q)
          {
            Tensor<1, Physics::n_components> U;
            std::vector<double>              row{fe_values.quadrature_point(q)[0]};
            for (unsigned int c = 0; c < Physics::n_components; ++c)
              {
                U[c] = values[q][c];
                row.push_back(U[c]);
              }
            for (const double d : scene.physics.derived(U, a))
              row.push_back(d);
            csv.row(row);
          }
      }
    return name;
  }

  template <int dim, typename Physics>
  void
  Solver<dim, Physics>::write_modes(const std::string &directory, const unsigned int index,
                                    const double t) const
  {
    const auto              &layout = limiter.layout();
    std::vector<std::string> header{"x_left", "h"};
    for (const auto &n : Physics::component_names())
      for (unsigned int k = 0; k < layout.n_modes(); ++k)
        header.push_back(n + "_" + std::to_string(k));
    CsvWriter csv;
    csv.open(directory + "/" + internal::snapshot_name("modes-", index, ".csv"), header,
             "time = " + format_number(t));
    for (unsigned int c = 0; c < layout.n_owned(); ++c)
      {
        std::vector<double> row{layout.cell(c)->vertex(0)[0], layout.extent(c, 0)};
        for (unsigned int i = 0; i < Physics::n_components; ++i)
          for (unsigned int k = 0; k < layout.n_modes(); ++k)
            row.push_back(solution.local_element(layout.index(c, i, k)));
        csv.row(row);
      }
  }

  template <int dim, typename Physics>
  RunResult
  run_simulation(const SceneData<dim, Physics> &scene, const RunParameters &run,
                 const DiscretizationParameters &method, const bool write_files,
                 const double dt_factor, VectorType *final_state)
  {
    Solver<dim, Physics> solver(scene, method, run, write_files);
    TimeLoop             loop(solver, run, write_files, dt_factor);
    const RunResult      result = loop.run();
    if (final_state)
      *final_state = solver.state();
    return result;
  }

  template <int dim, typename Physics>
  void
  run_convergence_study(
    const std::function<SceneData<dim, Physics>(unsigned int)> &make_scene,
    const RunParameters &run, const DiscretizationParameters &method)
  {
    StudyColumns columns;
    columns.values = {"cells",      "dofs",        "h",           "l2_error",       "l1_error",
                      "time_steps", "wall_time_s", "time_loop_s", "time_loop_cpu_s"};
    columns.rated  = {{"l2_error", "eoc"}, {"l1_error", "eoc_l1"}};
    columns.rates_comment = "L2 and L1 error rates of the two finest meshes (all components)";
    columns.printed       = {"degree", "cells", "dofs", "l2_error", "eoc", "time_steps"};
    const double h0       = 1. / run.convergence_cells.front();
    const auto   one_run  = [&](const unsigned int i, const unsigned int cells) {
      const auto scene = make_scene(cells);
      AssertThrow(scene.exact, ExcMessage("no exact solution"));
      // above degree 2 the time step shrinks as h^((p + 1)/3) so that the
      // error of SSP-RK3 does not cap the order of the space discretisation
      const double exponent = std::max(1., (run.convergence_degrees[i] + 1.) / 3.) - 1.;
      const double factor   = std::pow((1. / cells) / h0, exponent);
      const auto   r = run_simulation(scene, run, method.for_study(run, i), false, factor);
      return StudyRow{r.h_min,
                      {double(cells), double(r.n_dofs), r.h_min, r.l2_error, r.l1_error,
                       double(r.n_steps), r.wall_time_s, r.time_loop_s, r.time_loop_cpu_s}};
    };
    JsonObject summary;
    summary.add("scene", make_scene(run.convergence_cells.front()).scene);
    summary.add("mode", "convergence study");
    summary.add("dim", static_cast<long long>(dim));
    summary.add("cells",
                std::vector<double>(run.convergence_cells.begin(), run.convergence_cells.end()));
    granular_dg::run_convergence_study(columns, run, one_run, summary);
  }
} // namespace granular_dg::dg
