/**
 * The `hopper` scene: the steady Mohr-Coulomb stress field of a wedge or
 * cone (system.h), marched down the hopper in tau = -ln(r/r0) with DG in
 * theta on (0, theta_w), from the radial field (Theta_w = theta_w) or from a
 * wall-angle transition (transition.h). Modes: march, radial (write the
 * radial field only), scan (the admissibility scan of Fig. 9).
 */

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/grid/grid_generator.h>

#include <granular_dg/base/output.h>
#include <granular_dg/base/parameters.h>
#include <granular_dg/base/run_parameters.h>
#include <granular_dg/base/scene.h>
#include <granular_dg/base/time_loop.h>
#include <granular_dg/dg/parameters.h>
#include <granular_dg/dg/scene_entry.h>
#include <granular_dg/dg/solver.h>
#include <granular_dg/equations/hopper/diagnostics.h>
#include <granular_dg/equations/hopper/parameters.h>
#include <granular_dg/equations/hopper/radial_field.h>
#include <granular_dg/equations/hopper/system.h>
#include <granular_dg/equations/hopper/transition.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>

namespace granular_dg::hopper
{
  namespace
  {
    /// The radial field of half-angle theta (radians), or an InputError
    /// naming the parameter that asked for it.
    std::shared_ptr<RadialField>
    radial_field(const Parameters &p, const double theta, const std::string &parameter)
    {
      try
        {
          return std::make_shared<RadialField>(p.geometry, p.material, theta);
        }
      catch (const NoRadialField &e)
        {
          require(false, parameter, theta / deg,
                  std::string("a half-angle with a radial field: ") + e.what() +
                    " for this " + geometry_names.name(p.geometry) + ", delta = " +
                    format_number(p.material.delta / deg) + " deg, Phi = " +
                    format_number(p.material.Phi / deg) + " deg");
          return {};
        }
    }

    /// The initial data on Gamma_0 in the lower frame (U at tau = 0).
    class InitialData : public Function<1>
    {
    public:
      InitialData(const Transition &t, const double perturbation)
        : Function<1>(2)
        , transition(t)
        , factor(1. + perturbation)
      {}
      double
      value(const dealii::Point<1> &x, const unsigned int c) const override
      {
        return transition.initial_stress(x[0])[c] * (c == 0 ? factor : 1.);
      }

    private:
      const Transition &transition;
      const double      factor;
    };

    /// summary.json of the modes without a time loop
    void
    write_mode_summary(const RunParameters &common, const unsigned int degree,
                       const RunResult &r)
    {
      EvolutionInfo info;
      info.scene  = "hopper";
      info.degree = degree;
      write_summary(common.directory, info, r);
    }

    void
    run_radial(const Parameters &p, const RunParameters &common, const unsigned int degree)
    {
      const auto lower = radial_field(p, p.theta_w, "Hopper/lower half-angle");
      lower->write_csv(common.directory + "/radial-field.csv", p.radial_points);
      RunResult r;
      add_radial_diagnostics(r.diagnostics, "", *lower);
      r.diagnostics.add("psi_wall_deg", p.material.psi_wall() / deg);
      r.diagnostics.add("chi_wall", p.material.chi_wall());
      r.diagnostics.add("hyperbolic_limit_deg", p.material.hyperbolic_limit() / deg);
      r.diagnostics.add("singular_limit_deg", p.material.singular_limit() / deg);
      r.diagnostics.add("psi_derivative_at_wall", lower->psi_derivative_at_wall());
      write_mode_summary(common, degree, r);
      std::cout << "  radial field of the " << geometry_names.name(p.geometry) << ", theta_w = "
                << format_number(p.theta_w / deg) << " deg: sigma(0) = "
                << format_number(lower->sigma_axis()) << " rho g r, shooting residual "
                << format_number(lower->shooting_residual()) << "; written to "
                << common.directory << "/radial-field.csv" << std::endl;
    }

    void
    run_scan(const Parameters &p, const RunParameters &common, const unsigned int degree)
    {
      const auto scan =
        scan_transitions(p.geometry, p.material, p.scan_from, p.scan_to, p.scan_step);
      CsvWriter csv;
      csv.open(common.directory + "/fig9-scan.csv",
               {"Theta_w_deg", "max_psi_deg", "theta_of_max_psi_deg", "dpsi_dtheta_wall",
                "lambda_max", "char_bound_deg", "theta_w_min_C_deg", "admissible_lower_min_deg",
                "admissible_lower_max_deg"},
               std::string("Fig. 9 scan, ") + geometry_names.name(p.geometry) +
                 ", delta = " + format_number(p.material.delta / deg) +
                 " deg, Phi = " + format_number(p.material.Phi / deg) + " deg");
      for (const auto &r : scan.rows)
        csv.row({r.Theta_w, r.max_psi, r.theta_of_max_psi, r.dpsi_wall, r.lambda_max, r.bound,
                 r.theta_min_C, r.lo, r.hi});
      RunResult result;
      result.diagnostics.add("psi_monotone_up_to_deg", scan.monotone_up_to);
      result.diagnostics.add("zero_transition_at_deg", scan.zero_transition_at);
      result.diagnostics.add("no_radial_field_from_deg", scan.no_radial_field_from);
      result.diagnostics.add("psi_wall_deg", p.material.psi_wall() / deg);
      result.diagnostics.add("hyperbolic_limit_deg", p.material.hyperbolic_limit() / deg);
      write_mode_summary(common, degree, result);
      std::cout << "  Fig. 9 scan (" << geometry_names.name(p.geometry) << "): psi monotone up to "
                << format_number(scan.monotone_up_to) << " deg, no steeper transition from "
                << format_number(scan.zero_transition_at) << " deg; written to "
                << common.directory << "/fig9-scan.csv" << std::endl;
    }

