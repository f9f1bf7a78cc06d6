/**
 * The network's graph from the prm (Vertex N, Edge N) or from CSV files, and
 * its validation (graph_input.h).
 */

#include <deal.II/base/function.h>

#include <granular_dg/base/checkpoint.h>
#include <granular_dg/base/errors.h>
#include <granular_dg/base/input_path.h>
#include <granular_dg/base/parameter_binding.h>
#include <granular_dg/base/parameters.h>
#include <granular_dg/equations/network/graph_input.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <limits>
#include <optional>
#include <string_view>
#include <tuple>
#include <unordered_map>

namespace granular_dg::network
{
  namespace
  {
    const EnumNames<FarEnd>  far_end_names({{FarEnd::dirichlet, "dirichlet"},
                                            {FarEnd::outflow, "outflow"}});
    enum class EdgeKind
    {
      none,
      in,
      out,
      loop
    };
    const EnumNames<EdgeKind> direction_names({{EdgeKind::none, "none"},
                                               {EdgeKind::in, "in"},
                                               {EdgeKind::out, "out"},
                                               {EdgeKind::loop, "loop"}});

    std::string
    section(const std::string &kind, const unsigned int i)
    {
      return kind + " " + std::to_string(i + 1);
    }

    /// s as a double, if all of it is one in decimal notation (std::stod's
    /// hexadecimal numbers such as 0x1 are not numbers here)
    std::optional<double>
    as_number(const std::string &s)
    {
      if (s.find_first_of("xX") != std::string::npos)
        return {};
      try
        {
          std::size_t end = 0;
          const double x  = std::stod(s, &end);
          if (end == s.size())
            return x;
        }
      catch (const std::exception &)
        {}
      return {};
    }

    /// whether an expression names the variable x (not as part of a name)
    bool
    uses_x(const std::string &text)
    {
      static const std::regex x(R"((^|[^A-Za-z0-9_])x([^A-Za-z0-9_]|$))");
      return std::regex_search(text, x);
    }

    /// A constant for a number, else a parsed expression (in x, or in t:
    /// far-end data are a function of time at the end's point).
    std::shared_ptr<Function<1>>
    make_data(const std::string &text, const std::string &where, const bool time_dependent)
    {
      if (const auto x = as_number(text))
        {
          require(std::isfinite(*x), where, text, "a finite number or an expression");
          return std::make_shared<Functions::ConstantFunction<1>>(*x);
        }
      auto f = make_function<1>({text}, {where}, time_dependent);
      require(!time_dependent || !uses_x(text), where, text,
              "an expression in t and the constant pi (far-end data are a function of time; x "
              "would be the end's coordinate)");
      return f;
    }

    /// "stationary" (none) or a constant expression
    std::optional<double>
    vertex_value(const std::string &text, const std::string &parameter)
    {
      if (text == "stationary")
        return {};
      const std::string allowed = "'stationary' or a constant expression, e.g. sqrt(2/3)";
      double            v       = 0;
      try
        {
          const auto f = make_function<1>({text}, {parameter}, false);
          v            = f->value(Point<1>(0.3));
          require(!uses_x(text) && v == f->value(Point<1>(0.7)), parameter, text, allowed);
        }
      catch (const InputError &)
        {
          require(false, parameter, text, allowed);
        }
      require(std::isfinite(v), parameter, text, "a finite value");
      return v;
    }

    /// "x, y"
    Point<2>
    position(const std::string &text, const std::string &parameter)
    {
      std::vector<double> xy;
      try
        {
          xy = parse_doubles(text, parameter);
        }
      catch (const InputError &)
        {}
      require(xy.size() == 2 && std::isfinite(xy[0]) && std::isfinite(xy[1]), parameter, text,
              "two finite numbers 'x, y' (or empty: the program places the vertex)");
      return Point<2>(xy[0], xy[1]);
    }

    /// the flux law with its parameter (a of linear, alpha of traffic)
    FluxFunction
    make_flux(const std::string &law, const double parameter, const std::string &where,
              const std::string &parameter_name)
    {
      const FluxLaw kind = flux_law_names.parse(where + "flux", law);
      if (kind == FluxLaw::traffic)
        require(parameter > 0, where + parameter_name, parameter,
                "must be > 0 (the capacity scale of the traffic flux)");
      require(std::isfinite(parameter), where + parameter_name, parameter, "a finite number");
      return {kind, kind == FluxLaw::linear ? parameter : 1., kind == FluxLaw::traffic ? parameter : 1.};
    }

