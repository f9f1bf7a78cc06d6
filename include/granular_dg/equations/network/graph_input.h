#pragma once

#include <deal.II/base/parameter_handler.h>

#include <granular_dg/equations/network/system.h>
#include <granular_dg/network/graph.h>
#include <granular_dg/network/network.h>

#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace granular_dg
{
  class ParameterBinding;
}

namespace granular_dg::network
{
  /// The largest number N of the Network/Edge N and Vertex N subsections.
  constexpr unsigned int max_edge_sections   = 16;
  constexpr unsigned int max_vertex_sections = 8;

  /// The entries of one Network/Edge N subsection, as given.
  struct EdgeSection
  {
    std::string direction = "none";
    std::string from      = "none";
    std::string to        = "none";
    double      length    = 1.;
    std::string flux      = "burgers";
    double      advection_speed = 1.;
    double      alpha           = 1.;
    std::string initial_data    = "0";
    std::string far_end         = "outflow";
    std::string far_end_data    = "0";
  };

  /// The entries of one Network/Vertex N subsection, as given.
  struct VertexSection
  {
    std::string width_factor  = "default";
    std::string initial_value = "default";
    std::string position;
  };

  /**
   * The graph of a network case and the data of its edges, read from the
   * prm (subsections Vertex N and Edge N of Network) or from CSV files
   * (Network/graph file: an edge list; Network/vertex file: positions and
   * vertex data), validated: every error is an InputError naming the
   * parameter or the file, line, edge or vertex.
   */
  struct GraphInput
  {
    /// The entries (bind()): in subsection Network ...
    std::string graph_file;
    std::string vertex_file;
    double      vertex_width_factor  = 1.;
    std::string vertex_initial_value = "stationary";
    /// ... and its subsections Edge N and Vertex N
    std::vector<EdgeSection>   edge_sections   = std::vector<EdgeSection>(max_edge_sections);
    std::vector<VertexSection> vertex_sections = std::vector<VertexSection>(max_vertex_sections);

    /// What they describe, built and validated once they are read:
    Graph                     graph;
    /// per edge: its flux law and its data
    std::vector<FluxFunction> flux;
    std::vector<EdgeData>     data;
    /// per edge: its initial and far-end data as written
    std::vector<std::string> initial_text, far_end_text;
    /// where edge k was given: "Network/Edge 3/" or "Network/graph file
    /// 'grid.csv', line 4: "
    std::string
    where(unsigned int k) const;

    /// The graph's entries, each with its field, pattern and documentation
    /// (ParameterBinding); once read, the graph and its data built from them.
    void
    bind(ParameterBinding &b);

  private:
    void
    build();
    void
    build_from_sections();
    /// the vertices the edges name (the first n_vertices); a Vertex N
    /// section beyond them is refused
    void
    vertices_from_sections(unsigned int n_vertices);
    /// Far-end settings that could never act are refused: a far end given
    /// on an edge without a free end, data given without a free dirichlet
    /// end (far_end_given, data_given: written by the user).
    void
    require_far_end_used(const Edge &e, const std::string &far_end_name, const std::string &far_end,
                         bool far_end_given, const std::string &data_name, const std::string &data,
                         bool data_given) const;
    /// e with its flux law f and its data (numbers become constants, else
    /// expressions; the names are the data's parameters in messages), given
    /// in Edge N section origin (0-based) or at line origin of the graph file
    void
    add_edge(Edge e, const FluxFunction &f, unsigned int origin, std::string_view initial,
             std::string_view far_end_data, const char *initial_name, const char *far_end_name);
    /// per edge: add_edge()'s origin
    std::vector<unsigned int> edge_origin;
    /// the far-end data by their text: edges with the same data share one
    /// function (a stage evaluates each once, NetworkProblem::set_end_states)
    std::map<std::string, std::shared_ptr<Function<1>>> far_end_functions;
    /// per vertex: the parameter that gave its initial value ("": the
    /// default, Network/vertex initial value)
    std::vector<std::string> value_given;
    /// the graph file's vertex ids, in the order of graph.vertices
    /// (increasing)
    std::vector<long> vertex_ids;
    void
    read_edge_file(const std::string &parameter, const std::string &file);
    /// edges: the graph file as messages name it ("Network/graph file
    /// 'grid.csv'"); a vertex that no edge names is refused at its line
    void
    read_vertex_file(const std::string &parameter, const std::string &file,
                     const std::string &edges);
  };
} // namespace granular_dg::network