    void
    run_march(const Parameters &p, const RunParameters &common,
              const dg::DiscretizationParameters &method)
    {
      require(Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1, "MPI ranks",
              Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD), "1 (the hopper scene is serial)");
      const auto lower = radial_field(p, p.theta_w, "Hopper/lower half-angle");
      const auto upper = p.Theta_w == p.theta_w ?
                           lower :
                           radial_field(p, p.Theta_w, "Hopper/upper half-angle");
      const Transition transition(*upper, p.material, p.theta_w);
      const auto       check = transition.check(20001);

      dg::require_memory_fits(common, p.cells, method.degree, 1, System::n_components, "Hopper/cells",
                              std::to_string(p.cells), "use fewer cells or a lower degree");
      const System physics(p.geometry, p.variables, p.material,
                           numerical_flux_names.parse("Discretization/numerical flux",
                                                      method.flux));
      dg::SceneData<1, System> scene{"hopper", physics, {}, {}, {}, {}, {}};
      scene.time_name     = "tau";
      scene.triangulation = std::make_shared<Triangulation<1>>();
      GridGenerator::subdivided_hyper_rectangle(*scene.triangulation,
                                                std::vector<unsigned int>{p.cells},
                                                dealii::Point<1>(0.), dealii::Point<1>(p.theta_w),
                                                true);
      for (const auto &cell : scene.triangulation->active_cell_iterators())
        cell->set_material_id(0);
      scene.boundary[0].kind = System::symmetry;      // theta = 0
      scene.boundary[1].kind = System::friction_wall; // theta = theta_w
      scene.initial          = std::make_shared<InitialData>(transition, p.perturbation);
      scene.hooks.push_back(make_diagnostics(p, physics, lower, upper, common.scene_directory(),
                                             common.final_time, method.degree,
                                             common.write_vtu));

      require_reasonable_snapshot_count(
        common, dg::snapshot_bytes(p.cells, method.degree, 1, 6, common.write_vtu));
      dg::require_scheme_fits(method, scene);
      begin_output(common);
      if (!common.benchmark.enabled)
        {
          lower->write_csv(common.directory + "/radial-field.csv", p.radial_points);
          if (upper != lower)
            upper->write_csv(common.directory + "/radial-field-upper.csv", p.radial_points);
        }
      if (!check.ok)
        {
          std::ostringstream msg;
          msg << "inadmissible initial data on Gamma_0 at tau = 0, theta = "
              << format_number(check.theta / deg) << " deg (x = (" << format_number(check.theta)
              << ")), state (T_rr = " << format_number(check.stress[0]) << ", T_rtheta = "
              << format_number(check.stress[1]) << ", T_thetatheta = "
              << format_number(check.stress[2]) << ") rho g r0: " << check.reason
              << "; transition " << format_number(p.Theta_w / deg) << " -> "
              << format_number(p.theta_w / deg) << " deg (see mode = scan for the admissible "
              << "lower angles)";
          RunResult r;
          r.status = "failed: " + msg.str();
          write_mode_summary(common, method.degree, r);
          throw RunError(msg.str());
        }
      std::cout << "  " << geometry_names.name(p.geometry) << ", Theta_w = "
                << format_number(p.Theta_w / deg) << " deg -> theta_w = "
                << format_number(p.theta_w / deg) << " deg; radial field sigma(0) = "
                << format_number(lower->sigma_axis()) << " rho g r; marching to tau = "
                << format_number(common.final_time) << " (r = "
                << format_number(std::exp(-common.final_time)) << " r0)" << std::endl;
      dg::run_simulation(scene, common, method);
    }

    void
    run(const RunParameters &common, const dg::DiscretizationParameters &method,
        const Parameters &p)
    {
      if (p.mode == Mode::march)
        return run_march(p, common, method);
      if (p.mode == Mode::radial)
        radial_field(p, p.theta_w, "Hopper/lower half-angle"); // validate first
      begin_output(common);
      if (p.mode == Mode::radial)
        run_radial(p, common, method.degree);
      else
        run_scan(p, common, method.degree);
    }

    const RegisterScene registration(dg::scene_entry<Parameters>(
      "hopper",
      "steady Mohr-Coulomb stresses in a wedge or cone hopper, marched in tau = -ln(r/r0) "
      "(Gremaud & Matthews); radial fields, wall-angle transitions, the Fig. 9 scan",
      numerical_flux_names.selection(), "", run));
  } // namespace
} // namespace granular_dg::hopper
