#include <granular_dg/equations/hopper/transition.h>

#include <boost/math/tools/roots.hpp>

#include <cmath>
#include <functional>
#include <sstream>

namespace granular_dg::hopper
{
  Transition::Transition(const RadialField &upper, const MohrCoulomb &material,
                         const double theta_w)
    : upper(upper)
    , material(material)
    , lower_angle(theta_w)
  {
    const double R_0 = std::sin(theta_w) / std::sin(upper.theta_w());
    z_u              = std::cos(theta_w) - R_0 * std::cos(upper.theta_w());
  }

  std::pair<double, double>
  Transition::upper_coordinates(const double r, const double theta) const
  {
    const double x = r * std::sin(theta), z = r * std::cos(theta) - z_u;
    return {std::hypot(x, z), std::atan2(x, z)};
  }

  std::array<double, 3>
  Transition::initial_stress(const double theta) const
  {
    const auto [R, Theta] = upper_coordinates(1., theta);
    const auto T          = upper.stresses(Theta);
    auto       t          = rotate_stress(T[0], T[1], T[2], Theta - theta);
    for (auto &c : t)
      c *= R;
    return t;
  }

  Transition::Check
  Transition::check(const unsigned int n_samples) const
  {
    Check        result;
    const double limit = material.hyperbolic_limit();
    for (unsigned int i = 0; i < n_samples; ++i)
      {
        const double theta = lower_angle * i / (n_samples - 1.);
        const double Theta = upper_coordinates(1., theta).second;
        const auto   T     = initial_stress(theta);
        const double psi   = sokolovskii_angle(T[0], T[1], T[2]);
        std::ostringstream why;
        why.precision(6);
        if (Theta > upper.theta_w() * (1 + 1e-9) + 1e-12)
          why << "the point lies outside the upper hopper (Theta = " << Theta / deg
              << " deg > Theta_w)";
        else if (!(T[0] > 0))
          why << "T_rr = " << T[0] << " <= 0";
        else if (!(std::abs(psi) < limit))
          why << "|psi| = " << std::abs(psi) / deg << " deg >= pi/4 - delta/2 = " << limit / deg
              << " deg: the rotated tensor is not hyperbolic in tau (or not on the branch "
                 "T_thetatheta = h(T_rr, T_rtheta))";
        result.max_abs_psi = std::max(result.max_abs_psi, std::abs(psi));
        if (!why.str().empty())
          {
            result.ok     = false;
            result.reason = why.str();
            result.theta  = theta;
            result.stress = T;
            break;
          }
        if (std::abs(psi) >= result.max_abs_psi)
          {
            result.theta  = theta;
            result.stress = T;
          }
      }
    return result;
  }

  ScanResult
  scan_transitions(const Geometry geometry, const MohrCoulomb &material, const double from,
                   const double to, const double step)
  {
    ScanResult   result;
    const double eps = material.hyperbolic_limit();

    // the admissible lower angles of one upper field: bisection of the
    // boundary on each side of Theta_w (the set is taken to be an interval)
    auto boundary = [&](const RadialField &field, double ok_angle, double bad_angle) {
      auto ok = [&](const double a) {
        return Transition(field, material, a).check(801).ok;
      };
      if (ok(bad_angle))
        return bad_angle;
      for (unsigned int it = 0; it < 45; ++it)
        {
          const double mid = 0.5 * (ok_angle + bad_angle);
          (ok(mid) ? ok_angle : bad_angle) = mid;
        }
      return 0.5 * (ok_angle + bad_angle);
    };

    for (unsigned int k = 0;; ++k)
      {
        const double Theta = from + k * step;
        if (Theta > to * (1 + 1e-12))
          break;
        ScanRow row{};
        row.Theta_w = Theta;
        try
          {
            const RadialField field(geometry, material, Theta * deg, 1024);
            row.max_psi          = field.max_psi() / deg;
            row.theta_of_max_psi = field.theta_of_max_psi() / deg;
            row.dpsi_wall        = field.psi_derivative_at_wall();
            const double room    = eps - field.max_psi();
            row.lambda_max       = room > 0 ? 1. / std::tan(room) : INFINITY;
            row.bound            = room > 0 ? std::atan(1. / row.lambda_max) / deg : 0.;
            row.theta_min_C      = Theta - row.bound;
            if (Transition(field, material, Theta * deg).check(801).ok)
              {
                row.lo = boundary(field, Theta * deg, 1e-3 * deg) / deg;
                row.hi = boundary(field, Theta * deg, 89.999 * deg) / deg;
              }
            else
              row.lo = row.hi = NAN;
          }
        catch (const NoRadialField &)
          {
            result.no_radial_field_from = Theta;
            break;
          }
        result.rows.push_back(row);
      }

    // refine the two critical upper angles between scan rows
    auto refine = [&](const std::function<double(const ScanRow &)> &value,
                      const std::function<double(double)>          &f) {
      for (unsigned int i = 0; i + 1 < result.rows.size(); ++i)
        if ((value(result.rows[i]) < 0) != (value(result.rows[i + 1]) < 0))
          {
            boost::uintmax_t iterations = 100;
            const auto       b          = boost::math::tools::toms748_solve(
              f, result.rows[i].Theta_w, result.rows[i + 1].Theta_w,
              boost::math::tools::eps_tolerance<double>(40), iterations);
            return 0.5 * (b.first + b.second);
          }
      return double(NAN);
    };
    result.monotone_up_to = refine([](const ScanRow &r) { return r.dpsi_wall; },
                                   [&](const double Theta) {
                                     return RadialField(geometry, material, Theta * deg, 1024)
                                       .psi_derivative_at_wall();
                                   });
    result.zero_transition_at = refine([&](const ScanRow &r) { return r.max_psi - eps / deg; },
                                       [&](const double Theta) {
                                         return RadialField(geometry, material, Theta * deg,
                                                            4096)
                                                  .max_psi() -
                                                eps;
                                       });
    return result;
  }
} // namespace granular_dg::hopper
