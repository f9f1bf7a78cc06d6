/**
 * The `layered_strip` scene: nonlinear elasticity (system.h) in a layered
 * medium on an interval (1D) or a rectangle (2D) whose cell faces align with
 * the material interfaces (layers of width l of two materials A and B, vertical
 * or horizontal strips in 2D; layer width 0 is a homogeneous medium of
 * material A). Boundary conditions by side (periodic, outflow, moving wall,
 * traction, Dirichlet), optionally switched to periodic in x at a given time
 * (a second run started from the first one's final state), initial data as
 * strain or stress expressions, an exact or reference solution for errors,
 * interface diagnostics (diagnostics.h) and an optional positivity limiter
 * of the strain (dg::PositivityLimiter). Parameters: parameters.h.
 */

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <granular_dg/base/parameters.h>
#include <granular_dg/base/run_parameters.h>
#include <granular_dg/base/scene.h>
#include <granular_dg/dg/parameters.h>
#include <granular_dg/dg/positivity_limiter.h>
#include <granular_dg/dg/reference_solution.h>
#include <granular_dg/dg/scene_entry.h>
#include <granular_dg/dg/solver.h>
#include <granular_dg/equations/layered_strip/diagnostics.h>
#include <granular_dg/equations/layered_strip/parameters.h>
#include <granular_dg/equations/layered_strip/system.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>

namespace granular_dg::layered_strip
{
  namespace
  {
    /// A Function of dim + 1 components made from the expressions f of the
    /// prm file (and their time) and the layers.
    template <int dim>
    class LayeredData : public Function<dim>
    {
    public:
      LayeredData(std::shared_ptr<Function<dim>> f, const Layers &layers)
        : Function<dim>(dim + 1)
        , f(std::move(f))
        , layers(layers)
      {}
      void
      set_time(const double t) override
      {
        Function<dim>::set_time(t);
        f->set_time(t);
      }

    protected:
      std::shared_ptr<Function<dim>> f;
      const Layers                   layers;
    };

    /// (strain or stress, velocity) expressions -> conserved (strain, rho u),
    /// with the material of the point.
    template <int dim>
    class PrimitiveToConserved : public LayeredData<dim>
    {
    public:
      PrimitiveToConserved(std::shared_ptr<Function<dim>> f, const System<dim> &system,
                           const Layers &layers, const bool stress_given)
        : LayeredData<dim>(std::move(f), layers)
        , system(system)
        , stress_given(stress_given)
      {}
      double
      value(const Point<dim> &p, const unsigned int c) const override
      {
        const auto a = system.coefficients(this->layers.id(p));
        const auto v = this->f->value(p, c);
        if (c > 0)
          return a[density] * v;
        return stress_given ? system.strain_of_stress(v, a) : v;
      }

    private:
      const System<dim> system;
      const bool        stress_given;
    };

    /// Boundary data in the layout System::boundary_state() expects.
    template <int dim>
    class BoundaryData : public LayeredData<dim>
    {
    public:
      BoundaryData(std::shared_ptr<Function<dim>> f, const Side side, const Layers &layers)
        : LayeredData<dim>(std::move(f), layers)
        , side(side)
      {}
      double
      value(const Point<dim> &p, const unsigned int c) const override
      {
        const auto &f = this->f;
        switch (side)
          {
            case Side::wall:
              return c == 0 ? 0. : f->value(p, c - 1);
            case Side::traction:
              return c == 0 ? f->value(p, 0) : 0.;
            case Side::dirichlet:
              return (c == 0 ? 1. : this->layers.material(this->layers.id(p)).rho) *
                     f->value(p, c);
            default:
              return 0.;
          }
      }

    private:
      const Side side;
    };

    template <int dim>
    std::shared_ptr<Function<dim>>
    primitive_function(const PrimitiveExpressions &e, const System<dim> &system,
                       const Layers &layers, const bool time_dependent)
    {
      const auto v = split_expressions(e.velocity);
      require(v.size() == dim, e.section + "/velocity", e.velocity,
              std::to_string(dim) + " expression(s) separated by ';'");
      const bool stress_given = !Utilities::trim(e.stress).empty();
      require(!stress_given || Utilities::trim(e.strain) == "0", e.section + "/stress", e.stress,
              "empty when the strain is given (strain = '" + e.strain + "')");
      std::vector<std::string> all{stress_given ? e.stress : e.strain};
      all.insert(all.end(), v.begin(), v.end());
      std::vector<std::string> names{e.section + (stress_given ? "/stress" : "/strain")};
      names.resize(all.size(), e.section + "/velocity");
      return std::make_shared<PrimitiveToConserved<dim>>(
        make_function<dim>(all, names, time_dependent), system, layers, stress_given);
    }

