#include <deal.II/base/numbers.h>

#include <granular_dg/base/errors.h>
#include <granular_dg/equations/network_scalar/graph.h>
#include <granular_dg/equations/network_scalar/junction.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace granular_dg::network
{
  std::string
  direction_name(const Direction d)
  {
    return d == Direction::in ? "in" : d == Direction::out ? "out" : "loop";
  }

  std::vector<EdgeEnd>
  Graph::vertex_ends() const
  {
    std::vector<EdgeEnd> ends;
    for (unsigned int k = 0; k < edges.size(); ++k)
      {
        if (edges[k].direction != Direction::out)
          ends.push_back({k, true});
        if (edges[k].direction != Direction::in)
          ends.push_back({k, false});
      }
    return ends;
  }

  Point<3>
  Graph::embed(const unsigned int k, const double x) const
  {
    // spread the edges of a kind evenly over a sector
    unsigned int index = 0, count = 0;
    for (unsigned int j = 0; j < edges.size(); ++j)
      if (edges[j].direction == edges[k].direction)
        {
          if (j < k)
            ++index;
          ++count;
        }
    const double pi  = numbers::PI;
    const double L   = edges[k].length;
    const double pos = count > 1 ? index / double(count - 1) - 0.5 : 0.; // in [-1/2, 1/2]
    switch (edges[k].direction)
      {
        case Direction::in:
          {
            // from the far end on the left towards the vertex at the origin
            const double phi = pi - pos * (count > 2 ? 2 * pi / 3 : pi / 2);
            return Point<3>((L - x) * std::cos(phi), (L - x) * std::sin(phi), 0.);
          }
        case Direction::out:
          {
            const double phi = pos * (count > 2 ? 2 * pi / 3 : pi / 2);
            return Point<3>(x * std::cos(phi), x * std::sin(phi), 0.);
          }
        default:
          {
            // a petal in the sector psi +- 25 degrees, above (first loop) or
            // below the vertex, clear of the straight edges
            const double psi   = (index % 2 == 0) ? pi / 2 : -pi / 2;
            const double delta = 25. * pi / 180., s = x / L;
            const double r     = 0.5 * L * (1. + 0.2 * (index / 2)) * std::sin(pi * s);
            const double theta = psi - delta + 2 * delta * s;
            return Point<3>(r * std::cos(theta), r * std::sin(theta), 0.);
          }
      }
  }

  Junction::Junction(const Graph &graph, const NumericalFlux type, const double width)
    : end_list(graph.vertex_ends())
    , type(type)
    , dx0(width)
  {
    for (const auto &e : graph.edges)
      flux.push_back(e.flux);
  }

  std::vector<double>
  Junction::end_fluxes(const std::vector<double> &traces, const double u0) const
  {
    std::vector<double> F(end_list.size());
    for (unsigned int i = 0; i < end_list.size(); ++i)
      {
        const FluxFunction &f = flux[end_list[i].edge];
        F[i] = end_list[i].incoming ? f.numerical_flux(type, traces[i], u0) :
                                      f.numerical_flux(type, u0, traces[i]);
      }
    return F;
  }

  double
  Junction::net_outflow(const std::vector<double> &traces, const double u0) const
  {
    const auto F   = end_fluxes(traces, u0);
    double     sum = 0;
    for (unsigned int i = 0; i < end_list.size(); ++i)
      sum += end_list[i].incoming ? -F[i] : F[i];
    return sum;
  }

  double
  Junction::rate(const std::vector<double> &traces, const double u0) const
  {
    return dx0 > 0 ? -net_outflow(traces, u0) / dx0 : 0.;
  }

  double
  Junction::balance(const std::vector<double> &traces, const double t) const
  {
    // net_outflow is nondecreasing in u0: bracket a sign change, then bisect
    double lo = traces.empty() ? 0. : *std::min_element(traces.begin(), traces.end());
    double hi = traces.empty() ? 0. : *std::max_element(traces.begin(), traces.end());
    double width = std::max(1., hi - lo);
    lo -= 1e-3 * width;
    hi += 1e-3 * width;
    for (unsigned int i = 0; i < 60 && net_outflow(traces, lo) > 0; ++i, width *= 2)
      lo -= width;
    for (unsigned int i = 0; i < 60 && net_outflow(traces, hi) < 0; ++i, width *= 2)
      hi += width;
    if (!(net_outflow(traces, lo) <= 0 && net_outflow(traces, hi) >= 0))
      {
        std::ostringstream s;
        s << "no vertex state balances the edge fluxes at t = " << t
          << " (sum_out F - sum_in F stays "
          << (net_outflow(traces, hi) < 0 ? "negative" : "positive")
          << "): the outgoing edges cannot carry the incoming flux; use a vertex "
             "with volume (Network/vertex width factor > 0)";
        throw RunError(s.str());
      }
    for (unsigned int i = 0; i < 200; ++i)
      {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi)
          break;
        const double r = net_outflow(traces, mid);
        if (r == 0)
          return mid;
        (r < 0 ? lo : hi) = mid;
      }
    // the end with the smaller residual
    return std::abs(net_outflow(traces, lo)) <= std::abs(net_outflow(traces, hi)) ? lo : hi;
  }
} // namespace granular_dg::network
