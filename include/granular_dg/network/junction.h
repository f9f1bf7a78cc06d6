#pragma once

#include <deal.II/base/exceptions.h>

#include <granular_dg/base/errors.h>
#include <granular_dg/network/graph.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace granular_dg::network
{
  /**
   * The vertex control volume of Musch, Fjordholm & Risebro (Section 4): one
   * value u_0 on a cell of width dx_0 (the paper: N dx / 2, the half cells of
   * the N edge ends), updated by (4.1b)
   *   du_0/dt = -(sum_out F^k(u_0, u^k_+) - sum_in F^k(u^k_-, u_0)) / dx_0
   * with u^k_-+ the traces of the edges at the vertex and F^k their
   * numerical flux, the same flux values the edges' vertex faces use (the
   * edge's Dirichlet state there is u_0), so edges + vertex conserve mass.
   *
   * Width 0 is a vertex without volume: u_0 then solves the discrete
   * Rankine-Hugoniot condition net_outflow(u_0) = 0 (Remark 4.8) at every
   * stage. net_outflow is nondecreasing in u_0 for monotone fluxes, so the
   * root is found by bracketing and bisection to machine precision. The same
   * solve gives the discrete stationary vertex value c_0 of given edge data
   * (Definition 4.4, Lemma 4.9).
   *
   * Law: the physics of an edge (NetworkProblem); laws: one per edge of the
   * graph.
   */
  template <typename Law>
  class Junction
  {
  public:
    /// The junction of vertex v of the graph.
    Junction(const Graph &graph, const std::vector<Law> &laws, unsigned int v, double width)
      : Junction(graph, laws, v, graph.vertex_ends(v), width)
    {}
    /// ... with the vertex's ends (graph.vertex_ends(v)) given
    Junction(const Graph &graph, const std::vector<Law> &laws, unsigned int v,
             std::vector<EdgeEnd> ends, double width);

    /// The edge ends, in the order of the traces passed below.
    const std::vector<EdgeEnd> &
    ends() const
    {
      return end_list;
    }

    double
    width() const
    {
      return dx0;
    }

    /// Flux of each end in its edge's direction: F(trace, u_0) at an
    /// incoming end, F(u_0, trace) at an outgoing one. traces: one per end,
    /// in the order of ends() (here and below).
    std::vector<double>
    end_fluxes(const double *traces, double u0) const;

    /// sum_out F - sum_in F: the rate at which the vertex loses mass, i.e.
    /// minus the Rankine-Hugoniot residual sum_in - sum_out.
    double
    net_outflow(const double *traces, double u0) const;

    /// du_0/dt of (4.1b) from the net outflow (0 for a vertex without volume).
    double
    rate(const double net_outflow) const
    {
      return dx0 > 0 ? -net_outflow / dx0 : 0.;
    }

    /// The u_0 with net_outflow = 0. Throws RunError (naming t) when the
    /// outgoing edges cannot carry the incoming flux for any u_0.
    double
    balance(const double *traces, double t) const;

    /// the above with the traces in a vector
    std::vector<double>
    end_fluxes(const std::vector<double> &traces, const double u0) const
    {
      return end_fluxes(checked(traces), u0);
    }
    double
    net_outflow(const std::vector<double> &traces, const double u0) const
    {
      return net_outflow(checked(traces), u0);
    }
    double
    balance(const std::vector<double> &traces, const double t) const
    {
      return balance(checked(traces), t);
    }

  private:
    /// The flux of one end in its edge's direction (end_fluxes())
    static double
    end_flux(const Law &law, const bool in, const double trace, const double u0)
    {
      return in ? law.flux(trace, u0) : law.flux(u0, trace);
    }

    const double *
    checked(const std::vector<double> &traces) const
    {
      AssertDimension(traces.size(), end_list.size());
      return traces.data();
    }

    std::vector<EdgeEnd>       end_list;
    std::vector<Law>           flux;     ///< of each end's edge
    std::vector<unsigned char> incoming; ///< of each end
    double                     dx0;
    std::string                label; ///< "vertex" on a star, else "Vertex 3"
  };

  template <typename Law>
  Junction<Law>::Junction(const Graph &graph, const std::vector<Law> &laws, const unsigned int v,
                          std::vector<EdgeEnd> ends, const double width)
    : end_list(std::move(ends))
    , dx0(width)
    , label(graph.is_star() ? "vertex" : graph.vertices[v].label)
  {
    for (const auto &end : end_list)
      {
        flux.push_back(laws[end.edge]);
        incoming.push_back(end.incoming);
      }
  }

  template <typename Law>
  std::vector<double>
  Junction<Law>::end_fluxes(const double *traces, const double u0) const
  {
    std::vector<double> F(end_list.size());
    for (unsigned int i = 0; i < end_list.size(); ++i)
      F[i] = end_flux(flux[i], incoming[i], traces[i], u0);
    return F;
  }

  template <typename Law>
  double
  Junction<Law>::net_outflow(const double *traces, const double u0) const
  {
    // end_fluxes() summed without a vector (a balance calls it up to ~260 times)
    double sum = 0;
    for (unsigned int i = 0; i < end_list.size(); ++i)
      {
        const double F = end_flux(flux[i], incoming[i], traces[i], u0);
        sum += incoming[i] ? -F : F;
      }
    return sum;
  }

  template <typename Law>
  double
  Junction<Law>::balance(const double *traces, const double t) const
  {
    // net_outflow is nondecreasing in u0: bracket a sign change, then bisect
    const double *end = traces + end_list.size();
    if (const double *bad = std::find_if(traces, end, [](double x) { return !std::isfinite(x); });
        bad != end)
      {
        std::ostringstream s;
        s << "an edge's trace at " << label << " is not finite at t = " << t << " (u = " << *bad
          << "): no " << label << " state balances it (check the data of its edges)";
        throw RunError(s.str());
      }
    double        lo  = end_list.empty() ? 0. : *std::min_element(traces, end);
    double        hi  = end_list.empty() ? 0. : *std::max_element(traces, end);
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
        s << "no " << label << " state balances the edge fluxes at t = " << t
          << " (sum_out F - sum_in F stays "
          << (net_outflow(traces, hi) < 0 ? "negative" : "positive")
          << "): the outgoing edges cannot carry the incoming flux; "
          << (dx0 > 0 ? "there is no stationary initial value for these data: give the vertex an "
                        "initial value (Network/vertex initial value)" :
                        "use a vertex with volume (Network/vertex width factor > 0)");
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
