// L1 contraction and monotonicity of the network scheme (Theorem 4.14,
// Definition 4.1): two runs of the degree-0 scheme (4.1) on the network of
// Example 7.5 (Burgers, 2 in, 3 out, Dirichlet far ends with equal data),
// from data u <= v that differ on every edge and at the vertex, advanced
// with the same time steps. Printed:
//  - the largest ratio ||u^{n+1} - v^{n+1}||_L1 / ||u^n - v^n||_L1 over all
//    steps (<= 1: contraction at every step) and the final/initial ratio;
//  - the smallest v - u over all modes and the vertex (>= 0: order kept).
// First with the paper's fixed step dt = dx / 4 (CFL 1/2 for the speeds
// |u| <= 2 of these data), the naive method: for the paper's vertex cell
// dx_0 = N dx / 2, for one half as wide (still monotone: the vertex update
// needs dt sum_out |f'(u_0)| <= dx_0, i.e. a width factor >= 0.39 here) and
// for one 1/0.15 times too narrow, where both properties fail. Then the
// narrow cell with the program's time step (NetworkProblem::time_step(),
// which keeps dt sum max|f'| <= dx_0 at such a vertex): both hold again.
// The .output holds the outcomes (yes/no) and the ratios (4 digits).

#include <granular_dg/base/parameters.h>
#include <granular_dg/equations/network/system.h>
#include <granular_dg/network/network.h>

#include <cmath>
#include <iomanip>
#include <iostream>

using namespace granular_dg;
using namespace granular_dg::network;

namespace
{
  /// fixed_dt > 0: that step; 0: the program's (NetworkProblem::time_step())
  void
  compare(const double width_factor, const double fixed_dt)
  {
    Graph g;
    g.vertices.resize(1);
    g.vertices[0].width_factor = width_factor;
    for (const Direction d :
         {Direction::in, Direction::in, Direction::out, Direction::out, Direction::out})
      {
        Edge e;
        e.meet(d);
        e.far_end   = FarEnd::dirichlet;
        e.label     = "Edge";
        g.edges.push_back(e);
      }
    const std::vector<EdgeLaw>     laws(5, EdgeLaw{{FluxLaw::burgers, 1., 1.}, NumericalFlux::upwind});
    const std::vector<std::string> far = {"2", "1", "0.8", "0.8", "0.8"};
    const std::vector<std::string> du  = {"if(x < 0.8, 2, 1)", "1", "0.8", "0.8", "0.8"};
    const std::vector<std::string> dv  = {"if(x < 0.9, 2, 1.2)", "1 + 0.3*x", "0.9", "1.1",
                                          "0.8 + 0.4*x*(1-x)"};
    std::vector<EdgeData> data_u, data_v;
    for (unsigned int k = 0; k < 5; ++k)
      {
        data_u.push_back({make_function<1>({du[k]}, {"initial data"}, false),
                          make_function<1>({far[k]}, {"far-end data"}, true), {}});
        data_v.push_back({make_function<1>({dv[k]}, {"initial data"}, false),
                          make_function<1>({far[k]}, {"far-end data"}, true), {}});
      }
    // the paper's scheme: degree 0, upwind flux, CFL 0.5
    dg::DiscretizationParameters method;
    method.degree = 0;
    method.cfl    = 0.5;
    NetworkOptions options;
    options.cells_per_unit_length = 64;
    Graph gu = g, gv = g;
    gu.vertices[0].initial_value = 0.8;
    gv.vertices[0].initial_value = 1.0;
    NetworkProblem<EdgeLaw> u(gu, laws, method, options, data_u), v(gv, laws, method, options, data_v);
    u.initialize();
    v.initialize();

    const double  d0 = u.l1_distance(v);
    double        d = d0, max_ratio = 0, min_gap = 1e300, t = 0;
    unsigned long steps = 0;
    while (t < 0.5 * (1 - 1e-14))
      {
        const double dt = std::min(
          {fixed_dt > 0 ? fixed_dt : std::min(u.time_step(t), v.time_step(t)), 0.5 - t});
        u.advance(t, dt);
        v.advance(t, dt);
        t += dt;
        ++steps;
        const double d_new = u.l1_distance(v);
        max_ratio          = std::max(max_ratio, d_new / d);
        d                  = d_new;
        min_gap            = std::min(min_gap, v.vertex_value() - u.vertex_value());
        for (std::size_t i = 0; i < u.state().edges.size(); ++i)
          min_gap = std::min(min_gap, v.state().edges[i] - u.state().edges[i]);
      }
    std::cout << "vertex width factor " << width_factor << ", "
              << (fixed_dt > 0 ? "fixed step dx/4" : "the program's step") << ": " << steps
              << " steps"
              << "\n  contraction at every step: " << (max_ratio <= 1 + 1e-13 ? "yes" : "no")
              << " (max ratio " << max_ratio << ", final/initial " << d / d0 << ")"
              << "\n  order preserved: " << (min_gap >= -1e-14 ? "yes" : "no")
              << " (min v - u " << min_gap << ")" << std::endl;
  }
} // namespace

int
main()
{
  std::cout << std::setprecision(4);
  // monotone for width factors >= 0.39 here (dt sum_out f'(u_0) <= dx_0)
  const double dx = 1. / 64;
  for (const double f : {1., 0.5, 0.15})
    compare(f, dx / 4);
  compare(0.15, 0);
}
