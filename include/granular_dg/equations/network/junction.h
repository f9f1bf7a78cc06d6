#pragma once

#include <deal.II/base/exceptions.h>

#include <granular_dg/dg/numerical_flux.h>
#include <granular_dg/equations/network/graph.h>

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
   */
  class Junction
  {
  public:
    /// The junction of vertex v of the graph.
    Junction(const Graph &graph, unsigned int v, NumericalFlux type, double width);
    /// ... with the vertex's ends (graph.vertex_ends(v)) given
    Junction(const Graph &graph, unsigned int v, std::vector<EdgeEnd> ends, NumericalFlux type,
             double width);

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

    /// net_outflow() with the laws and directions (incoming: 1) of the ends
    /// read from arrays in the order of ends(): a network keeps those of all
    /// its vertices in one array, which a stage reads in order.
    double
    net_outflow(const FluxFunction *law, const unsigned char *incoming, const double *traces,
                double u0) const;

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
    double
    end_flux(const FluxFunction &law, const bool in, const double trace, const double u0) const
    {
      return in ? law.numerical_flux(type, trace, u0) : law.numerical_flux(type, u0, trace);
    }

    const double *
    checked(const std::vector<double> &traces) const
    {
      AssertDimension(traces.size(), end_list.size());
      return traces.data();
    }

    std::vector<EdgeEnd>       end_list;
    std::vector<FluxFunction>  flux;     ///< of each end's edge
    std::vector<unsigned char> incoming; ///< of each end
    NumericalFlux              type;
    double                     dx0;
    std::string                label; ///< "vertex" on a star, else "Vertex 3"
  };
} // namespace granular_dg::network
