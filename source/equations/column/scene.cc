/**
 * The `column` scene: a granular column with Coulomb wall friction (Coffey & Gremaud,
 * system.h), a wall load u(0, t) = u_b at z = 0 and an outflow end at z = L,
 * at rest initially. The friction inclusion is solved per cell and stage
 * (friction.h) or, for comparison, treated explicitly (the naive variants).
 * Parameters: parameters.h; what it measures: diagnostics.h; for m = 1 the
 * exact solution (closed_form.h).
 */

#include <deal.II/grid/grid_generator.h>

#include <granular_dg/base/parameters.h>
#include <granular_dg/base/run_parameters.h>
#include <granular_dg/base/scene.h>
#include <granular_dg/dg/parameters.h>
#include <granular_dg/dg/scene_entry.h>
#include <granular_dg/dg/solver.h>
#include <granular_dg/equations/column/closed_form.h>
#include <granular_dg/equations/column/diagnostics.h>
#include <granular_dg/equations/column/friction.h>
#include <granular_dg/equations/column/parameters.h>
#include <granular_dg/equations/column/system.h>

#include <cmath>

namespace granular_dg::column
{
  namespace
  {
    dg::SceneData<1, System>
    make_scene(const ColumnParameters &p, const RunParameters &common,
               const unsigned int cells)
    {
      dg::SceneData<1, System> scene{"column", System(p.physics), {}, {}, {}, {}};
      scene.triangulation = std::make_shared<Triangulation<1>>();
      GridGenerator::subdivided_hyper_rectangle(*scene.triangulation,
                                                std::vector<unsigned int>{cells}, Point<1>(0.),
                                                Point<1>(p.length), true);
      for (const auto &cell : scene.triangulation->active_cell_iterators())
        cell->set_material_id(0);
      // the wall load through the numerical flux at z = 0, outflow or a
      // closed end at z = L
      dg::BoundaryCondition<1> wall;
      wall.kind = dg::BoundaryKind::dirichlet;
      wall.data = std::make_shared<Functions::ConstantFunction<1>>(std::vector<double>{p.u_b, 0.});
      scene.boundary[0] = wall;
      scene.boundary[1].kind = p.closed_end ? dg::BoundaryKind::wall : dg::BoundaryKind::outflow;
      scene.initial     = std::make_shared<Functions::ZeroFunction<1>>(2);
      if (p.closed_form)
        scene.exact = std::make_shared<LinearColumnFunction>(p.u_b);
      const auto friction = std::make_shared<FrictionHooks>(scene.physics, p.printed_weights);
      scene.hooks         = {friction, make_diagnostics(scene.physics, p, common.final_time,
                                                       common.scene_directory(), *friction)};
      // the paper's time step: c dt/dx <= CFL with c = sqrt(-sigma'(u*)), u* the
      // largest strain, here the wall strain
      scene.min_wave_speed = scene.physics.sound_speed(p.u_b);
      // a constant wall load and gravity: the same operator at every time
      scene.autonomous = true;
      return scene;
    }

    void
    run(const RunParameters &common, const dg::DiscretizationParameters &method,
        const ColumnParameters &p)
    {
      const System system(p.physics);
      require(std::isfinite(system.stress(p.u_b)) && std::isfinite(system.sound_speed(p.u_b)),
              "Physics/wall strain", p.u_b,
              "a strain whose stress |u_b|^m and wave speed are finite in double precision "
              "(they overflow for m = " + format_number(p.physics.m) + ")");
      if (common.convergence)
        require(p.closed_form, "Diagnostics/closed form", "false",
                "true: a convergence study needs the exact solution");
      dg::require_memory_fits(common, p.cells, method.degree, 1, System::n_components, "Mesh/cells",
                              std::to_string(p.cells), "use fewer cells or a lower degree");
      require_reasonable_snapshot_count(
        common, dg::snapshot_bytes(p.cells, method.degree, 1, 7, common.write_vtu));
      // built (and so validated) before anything is written
      const auto scene =
        make_scene(p, common, common.convergence ? common.convergence_cells.front() : p.cells);
      dg::require_scheme_fits(method, scene);
      begin_output(common);
      if (common.convergence)
        dg::run_convergence_study<1, System>(
          [&](const unsigned int cells) { return make_scene(p, common, cells); }, common, method);
      else
        dg::run_simulation(scene, common, method);
    }

    const RegisterScene registration(dg::scene_entry<ColumnParameters>(
      "column",
      "granular column with Coulomb wall friction (dynamical Janssen model), "
      "u_t - v_z = 0, v_t + sigma(u)_z - G in -sgn(v) sigma(u), 1D",
      dg::local_lax_friedrichs_name, "", run));
  } // namespace
} // namespace granular_dg::column
