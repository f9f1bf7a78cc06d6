#include <deal.II/base/exceptions.h>
#include <deal.II/base/numbers.h>

#include <granular_dg/equations/network/examples.h>

#include <cmath>
#include <functional>
#include <utility>

namespace granular_dg::network
{
  namespace
  {
    const double sqrt2 = std::sqrt(2.);

    FluxFunction
    burgers()
    {
      return {FluxLaw::burgers, 1., 1.};
    }
    FluxFunction
    linear(const double a)
    {
      return {FluxLaw::linear, a, 1.};
    }
    FluxFunction
    traffic(const double alpha)
    {
      return {FluxLaw::traffic, 1., alpha};
    }

    /// An exact solution from lambdas.
    class Solution : public ExactSolution
    {
    public:
      using Value  = std::function<double(unsigned int, double, double)>;
      using Breaks = std::function<std::vector<double>(unsigned int, double)>;
      using Vertex = std::function<double(double)>;
      /// a star: one vertex
      Solution(std::string name, Value value, Breaks breaks, Vertex vertex,
               const double until = 1e300)
        : Solution(std::move(name), std::move(value), std::move(breaks),
                   std::vector<Vertex>{std::move(vertex)}, until)
      {}
      Solution(std::string name, Value value, Breaks breaks, std::vector<Vertex> vertices,
               const double until = 1e300)
        : label(std::move(name))
        , u(std::move(value))
        , b(std::move(breaks))
        , v(std::move(vertices))
        , until(until)
      {}
      double value(unsigned int k, double x, double t) const override { return u(k, x, t); }
      std::vector<double> breakpoints(unsigned int k, double t) const override { return b(k, t); }
      double vertex_value(unsigned int i, double t) const override { return v.at(i)(t); }
      double valid_until() const override { return until; }
      std::string name() const override { return label; }

    private:
      std::string                   label;
      Value                         u;
      Breaks                        b;
      std::vector<Vertex>           v;
      double                        until;
    };

    /// Example 7.1: Burgers with a roundabout. Edges: 0 in (2 | sqrt 2 at
    /// x = 0.5), 1 loop, 2 and 3 out, all other data 1; c_0 = 1.
    Example
    example_7_1()
    {
      const double s1 = (2 + sqrt2) / 2, t1 = 0.5 / s1; // t1 = 1 - 1/sqrt 2
      const double c1 = std::sqrt(5. / 3.), s2 = (1 + c1) / 2;
      Example e;
      e.name        = "example_7_1";
      e.description = "Burgers' equation with a roundabout (Musch et al. Example 7.1)";
      e.edges = {{Direction::in, burgers()}, {Direction::loop, burgers()},
                 {Direction::out, burgers()}, {Direction::out, burgers()}};
      e.exact = std::make_shared<Solution>(
        e.name,
        [=](unsigned int k, double x, double t) {
          if (k == 0)
            return x < 0.5 + s1 * t ? 2. : sqrt2;
          return (t > t1 && x < s2 * (t - t1)) ? c1 : 1.;
        },
        [=](unsigned int k, double t) {
          if (k == 0)
            return std::vector<double>{0.5 + s1 * t};
          return t > t1 ? std::vector<double>{s2 * (t - t1)} : std::vector<double>{};
        },
        [=](double t) { return t < t1 ? 1. : c1; },
        // the loop's shock reaches its far end (the vertex again)
        t1 + 1. / s2);
      return e;
    }

