#pragma once

#include <deal.II/base/parameter_handler.h>

#include <granular_dg/equations/network/graph.h>
#include <granular_dg/equations/network/network.h>

#include <string>
#include <vector>

namespace granular_dg::network
{
  /**
   * The graph of a network case and the data of its edges, read from the
   * prm (subsections Vertex N and Edge N of Network) or from CSV files
   * (Network/graph file: an edge list; Network/vertex file: positions and
   * vertex data), validated: every error is an InputError naming the
   * parameter or the file, line, edge or vertex.
   */
  struct GraphInput
  {
    Graph                    graph;
    std::vector<EdgeData>    data;
    /// per edge: its initial data as written, and where it was given
    /// ("Network/Edge 3/" or "Network/graph file 'grid.csv', line 4: ")
    std::vector<std::string> initial_text;
    std::vector<std::string> where;

    /// Declare the graph's entries (inside subsection Network).
    static void
    declare(ParameterHandler &prm);
    /// Read them (inside subsection Network).
    void
    parse(ParameterHandler &prm);

  private:
    void
    parse_sections(ParameterHandler &prm);
    /// e with its data (numbers become constants, else expressions; the
    /// names are the data's parameters in messages)
    void
    add_edge(Edge e, const std::string &where, const std::string &initial,
             const std::string &far_end_data, const std::string &initial_name,
             const std::string &far_end_name);
    /// per vertex: whether its initial value was given (else the default)
    std::vector<bool> value_given;
    /// the graph file's vertex ids, in the order of graph.vertices
    std::vector<long> vertex_ids;
    void
    read_edge_file(const std::string &parameter, const std::string &file);
    /// edges: the graph file as messages name it ("Network/graph file
    /// 'grid.csv'"); a vertex that no edge names is refused at its line
    void
    read_vertex_file(const std::string &parameter, const std::string &file,
                     const std::string &edges);
  };

  /// The largest number N of the Network/Edge N and Vertex N subsections.
  constexpr unsigned int max_edge_sections   = 16;
  constexpr unsigned int max_vertex_sections = 8;
} // namespace granular_dg::network
