#include <deal.II/base/data_out_base.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/grid/reference_cell.h>

#include <granular_dg/base/output.h>
#include <granular_dg/equations/hopper/diagnostics.h>
#include <granular_dg/equations/hopper/transition.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>

namespace granular_dg::hopper
{
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


  namespace
  {
    /// One point of hopper-field.vtu: position, stresses in Pa, the angles.
    struct FieldSample
    {
      double x, z, r, theta, T_rr, T_rt, T_tt, T_pp, psi, margin, rel, region;
    };

    /// The fields of hopper-field.vtu at a point (the Cartesian components
    /// of T are frame independent: continuous across Gamma_0).
    std::vector<double>
    field_values(const FieldSample &s)
    {
      const double sn = std::sin(s.theta), cs = std::cos(s.theta);
      return {s.T_rr / s.r,
              s.T_rt / s.r,
              s.T_tt / s.r,
              s.T_pp / s.r,
              s.T_rr,
              s.T_rt,
              s.T_tt,
              s.T_rr * sn * sn + 2 * s.T_rt * sn * cs + s.T_tt * cs * cs,
              s.T_rr * cs * cs - 2 * s.T_rt * sn * cs + s.T_tt * sn * sn,
              (s.T_rr - s.T_tt) * sn * cs + s.T_rt * (cs * cs - sn * sn),
              0.5 * (s.T_rr + s.T_tt) / s.r,
              s.psi,
              s.margin,
              s.rel,
              s.region};
    }

    /// hopper-field.vtu through deal.II's DataOutBase: every quadrilateral
    /// of the grids (rows of points) a patch in the (x, z) plane.
    void
    write_field_vtu(const std::string &directory,
                    const std::vector<std::vector<std::vector<FieldSample>>> &grids)
    {
      const std::vector<std::string> names{
        "T_rr_over_r", "T_rtheta_over_r", "T_thetatheta_over_r", "T_phiphi_over_r", "T_rr",
        "T_rtheta",    "T_thetatheta",    "T_xx",                "T_zz",            "T_xz",
        "mean_stress_over_r", "psi_deg",  "hyperbolicity_margin", "rel_diff_radial", "region"};
      std::vector<DataOutBase::Patch<2, 2>> patches;
      for (const auto &grid : grids)
        for (unsigned int j = 0; j + 1 < grid.size(); ++j)
          for (unsigned int i = 0; i + 1 < grid[j].size(); ++i)
            {
              DataOutBase::Patch<2, 2> patch;
              patch.n_subdivisions = 1;
              patch.patch_index    = patches.size();
              patch.reference_cell = ReferenceCells::get_hypercube<2>();
              patch.data.reinit(names.size(), 4);
              // the corners in deal.II's order: (i, j), (i+1, j), (i, j+1), (i+1, j+1)
              const FieldSample *corner[4] = {&grid[j][i], &grid[j][i + 1], &grid[j + 1][i],
                                              &grid[j + 1][i + 1]};
              for (unsigned int v = 0; v < 4; ++v)
                {
                  patch.vertices[v] = Point<2>(corner[v]->x, corner[v]->z);
                  const auto values = field_values(*corner[v]);
                  for (unsigned int k = 0; k < names.size(); ++k)
                    patch.data(k, v) = values[k];
                }
              patches.push_back(patch);
            }
      DataOutBase::VtkFlags flags;
      flags.print_date_and_time = false;
      flags.compression_level   = DataOutBase::VtkFlags::best_speed;
      write_to_file(directory + "/hopper-field.vtu", [&](std::ostream &out) {
        DataOutBase::write_vtu(patches, names, {}, flags, out);
      });
    }

