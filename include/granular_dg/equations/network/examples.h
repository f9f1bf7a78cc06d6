#pragma once

/**
 * @file
 * The exact solutions of the five examples of Section 7 of Musch, Fjordholm
 * & Risebro (2022) and of a smooth test, with the graph each expects.
 * Edges are numbered as in prm/network_example_7_*.prm: the ingoing edges
 * (paper: -1, -2) first, then the roundabout (7.1), then the outgoing edges
 * (1, 2, 3). Every edge has length 1. What the copy of the paper gets wrong
 * (corrected here; see doc/network.md):
 *  - 7.1: the in-edge shock starts at x = 0.5 (u = 2 for x < 0.5 + s t,
 *    s = (2 + sqrt 2)/2) and reaches the vertex at t* = 1 - 1/sqrt 2; then
 *    u_0 = sqrt(5/3) and the shocks sqrt(5/3) | 1 on the loop and the
 *    outgoing edges move at (1 + sqrt(5/3))/2 (not 1/(sqrt(5/3) - 1));
 *  - 7.2: alpha = 2 on the outgoing edge with data 0 (the rarefaction),
 *    alpha = 4 on those with data c_0 and 1 (the text swaps them); the shock
 *    on the alpha = 4 edge runs from c_0 to the right state 1 at speed
 *    3 - c_0, c_0 = (3 - sqrt 7)/2;
 *  - 7.4: c_0 = sqrt(2/3) (3 c_0^2 = 2; the text's sqrt(3/2) is a typo).
 */

#include <granular_dg/equations/network/system.h>
#include <granular_dg/network/exact_solution.h>
#include <granular_dg/network/graph.h>

#include <memory>
#include <string>
#include <vector>

namespace granular_dg::network
{
  /// What an example needs of an edge (checked against the prm): its
  /// vertices (free_end: none) and flux.
  struct ExpectedEdge
  {
    /// an edge of a star: in, out or loop at vertex 0
    ExpectedEdge(const Direction d, const FluxFunction &f)
      : flux(f)
    {
      Edge e;
      e.meet(d);
      from = e.from;
      to   = e.to;
    }
    ExpectedEdge(const unsigned int from, const unsigned int to, const FluxFunction &f)
      : from(from)
      , to(to)
      , flux(f)
    {}
    unsigned int from, to;
    FluxFunction flux;
  };

  struct Example
  {
    std::string                    name;        ///< "example_7_3"
    std::string                    description; ///< one line
    unsigned int                   n_vertices = 1;
    std::vector<ExpectedEdge>      edges;
    std::shared_ptr<ExactSolution> exact;
  };

  /// "example_7_1" ... "example_7_5", "smooth_linear", "two_stars",
  /// "smooth_two_vertices"
  std::vector<std::string>
  example_names();

  Example
  make_example(const std::string &name);
} // namespace granular_dg::network