    /// Example 7.2: traffic fluxes 4u(1 - u/alpha). Edges: 0, 1 in (alpha 1,
    /// data 0.5), 2 out (alpha 2, data 0: rarefaction), 3 out (alpha 4,
    /// data c_0), 4 out (alpha 4, data 1: shock); c_0 = (3 - sqrt 7)/2.
    Example
    example_7_2()
    {
      const double c0 = (3 - std::sqrt(7.)) / 2;
      Example      e;
      e.name        = "example_7_2";
      e.description = "traffic fluxes with different capacities (Musch et al. Example 7.2)";
      e.edges = {{Direction::in, traffic(1)}, {Direction::in, traffic(1)},
                 {Direction::out, traffic(2)}, {Direction::out, traffic(4)},
                 {Direction::out, traffic(4)}};
      e.exact = std::make_shared<Solution>(
        e.name,
        [=](unsigned int k, double x, double t) {
          switch (k)
            {
              case 0:
              case 1:
                return 0.5;
              case 2: // f' = 4 - 4u: fan from c_0 to 0
                if (x < (4 - 4 * c0) * t)
                  return c0;
                return x < 4 * t ? 1 - x / (4 * t) : 0.;
              case 3:
                return c0;
              default: // f = 4u - u^2: shock c_0 | 1 at speed 3 - c_0
                return x < (3 - c0) * t ? c0 : 1.;
            }
        },
        [=](unsigned int k, double t) {
          if (k == 2)
            return std::vector<double>{(4 - 4 * c0) * t, 4 * t};
          if (k == 4)
            return std::vector<double>{(3 - c0) * t};
          return std::vector<double>{};
        },
        [=](double) { return c0; });
      return e;
    }

    /// Two ingoing and three outgoing edges with the same flux.
    std::vector<ExpectedEdge>
    two_in_three_out(const FluxFunction &f)
    {
      return {{Direction::in, f}, {Direction::in, f}, {Direction::out, f},
              {Direction::out, f}, {Direction::out, f}};
    }

    /// Examples 7.3 and 7.5: the jump 2 | 1 at x = 0.8 of Edge 1 (speed
    /// s_in) reaches the vertex at t1 = 0.2 / s_in; Edge 2 carries 1; the
    /// outgoing edges start at c0 and, from t1 on, carry the jump c1 | c0
    /// (speed s_out) away from the vertex, whose value switches from c0 to c1.
    Example
    jump_through_vertex(const std::string &name, const std::string &description,
                        const FluxFunction &f, const double s_in, const double c0,
                        const double c1, const double s_out)
    {
      const double t1 = 0.2 / s_in;
      Example      e;
      e.name        = name;
      e.description = description;
      e.edges       = two_in_three_out(f);
      e.exact       = std::make_shared<Solution>(
        e.name,
        [=](unsigned int k, double x, double t) {
          if (k == 0)
            return x < 0.8 + s_in * t ? 2. : 1.;
          if (k == 1)
            return 1.;
          return (t > t1 && x < s_out * (t - t1)) ? c1 : c0;
        },
        [=](unsigned int k, double t) {
          if (k == 0)
            return std::vector<double>{0.8 + s_in * t};
          if (k == 1 || t <= t1)
            return std::vector<double>{};
          return std::vector<double>{s_out * (t - t1)};
        },
        [=](double t) { return t < t1 ? c0 : c1; });
      return e;
    }

    /// Example 7.3: linear advection f = u; c_0 = 2/3 (3 c_0 = 1 + 1), then
    /// 1 from t = 0.2 (3 u_0 = 2 + 1).
    Example
    example_7_3()
    {
      return jump_through_vertex("example_7_3", "linear advection (Musch et al. Example 7.3)",
                                 linear(1), 1., 2. / 3., 1., 1.);
    }

    /// Example 7.5: Burgers; the shock 2 | 1 (speed 3/2) reaches the vertex
    /// at t* = 2/15, u_0 jumps from sqrt(2/3) to sqrt(5/3) (3 u_0^2/2 = 2 +
    /// 1/2) and shocks sqrt(5/3) | sqrt(2/3) leave at their mean speed.
    Example
    example_7_5()
    {
      const double c0 = std::sqrt(2. / 3.), c1 = std::sqrt(5. / 3.);
      return jump_through_vertex("example_7_5",
                                 "Burgers' equation, a shock through the vertex (Musch et al. "
                                 "Example 7.5)",
                                 burgers(), 1.5, c0, c1, 0.5 * (c0 + c1));
    }

