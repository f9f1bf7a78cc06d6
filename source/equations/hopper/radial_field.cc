#include <granular_dg/base/output.h>
#include <granular_dg/equations/hopper/radial_field.h>

#include <boost/math/tools/roots.hpp>
#include <boost/numeric/odeint.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace granular_dg::hopper
{
  namespace
  {
    using ODEState = std::array<double, 2>;

    /// A shot that left the domain of (16): |psi| at the singular value or
    /// sigma <= 0; psi says on which side.
    struct ShotFailed
    {
      double psi;
    };

    constexpr double ode_tolerance = 1e-13;
  } // namespace

  std::array<double, 2>
  RadialField::derivative(const double theta, const double sigma, const double psi) const
  {
    const double s  = material.s();
    const double c2 = std::cos(2 * psi), s2 = std::sin(2 * psi);
    const bool   cone = geometry == Geometry::cone;
    if (theta == 0.)
      {
        // regular limit at the axis (psi = 0): sigma' = 0 and
        // -2 s sigma psi' = sigma ((k+1) s - 1 + [cone] 2 s psi') - 1
        const double k = cone ? 4. : 2.;
        return {{0., (1 - sigma * ((k + 1) * s - 1)) / (k * s * sigma)}};
      }
    double B0 = -std::cos(theta), B1 = std::sin(theta);
    if (cone)
      {
        const double cot = 1. / std::tan(theta);
        B0 += sigma * (4 * s * c2 - 1 + s + s * cot * s2);
        B1 += sigma * (4 * s * s2 - s * (c2 - 1) * cot);
      }
    else
      {
        B0 += sigma * (3 * s * c2 - 1);
        B1 += sigma * 3 * s * s2;
      }
    // A = [[-s sin2psi, -2 s sigma cos2psi], [1 + s cos2psi, -2 s sigma sin2psi]]
    const double a00 = -s * s2, a01 = -2 * s * sigma * c2;
    const double a10 = 1 + s * c2, a11 = -2 * s * sigma * s2;
    const double det = a00 * a11 - a01 * a10; // = 2 s sigma (s + cos 2psi)
    return {{(a11 * B0 - a01 * B1) / det, (a00 * B1 - a10 * B0) / det}};
  }

  RadialField::RadialField(const Geometry geometry, const MohrCoulomb &material,
                           const double theta_w, const unsigned int n_intervals)
    : geometry(geometry)
    , material(material)
    , half_angle(theta_w)
    , h(theta_w / n_intervals)
  {
    namespace odeint = boost::numeric::odeint;
    const double limit = material.singular_limit();
    const double psi_w = material.psi_wall();

    auto rhs = [&](const ODEState &y, ODEState &dy, const double theta) {
      if (!(y[0] > 0) || !(std::abs(y[1]) < limit - 1e-12) || !std::isfinite(y[0]))
        throw ShotFailed{y[1]};
      const auto d = derivative(theta, y[0], y[1]);
      dy           = {{d[0], d[1]}};
    };
    // the cone's ODE is singular at theta = 0: start at theta_0 from the
    // regular series sigma = sigma_0 + O(theta^2), psi = psi'(0) theta + O(theta^3)
    const double theta_start = geometry == Geometry::cone ? std::min(1e-7, 1e-3 * h) : 0.;
    auto         start       = [&](const double sigma_0) {
      const double dpsi = derivative(0., sigma_0, 0.)[1];
      return ODEState{{sigma_0, dpsi * theta_start}};
    };
    auto advance = [&](ODEState &y, const double from, const double to) {
      auto stepper = odeint::make_controlled(ode_tolerance, ode_tolerance,
                                             odeint::runge_kutta_dopri5<ODEState>());
      odeint::integrate_adaptive(stepper, rhs, y, from, to, (to - from) / 16.);
    };
    // residual of a shot, +-pi for a failed one (by the side it left on)
    auto shoot = [&](const double sigma_0) {
      try
        {
          ODEState y = start(sigma_0);
          advance(y, theta_start, theta_w);
          return y[1] - psi_w;
        }
      catch (const ShotFailed &f)
        {
          return f.psi >= 0 ? M_PI : -M_PI;
        }
    };

    // scan sigma_0 from large (gravity negligible, psi' < 0) to small
    // (psi' -> +infinity) for sign changes, refine each with TOMS 748 and
    // keep those that are true roots (not the jump to a failed shot)
    std::vector<double> roots;
    double              s_prev = 1e4, r_prev = shoot(s_prev);
    for (double s_next = s_prev / 1.25; s_next > 1e-4; s_next /= 1.25)
      {
        const double r_next = shoot(s_next);
        if ((r_prev < 0) != (r_next < 0))
          {
            boost::uintmax_t iterations = 200;
            const auto bracket = boost::math::tools::toms748_solve(
              shoot, s_next, s_prev, r_next, r_prev,
              boost::math::tools::eps_tolerance<double>(50), iterations);
            const double root = 0.5 * (bracket.first + bracket.second);
            if (std::abs(shoot(root)) < 1e-9)
              roots.push_back(root);
          }
        s_prev = s_next;
        r_prev = r_next;
      }
    n_roots = roots.size();
    if (roots.empty())
      throw NoRadialField("the radial-field BVP (16)-(17) has no solution with "
                          "sigma > 0 and |psi| < pi/4 + delta/2 (shooting over "
                          "sigma(0) in [1e-4, 1e4] rho g r)");
    const double sigma_0 = roots.front(); // the largest sigma_0

    // the table: nodes theta_i = i h with values and derivatives
    nodes.resize(n_intervals + 1);
    ODEState y = start(sigma_0);
    try
      {
        double from = theta_start;
        for (unsigned int i = 0; i <= n_intervals; ++i)
          {
            const double theta = i == n_intervals ? theta_w : i * h;
            if (i > 0)
              advance(y, from, theta);
            const ODEState yi = i == 0 ? ODEState{{sigma_0, 0.}} : y;
            const auto     d  = derivative(theta, yi[0], yi[1]);
            nodes[i]          = {{yi[0], yi[1], d[0], d[1]}};
            from              = i == 0 ? theta_start : theta;
          }
      }
    catch (const ShotFailed &)
      {
        throw NoRadialField("the radial-field BVP (16)-(17): the solution found by "
                            "shooting left the nonsingular set when tabulated");
      }
    residual = std::abs(nodes.back()[1] - psi_w);
  }

  std::array<double, 2>
  RadialField::evaluate(const double theta_in) const
  {
    const double theta = std::min(std::abs(theta_in), half_angle);
    const double sign  = theta_in < 0 ? -1. : 1.;
    const unsigned int i =
      std::min<unsigned int>(static_cast<unsigned int>(theta / h), nodes.size() - 2);
    const double t = (theta - i * h) / h;
    const auto  &a = nodes[i], &b = nodes[i + 1];
    const double h00 = (1 + 2 * t) * (1 - t) * (1 - t), h10 = t * (1 - t) * (1 - t);
    const double h01 = t * t * (3 - 2 * t), h11 = t * t * (t - 1);
    std::array<double, 2> y;
    for (unsigned int c = 0; c < 2; ++c)
      y[c] = h00 * a[c] + h10 * h * a[2 + c] + h01 * b[c] + h11 * h * b[2 + c];
    y[1] *= sign;
    return y;
  }

  double
  RadialField::sigma(const double theta) const
  {
    return evaluate(theta)[0];
  }

  double
  RadialField::psi(const double theta) const
  {
    return evaluate(theta)[1];
  }

  std::array<double, 4>
  RadialField::stresses(const double theta) const
  {
    const auto y = evaluate(theta);
    auto       T = sokolovskii_stresses(y[0], y[1], material.s());
    if (geometry == Geometry::wedge)
      T[3] = y[0];
    return T;
  }

  double
  RadialField::ode_residual() const
  {
    double worst = 0;
    for (unsigned int i = 0; i + 1 < nodes.size(); ++i)
      {
        // the interpolant's derivative at the midpoint against the ODE
        const auto  &a = nodes[i], &b = nodes[i + 1];
        const double theta = (i + 0.5) * h;
        const auto   y     = evaluate(theta);
        const auto   f     = derivative(theta, y[0], y[1]);
        for (unsigned int c = 0; c < 2; ++c)
          {
            // d/dtheta of the Hermite cubic at t = 1/2
            const double dy = 1.5 * (b[c] - a[c]) / h - 0.25 * (a[2 + c] + b[2 + c]);
            worst = std::max(worst, std::abs(dy - f[c]) / std::max(1., std::abs(f[c])));
          }
      }
    return worst;
  }

  double
  RadialField::theta_of_max_psi() const
  {
    unsigned int best = 0;
    for (unsigned int i = 1; i < nodes.size(); ++i)
      if (nodes[i][1] > nodes[best][1])
        best = i;
    // refine on the neighbouring intervals with the interpolant
    const double lo = std::max(0., (best - 1.) * h), hi = std::min(half_angle, (best + 1.) * h);
    double       theta_best = best * h, psi_best = nodes[best][1];
    for (unsigned int k = 0; k <= 2000; ++k)
      {
        const double theta = lo + (hi - lo) * k / 2000.;
        const double p     = psi(theta);
        if (p > psi_best)
          {
            psi_best   = p;
            theta_best = theta;
          }
      }
    return theta_best;
  }

  double
  RadialField::max_psi() const
  {
    return psi(theta_of_max_psi());
  }

  double
  RadialField::psi_derivative_at_wall() const
  {
    return nodes.back()[3];
  }

  double
  RadialField::nonsingularity_margin() const
  {
    double m = 0;
    for (const auto &n : nodes)
      m = std::max(m, std::abs(n[1]));
    return material.singular_limit() - std::max(m, max_psi());
  }

  void
  RadialField::write_csv(const std::string &filename, const unsigned int n_points) const
  {
    CsvWriter csv;
    csv.open(filename,
             {"theta", "theta_deg", "sigma", "psi", "psi_deg", "T_rr", "T_rtheta",
              "T_thetatheta", "T_phiphi"},
             std::string("radial (Jenike) field of a ") +
               (geometry == Geometry::cone ? "cone" : "wedge") + ", theta_w = " +
               format_number(half_angle * 180 / M_PI) +
               " deg; stresses per unit rho g r; sigma_0 = " + format_number(sigma_axis()) +
               ", shooting residual " + format_number(shooting_residual()));
    for (unsigned int i = 0; i < n_points; ++i)
      {
        const double theta = n_points == 1 ? 0. : half_angle * i / (n_points - 1);
        const auto   y     = evaluate(theta);
        const auto   T     = stresses(theta);
        csv.row({theta, theta * 180 / M_PI, y[0], y[1] + 0., y[1] * 180 / M_PI + 0., T[0], T[1] + 0., T[2],
                 T[3]});
      }
  }
} // namespace granular_dg::hopper
