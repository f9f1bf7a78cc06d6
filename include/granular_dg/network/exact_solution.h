#pragma once

#include <string>
#include <vector>

namespace granular_dg::network
{
  /// A known solution on a network, for error measurement: the value on
  /// every edge (edge coordinate x in [0, L]), the points where it is not
  /// smooth (shocks, fan edges: the error quadrature splits cells there) and
  /// the state at the vertex (the trace of the outgoing edges).
  class ExactSolution
  {
  public:
    virtual ~ExactSolution() = default;

    virtual double
    value(unsigned int edge, double x, double t) const = 0;

    virtual std::vector<double>
    breakpoints(unsigned int /*edge*/, double /*t*/) const
    {
      return {};
    }

    /// the value of vertex v (the graph's numbering, from 0)
    virtual double
    vertex_value(unsigned int v, double t) const = 0;

    /// The solution is known on [0, valid_until()].
    virtual double
    valid_until() const
    {
      return 1e300;
    }

    virtual std::string
    name() const = 0;
  };
} // namespace granular_dg::network