    /// A vertex reference "free", "loop" (to only: the from vertex) or a
    /// number 1, 2, ... (1-based); returns the index or free_end.
    unsigned int
    vertex_reference(const std::string &text, const std::string &parameter, const bool to,
                     const unsigned int from)
    {
      if (text == "free")
        return free_end;
      if (to && text == "loop")
        {
          require(from != free_end, parameter, text, "'loop' needs a from vertex");
          return from;
        }
      const auto n = as_number(text);
      require(n && *n >= 1 && *n == std::floor(*n) && *n < 1e9, parameter, text,
              std::string("free, ") + (to ? "loop, " : "") + "or a vertex number 1, 2, ...");
      const unsigned int v = static_cast<unsigned int>(*n) - 1;
      require(!to || v != from, parameter, text,
              "a vertex other than from: an edge from a vertex to itself is a roundabout; "
              "write to = loop if one is meant");
      return v;
    }

    std::string
    join(const std::vector<std::string> &names)
    {
      std::string s;
      for (const auto &n : names)
        s += (s.empty() ? "" : ",") + n;
      return s;
    }

    /// The rows of a CSV file after its header, whose names must be among
    /// `allowed` and include the first n_required: the file's text once and
    /// each field as a view into it (no string per field: a graph of 10^6
    /// edges has 5-9 million).
    class CsvTable
    {
    public:
      CsvTable(const std::string &parameter, const std::string &file,
               const std::vector<std::string> &allowed, unsigned int n_required);
      CsvTable(const CsvTable &) = delete;
      CsvTable &operator=(const CsvTable &) = delete;

      /// FNV-1a of the file's bytes (what a checkpoint compares)
      std::uint64_t content_hash() const { return hash; }
      unsigned int  n_rows() const { return lines.size(); }
      /// the line number of row r
      unsigned int  line(const unsigned int r) const { return lines[r]; }
      /// the index of a column (n_columns if the file has no such column)
      unsigned int
      column(const std::string &name) const
      {
        const auto c = columns.find(name);
        return c == columns.end() ? n_columns : c->second;
      }
      /// the field of row r in column c ("" if the file has no such column
      /// or the row ends before)
      std::string_view
      get(const unsigned int r, const unsigned int c) const
      {
        return c < n_columns ? fields[std::size_t(r) * n_columns + c] : std::string_view();
      }

    private:
      std::map<std::string, unsigned int> columns;
      unsigned int                        n_columns = 0;
      std::string                         text;
      std::vector<std::string_view>       fields;
      std::vector<unsigned int>           lines;
      std::uint64_t                       hash = 0;
    };

    std::string_view
    trim(std::string_view s)
    {
      const auto a = s.find_first_not_of(" \t\r");
      const auto b = s.find_last_not_of(" \t\r");
      return a == std::string_view::npos ? std::string_view() : s.substr(a, b - a + 1);
    }

    /// The fields of a line as RFC 4180 writes them, trimmed: split at
    /// commas outside double quotes. A field in double quotes (as spreadsheets
    /// and pandas write text) may hold commas, and "" stands for a quote; its
    /// text is unquoted in place (line lies in the table's own text). The
    /// empty field after a comma that ends the line is dropped (as
    /// std::getline splits). False for a quote not closed on its line or
    /// followed by more than blanks before the next comma.
    bool
    split_fields(char *const line, const std::size_t size, std::vector<std::string_view> &fields)
    {
      fields.clear();
      const std::string_view all(line, size);
      for (std::size_t start = 0;;)
        {
          std::size_t       comma;
          const std::size_t open = all.find_first_not_of(" \t\r", start);
          if (open != all.npos && all[open] == '"')
            {
              char       *out = line + open;
              std::size_t i   = open + 1;
              for (; i < size && !(all[i] == '"' && (i + 1 == size || all[i + 1] != '"')); ++i)
                {
                  i += all[i] == '"';
                  *out++ = all[i];
                }
              if (i == size)
                return false;
              fields.emplace_back(line + open, out - (line + open));
              comma = all.find(',', i + 1);
              if (!trim(all.substr(i + 1, comma - (i + 1))).empty())
                return false;
            }
          else
            {
              comma = all.find(',', start);
              fields.push_back(trim(all.substr(start, comma - start)));
            }
          if (comma == std::string_view::npos || comma + 1 == size)
            return true;
          start = comma + 1;
        }
    }