    /// Initial data outside the admissible set (a stress the law cannot
    /// reach, sigma' <= 0) are bad input: checked at 3^dim Gauss points of
    /// every cell (all ranks see all coarse cells, so all agree).
    template <int dim>
    void
    require_admissible_initial_state(const PrimitiveExpressions           &e,
                                     const dg::SceneData<dim, System<dim>> &scene)
    {
      const std::string stress = Utilities::trim(e.stress);
      const QGauss<dim> q(3);
      Vector<double>    U(dim + 1);
      for (const auto &cell : scene.triangulation->active_cell_iterators())
        for (const auto &xi : q.get_points())
          {
            Point<dim> x = cell->vertex(0);
            for (int d = 0; d < dim; ++d)
              x[d] += xi[d] * (cell->vertex(GeometryInfo<dim>::vertices_per_cell - 1)[d] -
                               cell->vertex(0)[d]);
            scene.initial->vector_value(x, U);
            Tensor<1, dim + 1> s;
            for (unsigned int c = 0; c <= dim; ++c)
              s[c] = U[c];
            const std::string why = scene.physics.admissibility_violation(
              s, scene.physics.coefficients(cell->material_id()));
            if (why.empty())
              continue;
            // the message is built only for the point that fails
            std::ostringstream at;
            at << "initial data in the admissible set; at x = (";
            for (int d = 0; d < dim; ++d)
              at << (d ? ", " : "") << format_number(x[d]);
            at << ") the strain is " << format_number(s[0]) << ": "
               << (!stress.empty() && !std::isfinite(s[0]) ?
                     "no strain gives this stress (the law's range: sigma > -1 for the "
                     "exponential law, 1 + 4 beta sigma >= 0 for the quadratic one)" :
                     why);
            require(false, e.section + (stress.empty() ? "/strain" : "/stress"),
                    stress.empty() ? e.strain : stress, at.str());
          }
    }

    /// Every material interface a mesh face: a whole number of cells per
    /// layer, and the interfaces on the grid lines.
    void
    require_aligned_layers(const LayeredParameters &p, const std::array<unsigned int, 2> &cells)
    {
      const Layers &layers = p.layers;
      if (layers.width <= 0)
        return;
      const unsigned int d     = layers.direction;
      const double       h     = (p.hi[d] - p.lo[d]) / cells[d];
      const double       per   = layers.width / h;
      const double       shift = (layers.nearest_origin() - p.lo[d]) / h;
      require(std::abs(per - std::round(per)) < 1e-9 && std::round(per) >= 1 &&
                std::abs(shift - std::round(shift)) < 1e-9,
              d == 0 ? "Mesh/cells x" : "Mesh/cells y", cells[d],
              "a number of cells that puts every material interface (layer width " +
                format_number(layers.width) + ", origin " + format_number(layers.origin) +
                ") on a mesh face (cell size " + format_number(h) + ")");
    }

    /// The coarse mesh whose `refinements` global refinements give `cells`
    /// cells per direction. In 2D every MPI rank holds the whole coarse mesh
    /// of a p4est triangulation (and p4est a tree per coarse cell), so it is
    /// the coarsest one: cells / 2^r with r the powers of two that both
    /// counts share (2000 x 200 cells: 250 x 25 coarse cells refined 3
    /// times). 1D: the cells themselves.
    template <int dim>
    std::shared_ptr<Triangulation<dim>>
    make_coarse_mesh(const LayeredParameters &p, const std::array<unsigned int, 2> &cells,
                     unsigned int &refinements)
    {
      refinements = 0;
      if constexpr (dim == 1)
        {
          auto tria = std::make_shared<Triangulation<1>>();
          GridGenerator::subdivided_hyper_rectangle(*tria, std::vector<unsigned int>{cells[0]},
                                                    Point<1>(p.lo[0]), Point<1>(p.hi[0]), true);
          return tria;
        }
      else
        {
          while (((cells[0] | cells[1]) >> refinements & 1u) == 0)
            ++refinements;
          auto tria = std::make_shared<parallel::distributed::Triangulation<2>>(MPI_COMM_WORLD);
          GridGenerator::subdivided_hyper_rectangle(
            *tria, std::vector<unsigned int>{cells[0] >> refinements, cells[1] >> refinements},
            p.lo, p.hi, true);
          return tria;
        }
    }

