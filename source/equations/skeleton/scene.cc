/**
 * The `skeleton` scene: linear advection (system.h) of u0 on the unit
 * interval or square, periodic or with inflow data, against the exact
 * solution u0(x - a t). A complete minimal scene: parameters (parameters.h),
 * the mesh and data (make_scene), a run or a convergence study, and the
 * registration. Copy this folder to start a new scene
 * (contrib/new_scene.sh NAME; doc/engine.md).
 */

#include <deal.II/distributed/tria.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <granular_dg/base/parameters.h>
#include <granular_dg/base/run_parameters.h>
#include <granular_dg/base/scene.h>
#include <granular_dg/dg/parameters.h>
#include <granular_dg/dg/scene_entry.h>
#include <granular_dg/dg/solver.h>
#include <granular_dg/equations/skeleton/parameters.h>
#include <granular_dg/equations/skeleton/system.h>

#include <cmath>

namespace granular_dg::skeleton
{
  namespace
  {
    /// u0(x - a t), x - a t taken back into the unit cell (u0 periodic)
    template <int dim>
    class Exact : public Function<dim>
    {
    public:
      Exact(std::shared_ptr<Function<dim>> u0, const Tensor<1, 2> &a)
        : Function<dim>(1)
        , u0(std::move(u0))
        , a(a)
      {}

      double
      value(const Point<dim> &x, const unsigned int) const override
      {
        Point<dim> y;
        for (int d = 0; d < dim; ++d)
          {
            const double s = x[d] - a[d] * this->get_time();
            y[d]           = s - std::floor(s);
          }
        return u0->value(y);
      }

    private:
      std::shared_ptr<Function<dim>> u0;
      Tensor<1, 2>                   a;
    };

    template <int dim>
    dg::SceneData<dim, System<dim>>
    make_scene(const SkeletonParameters &p, const dg::DiscretizationParameters &method,
               const unsigned int cells)
    {
      Tensor<1, dim> a;
      for (int d = 0; d < dim; ++d)
        a[d] = p.velocity[d];
      dg::SceneData<dim, System<dim>> scene{
        "skeleton",
        System<dim>(a, numerical_flux_names.parse("Discretization/numerical flux", method.flux))};
      if constexpr (dim == 1)
        scene.triangulation = std::make_shared<Triangulation<1>>();
      else
        scene.triangulation =
          std::make_shared<parallel::distributed::Triangulation<2>>(MPI_COMM_WORLD);
      GridGenerator::subdivided_hyper_cube(*scene.triangulation, cells, 0., 1., true);
      const auto u0 = make_function<dim>({p.initial}, {"Initial condition/u"}, false);
      scene.exact   = std::make_shared<Exact<dim>>(u0, p.velocity);
      scene.initial = scene.exact;
      if (p.periodic)
        {
          std::vector<GridTools::PeriodicFacePair<typename Triangulation<dim>::cell_iterator>>
            pairs;
          for (unsigned int d = 0; d < dim; ++d)
            GridTools::collect_periodic_faces(*scene.triangulation, 2 * d, 2 * d + 1, d, pairs);
          scene.triangulation->add_periodicity(pairs);
        }
      else
        for (unsigned int b = 0; b < 2 * dim; ++b)
          {
            scene.boundary[b].kind = dg::BoundaryKind::dirichlet;
            scene.boundary[b].data = scene.exact;
          }
      return scene;
    }

    template <int dim>
    void
    run(const SkeletonParameters &p, const RunParameters &common,
        const dg::DiscretizationParameters &method)
    {
      dg::require_memory_fits(common, std::pow(double(p.cells), dim), method.degree, dim,
                              System<dim>::n_components, "Mesh/cells", std::to_string(p.cells),
                              "use fewer cells or a lower degree");
      // build (and so validate) everything before anything is written
      const auto scene = make_scene<dim>(p, method, p.cells);
      require_reasonable_snapshot_count(
        common, dg::snapshot_bytes(scene.triangulation->n_global_active_cells(), method.degree,
                                   dim, 1, common.write_vtu));
      dg::require_scheme_fits(method, scene);
      begin_output(common);
      if (common.convergence)
        dg::run_convergence_study<dim, System<dim>>(
          [&](const unsigned int cells) { return make_scene<dim>(p, method, cells); }, common,
          method);
      else
        dg::run_simulation(scene, common, method);
    }

    void
    run_scene(const RunParameters &common, const dg::DiscretizationParameters &method,
              const SkeletonParameters &p)
    {
      if (p.dim == 1)
        run<1>(p, common, method);
      else
        run<2>(p, common, method);
    }

    const RegisterScene registration(dg::scene_entry<SkeletonParameters>(
      "skeleton",
      "linear advection u_t + div(a u) = 0 on the unit interval or square: the minimal "
      "scene to copy for a new one",
      numerical_flux_names.selection(), "", run_scene));
  } // namespace
} // namespace granular_dg::skeleton