    /// Example 7.4: Burgers, elementary waves. Edges: 0, 1 in (1), 2 out (0:
    /// shock), 3 out (c_0), 4 out (2: rarefaction); c_0 = sqrt(2/3).
    Example
    example_7_4()
    {
      const double c0 = std::sqrt(2. / 3.);
      Example      e;
      e.name        = "example_7_4";
      e.description = "Burgers' equation, shock, constant state and rarefaction "
                      "(Musch et al. Example 7.4)";
      e.edges = two_in_three_out(burgers());
      e.exact = std::make_shared<Solution>(
        e.name,
        [=](unsigned int k, double x, double t) {
          switch (k)
            {
              case 0:
              case 1:
                return 1.;
              case 2:
                return x < 0.5 * c0 * t ? c0 : 0.;
              case 3:
                return c0;
              default:
                if (x < c0 * t)
                  return c0;
                return x < 2 * t ? x / t : 2.;
            }
        },
        [=](unsigned int k, double t) {
          if (k == 2)
            return std::vector<double>{0.5 * c0 * t};
          if (k == 4)
            return std::vector<double>{c0 * t, 2 * t};
          return std::vector<double>{};
        },
        [=](double) { return c0; });
      return e;
    }

    /// A smooth solution through the vertex: linear advection, in-edges
    /// (speed 1) u = g_k(x - t), g_0 = 1 + sin(2 pi s)/2, g_1 = 1 + cos(2 pi
    /// s)/4; out-edges with speeds a = 1, 2, 1/2 carry u = c(t - x/a) with
    /// c(t) = (g_0(1 - t) + g_1(1 - t)) / 3.5, the zero-width vertex state.
    Example
    smooth_linear()
    {
      const double pi = numbers::PI;
      const double a[] = {1., 1., 1., 2., 0.5};
      auto c = [=](const double t) {
        return (2 - 0.5 * std::sin(2 * pi * t) + 0.25 * std::cos(2 * pi * t)) / 3.5;
      };
      Example e;
      e.name        = "smooth_linear";
      e.description = "smooth linear advection through the vertex (order test)";
      e.edges = {{Direction::in, linear(1)}, {Direction::in, linear(1)},
                 {Direction::out, linear(1)}, {Direction::out, linear(2)},
                 {Direction::out, linear(0.5)}};
      e.exact = std::make_shared<Solution>(
        e.name,
        [=](unsigned int k, double x, double t) {
          if (k == 0)
            return 1 + 0.5 * std::sin(2 * pi * (x - t));
          if (k == 1)
            return 1 + 0.25 * std::cos(2 * pi * (x - t));
          return c(t - x / a[k]);
        },
        [](unsigned int, double) { return std::vector<double>{}; },
        c);
      return e;
    }

    /// Two stars joined by an edge, Burgers: Edges 1, 2 (data 1, inflow 1)
    /// run into Vertex 1, Edge 3 from Vertex 1 to Vertex 2 (data 1), Edges
    /// 4, 5 out of Vertex 2 (data 1/sqrt 2). The stationary construction
    /// (Definition 4.4) at each vertex: Vertex 1 takes c = sqrt 2 (f(c) = 1,
    /// the two inflows), which sends a shock sqrt 2 | 1 into Edge 3 at speed
    /// s1 = (1 + sqrt 2)/2; Vertex 2 is stationary at 1/sqrt 2 (f = 1/4 on
    /// each out-edge) until the shock arrives at t1 = 1/s1, then takes c = 1
    /// (2 f(c) = f(sqrt 2) = 1) and sends shocks 1 | 1/sqrt 2 at speed
    /// s2 = (1 + 1/sqrt 2)/2 into Edges 4 and 5, which leave at t1 + 1/s2.
    Example
    two_stars()
    {
      const double s1 = (1 + sqrt2) / 2, t1 = 1 / s1, s2 = (1 + 1 / sqrt2) / 2;
      Example      e;
      e.name        = "two_stars";
      e.description = "two star vertices joined by an edge, Burgers' equation, shocks "
                      "from the stationary states at both vertices";
      e.n_vertices  = 2;
      e.edges       = {{free_end, 0, burgers()}, {free_end, 0, burgers()}, {0, 1, burgers()},
                       {1, free_end, burgers()}, {1, free_end, burgers()}};
      const auto shock2 = [=](double t) { return s2 * (t - t1); };
      e.exact           = std::make_shared<Solution>(
        e.name,
        [=](unsigned int k, double x, double t) {
          if (k < 2)
            return 1.;
          if (k == 2)
            return x < s1 * t ? sqrt2 : 1.;
          return t > t1 && x < shock2(t) ? 1. : 1 / sqrt2;
        },
        [=](unsigned int k, double t) {
          if (k == 2 && t < t1)
            return std::vector<double>{s1 * t};
          if (k > 2 && t > t1)
            return std::vector<double>{shock2(t)};
          return std::vector<double>{};
        },
        std::vector<Solution::Vertex>{[=](double) { return sqrt2; },
                                      [=](double t) { return t < t1 ? 1 / sqrt2 : 1.; }},
        t1 + 1 / s2);
      return e;
    }