    CsvTable::CsvTable(const std::string &parameter, const std::string &file,
                       const std::vector<std::string> &allowed, const unsigned int n_required)
    {
      const std::string path = resolve_input_path(file);
      std::ifstream     in(path);
      std::error_code   ec;
      // (a directory opens too, and a device such as /dev/zero never ends)
      require(in && std::filesystem::is_regular_file(path, ec), parameter, file,
              "a readable CSV file (relative paths are relative to the parameter file: " + path +
                ")");
      text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
      hash = fnv1a(text);
      const std::string_view all(text);
      // a spreadsheet's "CSV UTF-8" starts with a byte-order mark; lines end
      // in \n, \r\n (trim() takes the \r) or, from an old Mac, \r alone
      std::size_t                   start = all.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
      const char                    eol   = all.find('\n') == all.npos ? '\r' : '\n';
      std::vector<std::string_view> row;
      for (unsigned int number = 1; start < all.size(); ++number)
        {
          const auto             end  = std::min(all.find(eol, start), all.size());
          const std::string_view line = all.substr(start, end - start);
          start                       = end + 1;
          if (trim(line).empty() || trim(line)[0] == '#')
            continue;
          // (the line as written for the message: split_fields() unquotes in place)
          if (const std::string as_written(line.find('"') == line.npos ? "" : line);
              !split_fields(text.data() + (line.data() - all.data()), line.size(), row))
            require(false, parameter + " '" + file + "', line " + std::to_string(number),
                    as_written,
                    "a field in double quotes closed on its line, then a comma or the line's end");
          if (n_columns == 0)
            {
              for (unsigned int c = 0; c < row.size(); ++c)
                {
                  const std::string name(row[c]);
                  require(std::find(allowed.begin(), allowed.end(), name) != allowed.end() &&
                            !columns.count(name),
                          parameter, file,
                          "a header line naming each column once, from: " + join(allowed) +
                            " (line " + std::to_string(number) + " has '" + name + "')");
                  columns[name] = c;
                }
              for (unsigned int c = 0; c < n_required; ++c)
                require(columns.count(allowed[c]) > 0, parameter, file,
                        "a header line with the column '" + allowed[c] + "'");
              n_columns = row.size();
              continue;
            }
          if (row.size() > n_columns)
            require(false, parameter, file,
                    "at most " + std::to_string(n_columns) + " fields per line (line " +
                      std::to_string(number) + " has " + std::to_string(row.size()) +
                      "; an expression that contains commas goes in double quotes)");
          row.resize(n_columns);
          fields.insert(fields.end(), row.begin(), row.end());
          lines.push_back(number);
        }
      require(!lines.empty(), parameter, file, "a header line and at least one row");
    }

    /// "Network/graph file 'grid.csv', line 4: ", how messages place an
    /// entry of a CSV file
    std::string
    file_line(const std::string &parameter, const std::string &file, const unsigned int line)
    {
      return parameter + " '" + file + "', line " + std::to_string(line) + ": ";
    }

    /// an integer id of a CSV file (of an edge or a vertex); where() names
    /// the entry in the message (built only then: a large file has millions)
    template <typename Where>
    long
    integer_id(const std::string_view text, const Where &where, const char *allowed)
    {
      const auto x = as_number(std::string(text));
      if (!(x && *x == std::floor(*x) && std::abs(*x) < 1e15))
        require(false, where(), text, allowed);
      return static_cast<long>(*x);
    }

    /// end_vertex_ids()' entry for an end that names no vertex
    constexpr long no_vertex = std::numeric_limits<long>::min();

    /// The vertex ids of the ends of a graph file's edges, as written (row r:
    /// entries 2 r and 2 r + 1), each checked; free and loop: no_vertex.
    /// at(r, name) names the entry of row r in a message.
    template <typename At>
    std::vector<long>
    end_vertex_ids(const CsvTable &table, const unsigned int from_c, const unsigned int to_c,
                   const At &at)
    {
      std::vector<long> ids(2 * std::size_t(table.n_rows()), no_vertex);
      for (unsigned int r = 0; r < table.n_rows(); ++r)
        for (const unsigned int side : {0u, 1u})
          {
            const std::string_view v = table.get(r, side == 0 ? from_c : to_c);
            if (v != "free" && v != "loop")
              ids[2 * r + side] = integer_id(
                v, [&] { return at(r, side == 0 ? "from" : "to"); }, "free, or an integer id");
          }
      return ids;
    }

    /// a required number of a CSV file; where() names the entry
    template <typename Where>
    double
    csv_number(const std::string_view text, const Where &where)
    {
      const auto x = as_number(std::string(text));
      if (!(x && std::isfinite(*x)))
        require(false, where(), text,
                "a finite number of normal magnitude (0 or 2.2e-308 <= |x| <= 1.8e308)");
      return *x;
    }

    /// an Edge N section that describes an edge
    bool
    used(const EdgeSection &e)
    {
      return e.direction != "none" || e.from != "none" || e.to != "none";
    }

