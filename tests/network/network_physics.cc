// Unit test of the network physics (system.h) and the vertex (junction.h):
//  - consistency F(u, u) = f(u) of the upwind (Engquist-Osher), Godunov and
//    Lax-Friedrichs fluxes, and f' against a central difference;
//  - monotonicity: F nondecreasing in u_l and nonincreasing in u_r (on a
//    grid; LLF only where it is monotone, i.e. always for these checks);
//  - Godunov against brute-force min/max of f over [u_l, u_r], Engquist-
//    Osher against f(c) + int_c^u max(f', 0) + int_c^v min(f', 0) by
//    quadrature, and EO = upwind f(u_l) on increasing branches;
//  - EdgeLaw (the law as the network engine evaluates it) in the lanes of a
//    SIMD batch equal to its scalar values, bit for bit, and the law fixed
//    at compile time (with_fixed_law()) equal to it, bit for bit;
//  - the discrete stationary vertex values of Examples 7.1, 7.2, 7.4
//    (c_0 = 1, (3 - sqrt 7)/2, sqrt(2/3)) from Junction::balance, and the
//    error when the outgoing edges cannot carry the incoming flux.
// Printed deviations are compared with 0 at 1e-12 (absolute).

#include <granular_dg/base/errors.h>
#include <granular_dg/equations/network/system.h>
#include <granular_dg/network/junction.h>

#include <cmath>
#include <iomanip>
#include <iostream>

using namespace granular_dg;
using namespace granular_dg::network;

namespace
{
  std::vector<double>
  grid(const double lo, const double hi, const unsigned int n)
  {
    std::vector<double> g;
    for (unsigned int i = 0; i <= n; ++i)
      g.push_back(lo + (hi - lo) * i / n);
    return g;
  }

  void
  check_flux(const std::string &name, const FluxFunction &f, const double lo, const double hi)
  {
    const auto   u = grid(lo, hi, 60);
    double       consistency = 0, derivative = 0, godunov = 0, eo = 0;
    unsigned int non_monotone = 0;
    const NumericalFlux types[] = {NumericalFlux::upwind, NumericalFlux::godunov,
                                       NumericalFlux::local_lax_friedrichs};
    for (const double a : u)
      {
        for (const auto type : types)
          consistency = std::max(consistency, std::abs(f.numerical_flux(type, a, a) - f.value(a)));
        const double h = 1e-6;
        derivative     = std::max(derivative, std::abs(f.derivative(a) -
                                                   (f.value(a + h) - f.value(a - h)) / (2 * h)) *
                                                1e-3); // finite-difference error ~1e-10
        for (const double b : u)
          {
            // brute force: min over [a, b] if a <= b, else max over [b, a]
            double ext = f.value(a);
            for (const double s : grid(std::min(a, b), std::max(a, b), 2000))
              ext = a <= b ? std::min(ext, f.value(s)) : std::max(ext, f.value(s));
            for (const double c : {0., 0.5 * f.alpha()}) // where the extremum may be
              if (c >= std::min(a, b) && c <= std::max(a, b))
                ext = a <= b ? std::min(ext, f.value(c)) : std::max(ext, f.value(c));
            godunov = std::max(godunov, std::abs(f.godunov(a, b) - ext));
            // EO by quadrature of f' from 0 (midpoint rule, exact for the
            // linear f' on the pieces between the kinks of max(f', 0))
            auto integral = [&](const double to, const bool positive) {
              std::vector<double> pts{0., to};
              const double        c = 0.5 * f.alpha();
              if (f.law() == FluxLaw::traffic && c > std::min(0., to) && c < std::max(0., to))
                pts.insert(pts.begin() + 1, c);
              double sum = 0;
              for (unsigned int p = 0; p + 1 < pts.size(); ++p)
                for (unsigned int i = 0; i < 100; ++i)
                  {
                    const double h = (pts[p + 1] - pts[p]) / 100, s = pts[p] + (i + 0.5) * h;
                    sum += (positive ? std::max(f.derivative(s), 0.) :
                                       std::min(f.derivative(s), 0.)) * h;
                  }
              return sum;
            };
            eo = std::max(eo, std::abs(f.engquist_osher(a, b) - f.value(0.) - integral(a, true) -
                                       integral(b, false)));
            for (const auto type : types)
              {
                const double d = 1e-3;
                if (f.numerical_flux(type, a + d, b) < f.numerical_flux(type, a, b) - 1e-14 ||
                    f.numerical_flux(type, a, b + d) > f.numerical_flux(type, a, b) + 1e-14)
                  ++non_monotone;
              }
          }
      }
    std::cout << name << ": consistency " << consistency << ", derivative (x1e-3) " << derivative
              << ", godunov " << godunov << ", engquist_osher " << eo
              << ", non-monotone samples " << non_monotone << std::endl;
  }
} // namespace

