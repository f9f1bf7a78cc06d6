#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/special_functions/bessel.hpp>
#include <boost/math/tools/roots.hpp>

#include <granular_dg/base/errors.h>
#include <granular_dg/equations/column/closed_form.h>

#include <cmath>
#include <limits>

namespace granular_dg::column
{
  namespace
  {
    using Gauss = boost::math::quadrature::gauss<double, 40>;

    double
    j0(const double x)
    {
      return boost::math::cyl_bessel_j(0, x);
    }

    /// J_1(x)/x, continued to 1/2 at x = 0
    double
    j1x(const double x)
    {
      if (x < 1e-4)
        return 0.5 - x * x / 16.;
      return boost::math::cyl_bessel_j(1, x) / x;
    }

    /// I(z,t) = int_{z/t}^1 cosh((yt - z)/2) J_1(a s)/s dy, a = t/2, s = sqrt(1 - y^2)
    double
    integral_I(const double z, const double t)
    {
      const double a = 0.5 * t;
      return Gauss::integrate(
        [&](const double y) {
          const double s = std::sqrt(std::max(1. - y * y, 0.));
          return std::cosh(0.5 * (y * t - z)) * a * j1x(a * s);
        },
        z / t, 1.);
    }

    /// dI/dt
    double
    integral_I_t(const double z, const double t)
    {
      const double a  = 0.5 * t;
      const double y0 = z / t;
      const double s0 = std::sqrt(std::max(1. - y0 * y0, 0.));
      // the moving lower limit: -(d y0/dt) g(y0) with g(y0) = J_1(a s0)/s0
      const double boundary = z / (t * t) * a * j1x(a * s0);
      return boundary + Gauss::integrate(
                          [&](const double y) {
                            const double s = std::sqrt(std::max(1. - y * y, 0.));
                            const double A = 0.5 * (y * t - z);
                            // d/dt cosh(A) J_1(a s)/s + cosh(A) d/dt J_1(a s)/s
                            return 0.5 * y * std::sinh(A) * a * j1x(a * s) +
                                   0.5 * std::cosh(A) * (j0(a * s) - j1x(a * s));
                          },
                          y0, 1.);
    }
  } // namespace

  LinearColumnSolution::LinearColumnSolution(const double u_b)
    : u_b(u_b)
  {}

  double
  LinearColumnSolution::sliding_strain(const double z, const double t) const
  {
    if (z > t || t <= 0)
      return 0.;
    return u_b * std::exp(-0.5 * z) * (std::cosh(0.5 * (t - z)) - 0.5 * t * integral_I(z, t));
  }

  double
  LinearColumnSolution::sliding_strain_rate(const double z, const double t) const
  {
    if (z > t || t <= 0)
      return 0.;
    return u_b * std::exp(-0.5 * z) *
           (0.5 * std::sinh(0.5 * (t - z)) - 0.5 * integral_I(z, t) - 0.5 * t * integral_I_t(z, t));
  }

  double
  LinearColumnSolution::sliding_velocity(const double z, const double t) const
  {
    if (z > t || t <= 0)
      return 0.;
    // v(t, t) = -u_b e^{-t/2} (Rankine-Hugoniot at the front), then u_t = v_z
    return -u_b * std::exp(-0.5 * t) -
           Gauss::integrate([&](const double y) { return sliding_strain_rate(y, t); }, z, t);
  }

  double
  LinearColumnSolution::stop_time_at_node(const unsigned int k) const
  {
    while (stop_time_table.size() <= k)
      {
        const unsigned int n = stop_time_table.size();
        const double       z = n * table_spacing;
        // v > 0 just behind the front (t = z). The stopping front is
        // supersonic, 0 < dt_s/dz < 1, so t_s(z) lies in
        // [t_s(z - h), t_s(z - h) + h]; the first node is bracketed by a scan.
        double t0, t1;
        if (n == 0)
          {
            t0 = 1e-9;
            t1 = 0.25;
            while (sliding_velocity(z, t1) > 0)
              {
                t0 = t1;
                t1 += 0.25;
                AssertThrow(t1 < 40, dealii::ExcMessage("no stopping time found"));
              }
          }
        else
          {
            t0 = std::max(stop_time_table.back(), z + 1e-12);
            t1 = stop_time_table.back() + table_spacing;
          }
        boost::uintmax_t max_iter = 100;
        const auto       r        = boost::math::tools::toms748_solve(
          [&](const double t) { return sliding_velocity(z, t); }, t0, t1,
          boost::math::tools::eps_tolerance<double>(50), max_iter);
        stop_time_table.push_back(0.5 * (r.first + r.second));
      }
    return stop_time_table[k];
  }

  double
  LinearColumnSolution::stop_time(const double z) const
  {
    // cubic Lagrange interpolation through the four nodes around z
    const double       x     = z / table_spacing;
    const unsigned int first = x < 1 ? 0 : static_cast<unsigned int>(x) - 1;
    double             result = 0;
    for (unsigned int i = 0; i < 4; ++i)
      {
        double w = 1;
        for (unsigned int j = 0; j < 4; ++j)
          if (j != i)
            w *= (x - double(first + j)) / double(int(i) - int(j));
        result += w * stop_time_at_node(first + i);
      }
    return result;
  }

  double
  LinearColumnSolution::stop_front(const double t) const
  {
    if (t <= first_stop_time())
      return 0.;
    // v(z_s, t) = 0 with v > 0 for z in (z_s, t]; z_s < t
    boost::uintmax_t max_iter = 100;
    const auto       r        = boost::math::tools::toms748_solve(
      [&](const double z) { return sliding_velocity(z, t); }, 0., t,
      boost::math::tools::eps_tolerance<double>(50), max_iter);
    return 0.5 * (r.first + r.second);
  }

  double
  LinearColumnSolution::strain(const double z, const double t) const
  {
    if (z < stop_front(t))
      return sliding_strain(z, stop_time(z));
    return sliding_strain(z, t);
  }

  double
  LinearColumnSolution::velocity(const double z, const double t) const
  {
    if (z < stop_front(t))
      return 0.;
    return sliding_velocity(z, t);
  }

  LinearColumnFunction::LinearColumnFunction(const double u_b)
    : dealii::Function<1>(2)
    , solution(u_b)
  {}

  void
  LinearColumnFunction::set_time(const double t)
  {
    dealii::Function<1>::set_time(t);
    front = solution.stop_front(t);
  }

  double
  LinearColumnFunction::value(const dealii::Point<1> &p, const unsigned int component) const
  {
    const double z = p[0], t = this->get_time();
    if (z < front)
      return component == 0 ? solution.sliding_strain(z, solution.stop_time(z)) : 0.;
    return component == 0 ? solution.sliding_strain(z, t) : solution.sliding_velocity(z, t);
  }
} // namespace granular_dg::column
