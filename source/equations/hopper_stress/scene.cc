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
#include <granular_dg/dg/solver.h>
#include <granular_dg/equations/hopper_stress/radial_field.h>
#include <granular_dg/equations/hopper_stress/system.h>
#include <granular_dg/equations/hopper_stress/transition.h>

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
    constexpr double deg = M_PI / 180.;

    enum class Mode
    {
      march,
      radial,
      scan
    };
    const EnumNames<Mode>      mode_names({{Mode::march, "march"},
                                           {Mode::radial, "radial"},
                                           {Mode::scan, "scan"}});
    const EnumNames<Geometry>  geometry_names({{Geometry::wedge, "wedge"},
                                               {Geometry::cone, "cone"}});
    const EnumNames<Variables> variables_names({{Variables::scaled, "scaled"},
                                                {Variables::unscaled, "unscaled"}});

    struct Parameters
    {
      Mode         mode;
      Geometry     geometry;
      Variables    variables;
      MohrCoulomb  material;
      double       rho, g, r0, perturbation;
      double       Theta_w, theta_w; // radians
      unsigned int cells;
      unsigned int radial_points, sample_points, field_theta_points, field_rows,
        step_interval;
      double       upper_region;
      double       scan_from, scan_to, scan_step;
    };

    void
    declare(ParameterHandler &prm)
    {
      prm.enter_subsection("Hopper");
      prm.declare_entry("mode", "march", mode_names.pattern(),
                        "march: solve down the hopper in tau = -ln(r/r0); radial: only "
                        "write the radial (Jenike) field radial-field.csv; scan: the "
                        "admissibility scan of Fig. 9 (fig9-scan.csv) over the upper "
                        "half-angles of subsection Scan.");
      prm.declare_entry("geometry", "cone", geometry_names.pattern(),
                        "wedge (plane, d = 2) or cone (axisymmetric, d = 3).");
      prm.declare_entry("upper half-angle", "30", Patterns::Double(),
                        "Theta_w in degrees, in (0, 90): the hopper above the transition, "
                        "carrying its radial field.");
      prm.declare_entry("lower half-angle", "30", Patterns::Double(),
                        "theta_w in degrees, in (0, 90): the hopper that is marched "
                        "(equal to the upper one: radial-field preservation).");
      prm.declare_entry("initial radius", "1", Patterns::Double(),
                        "r0 in m: the radius of the wall corner (the initial arc Gamma_0) "
                        "in the lower hopper, > 0. Only scales coordinates and T.");
      prm.declare_entry("cells", "400", Patterns::Integer(1),
                        "N: cells in theta on (0, theta_w).");
      prm.declare_entry("initial perturbation", "0", Patterns::Double(),
                        "delta_p: the initial T_rr is multiplied by 1 + delta_p, |delta_p| < "
                        "0.5 (0: none). A test of the linear stability of the radial field "
                        "(doc/hopper.md).");
      prm.leave_subsection();

      prm.enter_subsection("Physics");
      prm.declare_entry("internal friction angle", "32.1", Patterns::Double(),
                        "delta in degrees, in (0, 90).");
      prm.declare_entry("wall friction angle", "11.7", Patterns::Double(),
                        "Phi in degrees (mu = tan Phi), in [0, delta).");
      prm.declare_entry("density", "790", Patterns::Double(), "rho in kg/m^3, > 0.");
      prm.declare_entry("gravity", "9.81", Patterns::Double(), "g in m/s^2, > 0.");
      prm.declare_entry("variables", "scaled", variables_names.pattern(),
                        "scaled: U = T/(rho g r), the radial field is a steady state; "
                        "unscaled: U = T/(rho g r0) with the tau-dependent gravity "
                        "source e^{-tau} of the paper's (7)/(11).");
      prm.leave_subsection();

      prm.enter_subsection("Hopper output");
      prm.declare_entry("radial field points", "61", Patterns::Integer(2),
                        "Rows of radial-field.csv (equidistant on [0, theta_w]).");
      prm.declare_entry("sample points", "401", Patterns::Integer(2),
                        "Equidistant theta points of stress-NNNN.csv (T/r in Pa/m per "
                        "output tau).");
      prm.declare_entry("field theta points", "101", Patterns::Integer(2),
                        "Theta points per half of hopper-field.vtu (the marched field in "
                        "physical coordinates).");
      prm.declare_entry("field rows", "120", Patterns::Integer(1),
                        "Rows (tau values) of hopper-field.vtu.");
      prm.declare_entry("upper region", "0.5", Patterns::Double(0),
                        "hopper-field.vtu also shows the upper hopper's radial field from "
                        "Gamma_0 up to R = R_0 + this * r0 (0: none).");
      prm.declare_entry("step series interval", "1", Patterns::Integer(0),
                        "Write margin and radial-field difference to hopper-steps.csv "
                        "every this many steps (0: never).");
      prm.leave_subsection();

      prm.enter_subsection("Scan");
      prm.declare_entry("upper half-angle from", "2", Patterns::Double(),
                        "First Theta_w of the Fig. 9 scan, degrees.");
      prm.declare_entry("upper half-angle to", "45", Patterns::Double(),
                        "Last Theta_w of the scan, degrees (the scan stops at the first "
                        "angle without a radial field).");
      prm.declare_entry("upper half-angle step", "0.5", Patterns::Double(),
                        "Step of the scan, degrees, > 0.");
      prm.leave_subsection();
    }

    Parameters
    parse(ParameterHandler &prm)
    {
      Parameters p;
      prm.enter_subsection("Hopper");
      p.mode     = mode_names.parse("Hopper/mode", prm.get("mode"));
      p.geometry = geometry_names.parse("Hopper/geometry", prm.get("geometry"));
      const double upper = prm.get_double("upper half-angle");
      const double lower = prm.get_double("lower half-angle");
      p.r0               = prm.get_double("initial radius");
      p.cells            = prm.get_integer("cells");
      p.perturbation     = prm.get_double("initial perturbation");
      prm.leave_subsection();
      require(std::abs(p.perturbation) < 0.5, "Hopper/initial perturbation", p.perturbation,
              "a relative amplitude in (-0.5, 0.5)");
      require(upper > 0 && upper < 90, "Hopper/upper half-angle", upper,
              "an angle in degrees in (0, 90)");
      require(lower > 0 && lower < 90, "Hopper/lower half-angle", lower,
              "an angle in degrees in (0, 90)");
      require(p.r0 > 0, "Hopper/initial radius", p.r0, "must be > 0 (m)");
      p.Theta_w = upper * deg;
      p.theta_w = lower * deg;

      prm.enter_subsection("Physics");
      const double delta = prm.get_double("internal friction angle");
      const double Phi   = prm.get_double("wall friction angle");
      p.rho              = prm.get_double("density");
      p.g                = prm.get_double("gravity");
      p.variables        = variables_names.parse("Physics/variables", prm.get("variables"));
      prm.leave_subsection();
      require(delta > 0 && delta < 90, "Physics/internal friction angle", delta,
              "an angle in degrees in (0, 90)");
      require(Phi >= 0 && Phi < delta, "Physics/wall friction angle", Phi,
              "an angle in degrees in [0, internal friction angle = " + format_number(delta) +
                ") (the passive wall state needs sin Phi < sin delta)");
      require(p.rho > 0, "Physics/density", p.rho, "must be > 0");
      require(p.g > 0, "Physics/gravity", p.g, "must be > 0");
      p.material = MohrCoulomb(delta * deg, Phi * deg);

      prm.enter_subsection("Hopper output");
      p.radial_points      = prm.get_integer("radial field points");
      p.sample_points      = prm.get_integer("sample points");
      p.field_theta_points = prm.get_integer("field theta points");
      p.field_rows         = prm.get_integer("field rows");
      p.upper_region       = prm.get_double("upper region");
      p.step_interval      = prm.get_integer("step series interval");
      prm.leave_subsection();

      prm.enter_subsection("Scan");
      p.scan_from = prm.get_double("upper half-angle from");
      p.scan_to   = prm.get_double("upper half-angle to");
      p.scan_step = prm.get_double("upper half-angle step");
      prm.leave_subsection();
      if (p.mode == Mode::scan)
        {
          require(p.scan_from > 0 && p.scan_from < 90, "Scan/upper half-angle from",
                  p.scan_from, "an angle in degrees in (0, 90)");
          require(p.scan_to >= p.scan_from && p.scan_to < 90, "Scan/upper half-angle to",
                  p.scan_to, "an angle in degrees in [upper half-angle from, 90)");
          require(p.scan_step > 0, "Scan/upper half-angle step", p.scan_step, "must be > 0");
        }
      return p;
    }

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

    void
    add_radial_diagnostics(JsonObject &d, const std::string &prefix, const RadialField &f)
    {
      d.add(prefix + "sigma_axis", f.sigma_axis());
      d.add(prefix + "sigma_wall", f.sigma(f.theta_w()));
      d.add(prefix + "shooting_residual", f.shooting_residual());
      d.add(prefix + "ode_residual", f.ode_residual());
      d.add(prefix + "max_psi_deg", f.max_psi() / deg);
      d.add(prefix + "theta_of_max_psi_deg", f.theta_of_max_psi() / deg);
      d.add(prefix + "nonsingularity_margin_deg", f.nonsingularity_margin() / deg);
      d.add(prefix + "n_solutions", static_cast<long long>(f.n_solutions()));
    }

    /**
     * Diagnostics of the march: per step the hyperbolicity margin and the
     * difference to the lower hopper's radial field (hopper-steps.csv), per
     * output tau the stresses T/r in Pa/m (stress-NNNN.csv), at the end the
     * whole marched field in physical coordinates (hopper-field.vtu/.pvd/.csv,
     * unless Output/write vtu is false).
     */
    class HopperHooks : public dg::SceneHooks<1>
    {
    public:
      HopperHooks(const Parameters &p, const System &physics,
                  std::shared_ptr<const RadialField> lower,
                  std::shared_ptr<const RadialField> upper, const std::string &directory,
                  const double tau_end, const unsigned int degree, const bool write_vtu)
        : p(p)
        , physics(physics)
        , lower(std::move(lower))
        , upper(std::move(upper))
        , transition(*this->upper, p.material, p.theta_w)
        , directory(directory)
        , tau_end(tau_end)
        , degree(degree)
        , write_vtu(write_vtu)
      {}

      void
      initialize(const DoFHandler<1> &, const Mapping<1> &,
                 const dg::ModalLayout<1> &l) override
      {
        layout = &l;
        // cells ordered by theta, and the monitor points: Gauss points of
        // the operator's quadrature (degree + 2) and both ends of each cell
        order.resize(l.n_owned());
        for (unsigned int i = 0; i < l.n_owned(); ++i)
          {
            const double left = l.cell(i)->vertex(0)[0];
            const unsigned int j =
              std::min<unsigned int>(std::lround(left / (p.theta_w / p.cells)), p.cells - 1);
            order[j] = i;
          }
        const QGauss<1>     gauss(degree + 2);
        std::vector<double> x{0.};
        for (const auto &q : gauss.get_points())
          x.push_back(q[0]);
        x.push_back(1.);
        monitor.clear();
        for (unsigned int i = 0; i < l.n_owned(); ++i)
          {
            const double a = l.cell(i)->vertex(0)[0], b = l.cell(i)->vertex(1)[0];
            for (const double xi : x)
              {
                MonitorPoint m;
                m.cell  = i;
                m.theta = a + xi * (b - a);
                m.L     = dg::legendre_values(degree + 1, xi);
                const auto T  = lower->stresses(m.theta);
                m.radial      = {{T[0], T[1]}};
                m.radial_norm = std::hypot(T[0], T[1]);
                monitor.push_back(m);
              }
          }
      }

      void
      end_of_step(const dg::VectorType &U, const double tau, const double dtau,
                  const unsigned long step) override
      {
        // max |psi| only for a row of hopper-steps.csv (atan2 per point)
        const bool row = p.step_interval > 0 && step % p.step_interval == 0;
        const auto m   = monitors(U, tau, row);
        if (m.margin < min_margin)
          {
            min_margin       = m.margin;
            tau_min_margin   = tau;
            theta_min_margin = m.theta_margin;
          }
        max_rel = std::max(max_rel, m.rel_diff);
        final_rel = m.rel_diff;
        if (row)
          {
            if (!steps.is_open())
              steps.open(directory + "/hopper-steps.csv",
                         {"tau", "r_over_r0", "step", "dtau", "hyperbolicity_margin",
                          "max_abs_psi_deg", "max_rel_diff_radial", "rel_diff_T_rr",
                          "rel_diff_T_rtheta"});
            steps.row({tau, std::exp(-tau), double(step), dtau, m.margin, m.max_psi / deg,
                       m.rel_diff, m.rel_rr, m.rel_rt});
          }
        if (tau >= next_row_tau * (1 - 1e-12))
          add_row(U, tau);
      }

      void
      save(ByteWriter &w) override
      {
        std::uint64_t steps_size = steps.is_open() ? steps.size() : 0;
        state_io(w, steps_size);
      }

      void
      load(ByteReader &r) override
      {
        std::uint64_t steps_size = 0;
        state_io(r, steps_size);
        if (steps_size > 0)
          steps.reopen(directory + "/hopper-steps.csv", steps_size);
      }

      std::vector<std::string>
      timeseries_names() const override
      {
        return {"hyperbolicity_margin", "max_abs_psi_deg", "max_rel_diff_radial",
                "T_rr_over_r_axis", "T_rr_over_r_wall"};
      }

      std::vector<double>
      timeseries_values(const dg::VectorType &U, const double tau) override
      {
        if (rows.empty())
          add_row(U, tau);
        const auto m = monitors(U, tau);
        write_stress_profile(U, tau);
        const double scale = to_pa_per_m(tau);
        return {m.margin, m.max_psi / deg, m.rel_diff, scale * value(U, 0.)[0],
                scale * value(U, p.theta_w)[0]};
      }

      void
      finish(const dg::VectorType &U, const double tau, JsonObject &d, const std::string &,
             const bool write_files) override
      {
        if (rows.empty() || rows.back().tau < tau)
          add_row(U, tau);
        const auto m = monitors(U, tau);
        d.add("min_hyperbolicity_margin", std::min(min_margin, m.margin));
        d.add("tau_of_min_margin", tau_min_margin);
        d.add("theta_of_min_margin_deg", theta_min_margin / deg);
        d.add("final_hyperbolicity_margin", m.margin);
        d.add("final_max_abs_psi_deg", m.max_psi / deg);
        d.add("max_rel_diff_radial", std::max(max_rel, m.rel_diff));
        d.add("final_rel_diff_radial", m.rel_diff);
        d.add("final_r_over_r0", std::exp(-tau));
        add_radial_diagnostics(d, "radial_", *lower);
        if (write_files)
          {
            // a failed run: the last good state's profile as well
            if (tau < tau_end * (1 - 1e-12))
              write_stress_profile(U, tau);
            if (write_vtu)
              write_field();
          }
      }

    private:
      /// The running state of a checkpoint (save/load): the monitors, the
      /// stored rows of the field, the size of hopper-steps.csv.
      template <typename Archive>
      void
      state_io(Archive &ar, std::uint64_t &steps_size)
      {
        ar.io(n_profiles);
        ar.io(next_row_tau);
        ar.io(min_margin);
        ar.io(tau_min_margin);
        ar.io(theta_min_margin);
        ar.io(max_rel);
        ar.io(final_rel);
        ar.io(steps_size);
        // rows: tau and the states, flattened
        std::vector<double> flat;
        for (const auto &row : rows)
          {
            flat.push_back(row.tau);
            flat.push_back(row.U.size());
            for (const auto &u : row.U)
              for (unsigned int c = 0; c < System::n_components; ++c)
                flat.push_back(u[c]);
          }
        ar.io(flat);
        rows.clear();
        for (std::size_t i = 0; i + 1 < flat.size();)
          {
            Row row;
            row.tau                 = flat[i++];
            const std::size_t n     = flat[i++];
            row.U.resize(n);
            for (auto &u : row.U)
              for (unsigned int c = 0; c < System::n_components; ++c)
                u[c] = flat[i++];
            rows.push_back(std::move(row));
          }
      }

      struct MonitorPoint
      {
        unsigned int          cell;
        double                theta;
        std::vector<double>   L;
        std::array<double, 2> radial;      ///< scaled radial state
        double                radial_norm; ///< hypot(radial[0], radial[1])
      };
      /// per monitor point: what the second pass of monitors() needs
      struct MonitorScratch
      {
        System::State<double> u;
        double                ratio, dx, dy, norm, estimate;
      };
      struct Monitors
      {
        double margin = INFINITY, theta_margin = 0, max_psi = 0, rel_diff = 0, rel_rr = 0,
               rel_rt = 0;
      };
      struct Row
      {
        double                                tau;
        std::vector<System::State<double>>    U;
      };

      /// T/r in Pa/m of one unit of U at tau
      double
      to_pa_per_m(const double tau) const
      {
        return p.rho * p.g * (p.variables == Variables::scaled ? 1. : std::exp(tau));
      }

      /// U as a multiple of the scaled radial field's units at tau
      double
      radial_factor(const double tau) const
      {
        return p.variables == Variables::scaled ? 1. : std::exp(-tau);
      }

      System::State<double>
      value_at(const dg::VectorType &U, const unsigned int cell,
               const std::vector<double> &L) const
      {
        System::State<double> u;
        for (unsigned int c = 0; c < 2; ++c)
          for (unsigned int k = 0; k <= degree; ++k)
            u[c] += U.local_element(layout->index(cell, c, k)) * L[k];
        return u;
      }

      /// U at any theta in [0, theta_w] (the left cell at a face)
      System::State<double>
      value(const dg::VectorType &U, const double theta) const
      {
        const double h = p.theta_w / p.cells;
        const unsigned int j =
          std::min<unsigned int>(static_cast<unsigned int>(std::max(0., theta / h)), p.cells - 1);
        const unsigned int  cell = order[j];
        const double        a    = layout->cell(cell)->vertex(0)[0];
        return value_at(U, cell, dg::legendre_values(degree + 1, std::clamp((theta - a) / h, 0., 1.)));
      }

      /// The monitors of a state (with_psi false: max_psi stays 0). The
      /// largest |psi| and |U - radial| / |radial| take two passes: cheap
      /// estimates at every point (the ratio 2 |T_rt| / (T_tt - T_rr), of
      /// which |psi| is an increasing function, and sqrt(dx^2 + dy^2)), then
      /// atan2() and hypot() only where the estimate is within 1e-9 of the
      /// largest one: the same maxima as evaluating them at every point.
      Monitors
      monitors(const dg::VectorType &U, const double tau, const bool with_psi = true) const
      {
        Monitors     m;
        const double f = radial_factor(tau);
        double       max_rr = 0, max_rt = 0, d_rr = 0, d_rt = 0;
        double       max_ratio = 0, max_estimate = 0;
        scratch.resize(monitor.size());
        for (unsigned int i = 0; i < monitor.size(); ++i)
          {
            const auto  &pt     = monitor[i];
            auto        &sc     = scratch[i];
            const auto   u      = value_at(U, pt.cell, pt.L);
            const double margin = physics.hyperbolicity_margin(u);
            sc.u                = u;
            if (margin < m.margin)
              {
                m.margin       = margin;
                m.theta_margin = pt.theta;
              }
            sc.ratio = -1.; // |psi| not wanted at this point
            if (with_psi && margin > 0 && u[0] > 0)
              {
                const double x = physics.h(u[0], u[1]) - u[0], r = std::abs(2 * u[1]) / x;
                if (x > 0 && r <= 100.)
                  {
                    sc.ratio  = r;
                    max_ratio = std::max(max_ratio, r);
                  }
                else
                  m.max_psi = std::max(m.max_psi, std::abs(physics.psi(u)));
              }
            const double rr = f * pt.radial[0], rt = f * pt.radial[1];
            sc.dx           = u[0] - rr;
            sc.dy           = u[1] - rt;
            sc.norm         = f == 1. ? pt.radial_norm : std::hypot(rr, rt);
            sc.estimate     = std::sqrt(sc.dx * sc.dx + sc.dy * sc.dy) / sc.norm;
            max_estimate    = std::max(max_estimate, sc.estimate);
            d_rr            = std::max(d_rr, std::abs(u[0] - rr));
            d_rt            = std::max(d_rt, std::abs(u[1] - rt));
            max_rr          = std::max(max_rr, std::abs(rr));
            max_rt          = std::max(max_rt, std::abs(rt));
          }
        const double ratio_bound = max_ratio * (1 - 1e-9), estimate_bound = max_estimate * (1 - 1e-9);
        for (const auto &sc : scratch)
          {
            if (sc.ratio >= 0 && sc.ratio >= ratio_bound)
              m.max_psi = std::max(m.max_psi, std::abs(physics.psi(sc.u)));
            if (!(sc.estimate < estimate_bound))
              m.rel_diff = std::max(m.rel_diff, std::hypot(sc.dx, sc.dy) / sc.norm);
          }
        m.rel_rr = d_rr / max_rr;
        m.rel_rt = d_rt / max_rt;
        return m;
      }

      void
      write_stress_profile(const dg::VectorType &U, const double tau)
      {
        const std::string name = directory + "/stress-" +
                                 Utilities::int_to_string(n_profiles++, 4) + ".csv";
        CsvWriter csv;
        csv.open(name,
                 {"theta", "theta_deg", "T_rr_over_r", "T_rtheta_over_r", "T_thetatheta_over_r",
                  "T_phiphi_over_r", "psi_deg", "hyperbolicity_margin", "radial_T_rr_over_r",
                  "radial_T_rtheta_over_r", "radial_T_thetatheta_over_r", "rel_diff_radial"},
                 "tau = " + format_number(tau) + ", r/r0 = " + format_number(std::exp(-tau)) +
                   "; stresses scaled by r in Pa/m (" + geometry_names.name(p.geometry) +
                   ", lower theta_w = " + format_number(p.theta_w / deg) + " deg)");
        const double scale = to_pa_per_m(tau), f = radial_factor(tau);
        for (unsigned int i = 0; i < p.sample_points; ++i)
          {
            const double theta = p.theta_w * i / (p.sample_points - 1.);
            const auto   u     = value(U, theta);
            const double T_tt  = physics.h(u[0], u[1]);
            const auto   R     = lower->stresses(theta);
            const double rel =
              std::hypot(u[0] - f * R[0], u[1] - f * R[1]) / (f * std::hypot(R[0], R[1]));
            csv.row({theta, theta / deg, scale * u[0], scale * u[1], scale * T_tt,
                     scale * physics.phiphi(u[0], T_tt), physics.psi(u) / deg,
                     physics.hyperbolicity_margin(u), p.rho * p.g * R[0], p.rho * p.g * R[1],
                     p.rho * p.g * R[2], rel});
          }
      }

      void
      add_row(const dg::VectorType &U, const double tau)
      {
        Row row;
        row.tau = tau;
        for (unsigned int i = 0; i < p.field_theta_points; ++i)
          row.U.push_back(value(U, p.theta_w * i / (p.field_theta_points - 1.)));
        rows.push_back(std::move(row));
        next_row_tau = tau_end * rows.size() / p.field_rows;
      }

      /// hopper-field.vtu: the marched field (both halves) in x = r sin theta,
      /// z = r cos theta (apex of the lower hopper at the origin, z up the
      /// axis) and, above Gamma_0, the upper hopper's radial field;
      /// hand-written VTU XML (deal.II 9.4.1's 1D writer cannot do this).
      void
      write_field() const
      {
        struct Sample
        {
          double x, z, r, theta, T_rr, T_rt, T_tt, T_pp, psi, margin, rel, region;
        };
        std::vector<std::vector<Sample>> grid_lower, grid_upper;
        const unsigned int               n = p.field_theta_points;
        for (const auto &row : rows)
          {
            const double r = p.r0 * std::exp(-row.tau), f = radial_factor(row.tau);
            const double scale = r * to_pa_per_m(row.tau); // T in Pa per unit of U
            std::vector<Sample> line;
            for (int i = -int(n) + 1; i < int(n); ++i)
              {
                const unsigned int k     = std::abs(i);
                const double       sign  = i < 0 ? -1. : 1.;
                const double       theta = sign * p.theta_w * k / (n - 1.);
                const auto        &u     = row.U[k];
                const double       T_tt  = physics.h(u[0], u[1]);
                const auto         R     = lower->stresses(theta);
                Sample             s;
                s.x = r * std::sin(theta);
                s.z = r * std::cos(theta);
                s.r = r;
                s.theta = theta;
                s.T_rr  = scale * u[0];
                s.T_rt  = sign * scale * u[1];
                s.T_tt  = scale * T_tt;
                s.T_pp  = scale * physics.phiphi(u[0], T_tt);
                s.psi   = sign * physics.psi(u) / deg;
                s.margin = physics.hyperbolicity_margin(u);
                s.rel = std::hypot(u[0] - f * R[0], u[1] - f * R[1]) / (f * std::hypot(R[0], R[1]));
                s.region = 1;
                line.push_back(s);
              }
            grid_lower.push_back(line);
          }
        if (p.upper_region > 0)
          {
            // rays from the upper apex through the points of Gamma_0, from
            // Gamma_0 up to R = R_0 + upper_region (units of r0)
            const double R_0   = std::sin(p.theta_w) / std::sin(p.Theta_w);
            const double R_top = R_0 + p.upper_region;
            const unsigned int n_up = std::max(2u, p.field_rows / 4);
            for (unsigned int j = 0; j < n_up; ++j)
              {
                std::vector<Sample> line;
                for (int i = -int(n) + 1; i < int(n); ++i)
                  {
                    const double sign  = i < 0 ? -1. : 1.;
                    const double theta = sign * p.theta_w * std::abs(i) / (n - 1.);
                    const auto [R_g, Theta] = transition.upper_coordinates(1., theta);
                    const double R = R_top + (R_g - R_top) * j / (n_up - 1.);
                    const auto   T = upper->stresses(Theta);
                    const double sc = p.rho * p.g * p.r0 * R;
                    Sample s;
                    s.x = p.r0 * R * std::sin(Theta);
                    s.z = p.r0 * (transition.upper_apex_z() + R * std::cos(Theta));
                    s.r = p.r0 * R;
                    s.theta = Theta;
                    s.T_rr = sc * T[0];
                    s.T_rt = sc * T[1];
                    s.T_tt = sc * T[2];
                    s.T_pp = sc * T[3];
                    s.psi = upper->psi(Theta) / deg;
                    s.margin = physics.hyperbolicity_margin(System::State<double>({T[0], T[1]}));
                    s.rel = 0;
                    s.region = 0;
                    line.push_back(s);
                  }
                grid_upper.push_back(line);
              }
          }

        // the lower field also as CSV (one row per tau and theta >= 0)
        {
          CsvWriter csv;
          csv.open(directory + "/hopper-field.csv",
                   {"tau", "theta_deg", "x", "z", "T_rr_over_r", "T_rtheta_over_r",
                    "T_thetatheta_over_r", "psi_deg", "hyperbolicity_margin",
                    "rel_diff_radial"},
                   "the marched field (Pa/m), rows of hopper-field.vtu");
          for (unsigned int j = 0; j < grid_lower.size(); ++j)
            for (unsigned int i = n - 1; i < grid_lower[j].size(); ++i)
              {
                const Sample &q = grid_lower[j][i];
                csv.row({rows[j].tau, q.theta / deg, q.x, q.z, q.T_rr / q.r, q.T_rt / q.r,
                         q.T_tt / q.r, q.psi, q.margin, q.rel});
              }
        }
        std::ofstream out(directory + "/hopper-field.vtu");
        out << std::setprecision(10);
        out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
               "byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n";
        auto piece = [&](const std::vector<std::vector<Sample>> &grid) {
          if (grid.size() < 2)
            return;
          const unsigned int nr = grid.size(), nc = grid.front().size();
          out << "<Piece NumberOfPoints=\"" << nr * nc << "\" NumberOfCells=\""
              << (nr - 1) * (nc - 1) << "\">\n<Points>\n<DataArray type=\"Float64\" "
              << "NumberOfComponents=\"3\" format=\"ascii\">\n";
          for (const auto &line : grid)
            for (const auto &s : line)
              out << s.x << ' ' << s.z << " 0\n";
          out << "</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" "
                 "Name=\"connectivity\" format=\"ascii\">\n";
          for (unsigned int j = 0; j + 1 < nr; ++j)
            for (unsigned int i = 0; i + 1 < nc; ++i)
              out << j * nc + i << ' ' << j * nc + i + 1 << ' ' << (j + 1) * nc + i + 1 << ' '
                  << (j + 1) * nc + i << '\n';
          out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
          for (unsigned int c = 1; c <= (nr - 1) * (nc - 1); ++c)
            out << 4 * c << '\n';
          out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
          for (unsigned int c = 0; c < (nr - 1) * (nc - 1); ++c)
            out << "9\n";
          out << "</DataArray>\n</Cells>\n<PointData Scalars=\"T_rr_over_r\">\n";
          auto array = [&](const char *name, auto get) {
            out << "<DataArray type=\"Float64\" Name=\"" << name << "\" format=\"ascii\">\n";
            for (const auto &line : grid)
              for (const auto &s : line)
                out << get(s) << '\n';
            out << "</DataArray>\n";
          };
          // Cartesian components of T (frame independent: continuous across Gamma_0)
          auto cart = [](const Sample &s, const int which) {
            const double sn = std::sin(s.theta), cs = std::cos(s.theta);
            if (which == 0)
              return s.T_rr * sn * sn + 2 * s.T_rt * sn * cs + s.T_tt * cs * cs;
            if (which == 1)
              return s.T_rr * cs * cs - 2 * s.T_rt * sn * cs + s.T_tt * sn * sn;
            return (s.T_rr - s.T_tt) * sn * cs + s.T_rt * (cs * cs - sn * sn);
          };
          array("T_rr_over_r", [](const Sample &s) { return s.T_rr / s.r; });
          array("T_rtheta_over_r", [](const Sample &s) { return s.T_rt / s.r; });
          array("T_thetatheta_over_r", [](const Sample &s) { return s.T_tt / s.r; });
          array("T_phiphi_over_r", [](const Sample &s) { return s.T_pp / s.r; });
          array("T_rr", [](const Sample &s) { return s.T_rr; });
          array("T_rtheta", [](const Sample &s) { return s.T_rt; });
          array("T_thetatheta", [](const Sample &s) { return s.T_tt; });
          array("T_xx", [&](const Sample &s) { return cart(s, 0); });
          array("T_zz", [&](const Sample &s) { return cart(s, 1); });
          array("T_xz", [&](const Sample &s) { return cart(s, 2); });
          array("mean_stress_over_r", [](const Sample &s) { return 0.5 * (s.T_rr + s.T_tt) / s.r; });
          array("psi_deg", [](const Sample &s) { return s.psi; });
          array("hyperbolicity_margin", [](const Sample &s) { return s.margin; });
          array("rel_diff_radial", [](const Sample &s) { return s.rel; });
          array("region", [](const Sample &s) { return s.region; });
          out << "</PointData>\n</Piece>\n";
        };
        piece(grid_upper);
        piece(grid_lower);
        out << "</UnstructuredGrid>\n</VTKFile>\n";
        out.close();
        write_pvd(directory + "/hopper-field.pvd", {{0., "hopper-field.vtu"}});
      }

      const Parameters                    p;
      const System                        physics;
      std::shared_ptr<const RadialField>  lower, upper;
      const Transition                    transition;
      const std::string                   directory;
      const double                        tau_end;
      const unsigned int                  degree;
      const bool                          write_vtu;
      const dg::ModalLayout<1>           *layout = nullptr;
      std::vector<unsigned int>           order;
      std::vector<MonitorPoint>           monitor;
      mutable std::vector<MonitorScratch> scratch;
      CsvWriter                           steps;
      unsigned int                        n_profiles = 0;
      std::vector<Row>                    rows;
      double                              next_row_tau = 0;
      double min_margin = INFINITY, tau_min_margin = 0, theta_min_margin = 0, max_rel = 0,
             final_rel = 0;
    };

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
      auto hooks = std::make_shared<HopperHooks>(p, physics, lower, upper,
                                                 common.scene_directory(), common.final_time,
                                                 method.degree, common.write_vtu);
      scene.hooks = hooks;

      require_reasonable_snapshot_count(
        common, dg::snapshot_bytes(p.cells, method.degree, 1, 6, common.write_vtu));
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
    declare_all(ParameterHandler &prm)
    {
      RunParameters::declare(prm);
      dg::DiscretizationParameters::declare(prm, numerical_flux_names.selection());
      declare(prm);
    }

    void
    run(ParameterHandler &prm)
    {
      RunParameters common;
      common.parse(prm);
      dg::DiscretizationParameters method;
      method.parse(prm, common);
      const Parameters p = parse(prm);
      require(!common.resume || p.mode == Mode::march, "Checkpoint/resume", "true",
              "false in Hopper/mode = " + mode_names.name(p.mode) +
                " (it has no time loop to continue)");
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

    const RegisterScene registration(
      {"hopper",
       "steady Mohr-Coulomb stresses in a wedge or cone hopper, marched in tau = -ln(r/r0) "
       "(Gremaud & Matthews); radial fields, wall-angle transitions, the Fig. 9 scan",
       declare_all, run});
  } // namespace
} // namespace granular_dg::hopper