    /// the first entry of an Edge N section that is not its default, as
    /// (name, value); none for a section left alone
    std::optional<std::pair<std::string, std::string>>
    first_given(const EdgeSection &e)
    {
      const EdgeSection d;
      const auto        number = [](const double x) { return format_number(x); };
      for (const auto &[name, value, unset] :
           {std::tuple<std::string, std::string, std::string>{"direction", e.direction, d.direction},
            {"from", e.from, d.from},
            {"to", e.to, d.to},
            {"length", number(e.length), number(d.length)},
            {"flux", e.flux, d.flux},
            {"advection speed", number(e.advection_speed), number(d.advection_speed)},
            {"alpha", number(e.alpha), number(d.alpha)},
            {"initial data", e.initial_data, d.initial_data},
            {"far end", e.far_end, d.far_end},
            {"far end data", e.far_end_data, d.far_end_data}})
        if (value != unset)
          return std::pair(name, value);
      return std::nullopt;
    }

    /// the first entry of a Vertex N section that is set, as (name, value)
    std::optional<std::pair<std::string, std::string>>
    first_given(const VertexSection &v)
    {
      for (const auto &[name, value, unset] :
           {std::tuple<std::string, std::string, std::string>{"width factor", v.width_factor,
                                                               "default"},
            {"initial value", v.initial_value, "default"},
            {"position", v.position, ""}})
        if (value != unset)
          return std::pair(name, value);
      return std::nullopt;
    }

    void
    bind_edge_section(ParameterBinding &b, const unsigned int i, EdgeSection &e)
    {
      b.section("Network/" + section("Edge", i));
      b.add("direction", e.direction, direction_names.pattern(),
            "Shorthand for a star graph: how the edge meets Vertex 1: in (it ends there, x = "
            "length), out (it starts there, x = 0), loop (a roundabout: both ends there) or "
            "none (use from/to, or no such edge).");
      b.add("from", e.from, Patterns::Anything(),
            "The vertex at x = 0: a number N (Vertex N), free (a free end: far end data or "
            "outflow), or none (no such edge, or direction is used).");
      b.add("to", e.to, Patterns::Anything(),
            "The vertex at x = length: N, free, loop (the from vertex: a roundabout) or none.");
      b.add("length", e.length, Patterns::Double(),
            "Length L of the edge; its coordinate x runs over [0, L] in the direction of the "
            "edge. Must be > 0.")
        .check([](const double l) { return l > 0; }, "must be > 0");
      b.add("flux", e.flux, flux_law_names.pattern(),
            "Flux: linear (f = a u), burgers (f = u^2/2) or traffic (f = alpha f0(u/alpha), "
            "f0(u) = 4u(1-u)).");
      b.add("advection speed", e.advection_speed, Patterns::Double(), "a of the linear flux.");
      b.add("alpha", e.alpha, Patterns::Double(),
            "alpha of the traffic flux (capacity alpha at u = alpha/2). Must be > 0.");
      b.add("initial data", e.initial_data, Patterns::Anything(),
            "u(x, 0) as an expression in x (edge coordinate) and pi, e.g. if(x < 0.5, 2, "
            "sqrt(2)).");
      b.add("far end", e.far_end, far_end_names.pattern(),
            "Condition at a free end: dirichlet (exterior state = far end data: inflow) or "
            "outflow (exterior = interior state, the paper's zero Neumann).");
      b.add("far end data", e.far_end_data, Patterns::Anything(),
            "Dirichlet state at a free end, an expression in t and pi.");
    }
  } // namespace

  void
  GraphInput::bind(ParameterBinding &b)
  {
    b.section("Network");
    b.add("graph file", graph_file, Patterns::Anything(),
          "A CSV edge list for large networks (instead of Edge N sections), relative to this "
          "parameter file: a header line, then one edge per line: "
          "id,from,to,length,flux[,parameter[,initial[,far_end[,far_end_data]]]] (from/to: a "
          "vertex id or free; to may be loop; parameter: a of linear, alpha of traffic (empty: "
          "1), empty for burgers; "
          "initial: a number or an expression in x; far_end: dirichlet or "
          "outflow; far_end_data: a number or an expression in t). A field that contains "
          "commas, e.g. min(x, 0.5), goes in double quotes; the columns may come in any "
          "order; lines starting with # are comments.");
    b.add("vertex file", vertex_file, Patterns::Anything(),
          "With a graph file: a CSV vertex list, id,x,y[,width_factor[,initial_value]] "
          "(positions for the drawing; width factor and initial value as in Vertex N). Without "
          "it the vertices are those the edges name.")
      .check([this](const std::string &f) { return f.empty() || !graph_file.empty(); },
             "only with a Network/graph file (Vertex N sections go with Edge N sections)");
    b.add("vertex width factor", vertex_width_factor, Patterns::Double(0),
          "Width of every vertex control volume (unless its Vertex N section says otherwise) "
          "in units of the paper's dx_0 = N dx/2 (the half cells of the N edge ends at the "
          "vertex; a loop has two). 1: the paper's scheme (4.1). 0: a vertex without volume "
          "whose value solves the discrete Rankine-Hugoniot condition sum_in F = sum_out F at "
          "every stage.");
    b.add("vertex initial value", vertex_initial_value, Patterns::Anything(),
          "u_0 of every vertex with volume at t = 0 (unless its Vertex N section says "
          "otherwise): 'stationary' (the discrete stationary value c_0 of the initial edge "
          "traces, Definition 4.4) or a constant expression, e.g. sqrt(2/3). A vertex without "
          "volume (width factor 0) takes the balance of its ends' traces instead; a constant "
          "that no vertex takes is refused.");
    for (unsigned int i = 0; i < max_vertex_sections; ++i)
      {
        VertexSection &v = vertex_sections[i];
        b.section("Network/" + section("Vertex", i));
        b.add("width factor", v.width_factor, Patterns::Anything(),
              "Width of this vertex's control volume in units of dx_0 = N dx/2 (0: no "
              "volume); default: Network/vertex width factor.");
        b.add("initial value", v.initial_value, Patterns::Anything(),
              "u_0 at t = 0: stationary, a constant expression, or default (Network/vertex "
              "initial value); stationary or default for a vertex without volume.");
        b.add("position", v.position, Patterns::Anything(),
              "'x, y' where the vertex is drawn (give all vertices one, or none).");
      }
    for (unsigned int i = 0; i < max_edge_sections; ++i)
      bind_edge_section(b, i, edge_sections[i]);
    if (b.reading())
      build();
  }