    /**
     * Diagnostics of the march: per step the hyperbolicity margin and the
     * difference to the lower hopper's radial field (hopper-steps.csv), per
     * output tau the stresses T/r in Pa/m (stress-NNNN.csv), at the end the
     * whole marched field in physical coordinates (hopper-field.vtu/.pvd/.csv,
     * unless Output/write vtu is false).
     */
    class HopperDiagnostics : public dg::SceneHooks<1>
    {
    public:
      HopperDiagnostics(const Parameters &p, const System &physics,
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

      /// The field at the points of the stored rows: the lower hopper in
      /// x = r sin theta, z = r cos theta (apex of the lower hopper at the
      /// origin, z up the axis), both halves, and above Gamma_0 the upper
      /// hopper's radial field up to R = R_0 + upper_region.
      std::vector<std::vector<FieldSample>>
      lower_grid() const
      {
        std::vector<std::vector<FieldSample>> grid;
        const unsigned int                    n = p.field_theta_points;
        for (const auto &row : rows)
          {
            const double r = p.r0 * std::exp(-row.tau), f = radial_factor(row.tau);
            const double scale = r * to_pa_per_m(row.tau); // T in Pa per unit of U
            std::vector<FieldSample> line;
            for (int i = -int(n) + 1; i < int(n); ++i)
              {
                const unsigned int k     = std::abs(i);
                const double       sign  = i < 0 ? -1. : 1.;
                const double       theta = sign * p.theta_w * k / (n - 1.);
                const auto        &u     = row.U[k];
                const double       T_tt  = physics.h(u[0], u[1]);
                const auto         R     = lower->stresses(theta);
                FieldSample        s;
                s.x      = r * std::sin(theta);
                s.z      = r * std::cos(theta);
                s.r      = r;
                s.theta  = theta;
                s.T_rr   = scale * u[0];
                s.T_rt   = sign * scale * u[1];
                s.T_tt   = scale * T_tt;
                s.T_pp   = scale * physics.phiphi(u[0], T_tt);
                s.psi    = sign * physics.psi(u) / deg;
                s.margin = physics.hyperbolicity_margin(u);
                s.rel    = std::hypot(u[0] - f * R[0], u[1] - f * R[1]) /
                        (f * std::hypot(R[0], R[1]));
                s.region = 1;
                line.push_back(s);
              }
            grid.push_back(line);
          }
        return grid;
      }

      std::vector<std::vector<FieldSample>>
      upper_grid() const
      {
        std::vector<std::vector<FieldSample>> grid;
        if (p.upper_region <= 0)
          return grid;
        // rays from the upper apex through the points of Gamma_0, from
        // Gamma_0 up to R = R_0 + upper_region (units of r0)
        const unsigned int n     = p.field_theta_points;
        const double       R_0   = std::sin(p.theta_w) / std::sin(p.Theta_w);
        const double       R_top = R_0 + p.upper_region;
        const unsigned int n_up  = std::max(2u, p.field_rows / 4);
        for (unsigned int j = 0; j < n_up; ++j)
          {
            std::vector<FieldSample> line;
            for (int i = -int(n) + 1; i < int(n); ++i)
              {
                const double sign       = i < 0 ? -1. : 1.;
                const double theta      = sign * p.theta_w * std::abs(i) / (n - 1.);
                const auto [R_g, Theta] = transition.upper_coordinates(1., theta);
                const double R          = R_top + (R_g - R_top) * j / (n_up - 1.);
                const auto   T          = upper->stresses(Theta);
                const double sc         = p.rho * p.g * p.r0 * R;
                FieldSample  s;
                s.x      = p.r0 * R * std::sin(Theta);
                s.z      = p.r0 * (transition.upper_apex_z() + R * std::cos(Theta));
                s.r      = p.r0 * R;
                s.theta  = Theta;
                s.T_rr   = sc * T[0];
                s.T_rt   = sc * T[1];
                s.T_tt   = sc * T[2];
                s.T_pp   = sc * T[3];
                s.psi    = upper->psi(Theta) / deg;
                s.margin = physics.hyperbolicity_margin(System::State<double>({T[0], T[1]}));
                s.rel    = 0;
                s.region = 0;
                line.push_back(s);
              }
            grid.push_back(line);
          }
        return grid;
      }

      /// hopper-field.csv: the lower field (Pa/m), one row per tau and theta >= 0
      void
      write_field_csv(const std::vector<std::vector<FieldSample>> &grid) const
      {
        const unsigned int n = p.field_theta_points;
        CsvWriter          csv;
        csv.open(directory + "/hopper-field.csv",
                 {"tau", "theta_deg", "x", "z", "T_rr_over_r", "T_rtheta_over_r",
                  "T_thetatheta_over_r", "psi_deg", "hyperbolicity_margin", "rel_diff_radial"},
                 "the marched field (Pa/m), rows of hopper-field.vtu");
        for (unsigned int j = 0; j < grid.size(); ++j)
          for (unsigned int i = n - 1; i < grid[j].size(); ++i)
            {
              const FieldSample &q = grid[j][i];
              csv.row({rows[j].tau, q.theta / deg, q.x, q.z, q.T_rr / q.r, q.T_rt / q.r,
                       q.T_tt / q.r, q.psi, q.margin, q.rel});
            }
      }

      /// hopper-field.vtu/.pvd/.csv: the marched field and the upper
      /// hopper's, in physical coordinates (write_field_vtu())
      void
      write_field() const
      {
        const auto lower_samples = lower_grid();
        write_field_csv(lower_samples);
        write_field_vtu(directory, {upper_grid(), lower_samples});
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
  } // namespace

  std::shared_ptr<dg::SceneHooks<1>>
  make_diagnostics(const Parameters &p, const System &physics,
                   std::shared_ptr<const RadialField> lower,
                   std::shared_ptr<const RadialField> upper, const std::string &directory,
                   const double tau_end, const unsigned int degree, const bool write_vtu)
  {
    return std::make_shared<HopperDiagnostics>(p, physics, std::move(lower), std::move(upper),
                                               directory, tau_end, degree, write_vtu);
  }
} // namespace granular_dg::hopper