    /// The boundary condition of side b (not periodic).
    template <int dim>
    dg::BoundaryCondition<dim>
    boundary_condition(const LayeredParameters &p, const unsigned int b)
    {
      const std::string          name = std::string("Boundary conditions/") + side_label[b] + " data";
      const auto                 expr = split_expressions(p.side_data[b]);
      dg::BoundaryCondition<dim> bc;
      unsigned int               expected = 0;
      switch (p.sides[b])
        {
          case Side::wall:
            bc.kind  = dg::BoundaryKind::wall;
            expected = dim;
            break;
          case Side::traction:
            bc.kind  = System<dim>::traction;
            expected = 1;
            break;
          case Side::dirichlet:
            bc.kind  = dg::BoundaryKind::dirichlet;
            expected = dim + 1;
            break;
          default:
            bc.kind = dg::BoundaryKind::outflow;
        }
      if (expected == 0)
        return bc;
      require(expr.size() == expected, name, p.side_data[b],
              side_name(p.sides[b]) + " takes " + std::to_string(expected) +
                " expression(s) separated by ';'");
      bc.data = std::make_shared<BoundaryData<dim>>(make_function<dim>(expr, {name}, true),
                                                    p.sides[b], p.layers);
      return bc;
    }

    /// Periodic pairs of sides (periodic_x: left and right whatever the file
    /// says, the second part of a run with "periodic from") and the others'
    /// conditions.
    template <int dim>
    void
    set_boundaries(const LayeredParameters &p, const bool periodic_x,
                   dg::SceneData<dim, System<dim>> &scene)
    {
      std::vector<GridTools::PeriodicFacePair<typename Triangulation<dim>::cell_iterator>>
        periodic;
      for (unsigned int d = 0; d < dim; ++d)
        if (p.sides[2 * d] == Side::periodic || (d == 0 && periodic_x))
          GridTools::collect_periodic_faces(*scene.triangulation, 2 * d, 2 * d + 1, d, periodic);
        else
          for (unsigned int b = 2 * d; b < 2 * d + 2; ++b)
            scene.boundary[b] = boundary_condition<dim>(p, b);
      if (!periodic.empty())
        scene.triangulation->add_periodicity(periodic);
    }

    /// The exact solution, or the reference file's (at the final time).
    template <int dim>
    std::shared_ptr<Function<dim>>
    exact_solution(const LayeredParameters &p, const System<dim> &system)
    {
      if (p.exact_available)
        return primitive_function<dim>(p.exact, system, p.layers, true);
      if constexpr (dim == 1)
        if (!p.reference_file.empty())
          {
            auto file = std::make_shared<dg::ModalReference>(p.reference_file, dim + 1);
            // a reference of another time is no reference for this run
            require(std::abs(file->time() - p.final_time) <= 1e-12 * std::abs(p.final_time),
                    "Exact solution/reference file", p.reference_file,
                    "a solution at the run's final time " + format_number(p.final_time) +
                      " (the file holds t = " + format_number(file->time()) + ")");
            return file;
          }
      return nullptr;
    }

    /// The scene with cells_override cells per direction (0: the file's);
    /// periodic_x: the second part of a run with "periodic from";
    /// directory: where the scene's own files go (empty: none).
    template <int dim>
    dg::SceneData<dim, System<dim>>
    make_scene(const LayeredParameters &p, const unsigned int cells_override,
               const std::string &directory, const bool periodic_x = false)
    {
      // a convergence study refines every direction
      std::array<unsigned int, 2> cells = p.cells;
      if (cells_override > 0)
        cells = {{cells_override, cells_override}};
      require_aligned_layers(p, cells);

      dg::SceneData<dim, System<dim>> scene{"layered_strip",
                                            System<dim>(p.law, p.layers.table(), p.flux)};
      unsigned int refinements = 0;
      scene.triangulation      = make_coarse_mesh<dim>(p, cells, refinements);
      // (p4est takes periodicity on the coarse mesh, before refinement)
      set_boundaries<dim>(p, periodic_x, scene);
      scene.triangulation->refine_global(refinements);
      for (const auto &cell : scene.triangulation->active_cell_iterators())
        cell->set_material_id(p.layers.id(cell->center()));
      scene.initial = primitive_function<dim>(p.initial, scene.physics, p.layers, false);
      require_admissible_initial_state(p.initial, scene);
      scene.exact = exact_solution<dim>(p, scene.physics);
      scene.hooks.push_back(
        std::make_shared<LayeredDiagnostics<dim>>(scene.physics, directory, p.slice_y));
      if (p.positivity)
        scene.hooks.push_back(std::make_shared<dg::PositivityLimiter<dim>>(
          0, "strain", "eps", "Limiter/strain positivity"));
      return scene;
    }

