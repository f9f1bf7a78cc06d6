#pragma once

#include <deal.II/base/point.h>

#include <granular_dg/equations/network_scalar/system.h>

#include <string>
#include <vector>

namespace granular_dg::network
{
  /// How an edge meets the vertex. Every edge runs from x = 0 to x = L in
  /// its own coordinate: an ingoing edge ends at the vertex (x = L), an
  /// outgoing one starts there (x = 0), a loop (roundabout) does both.
  enum class Direction
  {
    in,
    out,
    loop
  };

  /// The condition at the far end of an in/out edge (loops have none).
  enum class FarEnd
  {
    dirichlet, ///< exterior state g(t): inflow data
    outflow    ///< exterior state = interior one (the paper's "zero Neumann")
  };

  struct Edge
  {
    std::string  label; ///< "Edge 3", for messages and output
    Direction    direction = Direction::out;
    double       length    = 1.;
    FluxFunction flux;
    FarEnd       far_end = FarEnd::outflow;

    /// boundary ids of the edge's Triangulation<1>: 0 at x = 0, 1 at x = L
    bool
    vertex_at(const unsigned int boundary_id) const
    {
      return direction == Direction::loop || (boundary_id == 1) == (direction == Direction::in);
    }
  };

  /// One edge end at the vertex: the end x = L of an edge flowing in
  /// (incoming) or the end x = 0 of an edge flowing out.
  struct EdgeEnd
  {
    unsigned int edge;
    bool         incoming;
  };

  /// A star graph: edges meeting at one vertex.
  struct Graph
  {
    std::vector<Edge> edges;

    /// The edge ends at the vertex (a loop gives two); their number is the
    /// paper's N in the vertex width dx_0 = N dx / 2.
    std::vector<EdgeEnd>
    vertex_ends() const;

    /// Where point x of edge k is drawn in the plane: ingoing edges on the
    /// left, outgoing ones on the right, loops as petals through the vertex
    /// (at the origin), above and below.
    Point<3>
    embed(unsigned int edge, double x) const;
  };

  std::string
  direction_name(Direction d);
} // namespace granular_dg::network