  void
  GraphInput::build()
  {
    const auto value = vertex_value(vertex_initial_value, "Network/vertex initial value");
    if (graph_file.empty())
      build_from_sections();
    else
      {
        // the file replaces the sections: they must be unused
        for (unsigned int i = 0; i < max_edge_sections; ++i)
          if (const auto given = first_given(edge_sections[i]))
            require(false, "Network/" + section("Edge", i) + "/" + given->first, given->second,
                    "unset with a Network/graph file: give the edges in one place (the file)");
        for (unsigned int i = 0; i < max_vertex_sections; ++i)
          if (const auto given = first_given(vertex_sections[i]))
            require(false, "Network/" + section("Vertex", i) + "/" + given->first, given->second,
                    "unset with a Network/graph file: give the vertices' data in "
                    "Network/vertex file");
        read_edge_file("Network/graph file", graph_file);
        if (!vertex_file.empty())
          read_vertex_file("Network/vertex file", vertex_file,
                           "Network/graph file '" + graph_file + "'");
      }
    // the Network-wide defaults of the vertices
    value_given.resize(graph.vertices.size());
    for (unsigned int v = 0; v < graph.vertices.size(); ++v)
      {
        Vertex &vertex = graph.vertices[v];
        if (std::isnan(vertex.width_factor))
          vertex.width_factor = vertex_width_factor;
        if (value_given[v].empty())
          vertex.initial_value = value;
        // (the Network-wide value is for the vertices with volume)
        if (vertex.width_factor == 0 && vertex.initial_value && !value_given[v].empty())
          require(false, value_given[v], format_number(*vertex.initial_value),
                  "stationary or default for " + vertex.label +
                    ", a vertex without volume (width factor 0): its value balances the "
                    "fluxes of its ends at every stage and has no initial value of its own");
      }
    // a Network-wide constant that no vertex takes could never act
    bool taken = !value;
    for (unsigned int v = 0; v < graph.vertices.size(); ++v)
      taken = taken || (value_given[v].empty() && graph.vertices[v].width_factor > 0);
    require(taken, "Network/vertex initial value", vertex_initial_value,
            "'stationary' (the default): no vertex takes a constant here, as each has width "
            "factor 0 (no volume) or an initial value of its own");
    graph.validate(graph_file.empty() ? std::string("Network") :
                                        "Network/graph file '" + graph_file + "'");
  }

  void
  GraphInput::require_far_end_used(const Edge &e, const std::string &far_end_name,
                                   const std::string &far_end, const bool far_end_given,
                                   const std::string &data_name, const std::string &data,
                                   const bool data_given) const
  {
    // settings that could never act are refused, not ignored
    const bool free = e.from == free_end || e.to == free_end;
    require(free || !far_end_given, far_end_name, far_end,
            "unset: " + e.label + " has no free end (both ends are at vertices)");
    require(!data_given || (free && e.far_end == FarEnd::dirichlet), data_name, data,
            "unset unless the edge has a free end with dirichlet data (" + e.label +
              (free ? " has an outflow end, which takes the inner trace)" :
                      " has no free end)"));
  }

  std::string
  GraphInput::where(const unsigned int k) const
  {
    return graph_file.empty() ? "Network/" + section("Edge", edge_origin[k]) + "/" :
                                file_line("Network/graph file", graph_file, edge_origin[k]);
  }