    /// Two runs: t in [0, periodic from] in DIR/before-periodic with the
    /// file's boundary conditions, then periodic in x from the first part's
    /// final state in DIR. A resumed run continues part 2 if it wrote a
    /// checkpoint, else part 1.
    template <int dim>
    void
    run_in_two_parts(const LayeredParameters &p, const RunParameters &common,
                     const dg::DiscretizationParameters &method,
                     const dg::SceneData<dim, System<dim>> &first_scene)
    {
      const bool resume_second = common.resume && has_checkpoints(common.directory);
      const bool root          = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
      std::shared_ptr<dg::VectorType> part_1_end;
      if (!resume_second)
        {
          RunParameters first = common;
          first.final_time    = p.periodic_from;
          first.directory     = common.directory + "/before-periodic";
          first.output_times.erase(std::remove_if(first.output_times.begin(),
                                                  first.output_times.end(),
                                                  [&](const double t) {
                                                    return t >= p.periodic_from;
                                                  }),
                                   first.output_times.end());
          if (root && !common.resume)
            prepare_output_directory(first.directory, common.overwrite);
          MPI_Barrier(MPI_COMM_WORLD);
          if (root)
            std::cout << "  part 1: t in [0, " << format_number(p.periodic_from)
                      << "] with the boundary conditions of the file" << std::endl;
          part_1_end = std::make_shared<dg::VectorType>();
          if (dg::run_simulation(first_scene, first, method, true, 1., part_1_end.get())
                .status != "completed")
            return; // stopped at max steps: part 2 comes with --resume
        }
      auto after           = make_scene<dim>(p, 0, common.directory, true);
      after.start_time     = p.periodic_from;
      after.initial_vector = part_1_end; // none when part 2 resumes
      RunParameters second = common;
      second.resume        = resume_second;
      if (root)
        std::cout << "  part 2: t in [" << format_number(p.periodic_from) << ", "
                  << format_number(common.final_time) << "], periodic in x" << std::endl;
      dg::run_simulation(after, second, method);
    }

    template <int dim>
    void
    run(const LayeredParameters &p, const RunParameters &common,
        const dg::DiscretizationParameters &method)
    {
      // (named: the larger of cells x and cells y, with the other beside it)
      const unsigned int big = dim == 2 && p.cells[1] > p.cells[0] ? 1 : 0;
      if (!common.convergence)
        dg::require_memory_fits(common, double(p.cells[0]) * (dim == 2 ? p.cells[1] : 1), method.degree,
                                dim, System<dim>::n_components, big ? "Mesh/cells y" : "Mesh/cells x",
                                std::to_string(p.cells[big]) +
                                  (dim == 2 ? std::string(big ? " (cells x = " : " (cells y = ") +
                                                std::to_string(p.cells[1 - big]) + ")" :
                                              std::string()),
                                "use fewer cells or a lower degree, or run on more machines "
                                "(MPI ranks)");
      // build (and so validate) everything before anything is written
      const auto scene = make_scene<dim>(
        p, common.convergence ? common.convergence_cells.front() : 0,
        p.periodic_from > 0 ? common.directory + "/before-periodic" : common.scene_directory());
      dg::require_scheme_fits(method, scene);
      if (common.convergence)
        require(static_cast<bool>(scene.exact), "Exact solution/available", "false",
                "true: a convergence study needs the exact solution");
      if (p.periodic_from > 0)
        {
          require(p.periodic_from < common.final_time, "Boundary conditions/periodic from",
                  p.periodic_from,
                  "a time before the final time " + format_number(common.final_time));
          require(!common.convergence, "Boundary conditions/periodic from", p.periodic_from,
                  "0 in a convergence study");
          require(p.sides[0] != Side::periodic, "Boundary conditions/periodic from",
                  p.periodic_from, "0 when left and right are periodic from the start");
          make_scene<dim>(p, 0, "", true); // validates the second part too
        }
      require_reasonable_snapshot_count(
        common, dg::snapshot_bytes(scene.triangulation->n_global_active_cells(), method.degree,
                                   dim, 2 * dim + 2, common.write_vtu));
      begin_output(common);
      if (common.convergence)
        dg::run_convergence_study<dim, System<dim>>(
          [&](unsigned int cells) { return make_scene<dim>(p, cells, ""); }, common, method);
      else if (p.periodic_from > 0)
        run_in_two_parts<dim>(p, common, method, scene);
      else
        dg::run_simulation(scene, common, method);
    }

    void
    run_scene(const RunParameters &common, const dg::DiscretizationParameters &method,
              const LayeredParameters &p)
    {
      if (p.dim == 1)
        run<1>(p, common, method);
      else
        run<2>(p, common, method);
    }

    const RegisterScene registration(dg::scene_entry<LayeredParameters>(
      "layered_strip",
      "nonlinear elasticity eps_t - div u = 0, (rho u)_t - grad sigma(eps) = 0 in a layered "
      "(or homogeneous) medium, 1D or 2D",
      numerical_flux_names.selection(), System<1>::limiting_variables_name, run_scene));
  } // namespace
} // namespace granular_dg::layered_strip