    /// A smooth solution through two vertices, linear advection: Edge 1
    /// (speed 1, u = 1 + sin(2 pi (x - t))/2) into Vertex 1, Edges 2 (to
    /// Vertex 2, speed 1) and 3 (free, speed 2) out of it; Edge 5 (speed 1,
    /// u = 1 + cos(2 pi (x - t))/4) into Vertex 2 and Edge 4 (speed 1/2) out
    /// of it. Without vertex volume the vertex states are
    /// c1(t) = u_1(1, t)/3 = (1 - sin(2 pi t)/2)/3 and
    /// c2(t) = (u_2(1, t) + u_5(1, t))/(1/2) = 2 (c1(t - 1) + 1 + cos(2 pi t)/4),
    /// and every out-edge carries its vertex state: u = c(t - x/a).
    Example
    smooth_two_vertices()
    {
      const double pi = numbers::PI;
      const double a[] = {1., 1., 2., 0.5, 1.};
      const auto   c1 = [=](const double t) { return (1 - 0.5 * std::sin(2 * pi * t)) / 3; };
      const auto   c2 = [=](const double t) {
        return 2 * (c1(t - 1) + 1 + 0.25 * std::cos(2 * pi * t));
      };
      Example e;
      e.name        = "smooth_two_vertices";
      e.description = "smooth linear advection through two vertices (order test)";
      e.n_vertices  = 2;
      e.edges       = {{free_end, 0, linear(1)}, {0, 1, linear(1)}, {0, free_end, linear(2)},
                       {1, free_end, linear(0.5)}, {free_end, 1, linear(1)}};
      e.exact       = std::make_shared<Solution>(
        e.name,
        [=](unsigned int k, double x, double t) {
          switch (k)
            {
              case 0:
                return 1 + 0.5 * std::sin(2 * pi * (x - t));
              case 4:
                return 1 + 0.25 * std::cos(2 * pi * (x - t));
              case 3:
                return c2(t - x / a[k]);
              default:
                return c1(t - x / a[k]);
            }
        },
        [](unsigned int, double) { return std::vector<double>{}; },
        std::vector<Solution::Vertex>{c1, c2});
      return e;
    }

    /// every example by its name (Network/exact solution)
    const std::vector<std::pair<std::string, Example (*)()>> &
    examples()
    {
      static const std::vector<std::pair<std::string, Example (*)()>> table{
        {"example_7_1", example_7_1},     {"example_7_2", example_7_2},
        {"example_7_3", example_7_3},     {"example_7_4", example_7_4},
        {"example_7_5", example_7_5},     {"smooth_linear", smooth_linear},
        {"two_stars", two_stars},         {"smooth_two_vertices", smooth_two_vertices}};
      return table;
    }
  } // namespace

  std::vector<std::string>
  example_names()
  {
    std::vector<std::string> names;
    for (const auto &e : examples())
      names.push_back(e.first);
    return names;
  }

  Example
  make_example(const std::string &name)
  {
    for (const auto &[n, make] : examples())
      if (n == name)
        return make();
    AssertThrow(false, ExcMessage("unknown example " + name));
    return {};
  }
} // namespace granular_dg::network