  void
  GraphInput::add_edge(Edge e, const FluxFunction &f, const unsigned int origin,
                       const std::string_view initial, const std::string_view far_end_data,
                       const char *initial_name, const char *far_end_name)
  {
    const unsigned int k = graph.edges.size();
    edge_origin.push_back(origin);
    EdgeData d;
    // (an edge with the initial data of the edge before shares its function)
    if (k > 0 && initial == initial_text.back())
      d.initial = data.back().initial;
    else
      d.initial = make_data(std::string(initial), where(k) + initial_name, false);
    if (e.far_end == FarEnd::dirichlet && (e.from == free_end || e.to == free_end))
      {
        auto &g = far_end_functions[std::string(far_end_data)];
        if (!g)
          g = make_data(std::string(far_end_data), where(k) + far_end_name, true);
        d.far_end = g;
      }
    graph.edges.push_back(std::move(e));
    flux.push_back(f);
    data.push_back(d);
    initial_text.emplace_back(initial);
    far_end_text.emplace_back(far_end_data);
  }

  void
  GraphInput::read_edge_file(const std::string &parameter, const std::string &file)
  {
    const CsvTable table(parameter, file,
                         {"id", "from", "to", "length", "flux", "parameter", "initial", "far_end",
                          "far_end_data"},
                         5);
    graph.files.push_back({parameter, file, table.content_hash()});
    const unsigned int id_c = table.column("id"), from_c = table.column("from"),
                       to_c = table.column("to"), length_c = table.column("length"),
                       flux_c = table.column("flux"), parameter_c = table.column("parameter"),
                       initial_c = table.column("initial"), far_end_c = table.column("far_end"),
                       data_c = table.column("far_end_data");
    const auto at = [&](const unsigned int r, const char *name) {
      return file_line(parameter, file, table.line(r)) + name;
    };
    // the vertices: the ids the edges' ends name, in increasing order
    const std::vector<long> end_ids = end_vertex_ids(table, from_c, to_c, at);
    vertex_ids                      = end_ids;
    std::sort(vertex_ids.begin(), vertex_ids.end());
    vertex_ids.erase(std::unique(vertex_ids.begin(), vertex_ids.end()), vertex_ids.end());
    if (!vertex_ids.empty() && vertex_ids.front() == no_vertex)
      vertex_ids.erase(vertex_ids.begin());
    for (const long id : vertex_ids)
      {
        Vertex v;
        v.label        = "Vertex " + std::to_string(id);
        v.width_factor = NAN;
        graph.vertices.push_back(v);
      }
    std::unordered_map<long, unsigned int> line_of_edge;
    line_of_edge.reserve(table.n_rows());
    // (the flux of the row before, reused while the rows repeat its law and parameter)
    std::optional<std::pair<std::string_view, std::string_view>> last_flux;
    FluxFunction                                                 f;
    for (unsigned int r = 0; r < table.n_rows(); ++r)
      {
        const long id = integer_id(
          table.get(r, id_c), [&] { return at(r, "id"); }, "an integer edge id");
        const auto [first, unique] = line_of_edge.emplace(id, table.line(r));
        if (!unique)
          require(false, at(r, "id"), id,
                  "a unique edge id (line " + std::to_string(first->second) + " has it too)");
        Edge e;
        e.label = "Edge " + std::to_string(id);
        const auto end = [&](const unsigned int side, const unsigned int from) {
          const std::string_view v = table.get(r, side == 0 ? from_c : to_c);
          if (v == "free")
            return free_end;
          if (v == "loop" && side == 1 && from != free_end)
            return from;
          if (v == "loop")
            require(false, at(r, side == 0 ? "from" : "to"), v,
                    "loop only in 'to', after a from vertex");
          return unsigned(std::lower_bound(vertex_ids.begin(), vertex_ids.end(),
                                           end_ids[2 * r + side]) -
                          vertex_ids.begin());
        };
        e.from                  = end(0, free_end);
        e.to                    = end(1, e.from);
        const std::string_view to = table.get(r, to_c);
        if (e.from != free_end && e.to == e.from && to != "loop")
          require(false, at(r, "to"), to, "a vertex other than from: write loop for a roundabout");
        const std::string_view length = table.get(r, length_c);
        e.length = csv_number(length, [&] { return at(r, "length"); });
        if (!(e.length > 0))
          require(false, at(r, "length"), length, "must be > 0");
        const std::string_view law = table.get(r, flux_c), p = table.get(r, parameter_c);
        if (law == "burgers" && !p.empty())
          require(false, at(r, "parameter"), p,
                  "empty for burgers (parameter: a of linear, alpha of traffic)");
        if (last_flux != std::pair(law, p))
          {
            f = make_flux(std::string(law),
                          p.empty() ? 1. : csv_number(p, [&] { return at(r, "parameter"); }),
                          at(r, ""), "parameter");
            last_flux = std::pair(law, p);
          }
        const std::string_view far = table.get(r, far_end_c), g = table.get(r, data_c),
                               initial = table.get(r, initial_c);
        // (an expression split at its commas: its first field lacks a parenthesis)
        for (const auto &[name, text] :
             {std::pair("initial", initial), std::pair("far_end_data", g)})
          if (std::count(text.begin(), text.end(), '(') !=
              std::count(text.begin(), text.end(), ')'))
            require(false, at(r, name), text,
                    "an expression with balanced parentheses (one that contains commas goes in "
                    "double quotes)");
        e.far_end = far.empty() ? FarEnd::outflow :
                                  far_end_names.parse(at(r, "far_end"), std::string(far));
        if (!far.empty() || !g.empty())
          require_far_end_used(e, at(r, "far_end"), std::string(far), !far.empty(),
                               at(r, "far_end_data"), std::string(g), !g.empty());
        if (g.empty() && e.far_end == FarEnd::dirichlet)
          require(false, at(r, "far_end_data"), g,
                  "the inflow state of the dirichlet end (a number or an expression in t)");
        add_edge(e, f, table.line(r), initial.empty() ? "0" : initial, g.empty() ? "0" : g,
                 "initial", "far_end_data");
      }
  }