int
main()
{
  std::cout << std::setprecision(3);
  check_flux("linear a = 1", {FluxLaw::linear, 1., 1.}, -1., 2.);
  check_flux("linear a = -0.5", {FluxLaw::linear, -0.5, 1.}, -1., 2.);
  check_flux("burgers", {FluxLaw::burgers, 1., 1.}, -1.5, 2.);
  check_flux("traffic alpha = 1", {FluxLaw::traffic, 1., 1.}, 0., 1.);
  check_flux("traffic alpha = 4", {FluxLaw::traffic, 1., 4.}, 0., 4.);

  // upwind = f(u_l) on increasing branches (the paper's upwind flux)
  {
    const FluxFunction b{FluxLaw::burgers, 1., 1.}, tr{FluxLaw::traffic, 1., 2.};
    double             d = 0;
    for (const double a : grid(0., 1., 20))
      for (const double c : grid(0., 1., 20))
        d = std::max({d, std::abs(b.engquist_osher(a, c) - b.value(a)),
                      std::abs(tr.engquist_osher(a, c) - tr.value(a))});
    std::cout << "upwind = f(u_l) on increasing branches: " << d << std::endl;
  }

  // the law as the engine evaluates it (EdgeLaw): in the lanes of a SIMD
  // batch as in scalar code, bit for bit (a cell gives the same value in a
  // batch and in the scalar remainder of an edge)
  {
    using VA = VectorizedArray<double>;
    double d = 0;
    for (const FluxFunction f : {FluxFunction{FluxLaw::linear, -0.5, 1.},
                                 FluxFunction{FluxLaw::burgers, 1., 1.},
                                 FluxFunction{FluxLaw::traffic, 1., 4.}})
      for (const auto type : {NumericalFlux::upwind, NumericalFlux::godunov,
                              NumericalFlux::local_lax_friedrichs})
        {
          const EdgeLaw law{f, type};
          VA            ul, ur;
          for (unsigned int l = 0; l < VA::size(); ++l)
            {
              ul[l] = -1. + 0.7 * l;
              ur[l] = 2. - 0.45 * l;
            }
          const VA F = law.flux(ul, ur), s = law.derivative(ul), v = law.value(ur);
          for (unsigned int l = 0; l < VA::size(); ++l)
            d = std::max({d, std::abs(F[l] - law.flux(ul[l], ur[l])),
                          std::abs(s[l] - law.derivative(ul[l])),
                          std::abs(v[l] - law.value(ur[l]))});
        }
    std::cout << "EdgeLaw in SIMD lanes - scalar: " << d << std::endl;
  }

  // the law fixed at compile time (with_fixed_law(): the engine's kernels)
  // rounds as the law that branches on its kind at run time: the same bits,
  // in scalar code and in the lanes of a SIMD batch
  {
    using VA        = VectorizedArray<double>;
    const auto same = [](const double x, const double y) {
      return x == y && std::signbit(x) == std::signbit(y);
    };
    bool equal = true;
    for (const FluxFunction f : {FluxFunction{FluxLaw::linear, -0.5, 1.},
                                 FluxFunction{FluxLaw::linear, 0.75, 1.},
                                 FluxFunction{FluxLaw::burgers, 1., 1.},
                                 FluxFunction{FluxLaw::traffic, 1., 4.}})
      for (const auto type : {NumericalFlux::upwind, NumericalFlux::godunov,
                              NumericalFlux::local_lax_friedrichs})
        {
          const EdgeLaw law{f, type};
          with_fixed_law(law, [&](const auto &fixed) {
            for (const double a : grid(-1.3, 4.1, 23))
              for (const double c : grid(-0.7, 4.4, 19))
                {
                  VA A = a, C = c;
                  for (unsigned int l = 0; l < VA::size(); ++l)
                    A[l] += 0.1 * l, C[l] -= 0.3 * l;
                  const VA F = fixed.flux(A, C), s = fixed.derivative(A), v = fixed.value(C);
                  equal = equal && same(fixed.flux(a, c), law.flux(a, c)) &&
                          same(fixed.derivative(a), law.derivative(a)) &&
                          same(fixed.value(c), law.value(c));
                  for (unsigned int l = 0; l < VA::size(); ++l)
                    equal = equal && same(F[l], law.flux(A[l], C[l])) &&
                            same(s[l], law.derivative(A[l])) && same(v[l], law.value(C[l]));
                }
          });
        }
    std::cout << "law fixed at compile time = runtime law, bit for bit: " << (equal ? "yes" : "no")
              << std::endl;
  }

  // discrete stationary vertex values (Definition 4.4)
  // a star with these edges and its junction (vertex without volume)
  auto star = [](const std::vector<std::pair<Direction, FluxFunction>> &edges) {
    Graph                g;
    std::vector<EdgeLaw> laws;
    g.vertices.resize(1);
    for (const auto &[dir, f] : edges)
      {
        Edge e;
        e.meet(dir);
        g.edges.push_back(e);
        laws.push_back({f, NumericalFlux::upwind});
      }
    return Junction<EdgeLaw>(g, laws, 0, 0.);
  };
  const FluxFunction burgers{FluxLaw::burgers, 1., 1.};
  auto               traffic = [](double a) { return FluxFunction{FluxLaw::traffic, 1., a}; };
  {
    // 7.1: in sqrt 2, loop (in-end 1, out-end 1), two out 1; the traces are
    // per end: in-edge, loop in-end, loop out-end, out, out
    const auto j = star({{Direction::in, burgers}, {Direction::loop, burgers},
                          {Direction::out, burgers}, {Direction::out, burgers}});
    std::cout << "7.1 c_0 - 1: "
              << j.balance({std::sqrt(2.), 1., 1., 1., 1.}, 0.) - 1. << std::endl;
  }
  {
    const auto j = star({{Direction::in, traffic(1)}, {Direction::in, traffic(1)},
                             {Direction::out, traffic(2)}, {Direction::out, traffic(4)},
                             {Direction::out, traffic(4)}});
    const double   c0 = j.balance({0.5, 0.5, 0., 0.2, 1.}, 0.);
    std::cout << "7.2 c_0 - (3 - sqrt 7)/2: " << c0 - (3 - std::sqrt(7.)) / 2
              << ", residual " << j.net_outflow({0.5, 0.5, 0., 0.2, 1.}, c0) << std::endl;
  }
  {
    const auto j = star({{Direction::in, burgers}, {Direction::in, burgers},
                             {Direction::out, burgers}, {Direction::out, burgers},
                             {Direction::out, burgers}});
    std::cout << "7.4 c_0 - sqrt(2/3): "
              << j.balance({1., 1., 0., 0.8, 2.}, 0.) - std::sqrt(2. / 3.) << std::endl;
  }
  {
    // two full roads (flux 1 each) into one road of capacity 1: the
    // Engquist-Osher vertex congests, u_0 = (1 + sqrt(1/2))/2 > 1/2 halves
    // the inflow of each road (f(u_0) = 1/2) and the outflow is the capacity
    const auto j = star({{Direction::in, traffic(1)}, {Direction::in, traffic(1)},
                          {Direction::out, traffic(1)}});
    const double   u0 = j.balance({0.5, 0.5, 0.2}, 0.);
    const auto     F  = j.end_fluxes({0.5, 0.5, 0.2}, u0);
    std::cout << "congested vertex: u_0 - (1 + sqrt(1/2))/2 = "
              << u0 - (1 + std::sqrt(0.5)) / 2 << ", fluxes - (1/2, 1/2, 1): " << F[0] - 0.5
              << " " << F[1] - 0.5 << " " << F[2] - 1. << std::endl;
  }
  {
    // an ingoing edge and no outgoing one: nothing balances a positive flux
    const auto j = star({{Direction::in, FluxFunction{FluxLaw::linear, 1., 1.}}});
    try
      {
        j.balance({1.}, 0.25);
        std::cout << "dead end: no error (wrong)" << std::endl;
      }
    catch (const RunError &e)
      {
        std::cout << "dead end: " << e.what() << std::endl;
      }
  }
}
