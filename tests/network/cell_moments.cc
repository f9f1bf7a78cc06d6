// Unit test of the initial projection of the network's edges,
// add_cell_moments() (network.h): the Legendre moments of the data in one
// cell by adaptive Gauss integration.
//  - Smooth data need one level (three rules of 5 points: 15 evaluations of
//    the data) in every cell, also far from x = 0 on a fine mesh. The
//    Legendre argument must not be computed as (x - x0) / h: that carries
//    the rounding of x magnified by x / h, the two levels then never agree
//    to round-off, and the bisection runs to a depth of ~38 (2.5 10^6
//    evaluations per cell at 20000 cells per unit length; Example 7.3 at
//    p = 2 and 33053 cells per unit length did not finish its set-up in
//    10 minutes).
//  - A jump inside a cell is located to round-off: the exact cell average.
// Degree 2 (modes 0-2), the rule of NetworkProblem::initialize() (p + 3
// points); the counts and verdicts are compared exactly.

#include <deal.II/base/function.h>
#include <deal.II/base/polynomial.h>
#include <deal.II/base/quadrature_lib.h>

#include <granular_dg/network/network.h>

#include <cmath>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <string>
#include <utility>

using namespace dealii;
using namespace granular_dg::network;

namespace
{
  /// g(x), counting its evaluations
  class Counted : public Function<1>
  {
  public:
    explicit Counted(const std::function<double(double)> &g)
      : g(g)
    {}
    double
    value(const Point<1> &p, const unsigned int = 0) const override
    {
      ++calls;
      return g(p[0]);
    }
    mutable unsigned long calls = 0;

  private:
    std::function<double(double)> g;
  };
} // namespace

int
main()
{
  std::cout << std::setprecision(3);
  const unsigned int                 degree = 2;
  std::vector<Polynomials::Legendre> legendre;
  for (unsigned int k = 0; k <= degree; ++k)
    legendre.emplace_back(k);
  const QGauss<1> quad(degree + 3);

  const unsigned int n = 20000; // cells per unit length
  const double       h = 1. / n;
  for (const unsigned int c : {3u, 10000u, 19999u})
    {
      const double x0 = c * h;
      // x0 + h carries the rounding of x0 (its ulp is x0 / h times larger
      // than h's): the moments agree with those in the cell's own
      // coordinate to that scale, not to machine precision
      const double round_off = 16 * std::numeric_limits<double>::epsilon() * (1. + x0 / h);
      const auto   report    = [&](const std::string &what, const Counted &g,
                              const std::vector<double> &m, const std::vector<double> &exact) {
        double largest = 0;
        for (unsigned int k = 0; k <= degree; ++k)
          largest = std::max(largest, std::abs(m[k] - exact[k]) / h);
        std::cout << "cell " << c << " of " << n << ", " << what << ": " << g.calls
                  << " evaluations, moments within the rounding of the cell's ends: "
                  << (largest <= round_off ? "yes" : "no") << std::endl;
      };
      // the moments by one Gauss rule of 8 points in the cell's coordinate
      const auto reference = [&](const std::function<double(double)> &g) {
        const QGauss<1>     fine(8);
        std::vector<double> m(degree + 1, 0.);
        for (unsigned int q = 0; q < fine.size(); ++q)
          for (unsigned int k = 0; k <= degree; ++k)
            m[k] += h * fine.weight(q) * g(x0 + h * fine.point(q)[0]) *
                    legendre[k].value(fine.point(q)[0]);
        return m;
      };
      const std::function<double(double)> constant = [](double) { return 2. / 3.; };
      const std::function<double(double)> smooth   = [](double x) {
        return 1. + 0.3 * std::sin(3. * x);
      };
      for (const auto &[name, g] : {std::pair{"constant 2/3", constant},
                                    std::pair{"1 + 0.3 sin 3x", smooth}})
        {
          Counted             counted(g);
          std::vector<double> m(degree + 1, 0.);
          add_cell_moments(counted, legendre, quad, x0, h, x0, x0 + h, m);
          report(name, counted, m, reference(g));
        }
      // a jump at (about) 3/10 of the cell: mean 1 + (jump - x0) / h
      const double        jump = x0 + 0.3 * h;
      Counted             step([jump](double x) { return x < jump ? 2. : 1.; });
      std::vector<double> m(degree + 1, 0.);
      add_cell_moments(step, legendre, quad, x0, h, x0, x0 + h, m);
      std::cout << "cell " << c << " of " << n << ", jump 2 | 1 inside: mean within the "
                << "rounding of the cell's ends: "
                << (std::abs(m[0] / h - (1. + (jump - x0) / h)) <= round_off ? "yes" : "no")
                << std::endl;
    }
}
