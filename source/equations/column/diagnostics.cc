#include <deal.II/base/quadrature_lib.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <granular_dg/base/output.h>
#include <granular_dg/equations/column/diagnostics.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace granular_dg::column
{
  namespace
  {
    /// Everything the scene measures along the way.
    class ColumnDiagnostics : public dg::SceneHooks<1>
    {
    public:
      /// directory empty: write nothing (convergence studies); friction: the
      /// stage operation whose stuck cells and multipliers are reported
      ColumnDiagnostics(const System &system, const ColumnParameters &prm,
                        const double final_time, const std::string &directory,
                        const FrictionHooks &friction)
        : system(system)
        , prm(prm)
        , friction(friction)
        , sigma_b(system.stress(prm.u_b))
        , sample_dt(prm.sample_dt > 0 ? prm.sample_dt : final_time / 400.)
        , directory(directory)
      {}

      ~ColumnDiagnostics() override
      {
        if (sgn_map_file)
          std::fclose(sgn_map_file);
      }

      void
      initialize(const DoFHandler<1> &, const Mapping<1> &,
                 const dg::ModalLayout<1> &cell_layout) override
      {
        layout = &cell_layout;
        const unsigned int n = cell_layout.n_owned();
        center.resize(n);
        for (unsigned int c = 0; c < n; ++c)
          center[c] = cell_layout.cell(c)->center()[0];
        h = cell_layout.extent(0, 0);
        previous_sign.assign(n, 0);
        moving.assign(n, 1);
        previous_state.assign(n, FrictionProjection::CellState::unloaded);
        // values at the cell centre and at the left end, per mode
        const unsigned int n1d = cell_layout.degree() + 1;
        at_center              = dg::legendre_values(n1d, 0.5);
        at_left                = dg::legendre_values(n1d, 0.);
        const QGauss<1> q(n1d + 2);
        q_weights = q.get_weights();
        for (unsigned int i = 0; i < q.size(); ++i)
          q_basis.push_back(dg::legendre_values(n1d, q.point(i)[0]));

        // written row by row, so that a long run can be watched (and a failed
        // one keeps its history); a resumed run continues them in load()
        if (directory.empty() || resuming())
          return;
        history_file.open(directory + "/history.csv",
                          {"time", "max_velocity", "front_position", "front_strain",
                           "front_velocity", "stop_front", "stuck_cells", "max_stuck_multiplier",
                           "energy", "friction_work", "wall_work", "probe_strain",
                           "critical_loadings"});
        if (prm.write_sgn_map)
          {
            claim_output_file(directory + "/sgn-map.csv");
            sgn_map_file = std::fopen((directory + "/sgn-map.csv").c_str(), "w");
            require_written(sgn_map_file != nullptr, directory + "/sgn-map.csv");
            std::fprintf(sgn_map_file,
                         "# sgn(v) per cell (columns: cell centres z), one row per sample time\n");
            std::fprintf(sgn_map_file, "time");
            for (const double z : center)
              std::fprintf(sgn_map_file, ",%.8g", z);
            std::fprintf(sgn_map_file, "\n");
          }
      }

      void
      end_of_step(const dg::VectorType &U, const double t, const double dt,
                  const unsigned long) override
      {
        // the cells the step computed (with skipped cells: no other changed)
        dg::for_active_ranges(active_cells(), layout->n_owned(),
                              [&](const unsigned int first, const unsigned int end) {
                                for (unsigned int c = first; c < end; ++c)
                                  watch_cell(U, c, t);
                              });

        // friction and wall work: int |v| sigma dz dt and sigma_b v(0) dt;
        // cells at rest (all velocity modes 0, e.g. stuck) add exactly 0
        const double friction_power = integrate(
          U, [&](const double u, const double v) { return std::abs(v) * system.stress(u); },
          [&](const unsigned int c) { return moving[c] != 0; });
        double v_wall = 0;
        for (unsigned int k = 0; k <= layout->degree(); ++k)
          v_wall += U.local_element(layout->index(0, 1, k)) * at_left[k];
        friction_work += dt * friction_power;
        wall_work += dt * sigma_b * v_wall;

        if (t >= next_sample - 1e-12 * sample_dt)
          {
            sample(U, t);
            next_sample += sample_dt;
          }
      }

      void
      save(ByteWriter &w) override
      {
        std::uint64_t history_size = history_file.is_open() ? history_file.size() : 0;
        std::uint64_t sgn_map_size = 0;
        if (sgn_map_file)
          {
            std::fflush(sgn_map_file);
            sgn_map_size = std::ftell(sgn_map_file);
          }
        state_io(w, history_size, sgn_map_size);
      }

      void
      load(ByteReader &r) override
      {
        std::uint64_t history_size = 0, sgn_map_size = 0;
        state_io(r, history_size, sgn_map_size);
        if (directory.empty())
          return;
        history_file.reopen(directory + "/history.csv", history_size);
        if (prm.write_sgn_map)
          {
            const std::string name = directory + "/sgn-map.csv";
            truncate_file(name, sgn_map_size);
            sgn_map_file = std::fopen(name.c_str(), "a");
          }
      }

      std::vector<std::string>
      timeseries_names() const override
      {
        return {"max_velocity", "front_position", "front_strain", "front_velocity",
                "stop_front",   "stuck_cells",    "max_stuck_multiplier", "friction_work",
                "wall_work"};
      }

      std::vector<double>
      timeseries_values(const dg::VectorType &U, double) override
      {
        const Fronts f = fronts(U);
        return {f.max_velocity, f.position,        f.strain,         f.velocity,    f.stop,
                double(f.n_stuck), f.max_multiplier, friction_work, wall_work};
      }

      void
      finish(const dg::VectorType &U, const double t, JsonObject &diagnostics,
             const std::string &directory, const bool write_files) override
      {
        if (history.empty() || history.back()[0] < t)
          sample(U, t);
        const Fronts f = fronts(U);
        diagnostics.add("max_velocity", f.max_velocity);
        diagnostics.add("front_position", f.position);
        diagnostics.add("front_strain", f.strain);
        diagnostics.add("front_velocity", f.velocity);
        diagnostics.add("stop_front", f.stop);
        double extent = 0;
        for (const auto &row : history)
          extent = std::max(extent, row[2]);
        diagnostics.add("disturbance_extent", extent);
        // the strain at the probe over the second half of the run: material
        // at rest must keep its strain (0 when the probe is stuck)
        {
          unsigned int half = 0;
          for (unsigned int r = 0; r < history.size(); ++r)
            if (std::abs(history[r][0] - 0.5 * t) < std::abs(history[half][0] - 0.5 * t))
              half = r;
          diagnostics.add("probe_strain_drift", history.back()[11] - history[half][11]);
        }
        diagnostics.add("length", prm.length);
        diagnostics.add("friction_work", friction_work);
        diagnostics.add("wall_work", wall_work);
        diagnostics.add("velocity_sign_flips", static_cast<long long>(velocity_sign_flips));
        diagnostics.add("velocity_chatter_detected",
                        static_cast<long long>(velocity_sign_flips > 0 ? 1 : 0));
        if (system.parameters().friction == FrictionTreatment::projection)
          {
            diagnostics.add("max_stuck_velocity", max_stuck_velocity);
            diagnostics.add("max_stuck_multiplier", max_stuck_multiplier);
            diagnostics.add("stuck_multiplier_in_bounds",
                            static_cast<long long>(max_stuck_multiplier <= 1. ? 1 : 0));
            diagnostics.add("critical_loadings", static_cast<long long>(critical_loadings));
            diagnostics.add("first_critical_loading_time", first_critical_time);
            diagnostics.add("first_critical_loading_position", first_critical_position);
            diagnostics.add("last_critical_loading_time", last_critical_time);
          }
        rankine_hugoniot(diagnostics);
        stationary_comparison(U, diagnostics, directory, write_files);
        if (sgn_map_file)
          require_written(std::fflush(sgn_map_file) == 0 && !std::ferror(sgn_map_file),
                          directory + "/sgn-map.csv");
      }

    private:
      struct Fronts
      {
        double       max_velocity = 0, position = 0, strain = 0, velocity = 0, stop = 0;
        double       max_multiplier = 0;
        unsigned int n_stuck        = 0;
      };

      double
      mode_value(const dg::VectorType &U, const unsigned int c, const unsigned int comp,
                 const std::vector<double> &basis_values) const
      {
        return layout->value(U, c, comp, {{basis_values.data()}});
      }

      /// The sign flips, stuck cells and critical loadings of cell c after a
      /// step, and whether it moves (a velocity mode is not 0).
      void
      watch_cell(const dg::VectorType &U, const unsigned int c, const double t)
      {
        bool is_moving = false;
        for (unsigned int k = 0; k < layout->n_modes(); ++k)
          is_moving |= U.local_element(layout->index(c, 1, k)) != 0.;
        moving[c] = is_moving;
        // only the disturbed region counts: ahead of the front the scheme
        // leaves round-off-sized velocities of either sign
        if (std::abs(U.local_element(layout->index(c, 0, 0))) <= prm.threshold * std::abs(prm.u_b))
          return;
        const double v0   = U.local_element(layout->index(c, 1, 0));
        const int    sign = v0 > 0 ? 1 : (v0 < 0 ? -1 : 0);
        if (sign * previous_sign[c] < 0)
          ++velocity_sign_flips;
        previous_sign[c] = sign;
        if (!friction.implicit())
          return;
        const auto &state = friction.state().states();
        if (state[c] == FrictionProjection::CellState::stuck)
          {
            for (unsigned int k = 0; k < layout->n_modes(); ++k)
              max_stuck_velocity =
                std::max(max_stuck_velocity, std::abs(U.local_element(layout->index(c, 1, k))));
            max_stuck_multiplier =
              std::max(max_stuck_multiplier, std::abs(friction.state().multipliers()[c]));
          }
        // a stuck cell that starts to slide again: critical loading
        if (previous_state[c] == FrictionProjection::CellState::stuck &&
            state[c] == FrictionProjection::CellState::sliding)
          {
            ++critical_loadings;
            if (first_critical_time < 0)
              {
                first_critical_time     = t;
                first_critical_position = center[c];
              }
            last_critical_time = t;
          }
        previous_state[c] = state[c];
      }

      /// The integral of density(u, v) over the cells c with keep(c) (the
      /// cells where it does not vanish: the sum is the same to the last bit).
      template <typename Density, typename Keep>
      double
      integrate(const dg::VectorType &U, const Density &density, const Keep &keep) const
      {
        double sum = 0;
        for (unsigned int c = 0; c < layout->n_owned(); ++c)
          {
            if (!keep(c))
              continue;
            for (unsigned int i = 0; i < q_weights.size(); ++i)
              sum += q_weights[i] * h *
                     density(mode_value(U, c, 0, q_basis[i]), mode_value(U, c, 1, q_basis[i]));
          }
        return sum;
      }

      /// The pressure front (the steepest drop of |u| at the leading edge),
      /// the strain and velocity just behind it (extrapolated with a parabola
      /// from the cells 8 to 20 cells behind, outside the smeared zone), and the stopping front
      /// (the right end of the rest region behind it).
      Fronts
      fronts(const dg::VectorType &U) const
      {
        Fronts             f;
        const unsigned int n   = layout->n_owned();
        const double       tol = prm.threshold * std::abs(prm.u_b);
        const auto        &state    = friction.state().states();
        const bool         implicit = friction.implicit();
        std::vector<double> u(n), v(n);
        int                 last = -1;
        for (unsigned int c = 0; c < n; ++c)
          {
            u[c]           = U.local_element(layout->index(c, 0, 0));
            v[c]           = U.local_element(layout->index(c, 1, 0));
            f.max_velocity = std::max(f.max_velocity, mode_value(U, c, 1, at_center));
            if (std::abs(u[c]) > tol)
              last = c;
            if (implicit && state[c] == FrictionProjection::CellState::stuck)
              {
                ++f.n_stuck;
                f.max_multiplier = std::max(f.max_multiplier,
                                            std::abs(friction.state().multipliers()[c]));
              }
          }
        if (last < 0)
          return f;
        // the front: the steepest drop of the cell averages near the leading
        // edge (within 20 cells behind the last disturbed cell), placed at the
        // face between the two cells
        int    i     = last;
        double steep = 0;
        for (int c = std::max(0, last - 20); c < last && c + 1 < int(n); ++c)
          if (std::abs(u[c]) - std::abs(u[c + 1]) > steep)
            {
              steep = std::abs(u[c]) - std::abs(u[c + 1]);
              i     = c;
            }
        f.position = center[i] + 0.5 * h;
        // least-squares parabola through the cell averages 8 to 20 cells
        // behind (outside the zone the scheme smears), extrapolated to the front
        const int first = std::max(0, i - 20), end = std::max(first + 1, i - 7);
        f.strain        = extrapolate(u, first, end, f.position);
        f.velocity      = extrapolate(v, first, end, f.position);
        // stopping front: the first cell at rest left of the front
        for (int c = i; c >= 0; --c)
          if (implicit ? state[c] == FrictionProjection::CellState::stuck : v[c] <= 0.)
            {
              f.stop = center[c] + 0.5 * h;
              break;
            }
        return f;
      }

      /// The value at z0 of the least-squares polynomial of degree <= 2
      /// through the cell averages y[first..end) at the cell centres (a
      /// lower degree when there are too few cells).
      double
      extrapolate(const std::vector<double> &y, const int first, const int end,
                  const double z0) const
      {
        const int    n_points = end - first;
        const int    degree   = std::min(2, n_points - 1);
        FullMatrix<double> A(degree + 1, degree + 1);
        Vector<double>     b(degree + 1), x(degree + 1);
        for (int c = first; c < end; ++c)
          {
            // scaled coordinate, so that the normal equations stay well conditioned
            const double z = (center[c] - z0) / (20 * h);
            double       zi = 1;
            for (int r = 0; r <= degree; ++r, zi *= z)
              {
                double zj = 1;
                for (int k = 0; k <= degree; ++k, zj *= z)
                  A(r, k) += zi * zj;
                b(r) += zi * y[c];
              }
          }
        A.gauss_jordan();
        A.vmult(x, b);
        return x(0);
      }

      /// The running state of a checkpoint (save/load), and the sizes of
      /// the files appended to.
      template <typename Archive>
      void
      state_io(Archive &ar, std::uint64_t &history_size, std::uint64_t &sgn_map_size)
      {
        ar.io(previous_sign);
        ar.io(previous_state);
        ar.io(velocity_sign_flips);
        ar.io(critical_loadings);
        ar.io(max_stuck_velocity);
        ar.io(max_stuck_multiplier);
        ar.io(first_critical_time);
        ar.io(first_critical_position);
        ar.io(last_critical_time);
        ar.io(friction_work);
        ar.io(wall_work);
        ar.io(next_sample);
        ar.io(history);
        ar.io(history_size);
        ar.io(sgn_map_size);
      }

      void
      sample(const dg::VectorType &U, const double t)
      {
        const Fronts f = fronts(U);
        const double energy =
          integrate(U, [&](const double u, const double v) { return 0.5 * v * v + system.stored_energy(u); },
                    [](unsigned int) { return true; });
        // strain at the probe point
        const unsigned int probe = std::min(layout->n_owned() - 1,
                                            static_cast<unsigned int>(std::max(0., prm.probe / h)));
        history.push_back({t, f.max_velocity, f.position, f.strain, f.velocity, f.stop,
                           double(f.n_stuck), f.max_multiplier, energy, friction_work,
                           wall_work, mode_value(U, probe, 0, at_center),
                           double(critical_loadings)});
        if (history_file.is_open())
          history_file.row(history.back());
        if (sgn_map_file)
          {
            const bool implicit = system.parameters().friction == FrictionTreatment::projection;
            std::fprintf(sgn_map_file, "%.10g", t);
            for (unsigned int c = 0; c < layout->n_owned(); ++c)
              {
                const double v0 = U.local_element(layout->index(c, 1, 0));
                std::fprintf(sgn_map_file, ",%.5g",
                             implicit ? friction.state().multipliers()[c] : double((v0 > 0) - (v0 < 0)));
              }
            std::fprintf(sgn_map_file, "\n");
          }
      }

      /// The front speed from the history (central differences of the front
      /// position) against the Rankine-Hugoniot speed |u_L|^{(m-1)/2}, and
      /// v_L^2 against |u_L|^{m+1} (2.10)-(2.11), at the last sample whose
      /// neighbours are in the history.
      void
      rankine_hugoniot(JsonObject &diagnostics) const
      {
        if (history.size() < 3)
          return;
        const auto  &a = history[history.size() - 3];
        const auto  &b = history[history.size() - 2];
        const auto  &c = history[history.size() - 1];
        const double speed = (c[2] - a[2]) / (c[0] - a[0]);
        const double m     = system.parameters().m;
        const double uL = std::abs(b[3]), vL = b[4];
        diagnostics.add("front_speed", speed);
        diagnostics.add("front_speed_over_rankine_hugoniot",
                        speed / std::pow(uL, 0.5 * (m - 1.)));
        diagnostics.add("front_velocity_squared_over_rankine_hugoniot",
                        vL * vL / std::pow(uL, m + 1.));
      }

      /// Final strain beside Janssen's profile and beside the stationary
      /// problem (4.1)-(4.2) integrated with the final sgn(v) per cell, over
      /// the disturbed region.
      void
      stationary_comparison(const dg::VectorType &U, JsonObject &diagnostics,
                            const std::string &directory, const bool write_files) const
      {
        const double       G   = system.parameters().gravity;
        const double       m   = system.parameters().m;
        const double       tol = prm.threshold * std::abs(prm.u_b);
        const unsigned int n   = layout->n_owned();
        const auto        &s   = friction.state().multipliers();
        auto               strain_of = [&](const double sigma) {
          return -std::pow(std::max(sigma, 0.), 1. / m);
        };
        // d sigma/dz = G - s sigma over a piece of constant s
        auto step = [&](const double sigma, const double sc, const double dz) {
          if (std::abs(sc) < 1e-14)
            return sigma + G * dz;
          return G / sc + (sigma - G / sc) * std::exp(-sc * dz);
        };
        std::FILE *out = nullptr;
        if (write_files)
          {
            claim_output_file(directory + "/final-profile.csv");
            out = std::fopen((directory + "/final-profile.csv").c_str(), "w");
            require_written(out != nullptr, directory + "/final-profile.csv");
            std::fprintf(out, "z,strain,strain_janssen,strain_auxiliary,sgn_v\n");
          }
        double sigma = sigma_b, max_j = 0, max_a = 0, l2_j = 0, l2_a = 0;
        for (unsigned int c = 0; c < n; ++c)
          {
            const double sc    = system.parameters().friction == FrictionTreatment::projection ?
                                   s[c] :
                                   (U.local_element(layout->index(c, 1, 0)) > 0 ? 1. : 0.);
            const double s_mid = step(sigma, sc, 0.5 * h);
            sigma              = step(s_mid, sc, 0.5 * h);
            const double z     = center[c];
            const double u     = mode_value(U, c, 0, at_center);
            const double u_j   = strain_of((sigma_b - G) * std::exp(-z) + G);
            const double u_a   = strain_of(s_mid);
            if (out)
              std::fprintf(out, "%.12g,%.12g,%.12g,%.12g,%.12g\n", z, u, u_j, u_a, sc);
            if (std::abs(U.local_element(layout->index(c, 0, 0))) <= tol)
              continue;
            max_j = std::max(max_j, std::abs(u - u_j));
            max_a = std::max(max_a, std::abs(u - u_a));
            l2_j += h * (u - u_j) * (u - u_j);
            l2_a += h * (u - u_a) * (u - u_a);
          }
        if (out)
          require_written(std::fclose(out) == 0, directory + "/final-profile.csv");
        diagnostics.add("janssen_max_difference", max_j);
        diagnostics.add("janssen_l2_difference", std::sqrt(l2_j));
        diagnostics.add("auxiliary_max_difference", max_a);
        diagnostics.add("auxiliary_l2_difference", std::sqrt(l2_a));
      }

      const System           system;
      const ColumnParameters prm;
      const FrictionHooks   &friction;
      const double           sigma_b, sample_dt;

      const dg::ModalLayout<1>        *layout = nullptr;
      std::vector<double>              center, at_center, at_left, q_weights;
      std::vector<std::vector<double>> q_basis;
      double                           h = 1.;

      std::vector<int>                           previous_sign;
      /// per cell: a velocity mode is not 0 (after the last step that computed it)
      std::vector<unsigned char>                 moving;
      std::vector<FrictionProjection::CellState> previous_state;
      unsigned long long                         velocity_sign_flips = 0, critical_loadings = 0;
      double max_stuck_velocity = 0, max_stuck_multiplier = 0;
      double first_critical_time = -1, first_critical_position = -1, last_critical_time = -1;
      double friction_work = 0, wall_work = 0;

      const std::string                directory;
      double                           next_sample = 0;
      std::vector<std::vector<double>> history;
      CsvWriter                        history_file;
      std::FILE                       *sgn_map_file = nullptr;
    };
  } // namespace

  std::shared_ptr<dg::SceneHooks<1>>
  make_diagnostics(const System &system, const ColumnParameters &prm, const double final_time,
                   const std::string &directory, const FrictionHooks &friction)
  {
    return std::make_shared<ColumnDiagnostics>(system, prm, final_time, directory, friction);
  }
} // namespace granular_dg::column
