#pragma once

#include <deal.II/base/numbers.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace granular_dg::network
{
  using namespace dealii;

  /// The end of an edge that meets no vertex (inflow data or outflow).
  constexpr unsigned int free_end = numbers::invalid_unsigned_int;

  /// How an edge meets one vertex (the star graph's words). Every edge runs
  /// from x = 0 to x = L in its own coordinate: an ingoing edge ends at the
  /// vertex (x = L), an outgoing one starts there (x = 0), a loop
  /// (roundabout) does both, `apart` does neither.
  enum class Direction
  {
    in,
    out,
    loop,
    apart
  };

  /// The condition at a free end of an edge.
  enum class FarEnd
  {
    dirichlet, ///< exterior state g(t): inflow data
    outflow    ///< exterior state = interior one (the paper's "zero Neumann")
  };

  struct Edge
  {
    std::string  label; ///< "Edge 3", for messages and output
    /// the vertices at x = 0 and x = L (free_end: none)
    unsigned int from   = free_end;
    unsigned int to     = free_end;
    double       length = 1.;
    FarEnd       far_end = FarEnd::outflow;

    /// boundary ids of the edge's Triangulation<1>: 0 at x = 0, 1 at x = L
    bool
    vertex_at(const unsigned int boundary_id) const
    {
      return (boundary_id == 0 ? from : to) != free_end;
    }

    /// How the edge meets vertex v.
    Direction
    direction(const unsigned int v) const
    {
      return from == v ? (to == v ? Direction::loop : Direction::out) :
                         (to == v ? Direction::in : Direction::apart);
    }

    /// Attach the edge to vertex v of a star: in, out or loop.
    void
    meet(Direction d, unsigned int v = 0);
  };

  struct Vertex
  {
    std::string label; ///< "Vertex 2", for messages and output
    /// dx_0 = width_factor * (sum over the vertex's edge ends of h_k / 2)
    double width_factor = 1.;
    /// u_0 at t = 0 (none: the discrete stationary value of the edge traces)
    std::optional<double> initial_value;
    /// where the vertex is drawn (none: the scene places it)
    std::optional<Point<2>> position;

    /// A cell the edges' CFL step does not cover: with the edge speeds of
    /// the CFL scan, dt sum_k max|f'| <= cfl sum_k h_k = 2 cfl dx_0 / width
    /// factor, so a factor below 2 cfl needs a bound of its own
    /// (NetworkProblem::time_step(); the paper's 1 at CFL 1/2 does not).
    bool
    narrower_than_step(const double cfl) const
    {
      return width_factor > 0 && width_factor < 2 * cfl;
    }
  };

  /// One edge end at a vertex: the end x = L of an edge flowing in
  /// (incoming) or the end x = 0 of an edge flowing out.
  struct EdgeEnd
  {
    unsigned int edge;
    bool         incoming;
  };

  /// A file a graph was read from (Network/graph file, vertex file) and the
  /// FNV-1a hash of its bytes: a checkpoint stores it, and resuming with a
  /// file whose content changed since is refused.
  struct GraphFile
  {
    std::string   parameter; ///< "Network/graph file"
    std::string   name;      ///< as the parameter gives it
    std::uint64_t content_hash = 0;
  };

  /// A directed graph: edges between vertices or free ends. The paper's star
  /// graph is the graph with one vertex. It holds no physics: the engine
  /// (NetworkProblem) takes the flux law of every edge beside it.
  struct Graph
  {
    std::vector<Vertex> vertices;
    std::vector<Edge>   edges;
    /// the files it was read from (none: the prm's sections)
    std::vector<GraphFile> files;

    /// The edge ends at vertex v (a loop gives two); their number is the
    /// paper's N in the vertex width dx_0 = N dx / 2.
    std::vector<EdgeEnd>
    vertex_ends(unsigned int v) const;

    /// vertex_ends(v) of every vertex, in one pass over the edges
    std::vector<std::vector<EdgeEnd>>
    all_vertex_ends() const;

    /// One vertex whose every edge has its other end free (the paper's
    /// setting): its output keeps the paper's words in/out/loop.
    bool
    is_star() const;

    /// Throws InputError naming the first edge or vertex that does not make
    /// a graph: a dangling vertex reference, a vertex without edges, an
    /// edge with length <= 0 or non-finite.
    void
    validate(const std::string &where) const;

    /// "in" / "out" / "loop" on a star, else "vertex 1 -> vertex 2",
    /// "free -> vertex 3", ...
    std::string
    describe(unsigned int edge) const;
    /// the same for an edge from `from` to `to` (free_end: none)
    std::string
    describe_ends(unsigned int from, unsigned int to) const;

    /// Where vertex v is drawn: its position, or (a graph without
    /// positions) on a circle, the star's vertex at the origin.
    Point<2>
    position(unsigned int v) const;
  };

  /**
   * Where the network is drawn in the plane (solution-NNNN.vtu), computed once
   * for the graph. A star: ingoing edges on the left, outgoing ones on the
   * right, loops as petals through the vertex at the origin. Any other graph:
   * edges between two vertices straight from one to the other; an edge with a
   * free end leaves its vertex in the direction opposite to one of the
   * vertex's other edges, the one farthest from the directions already taken
   * there (a road continues the street it ends; the away-from-the-centre
   * direction when the vertex has no other edges); loops as petals. A free
   * edge is drawn with the mean drawn length per unit length of the
   * vertex-to-vertex edges.
   */
  class GraphDrawing
  {
  public:
    explicit GraphDrawing(const Graph &graph);

    /// where point x of edge k is drawn
    Point<3>
    operator()(unsigned int edge, double x) const;

    const Point<2> &
    vertex(const unsigned int v) const
    {
      return vertices[v];
    }

  private:
    Point<3>
    star(unsigned int edge, double x) const;

    const Graph             &graph;
    bool                     is_star;
    double                   scale = 1.;
    std::vector<Point<2>>    vertices;
    /// per edge with a free end or a loop: the unit direction it is drawn in
    std::vector<Tensor<1, 2>> direction;
  };

  std::string
  direction_name(Direction d);
} // namespace granular_dg::network