  void
  GraphInput::read_vertex_file(const std::string &parameter, const std::string &file,
                               const std::string &edges)
  {
    const CsvTable table(parameter, file, {"id", "x", "y", "width_factor", "initial_value"}, 3);
    graph.files.push_back({parameter, file, table.content_hash()});
    const unsigned int id_c = table.column("id"), x_c = table.column("x"),
                       y_c = table.column("y"), width_c = table.column("width_factor"),
                       value_c = table.column("initial_value");
    // per vertex: the line that lists it (0: none yet)
    std::vector<unsigned int> listed(graph.vertices.size(), 0);
    value_given.assign(graph.vertices.size(), "");
    for (unsigned int r = 0; r < table.n_rows(); ++r)
      {
        const auto at = [&](const char *name) {
          return file_line(parameter, file, table.line(r)) + name;
        };
        const long id = integer_id(
          table.get(r, id_c), [&] { return at("id"); }, "an integer vertex id");
        const auto         it = std::lower_bound(vertex_ids.begin(), vertex_ids.end(), id);
        const unsigned int i  = it - vertex_ids.begin();
        if (it == vertex_ids.end() || *it != id)
          require(false, at("id"), id,
                  "a vertex that an edge of " + edges + " names (Vertex " + std::to_string(id) +
                    " has no edges; every vertex needs at least one)");
        if (listed[i] != 0)
          require(false, at("id"), id,
                  "a unique vertex id (line " + std::to_string(listed[i]) + " has it too)");
        listed[i]       = table.line(r);
        Vertex      &v  = graph.vertices[i];
        const double x  = csv_number(table.get(r, x_c), [&] { return at("x"); });
        v.position      = Point<2>(x, csv_number(table.get(r, y_c), [&] { return at("y"); }));
        const std::string_view w = table.get(r, width_c), u0 = table.get(r, value_c);
        if (!w.empty())
          {
            v.width_factor = csv_number(w, [&] { return at("width_factor"); });
            if (!(v.width_factor >= 0))
              require(false, at("width_factor"), w, "a number >= 0");
          }
        if (!u0.empty())
          {
            v.initial_value = vertex_value(std::string(u0), at("initial_value"));
            value_given[i]  = at("initial_value");
          }
      }
    // every vertex an edge names must be listed
    for (unsigned int k = 0; k < graph.edges.size(); ++k)
      for (const unsigned int v : {graph.edges[k].from, graph.edges[k].to})
        if (v != free_end && listed[v] == 0)
          throw InputError(where(k) + graph.edges[k].label + " names " + graph.vertices[v].label +
                           ", which " + parameter + " '" + file + "' does not list");
  }

