// The network engine is a template on the physics of an edge: a Law of this
// test's own, written from the contract in granular_dg/network/network.h
// (value, derivative, flux, admissible_range, vertex_range, describe,
// flux_name, name) and nothing else, runs it. Linear advection f = a u (a = 0.75) with the
// upwind flux a u_l on a star of 2 ingoing and 2 outgoing edges (Dirichlet
// inflow data, a vertex with volume), degree 2, SSP-RK3, 40 steps: the state must equal,
// bit for bit, that of the scene's EdgeLaw (linear flux, Engquist-Osher =
// upwind for a > 0) on the same network, and so must the time steps.

#include <granular_dg/base/parameters.h>
#include <granular_dg/equations/network/system.h>
#include <granular_dg/network/edge_lines.templates.h>
#include <granular_dg/network/network.templates.h>
#include <granular_dg/network/output.templates.h>

#include <array>
#include <cmath>
#include <iostream>

using namespace granular_dg;
using namespace granular_dg::network;

namespace
{
  /// f = a u, a > 0, with the upwind flux
  struct Advection
  {
    double a = 1.;

    static constexpr const char *name = "linear advection";

    template <typename Number>
    Number
    value(const Number &u) const
    {
      return a * u;
    }

    template <typename Number>
    Number
    derivative(const Number &) const
    {
      return Number(a);
    }

    template <typename Number>
    Number
    flux(const Number &u_l, const Number &) const
    {
      return a * u_l;
    }

    std::array<double, 2>
    admissible_range() const
    {
      return {{-INFINITY, INFINITY}};
    }

    std::array<double, 2>
    vertex_range(bool) const
    {
      return admissible_range();
    }

    std::string
    describe() const
    {
      return "f = " + std::to_string(a) + " u";
    }

    std::string
    flux_name() const
    {
      return "upwind";
    }
  };
} // namespace

int
main()
{
  constexpr double a = 0.75;
  Graph            g;
  g.vertices.resize(1);
  for (const Direction d : {Direction::in, Direction::in, Direction::out, Direction::out})
    {
      Edge e;
      e.meet(d);
      e.far_end = FarEnd::dirichlet;
      e.label   = "Edge";
      g.edges.push_back(e);
    }
  std::vector<EdgeData> data;
  for (const std::string u0 : {"1 + 0.5*sin(2*pi*x)", "if(x < 0.5, 1, 0.2)", "0.3", "x*x"})
    data.push_back({make_function<1>({u0}, {"initial data"}, false),
                    make_function<1>({"1 + 0.2*sin(3*t)"}, {"far-end data"}, true),
                    {}});

  dg::DiscretizationParameters method;
  method.degree = 2;
  method.cfl    = 0.2;
  NetworkOptions options;
  options.cells_per_unit_length = 24;

  NetworkProblem<EdgeLaw> scene_law(
    g, std::vector<EdgeLaw>(4, EdgeLaw{{FluxLaw::linear, a, 1.}, NumericalFlux::upwind}), method,
    options, data);
  NetworkProblem<Advection> own_law(g, std::vector<Advection>(4, Advection{a}), method, options,
                                    data);
  scene_law.initialize();
  own_law.initialize();
  double       t = 0, dt_difference = 0;
  unsigned int steps = 0;
  for (; steps < 40; ++steps)
    {
      const double dt = scene_law.time_step(t);
      dt_difference   = std::max(dt_difference, std::abs(own_law.time_step(t) - dt));
      scene_law.advance(t, dt);
      own_law.advance(t, dt);
      t += dt;
    }
  double difference = std::abs(scene_law.vertex_value() - own_law.vertex_value());
  for (std::size_t i = 0; i < scene_law.state().edges.size(); ++i)
    difference =
      std::max(difference, std::abs(scene_law.state().edges[i] - own_law.state().edges[i]));
  std::cout << own_law.info().physics << ", " << steps << " steps to t = " << t
            << "\nlargest difference to EdgeLaw: time step " << dt_difference << ", state "
            << difference << std::endl;
}
