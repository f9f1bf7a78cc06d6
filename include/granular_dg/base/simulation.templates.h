#pragma once

#include <deal.II/base/quadrature.h>
#include <deal.II/base/timer.h>

#include <optional>
#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <deal.II/base/conditional_ostream.h>

#include <granular_dg/base/errors.h>
#include <granular_dg/base/simulation.h>
#include <granular_dg/dg/dg_operator.h>
#include <granular_dg/dg/line_operator.h>
#include <granular_dg/dg/time_integrator.h>

#include <algorithm>
#include <cstring>
#include <chrono>
#include <cmath>
#include <type_traits>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace granular_dg
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
        for (unsigned int q = 0; q < inputs.solution_values.size(); ++q)
          {
            Tensor<1, Physics::n_components> U;
            for (unsigned int c = 0; c < Physics::n_components; ++c)
              U[c] = inputs.solution_values[q][c];
            const auto d = physics.derived(
              U, physics.coefficients(inputs.template get_cell<dim>()->material_id()));
            for (unsigned int i = 0; i < d.size(); ++i)
              computed[q][i] = d[i];
          }
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
      const Physics physics;
    };

    inline std::string
    snapshot_name(const std::string &prefix, const unsigned int index,
                  const std::string &suffix)
    {
      return prefix + Utilities::int_to_string(index, 4) + suffix;
    }

    /// Writes the VTU/PVTU snapshots, the PVD index and (1D) the CSV profiles.
    template <int dim, typename Physics>
    class SnapshotWriter
    {
    public:
      SnapshotWriter(const std::string &directory, const Physics &physics,
                     const unsigned int degree, const unsigned int profile_points,
                     const bool write_vtu, const bool write_modes)
        : directory(directory)
        , physics(physics)
        , degree(degree)
        , profile_points(profile_points > 0 ? profile_points : std::max(2u, degree + 1))
        , write_vtu(write_vtu)
        , write_modes(write_modes)
      {}

      /// (time, file) of every snapshot so far: a checkpoint keeps them, so
      /// that a resumed run continues the numbering and solution.pvd.
      std::vector<std::pair<double, std::string>> &
      snapshot_records()
      {
        return records;
      }

      /// Returns the name of the VTU/PVTU file written (empty if none).
      std::string
      write(const DoFHandler<dim> &dof_handler, const Mapping<dim> &mapping,
            const dg::VectorType &solution, const double time)
      {
        const unsigned int index = records.size();
        solution.update_ghost_values();
        std::string name;
        if (write_vtu)
          name = write_vtu_file(dof_handler, mapping, solution, time, index);
        if constexpr (dim == 1)
          {
            write_profile(dof_handler, mapping, solution, time, index);
            if (write_modes)
              write_mode_table(dof_handler, solution, time, index);
          }
        solution.zero_out_ghost_values();
        if (!name.empty())
          {
            records.emplace_back(time, name);
            if (Utilities::MPI::this_mpi_process(solution.get_mpi_communicator()) == 0)
              write_pvd(directory + "/solution.pvd", records);
          }
        else
          records.emplace_back(time, "");
        return name;
      }

    private:
      std::string
      write_vtu_file(const DoFHandler<dim> &dof_handler, const Mapping<dim> &mapping,
                     const dg::VectorType &solution, const double time,
                     const unsigned int index)
      {
        const MPI_Comm comm = solution.get_mpi_communicator();
        DataOut<dim>   data_out;
        DataOutBase::VtkFlags flags(time, index);
        // deterministic files: a resumed run writes the same bytes
        flags.print_date_and_time = false;
        // deal.II 9.4.1 writes broken high-order cells in 1D: subdivided
        // linear patches there, Lagrange cells in 2D
        flags.write_higher_order_cells = (dim > 1);
        data_out.set_flags(flags);
        data_out.attach_dof_handler(dof_handler);
        const DerivedFields<dim, Physics> derived(physics);
        data_out.add_data_vector(solution, Physics::component_names());
        data_out.add_data_vector(solution, derived);
        data_out.build_patches(mapping, std::max(1u, degree));

        const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
        const unsigned int rank    = Utilities::MPI::this_mpi_process(comm);
        if (n_ranks == 1)
          {
            const std::string name = snapshot_name("solution-", index, ".vtu");
            std::ofstream     out(directory + "/" + name);
            data_out.write_vtu(out);
            return name;
          }
        const std::string base = snapshot_name("solution-", index, "");
        {
          std::ofstream out(directory + "/" + base + "." +
                            Utilities::int_to_string(rank, 4) + ".vtu");
          data_out.write_vtu(out);
        }
        if (rank == 0)
          {
            std::vector<std::string> pieces;
            for (unsigned int r = 0; r < n_ranks; ++r)
              pieces.push_back(base + "." + Utilities::int_to_string(r, 4) + ".vtu");
            std::ofstream out(directory + "/" + base + ".pvtu");
            data_out.write_pvtu_record(out, pieces);
          }
        return base + ".pvtu";
      }

      void
      write_profile(const DoFHandler<dim> &dof_handler, const Mapping<dim> &mapping,
                    const dg::VectorType &solution, const double time,
                    const unsigned int index)
      {
        std::vector<Point<dim>> points;
        for (unsigned int i = 0; i < profile_points; ++i)
          points.emplace_back(profile_points == 1 ? 0.5 : double(i) / (profile_points - 1));
        const Quadrature<dim> quadrature(points);
        FEValues<dim> fe_values(mapping, dof_handler.get_fe(), quadrature,
                                update_values | update_quadrature_points);
        std::vector<Vector<double>> values(points.size(),
                                           Vector<double>(Physics::n_components));

        std::vector<std::string> header{"x"};
        for (const auto &n : Physics::component_names())
          header.push_back(n);
        for (const auto &n : Physics::derived_names())
          header.push_back(n);
        CsvWriter csv;
        csv.open(directory + "/" + snapshot_name("profile-", index, ".csv"),
                 header, "time = " + format_number(time));
        for (const auto &cell : dof_handler.active_cell_iterators())
          {
            fe_values.reinit(cell);
            fe_values.get_function_values(solution, values);
            const auto a = physics.coefficients(cell->material_id());
            for (unsigned int q = 0; q < points.size(); ++q)
              {
                Tensor<1, Physics::n_components> U;
                std::vector<double> row{fe_values.quadrature_point(q)[0]};
                for (unsigned int c = 0; c < Physics::n_components; ++c)
                  {
                    U[c] = values[q][c];
                    row.push_back(U[c]);
                  }
                for (const double d : physics.derived(U, a))
                  row.push_back(d);
                csv.row(row);
              }
          }
      }

      /// modes-NNNN.csv: x_left, h and the Legendre modes of every cell
      void
      write_mode_table(const DoFHandler<dim> &dof_handler, const dg::VectorType &solution,
                       const double time, const unsigned int index)
      {
        dg::ModalLayout<dim> layout;
        layout.reinit(dof_handler);
        std::vector<std::string> header{"x_left", "h"};
        for (const auto &n : Physics::component_names())
          for (unsigned int k = 0; k < layout.n_modes(); ++k)
            header.push_back(n + "_" + std::to_string(k));
        CsvWriter csv;
        csv.open(directory + "/" + snapshot_name("modes-", index, ".csv"), header,
                 "time = " + format_number(time));
        for (unsigned int c = 0; c < layout.n_owned(); ++c)
          {
            std::vector<double> row{layout.cell(c)->vertex(0)[0], layout.extent(c, 0)};
            for (unsigned int i = 0; i < Physics::n_components; ++i)
              for (unsigned int k = 0; k < layout.n_modes(); ++k)
                row.push_back(solution(layout.index(c, i, k)));
            csv.row(row);
          }
      }

      const std::string directory;
      const Physics     physics;
      const unsigned int degree, profile_points;
      const bool        write_vtu, write_modes;
      std::vector<std::pair<double, std::string>> records;
    };

    /// The output times of a run: the list, or multiples of the interval,
    /// always ending with the final time.
    inline std::vector<double>
    output_schedule(const CommonParameters &p, const double start_time = 0.)
    {
      std::vector<double> times;
      if (!p.output_times.empty())
        times = p.output_times;
      else if (p.output_interval > 0)
        for (unsigned int k = 1; k * p.output_interval < p.final_time * (1 - 1e-12); ++k)
          times.push_back(k * p.output_interval);
      times.erase(std::remove_if(times.begin(), times.end(),
                                 [&](const double t) {
                                   return t <= start_time * (1 + 1e-12);
                                 }),
                  times.end());
      times.push_back(p.final_time);
      std::sort(times.begin(), times.end());
      times.erase(std::unique(times.begin(), times.end(),
                              [&](double a, double b) {
                                return std::abs(a - b) <= 1e-12 * p.final_time;
                              }),
                  times.end());
      return times;
    }

    /// A violation found in a post-stage check.
    struct Inadmissible
    {
      double                  time;
      dg::AdmissibilityReport report;
      bool                    initial = false;
    };

    /// The operator as the integrator sees it: apply() charged to the
    /// operator phase of the current step (nothing when phases is null).
    template <typename Operator>
    struct TimedOperator
    {
      const Operator    &op;
      StepPhases *const &phases;

      void
      apply(const double t, const dg::VectorType &src, dg::VectorType &dst) const
      {
        StepPhases::Scope scope(phases, StepPhases::operator_apply);
        op.apply(t, src, dst);
      }

      /// the fused stage of an operator that has one (dg::StageUpdate)
      template <typename Op = Operator>
      auto
      apply_stage(const double t, const dg::VectorType &src, dg::VectorType &dst,
                  const dg::StageUpdate<> &s) const
        -> decltype(std::declval<const Op &>().apply_stage(t, src, dst, s))
      {
        StepPhases::Scope scope(phases, StepPhases::operator_apply);
        op.apply_stage(t, src, dst, s);
      }
    };
  } // namespace internal

  namespace internal
  {
    /// The solution cell by cell, keyed by CellId (partition independent):
    /// rank 0 gets every cell, sorted by key, the other ranks "".
    /// Collective.
    template <int dim>
    std::string
    save_cell_values(const DoFHandler<dim> &dof_handler, const dg::VectorType &u)
    {
      using Key                        = CellId::binary_type;
      const unsigned int n             = dof_handler.get_fe().n_dofs_per_cell();
      const std::size_t  record        = sizeof(Key) + n * sizeof(double);
      std::vector<types::global_dof_index> dofs(n);
      std::string                          mine;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const Key key = cell->id().template to_binary<dim>();
            mine.append(reinterpret_cast<const char *>(&key), sizeof(Key));
            cell->get_dof_indices(dofs);
            for (const auto i : dofs)
              {
                const double v = u(i);
                mine.append(reinterpret_cast<const char *>(&v), sizeof(double));
              }
          }
      const MPI_Comm comm = u.get_mpi_communicator();
      const auto     all  = Utilities::MPI::gather(comm, mine, 0);
      if (Utilities::MPI::this_mpi_process(comm) != 0)
        return "";
      std::vector<std::pair<Key, const char *>> cells;
      for (const auto &part : all)
        for (std::size_t o = 0; o + record <= part.size(); o += record)
          {
            Key key;
            std::memcpy(&key, part.data() + o, sizeof(Key));
            cells.emplace_back(key, part.data() + o);
          }
      std::sort(cells.begin(), cells.end(),
                [](const auto &a, const auto &b) { return a.first < b.first; });
      ByteWriter w;
      w.io(static_cast<std::uint64_t>(cells.size()));
      w.io(n);
      for (const auto &c : cells)
        w.bytes.append(c.second, record);
      return w.bytes;
    }

    /// Set the owned cells of u from what save_cell_values() wrote.
    template <int dim>
    void
    load_cell_values(const DoFHandler<dim> &dof_handler, const std::string &bytes,
                     dg::VectorType &u)
    {
      using Key = CellId::binary_type;
      ByteReader    r(bytes);
      std::uint64_t n_cells = 0;
      unsigned int  n       = 0;
      r.io(n_cells);
      r.io(n);
      const std::size_t record = sizeof(Key) + n * sizeof(double);
      if (n != dof_handler.get_fe().n_dofs_per_cell() ||
          n_cells != dof_handler.get_triangulation().n_global_active_cells() ||
          bytes.size() != sizeof(std::uint64_t) + sizeof(unsigned int) + n_cells * record)
        throw RunError("the checkpoint's solution does not fit this mesh (" +
                       std::to_string(n_cells) + " cells of " + std::to_string(n) + " DoFs)");
      const char *first = bytes.data() + sizeof(std::uint64_t) + sizeof(unsigned int);
      auto        key_of = [&](const std::size_t i) {
        Key key;
        std::memcpy(&key, first + i * record, sizeof(Key));
        return key;
      };
      std::vector<types::global_dof_index> dofs(n);
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const Key   key = cell->id().template to_binary<dim>();
            std::size_t lo = 0, hi = n_cells;
            while (lo < hi)
              {
                const std::size_t mid = (lo + hi) / 2;
                if (key_of(mid) < key)
                  lo = mid + 1;
                else
                  hi = mid;
              }
            if (lo == n_cells || key_of(lo) != key)
              throw RunError("the checkpoint has no values for cell " + cell->id().to_string());
            const char *values = first + lo * record + sizeof(Key);
            cell->get_dof_indices(dofs);
            for (unsigned int i = 0; i < n; ++i)
              std::memcpy(&u(dofs[i]), values + i * sizeof(double), sizeof(double));
          }
    }

  /// The time loop of run_simulation() on one operator type (MatrixFree's
  /// DGOperator or, in 1D, the LineOperator).
  template <int dim, typename Physics, typename Operator>
  RunResult
  run_with(const SceneData<dim, Physics> &scene,
           const CommonParameters        &params,
           const unsigned int             degree,
           const bool                     write_files,
           const double                   dt_factor)
  {
    Timer wall_timer;
    const MPI_Comm comm = MPI_COMM_WORLD;
    const bool     root = Utilities::MPI::this_mpi_process(comm) == 0;

    const Triangulation<dim> &tria = *scene.triangulation;
    const FESystem<dim>  fe(FE_DGQLegendre<dim>(degree), Physics::n_components);
    DoFHandler<dim>      dof_handler(tria);
    dof_handler.distribute_dofs(fe);
    const MappingQ1<dim> mapping;

    Operator op(scene.physics, params.flux, scene.boundary);
    op.reinit(mapping, dof_handler);
    dg::VectorType solution, last_good;
    op.initialize_vector(solution);
    op.initialize_vector(last_good);

    dg::ModalLimiter<dim, Physics> limiter(scene.physics, params.limiter, params.tvb_M,
                                           scene.boundary);
    limiter.reinit(dof_handler, solution);
    dg::SSPRK3<> integrator;
    SceneHooks<dim> no_hooks;
    SceneHooks<dim> &hooks = scene.hooks ? *scene.hooks : no_hooks;
    const CheckpointIdentity identity{scene.scene,
                                      Physics::name,
                                      dim,
                                      degree,
                                      tria.n_global_active_cells(),
                                      dof_handler.n_dofs()};
    // a resumed run takes its state from the checkpoint (below)
    const bool                resume = params.resume && write_files;
    std::optional<Checkpoint> checkpoint;
    if (resume)
      {
        checkpoint = read_checkpoint(params.directory, identity, params.parameters, comm);
        require_beyond_checkpoint(params, *checkpoint, scene.time_name);
      }
    hooks.set_resuming(resume);
    hooks.initialize(dof_handler, mapping, limiter.layout());
    if (resume)
      ;
    else if (scene.initial_vector)
      {
        AssertThrow(scene.initial_vector->size() == solution.size(),
                    ExcMessage("the initial vector belongs to another discretisation"));
        solution.copy_locally_owned_data_from(*scene.initial_vector);
      }
    else
      {
        scene.initial->set_time(scene.start_time);
        op.project(*scene.initial, solution);
        limiter.apply(solution, scene.start_time);
      }
    last_good = solution;

    RunResult result;
    result.n_dofs  = dof_handler.n_dofs();
    result.n_cells = tria.n_global_active_cells();
    result.h_min   = GridTools::minimal_cell_diameter(tria);

    // an optional, so that a failed run can destroy it before throwing: a
    // TimerOutput destroyed during stack unwinding prints an MPI warning
    ConditionalOStream         timer_out(std::cout, Utilities::MPI::this_mpi_process(comm) == 0);
    std::optional<TimerOutput> timer_storage;
    timer_storage.emplace(comm, timer_out, TimerOutput::never, TimerOutput::wall_times);
    TimerOutput &timer = *timer_storage;

    internal::SnapshotWriter<dim, Physics> snapshots(params.directory, scene.physics, degree,
                                                     params.profile_points, params.write_vtu,
                                                     params.write_modes);

    const auto names = Physics::component_names();
    CsvWriter  timeseries;
    if (write_files && root)
      {
        std::vector<std::string> header{"time", "step", "dt"};
        for (const auto &n : names)
          header.push_back("integral_" + n);
        header.push_back("energy");
        header.push_back("troubled_cells");
        if (scene.exact)
          {
            header.push_back("l2_error");
            for (const auto &n : names)
              header.push_back("l1_error_" + n);
          }
        for (const auto &n : hooks.timeseries_names())
          header.push_back(n);
        if (!resume)
          timeseries.open(params.directory + "/timeseries.csv", header);
      }

    double        t = scene.start_time, dt = 0.;
    unsigned long step = 0;
    unsigned int  troubled = 0;

    // a checkpoint: the loop's state, the solution and the scene's state
    // (written and read by the same io() sequence)
    auto loop_state = [&](auto &ar, std::uint64_t &timeseries_size) {
      ar.io(t);
      ar.io(step);
      ar.io(dt);
      ar.io(troubled);
      ar.io(snapshots.snapshot_records());
      ar.io(timeseries_size);
    };
    auto save_checkpoint = [&]() {
      ByteWriter    w;
      std::uint64_t timeseries_size = root ? timeseries.size() : 0;
      loop_state(w, timeseries_size);
      w.io(save_cell_values(dof_handler, solution));
      ByteWriter h;
      hooks.save(h);
      w.io(h.bytes);
      return write_checkpoint(params.directory, identity, params.parameters, step, t, w.bytes,
                              comm);
    };
    if (resume)
      {
        ByteReader    r(checkpoint->payload);
        std::uint64_t timeseries_size = 0;
        std::string   cells, hook_state;
        loop_state(r, timeseries_size);
        r.io(cells);
        r.io(hook_state);
        load_cell_values(dof_handler, cells, solution);
        ByteReader h(hook_state);
        hooks.load(h);
        if (root)
          timeseries.reopen(params.directory + "/timeseries.csv", timeseries_size);
        result.resumed_from_step = step;
        last_good = solution;
        if (root)
          std::cout << "  resuming from " << checkpoint->file << ": " << scene.time_name
                    << " = " << format_number(t) << ", step " << step << std::endl;
      }
    const unsigned long first_step   = step;
    const auto          output_times = internal::output_schedule(params, t);
    auto energy = [&](const Tensor<1, Physics::n_components> &U,
                      const typename Operator::template Coefficients<double> &a) {
      return scene.physics.energy(U, a);
    };
    auto l2_error = [&](const dg::VectorType &u) {
      scene.exact->set_time(t);
      double sum = 0;
      result.errors.clear();
      for (const auto &e : op.errors(u, *scene.exact))
        {
          result.errors.push_back(e);
          sum += e[1] * e[1];
        }
      return std::sqrt(sum);
    };
    auto record = [&]() {
      TimerOutput::Scope scope(timer, "output");
      if (!write_files)
        return;
      snapshots.write(dof_handler, mapping, solution, t);
      std::vector<double> row{t, double(step), dt};
      for (const double s : op.integrals(solution))
        row.push_back(s);
      row.push_back(op.integrate(solution, energy));
      row.push_back(Utilities::MPI::sum(troubled, comm));
      if (scene.exact)
        {
          row.push_back(l2_error(solution));
          for (const auto &e : result.errors)
            row.push_back(e[0]);
        }
      for (const double v : hooks.timeseries_values(solution, t))
        row.push_back(v);
      if (root)
        timeseries.row(row);
    };

    // the phases of a step are timed in benchmark mode only (phases != nullptr)
    StepPhases *phases     = nullptr;
    auto        post_stage = [&](dg::VectorType &u, const double stage_time, const double weight) {
      {
        StepPhases::Scope scope(phases, StepPhases::post_stage_hook);
        hooks.post_stage(u, stage_time, weight);
      }
      {
        StepPhases::Scope scope(phases, StepPhases::limiter);
        troubled = limiter.apply(u, stage_time);
      }
      {
        StepPhases::Scope scope(phases, StepPhases::post_limiter_hook);
        hooks.post_limiter(u, stage_time);
      }
      StepPhases::Scope scope(phases, StepPhases::admissibility);
      auto              report = op.check_admissibility(u);
      if (report.ok)
        report = dg::first_failure(hooks.check_admissibility(u), comm);
      if (!report.ok)
        throw internal::Inadmissible{stage_time, report};
    };
    const internal::TimedOperator<Operator> timed_op{op, phases};
    // one Runge-Kutta step; what is neither operator nor post-stage work is
    // charged to the vector updates
    auto rk_step = [&](const double dt_step) {
      if (!phases)
        return integrator.step(timed_op, solution, t, dt_step, post_stage);
      const double before = phases->total();
      const auto   start  = std::chrono::steady_clock::now();
      integrator.step(timed_op, solution, t, dt_step, post_stage);
      const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      phases->seconds[StepPhases::vector_updates] += elapsed - (phases->total() - before);
    };

    if (write_files && root)
      std::cout << "  " << result.n_cells << " cells, " << result.n_dofs
                << " DoFs, degree " << degree << ", " << Physics::name
                << "; output to " << params.directory << "/ (solution.pvd"
                << (dim == 1 ? ", profile-NNNN.csv" : "")
                << ", timeseries.csv, summary.json)" << std::endl;

    if (params.benchmark.enabled)
      {
        const auto report = op.check_admissibility(solution);
        if (!report.ok)
          throw RunError("benchmark: inadmissible initial state: " + report.reason);
        const std::string load = load_average();
        try
          {
            const auto reps = run_benchmark(params.benchmark, [&](StepPhases *ph) {
              phases = ph;
              {
                StepPhases::Scope scope(ph, StepPhases::state_copy);
                last_good = solution;
              }
              double speed;
              {
                StepPhases::Scope scope(ph, StepPhases::time_step);
                speed = op.max_speed_over_h(solution, scene.min_wave_speed);
              }
              dt = dt_factor * params.cfl / speed;
              if (!(std::isfinite(dt) && dt > 0))
                throw RunError("benchmark: time step is " + format_number(dt));
              rk_step(dt);
              t += dt;
              ++step;
              StepPhases::Scope scope(ph, StepPhases::end_of_step_hook);
              hooks.end_of_step(solution, t, dt, step);
            });
            JsonObject c;
            c.add("scene", scene.scene);
            c.add("physics", Physics::name);
            c.add("dim", static_cast<long long>(dim));
            c.add("degree", degree);
            c.add("engine", std::is_same_v<Operator, dg::DGOperator<dim, Physics>> ?
                              "matrix_free" :
                              "line");
            c.add("n_cells", static_cast<long long>(result.n_cells));
            c.add("limiter", static_cast<long long>(params.limiter));
            write_benchmark(params.directory, c, reps, result.n_dofs, dg::SSPRK3<>::n_stages,
                            load);
          }
        catch (const internal::Inadmissible &failure)
          {
            throw RunError("benchmark: inadmissible state at " + scene.time_name + " = " +
                           format_number(failure.time) + ": " + failure.report.reason);
          }
        result.status     = "benchmark";
        result.n_steps    = step;
        result.final_time = t;
        timer_storage.reset();
        return result;
      }

    if (!resume)
      record();
    Progress progress(t, params.final_time,
                      (write_files && root) ? params.progress_interval : 0.);
    const InterruptHandlers interrupt_handlers;
    CheckpointSchedule      schedule(params.checkpoint_steps, params.checkpoint_seconds,
                                write_files ? params.max_steps : 0, write_files, comm);
    // accumulates wall and CPU time of the steps alone (no output, no diagnostics)
    Timer loop_timer;
    loop_timer.stop();
    loop_timer.reset();
    unsigned int next_output = 0;
    try
      {
        {
          auto report = op.check_admissibility(solution);
          if (report.ok)
            report = dg::first_failure(hooks.check_admissibility(solution), comm);
          if (!report.ok)
            throw internal::Inadmissible{t, report, true};
        }
        while (next_output < output_times.size())
          {
            last_good = solution;
            const double speed =
              op.max_speed_over_h(solution, scene.min_wave_speed);
            dt = dt_factor * params.cfl / speed;
            if (!(std::isfinite(dt) && dt > 0))
              throw RunError("time step is " + format_number(dt) + " at " + scene.time_name +
                             " = " + format_number(t) + " (max wave speed/h = " +
                             format_number(speed) + ")");
            bool lands = false;
            if (t + dt >= output_times[next_output] * (1 - 1e-14))
              {
                dt    = output_times[next_output] - t;
                lands = true;
              }
            {
              TimerOutput::Scope scope(timer, "time stepping");
              loop_timer.start();
              rk_step(dt);
              loop_timer.stop();
            }
            t = lands ? output_times[next_output] : t + dt;
            ++step;
            hooks.end_of_step(solution, t, dt, step);
            if (lands)
              {
                record();
                ++next_output;
              }
            progress.update(step, t, dt);

            const auto decision = schedule.poll(step);
            std::string checkpoint_file;
            if (decision.write)
              {
                TimerOutput::Scope scope(timer, "checkpoint");
                checkpoint_file = save_checkpoint();
                schedule.written();
                if (root && !decision.stop() && params.progress_interval > 0)
                  std::cout << "  checkpoint " << checkpoint_file << " (" << scene.time_name
                            << " = " << format_number(t) << ", step " << step << ")"
                            << std::endl;
              }
            if (decision.stop())
              {
                result.status = stop_status(decision, scene.time_name, t, step,
                                            checkpoint_file);
                result.n_steps     = step;
                result.final_time  = t;
                result.wall_time_s = wall_timer.wall_time();
                if (write_files)
                  write_summary(params.directory, scene.scene, dim, degree, result);
                timer_storage.reset();
                if (decision.signal != 0)
                  throw Interrupted(decision.signal, result.status);
                if (root)
                  std::cout << "  " << result.status << std::endl;
                result.final_solution = std::make_shared<dg::VectorType>(solution);
                return result;
              }
          }
      }
    catch (const internal::Inadmissible &failure)
      {
        std::ostringstream msg;
        if (failure.initial)
          msg << "inadmissible initial state at x = (";
        else
          msg << "inadmissible state at " << scene.time_name << " = "
              << format_number(failure.time)
              << " (step " << step + 1 << "), x = (";
        for (int d = 0; d < dim; ++d)
          msg << (d ? ", " : "") << format_number(failure.report.position[d]);
        msg << "), state (";
        for (unsigned int c = 0; c < failure.report.state.size(); ++c)
          msg << (c ? ", " : "") << names[c] << " = "
              << format_number(failure.report.state[c]);
        msg << "): " << failure.report.reason;
        result.status = "failed: " + msg.str();
        if (write_files && failure.initial)
          msg << "; initial state written to " << params.directory << "/";
        else if (write_files)
          {
            solution = last_good;
            std::string file = snapshots.write(dof_handler, mapping, solution, t);
            if (file.empty() && dim == 1)
              file = internal::snapshot_name("profile-", snapshots.snapshot_records().size() - 1,
                                             ".csv");
            msg << "; last good state (" << scene.time_name << " = " << format_number(t)
                << ") written to " << params.directory << "/"
                << (file.empty() ? "summary.json only (Output/write vtu = false)" : file);
          }
        result.n_steps     = step;
        result.final_time  = t;
        result.wall_time_s = wall_timer.wall_time();
        hooks.finish(solution, t, result.diagnostics, params.directory, write_files);
        if (write_files)
          write_summary(params.directory, scene.scene, dim, degree, result);
        timer_storage.reset();
        throw RunError(msg.str());
      }
    catch (const RunError &e)
      {
        result.status     = std::string("failed: ") + e.what();
        result.n_steps    = step;
        result.final_time = t;
        solution = last_good;
        hooks.finish(solution, t, result.diagnostics, params.directory, write_files);
        if (write_files)
          {
            snapshots.write(dof_handler, mapping, solution, t);
            write_summary(params.directory, scene.scene, dim, degree, result);
          }
        timer_storage.reset();
        throw;
      }

    result.final_solution = std::make_shared<dg::VectorType>(solution);
    result.n_steps     = step;
    result.final_time  = t;
    result.time_loop_s     = loop_timer.wall_time();
    result.time_loop_cpu_s = loop_timer.cpu_time();
    const double updates = double(result.n_dofs) * dg::SSPRK3<>::n_stages * (step - first_step);
    result.dof_updates_per_s = result.time_loop_s > 0 ? updates / result.time_loop_s : 0;
    result.dof_updates_per_cpu_s_per_rank =
      result.time_loop_cpu_s > 0 ?
        updates / Utilities::MPI::n_mpi_processes(comm) / result.time_loop_cpu_s :
        0;
    if (scene.exact)
      {
        result.l2_error = l2_error(solution);
        result.l1_error = 0;
        for (const auto &e : result.errors)
          result.l1_error += e[0];
      }
    const auto integrals = op.integrals(solution);
    for (unsigned int c = 0; c < names.size(); ++c)
      result.diagnostics.add("integral_" + names[c], integrals[c]);
    result.diagnostics.add("energy", op.integrate(solution, energy));
    hooks.finish(solution, t, result.diagnostics, params.directory, write_files);
    result.wall_time_s = wall_timer.wall_time();

    if (write_files)
      {
        write_summary(params.directory, scene.scene, dim, degree, result);
        if (root)
          {
            std::cout << "  completed " << step << " steps to t = " << format_number(t)
                      << " in " << format_duration(result.wall_time_s) << " ("
                      << format_number(result.dof_updates_per_s / 1e6)
                      << " MDoF-stage updates/s in the time loop)" << std::endl;
          }
        // collective: every rank takes part, rank 0 prints
        timer.print_wall_time_statistics(comm);
      }
    return result;
  }

  } // namespace internal

  template <int dim, typename Physics>
  RunResult
  run_simulation(const SceneData<dim, Physics> &scene,
                 const CommonParameters        &params,
                 const unsigned int             degree,
                 const bool                     write_files,
                 const double                   dt_factor)
  {
    if constexpr (dim == 1)
      if (params.engine == dg::Engine::line ||
          (params.engine == dg::Engine::automatic &&
           Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1))
        return internal::run_with<dim, Physics, dg::LineOperator<Physics>>(scene, params, degree,
                                                                            write_files, dt_factor);
    return internal::run_with<dim, Physics, dg::DGOperator<dim, Physics>>(scene, params, degree,
                                                                          write_files, dt_factor);
  }

  template <int dim, typename Physics>
  void
  run_convergence_study(
    const std::function<SceneData<dim, Physics>(unsigned int)> &make_scene,
    const CommonParameters                                     &params)
  {
    const bool root = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
    CsvWriter  table, rates;
    if (root)
      {
        table.open(params.directory + "/convergence.csv",
                   {"degree", "cells", "dofs", "h", "l2_error", "eoc", "l1_error", "eoc_l1",
                    "time_steps", "wall_time_s", "time_loop_s", "time_loop_cpu_s"});
        rates.open(params.directory + "/convergence-rates.csv",
                   {"degree", "eoc_finest", "eoc_l1_finest"},
                   "L2 and L1 error rates of the two finest meshes (all components)");
        std::cout << "  degree    cells       dofs       L2 error     EOC   steps" << std::endl;
      }
    JsonObject errors;
    for (const unsigned int p : params.convergence_degrees)
      {
        double       e_prev = -1, h_prev = -1, eoc = NAN, e1_prev = -1, eoc1 = NAN;
        const double exponent = std::max(1., (p + 1.) / 3.) - 1.;
        const double h0       = 1. / params.convergence_cells.front();
        std::vector<double> errs;
        for (const unsigned int cells : params.convergence_cells)
          {
            const auto   scene  = make_scene(cells);
            AssertThrow(scene.exact, ExcMessage("no exact solution"));
            const double factor = std::pow((1. / cells) / h0, exponent);
            const auto   r      = run_simulation(scene, params, p, false, factor);
            eoc = e_prev > 0 ? std::log(e_prev / r.l2_error) / std::log(h_prev / r.h_min) : NAN;
            eoc1 =
              e1_prev > 0 ? std::log(e1_prev / r.l1_error) / std::log(h_prev / r.h_min) : NAN;
            if (root)
              {
                table.row({double(p), double(cells), double(r.n_dofs), r.h_min, r.l2_error,
                           eoc, r.l1_error, eoc1, double(r.n_steps), r.wall_time_s,
                           r.time_loop_s, r.time_loop_cpu_s});
                std::cout << std::setw(8) << p << std::setw(9) << cells << std::setw(11)
                          << r.n_dofs << std::setw(15) << std::scientific
                          << std::setprecision(4) << r.l2_error << std::defaultfloat
                          << std::setw(8) << std::fixed << std::setprecision(2) << eoc
                          << std::defaultfloat << std::setw(8) << r.n_steps << std::endl;
              }
            e_prev  = r.l2_error;
            e1_prev = r.l1_error;
            h_prev  = r.h_min;
            errs.push_back(r.l2_error);
          }
        if (root)
          rates.row({double(p), eoc, eoc1});
        errors.add("degree_" + std::to_string(p) + "_l2_errors", errs);
      }
    if (root)
      {
        JsonObject summary;
        summary.add("scene", make_scene(params.convergence_cells.front()).scene);
        summary.add("mode", "convergence study");
        summary.add("dim", static_cast<long long>(dim));
        summary.add("status", "completed");
        summary.add("cells", std::vector<double>(params.convergence_cells.begin(),
                                                 params.convergence_cells.end()));
        summary.add_object("errors", errors);
        summary.write(params.directory + "/summary.json");
      }
  }
} // namespace granular_dg