  void
  GraphInput::build_from_sections()
  {
    unsigned int n_vertices = 0;
    for (unsigned int i = 0; i < max_edge_sections; ++i)
      {
        const EdgeSection &given = edge_sections[i];
        const std::string  at    = "Network/" + section("Edge", i) + "/";
        if (!used(given))
          {
            // (direction = none written out leaves an edge out on purpose)
            const bool left_out = !parameter_origin(at + "direction").empty() ||
                                  !parameter_origin(at + "from").empty() ||
                                  !parameter_origin(at + "to").empty();
            if (const auto set = first_given(given); set && !left_out)
              require(false, at + set->first, set->second,
                      "unset in an Edge N section without direction or from/to (there is no " +
                        section("Edge", i) + "): give its direction, or its from and to (or " +
                        "direction = none to leave the edge out)");
            continue;
          }
        const EdgeKind    kind = direction_names.parse(at + "direction", given.direction);
        Edge              e;
        e.label = section("Edge", i);
        if (kind != EdgeKind::none)
          {
            require(given.from == "none" && given.to == "none", at + "direction",
                    given.direction,
                    "none when from/to are given (direction is the star graph's shorthand "
                    "for an edge at Vertex 1)");
            e.meet(kind == EdgeKind::in ? Direction::in :
                   kind == EdgeKind::out ? Direction::out : Direction::loop);
          }
        else
          {
            require(given.from != "none", at + "from", given.from,
                    "free or a vertex number, since to is set");
            require(given.to != "none", at + "to", given.to,
                    "free, loop or a vertex number, since from is set");
            e.from = vertex_reference(given.from, at + "from", false, free_end);
            e.to   = vertex_reference(given.to, at + "to", true, e.from);
          }
        for (const auto &[v, end] : {std::pair(e.from, "from"), std::pair(e.to, "to")})
          if (v != free_end)
            {
              require(v < max_vertex_sections, at + end, v + 1,
                      "a vertex number up to " + std::to_string(max_vertex_sections) +
                        " (Vertex N sections; use a Network/graph file for larger networks)");
              n_vertices = std::max(n_vertices, v + 1);
            }
        e.length = given.length;
        const bool linear = given.flux == "linear";
        const FluxFunction f = make_flux(given.flux, linear ? given.advection_speed : given.alpha,
                                         at, linear ? "advection speed" : "alpha");
        // the parameter of the other flux law would be ignored
        require(given.flux == "traffic" || parameter_origin(at + "alpha").empty(), at + "alpha",
                given.alpha, "unset: the flux of " + section("Edge", i) + " is " + given.flux +
                               " (alpha scales the traffic flux)");
        require(linear || parameter_origin(at + "advection speed").empty(),
                at + "advection speed", given.advection_speed,
                "unset: the flux of " + section("Edge", i) + " is " + given.flux +
                  " (the speed of the linear flux)");
        e.far_end = far_end_names.parse(at + "far end", given.far_end);
        require_far_end_used(e, at + "far end", given.far_end,
                             !parameter_origin(at + "far end").empty(), at + "far end data",
                             given.far_end_data, !parameter_origin(at + "far end data").empty());
        add_edge(e, f, i, given.initial_data, given.far_end_data, "initial data", "far end data");
      }
    require(!graph.edges.empty(), "Network/Edge 1/direction", "none",
            "in, out or loop (or from/to) for at least one Network/Edge N");
    // prm vertex numbers run from 1 without gaps (a graph file's ids need not)
    std::vector<bool> named(n_vertices, false);
    for (const Edge &e : graph.edges)
      for (const unsigned int v : {e.from, e.to})
        if (v != free_end)
          named[v] = true;
    for (unsigned int v = 0; v < n_vertices; ++v)
      if (!named[v])
        throw InputError("Network: no Edge N section names " + section("Vertex", v) +
                         ", but one names " + section("Vertex", n_vertices - 1) +
                         ": the vertices of Edge N sections are numbered from 1 without gaps "
                         "(a Network/graph file's vertex ids may have gaps)");
    vertices_from_sections(n_vertices);
  }

  void
  GraphInput::vertices_from_sections(unsigned int n_vertices)
  {
    // the vertices: those the edges name; a section beyond them has no edges
    for (unsigned int i = n_vertices; i < max_vertex_sections; ++i)
      if (const auto set = first_given(vertex_sections[i]))
        require(false, "Network/" + section("Vertex", i) + "/" + set->first, set->second,
                "unset: no edge names " + section("Vertex", i) + " (the highest the edges name is " +
                  section("Vertex", n_vertices - 1) + ")");
    for (unsigned int i = 0; i < n_vertices; ++i)
      {
        const VertexSection &given = vertex_sections[i];
        const std::string    at    = "Network/" + section("Vertex", i) + "/";
        Vertex               v;
        v.label        = section("Vertex", i);
        v.width_factor = NAN;
        if (given.width_factor != "default")
          {
            const auto x = as_number(given.width_factor);
            require(x && *x >= 0 && std::isfinite(*x), at + "width factor", given.width_factor,
                    "default or a number >= 0");
            v.width_factor = *x;
          }
        value_given.push_back(given.initial_value != "default" ? at + "initial value" : "");
        if (given.initial_value != "default")
          v.initial_value = vertex_value(given.initial_value, at + "initial value");
        if (!given.position.empty())
          v.position = position(given.position, at + "position");
        graph.vertices.push_back(v);
      }
  }
} // namespace granular_dg::network
