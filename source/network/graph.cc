#include <deal.II/base/numbers.h>

#include <granular_dg/base/errors.h>
#include <granular_dg/network/graph.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace granular_dg::network
{
  std::string
  direction_name(const Direction d)
  {
    return d == Direction::in ? "in" : d == Direction::out ? "out" : d == Direction::loop ? "loop" : "apart";
  }

  void
  Edge::meet(const Direction d, const unsigned int v)
  {
    from = (d == Direction::out || d == Direction::loop) ? v : free_end;
    to   = (d == Direction::in || d == Direction::loop) ? v : free_end;
  }

  std::vector<EdgeEnd>
  Graph::vertex_ends(const unsigned int v) const
  {
    std::vector<EdgeEnd> ends;
    for (unsigned int k = 0; k < edges.size(); ++k)
      {
        if (edges[k].to == v)
          ends.push_back({k, true});
        if (edges[k].from == v)
          ends.push_back({k, false});
      }
    return ends;
  }

  std::vector<std::vector<EdgeEnd>>
  Graph::all_vertex_ends() const
  {
    std::vector<std::vector<EdgeEnd>> ends(vertices.size());
    for (unsigned int k = 0; k < edges.size(); ++k)
      {
        if (edges[k].to != free_end)
          ends[edges[k].to].push_back({k, true});
        if (edges[k].from != free_end)
          ends[edges[k].from].push_back({k, false});
      }
    return ends;
  }

  bool
  Graph::is_star() const
  {
    return vertices.size() == 1 && std::all_of(edges.begin(), edges.end(), [](const Edge &e) {
             return e.direction(0) != Direction::apart;
           });
  }

  void
  Graph::validate(const std::string &where) const
  {
    auto fail = [&](const std::string &what) { throw InputError(where + ": " + what); };
    if (edges.empty())
      fail("the network has no edges");
    std::vector<unsigned int> degree(vertices.size(), 0);
    for (const Edge &e : edges)
      {
        if (!(std::isfinite(e.length) && e.length > 0))
          {
            std::ostringstream s;
            s << e.label << " has length " << e.length << ": must be finite and > 0";
            fail(s.str());
          }
        for (const unsigned int v : {e.from, e.to})
          if (v != free_end)
            {
              if (v >= vertices.size())
                fail(e.label + " refers to a vertex that does not exist (" +
                     std::to_string(v + 1) + "; the network has " +
                     std::to_string(vertices.size()) + ")");
              ++degree[v];
            }
      }
    for (unsigned int v = 0; v < vertices.size(); ++v)
      if (degree[v] == 0)
        fail(vertices[v].label + " has no edges (every vertex needs at least one)");
    const auto has_position = [](const Vertex &x) { return x.position.has_value(); };
    const auto n_positions = std::count_if(vertices.begin(), vertices.end(), has_position);
    if (n_positions != 0 && n_positions != long(vertices.size()))
      fail(std::find_if_not(vertices.begin(), vertices.end(), has_position)->label +
           " has no position: give every vertex a position, or none");
  }

  std::string
  Graph::describe(const unsigned int k) const
  {
    return describe_ends(edges[k].from, edges[k].to);
  }

  std::string
  Graph::describe_ends(const unsigned int from, const unsigned int to) const
  {
    if (is_star())
      {
        Edge e;
        e.from = from;
        e.to   = to;
        return direction_name(e.direction(0));
      }
    auto name = [&](const unsigned int v) {
      return v == free_end ? std::string("free end") : vertices[v].label;
    };
    return name(from) + " -> " + name(to);
  }

  Point<2>
  Graph::position(const unsigned int v) const
  {
    if (vertices[v].position)
      return *vertices[v].position;
    if (vertices.size() == 1)
      return Point<2>();
    // on a circle whose circumference is the mean edge length per vertex
    double total = 0;
    for (const Edge &e : edges)
      total += e.length;
    const double r   = total / edges.size() * vertices.size() / (2 * numbers::PI);
    const double phi = 2 * numbers::PI * v / vertices.size();
    return Point<2>(r * std::cos(phi), r * std::sin(phi));
  }

  GraphDrawing::GraphDrawing(const Graph &graph)
    : graph(graph)
    , is_star(graph.is_star())
  {
    const auto &edges = graph.edges;
    for (unsigned int v = 0; v < graph.vertices.size(); ++v)
      vertices.push_back(graph.position(v));
    direction.resize(edges.size());
    if (is_star)
      return;
    auto joins = [&](const Edge &e) {
      return e.from != free_end && e.to != free_end && e.from != e.to;
    };
    // drawn length per unit edge length of the vertex-to-vertex edges
    double       sum = 0;
    unsigned int n   = 0;
    for (const Edge &e : edges)
      if (joins(e))
        {
          sum += vertices[e.from].distance(vertices[e.to]) / e.length;
          ++n;
        }
    scale = n > 0 && sum > 0 ? sum / n : 1.;
    Point<2> centre;
    for (const auto &p : vertices)
      centre += p / double(vertices.size());

    // the directions of the edges at each vertex, then the free ends and loops
    std::vector<std::vector<Tensor<1, 2>>> taken(vertices.size());
    for (const Edge &e : edges)
      if (joins(e))
        {
          const Tensor<1, 2> d = vertices[e.to] - vertices[e.from];
          if (d.norm() > 0)
            {
              taken[e.from].push_back(d / d.norm());
              taken[e.to].push_back(-d / d.norm());
            }
        }
    const auto streets = taken;
    for (unsigned int k = 0; k < edges.size(); ++k)
      {
        if (joins(edges[k]))
          continue;
        const unsigned int v = edges[k].from != free_end ? edges[k].from : edges[k].to;
        if (v == free_end)
          continue;
        Tensor<1, 2> away = vertices[v] - centre;
        away = away.norm() > 0 ? away / away.norm() : Tensor<1, 2>({1., 0.});
        // the continuation of a street farthest (in angle) from every
        // direction taken at v; away from the centre if none is 45 degrees clear
        auto clearance = [&](const Tensor<1, 2> &c) {
          double nearest = 2; // 1 - cos(angle) in [0, 2]
          for (const auto &d : taken[v])
            nearest = std::min(nearest, 1 - c * d);
          return nearest;
        };
        double best  = -1;
        direction[k] = away;
        for (const auto &d : streets[v])
          if (clearance(-d) > best + 1e-12)
            {
              best         = clearance(-d);
              direction[k] = -d;
            }
        if (best < 1 - std::sqrt(0.5))
          direction[k] = away;
        taken[v].push_back(direction[k]);
      }
  }

  Point<3>
  GraphDrawing::operator()(const unsigned int k, const double x) const
  {
    if (is_star)
      return star(k, x);
    const Edge  &e = graph.edges[k];
    const double s = x / e.length;
    if (e.from != free_end && e.to != free_end && e.from != e.to)
      {
        const Point<2> p = vertices[e.from] + s * (vertices[e.to] - vertices[e.from]);
        return Point<3>(p[0], p[1], 0.);
      }
    const unsigned int v = e.from != free_end ? e.from : e.to;
    if (v == free_end) // a line on its own, below the drawing
      return Point<3>(scale * x, -1. - k, 0.);
    const Tensor<1, 2> &d = direction[k];
    if (e.from == e.to) // a loop: a petal around d
      {
        const double   phi   = std::atan2(d[1], d[0]);
        const double   r     = 0.5 * scale * e.length * std::sin(numbers::PI * s);
        const double   theta = phi - 0.4 + 0.8 * s;
        const Point<2> p = vertices[v] + r * Tensor<1, 2>({std::cos(theta), std::sin(theta)});
        return Point<3>(p[0], p[1], 0.);
      }
    // an outgoing free edge runs away from v, an incoming one towards it
    const Point<2> p = vertices[v] + scale * (e.from == v ? x : e.length - x) * d;
    return Point<3>(p[0], p[1], 0.);
  }

  Point<3>
  GraphDrawing::star(const unsigned int k, const double x) const
  {
    const auto &edges = graph.edges;
    // spread the edges of a kind evenly over a sector
    const Direction dir   = edges[k].direction(0);
    unsigned int    index = 0, count = 0;
    for (unsigned int j = 0; j < edges.size(); ++j)
      if (edges[j].direction(0) == dir)
        {
          if (j < k)
            ++index;
          ++count;
        }
    const double pi  = numbers::PI;
    const double L   = edges[k].length;
    const double pos = count > 1 ? index / double(count - 1) - 0.5 : 0.; // in [-1/2, 1/2]
    switch (dir)
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

} // namespace granular_dg::network
