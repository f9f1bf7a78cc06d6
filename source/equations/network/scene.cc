/**
 * The `network` scene: scalar conservation laws (system.h) on a directed
 * graph whose edges (length, flux, initial data, free-end conditions) and
 * vertices are given in the prm (Network/Edge N, Vertex N) or in CSV files
 * (graph_input.h), coupled by vertex control volumes (junction.h); a single
 * run or a convergence study against one of the exact solutions of
 * examples.h.
 */

#include <deal.II/base/mpi.h>

#include <granular_dg/base/output.h>
#include <granular_dg/base/parameter_binding.h>
#include <granular_dg/base/parameters.h>
#include <granular_dg/base/run_parameters.h>
#include <granular_dg/base/scene.h>
#include <granular_dg/dg/parameters.h>
#include <granular_dg/dg/scene_entry.h>
#include <granular_dg/equations/network/examples.h>
#include <granular_dg/equations/network/graph_input.h>
#include <granular_dg/equations/network/system.h>
#include <granular_dg/network/network.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace granular_dg::network
{
  namespace
  {
    const EnumNames<Profiles>   profile_names({{Profiles::per_edge, "per_edge"},
                                               {Profiles::one_file, "one_file"},
                                               {Profiles::none, "none"}});
    /// Network/edge profiles = auto: one CSV file per edge and snapshot for
    /// a graph of up to this many edges, none for a larger one
    constexpr std::size_t       most_edges_with_profiles = 100;
    const EnumNames<Integrator> integrator_names({{Integrator::automatic, "auto"},
                                                  {Integrator::forward_euler, "forward_euler"},
                                                  {Integrator::ssprk3, "ssprk3"}});

    std::string
    exact_choices()
    {
      std::string s = "none|initial_data";
      for (const auto &n : example_names())
        s += "|" + n;
      return s;
    }

    /// Everything the network scene reads from the prm file: the graph,
    /// the data of its edges, the method on it, the vertex value and the
    /// exact solution.
    struct Case
    {
      void
      bind(ParameterBinding &b, const RunParameters &common,
           const dg::DiscretizationParameters &method);

      GraphInput                     input;
      dg::DiscretizationParameters   method;
      NumericalFlux                  flux = NumericalFlux::upwind;
      NetworkOptions                 options;
      std::string                    exact_name = "none";
      std::shared_ptr<ExactSolution> exact;
      /// Network/edge profiles as given: auto or one of profile_names
      /// (options.profiles once the graph is read)
      std::string                    profiles = "auto";

      /// the physics of every edge: its flux law with the numerical flux
      std::vector<EdgeLaw>
      laws() const
      {
        std::vector<EdgeLaw> l;
        for (const FluxFunction &f : input.flux)
          l.push_back({f, flux});
        return l;
      }

    private:
      /// Refuse a method the network cannot run, then take it (and the
      /// numerical flux and VTU switch it implies).
      void
      take_method(const RunParameters &common, const dg::DiscretizationParameters &method);
      void
      build_exact_solution(const RunParameters &common);
    };

    /// The initial data as the exact solution: a stationary state.
    class InitialData : public ExactSolution
    {
    public:
      InitialData(std::vector<std::shared_ptr<Function<1>>> f, std::vector<double> vertex)
        : f(std::move(f))
        , vertex(std::move(vertex))
      {}
      double value(unsigned int k, double x, double) const override
      {
        return f[k]->value(Point<1>(x));
      }
      double vertex_value(unsigned int v, double) const override { return vertex[v]; }
      std::string name() const override { return "initial_data"; }

    private:
      std::vector<std::shared_ptr<Function<1>>> f;
      std::vector<double>                       vertex;
    };

    std::string
    number(const double x)
    {
      return format_number(x);
    }

    /// An example's exact solution is only used for the graph and data it
    /// belongs to: the directions, lengths (1), fluxes, initial data and
    /// Dirichlet data.
    void
    check_example(const Example &ex, const Case &c, const double final_time)
    {
      const std::string name  = "Network/exact solution";
      const Graph      &graph = c.input.graph;
      require(graph.edges.size() == ex.edges.size() && graph.vertices.size() == ex.n_vertices,
              name, ex.name,
              "an example whose graph is the prm's: " + ex.name + " has " +
                std::to_string(ex.edges.size()) + " edges and " +
                std::to_string(ex.n_vertices) + " vertices, the prm " +
                std::to_string(graph.edges.size()) + " and " +
                std::to_string(graph.vertices.size()));
      require(final_time <= ex.exact->valid_until() * (1 + 1e-12), name, ex.name,
              "an exact solution known up to the final time: " + ex.name + " is known for t <= " +
                number(ex.exact->valid_until()));
      for (unsigned int k = 0; k < ex.edges.size(); ++k)
        {
          const Edge         &e    = graph.edges[k];
          const FluxFunction &f    = c.input.flux[k];
          const auto         &want = ex.edges[k];
          const std::string   sec  = c.input.where(k);
          const std::string   why  = ", as " + ex.name + " expects (or set Network/exact solution = none)";
          // (named by the entry the user set: direction, else from or to)
          const auto label = [&](const unsigned int v) {
            return v == free_end ? std::string("free") : graph.vertices[v].label;
          };
          if (!parameter_origin(sec + "direction").empty())
            require(e.from == want.from && e.to == want.to, sec + "direction",
                    graph.describe(k), graph.describe_ends(want.from, want.to) + why);
          require(e.from == want.from, sec + "from", label(e.from), label(want.from) + why);
          require(e.to == want.to, sec + "to", label(e.to), label(want.to) + why);
          require(std::abs(e.length - 1.) <= 1e-12, sec + "length", e.length, "1" + why);
          require(f.law() == want.flux.law(), sec + "flux", flux_law_names.name(f.law()),
                  flux_law_names.name(want.flux.law()) + why);
          if (want.flux.law() == FluxLaw::linear)
            require(std::abs(f.speed() - want.flux.speed()) < 1e-12, sec + "advection speed", f.speed(),
                    number(want.flux.speed()) + why);
          if (want.flux.law() == FluxLaw::traffic)
            require(std::abs(f.alpha() - want.flux.alpha()) < 1e-12, sec + "alpha", f.alpha(),
                    number(want.flux.alpha()) + why);
          // the initial data away from the jumps, and Dirichlet inflow data
          const auto breaks = ex.exact->breakpoints(k, 0.);
          for (unsigned int i = 0; i <= 200; ++i)
            {
              const double x = e.length * i / 200.;
              bool         near_jump = false;
              for (const double b : breaks)
                near_jump |= std::abs(x - b) < 1e-9;
              if (near_jump)
                continue;
              const double given = c.input.data[k].initial->value(Point<1>(x));
              const double exact = ex.exact->value(k, x, 0.);
              require(std::abs(given - exact) <= 1e-12 * std::max(1., std::abs(exact)),
                      sec + "initial data", c.input.initial_text[k],
                      "the initial data of " + ex.name + " (or set Network/exact solution = "
                      "none): at x = " + number(x) + " it gives " + number(given) +
                        ", the example " + number(exact));
            }
          // Dirichlet data at a free end (inflow or outflow) at 201 times
          const bool   at_start = e.from == free_end;
          const double x_end    = at_start ? 0. : e.length;
          if (e.far_end == FarEnd::dirichlet && (at_start || e.to == free_end))
            for (unsigned int i = 0; i <= 200; ++i)
              {
                const double t = final_time * i / 200.;
                c.input.data[k].far_end->set_time(t);
                const double given = c.input.data[k].far_end->value(Point<1>(x_end));
                const double exact = ex.exact->value(k, x_end, t);
                require(std::abs(given - exact) <= 1e-12 * std::max(1., std::abs(exact)),
                        sec + "far end data", c.input.far_end_text[k],
                        "the solution of " + ex.name + " at that free end (or set Network/exact "
                        "solution = none): at t = " + number(t) + " it gives " + number(given) +
                          ", the example " + number(exact));
              }
        }
    }

    /// Memory of a network run above the program's own (about 165 MB of
    /// libraries), measured as peak RSS on the 224 x 224 city grid of
    /// contrib/make_network_grid.py (100800 edges; doc/network.md, "Memory"):
    /// per edge the graph, its data functions and the partition (one cell per
    /// edge, degree 0); per cell and mode the state, the Runge-Kutta stage and
    /// the last good state, and a checkpoint's gathered copy (16 cells per
    /// edge, degrees 0 and 2); per sample point of a VTU piece being written
    /// its patches and buffers (a piece: vtu_piece_points and the edge that
    /// passes them; 103 bytes per point measured for an edge of 8.4 10^6
    /// points), and the profiles of the whole network gathered on rank 0.
    constexpr double bytes_per_edge          = 1.1e3;
    constexpr double bytes_per_cell          = 2.;
    constexpr double bytes_per_mode          = 52.;
    constexpr double vtu_bytes_per_point     = 115.;
    constexpr double profile_bytes_per_point = 16.;

    /// The cells of every edge at `cells` per unit length, as NetworkProblem
    /// makes them (round(L * cells), at least one), in double: counted
    /// before anything is allocated, without overflow.
    std::vector<double>
    cell_counts(const Graph &graph, const double cells)
    {
      std::vector<double> n;
      for (const Edge &e : graph.edges)
        n.push_back(std::max(1., std::round(e.length * cells)));
      return n;
    }

    /// An InputError when the network needs more memory than this MPI rank
    /// has (available_memory_per_rank()), refused before anything is
    /// allocated as the other scenes' meshes are: the edges, cells and VTU
    /// piece of a rank (at least the longest edge: the partition keeps edges
    /// whole) and, on rank 0, the profiles of the whole network. It names
    /// the number of cells per unit length (of a convergence study:
    /// Convergence/cells), or the graph file when its edges take most of the
    /// memory. Returns how many VTU pieces may be compressed at once: at
    /// least 1, more where the memory holds one more piece beside each
    /// (the next one, sampled meanwhile). Collective.
    unsigned int
    require_network_fits(const Case &c, const RunParameters &common)
    {
      const bool study = common.convergence;
      const std::vector<unsigned int> degrees =
        study ? common.convergence_degrees : std::vector<unsigned int>{c.method.degree};
      const double cells =
        study ? double(*std::max_element(common.convergence_cells.begin(),
                                         common.convergence_cells.end())) :
                c.options.cells_per_unit_length;
      const unsigned int degree = *std::max_element(degrees.begin(), degrees.end());
      const auto         n      = cell_counts(c.input.graph, cells);
      double             total  = 0;
      for (const double x : n)
        total += x;
      const double ranks = Utilities::MPI::job_supports_mpi() ?
                             Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) :
                             1.;
      const double per_cell   = bytes_per_cell + bytes_per_mode * (degree + 1);
      const double edge_bytes = std::ceil(n.size() / ranks) * bytes_per_edge;
      const double longest    = *std::max_element(n.begin(), n.end());
      const double rank_cells = std::max(total / ranks, longest);
      const double cell_bytes = rank_cells * per_cell;
      const bool   snapshots  = !study && !common.benchmark.enabled &&
                             (c.options.write_vtu || c.options.profiles != Profiles::none);
      const double points     = c.method.profile_points > 0 ? std::max(2u, c.method.profile_points) :
                                                            std::max(2u, degree + 1);
      const double piece_points =
        std::min(rank_cells * points, double(vtu_piece_points) + longest * points);
      const double piece_bytes =
        snapshots && c.options.write_vtu ? piece_points * vtu_bytes_per_point : 0.;
      const double snapshot_bytes =
        piece_bytes + (snapshots && c.options.profiles != Profiles::none ?
                         points * total * profile_bytes_per_point :
                         0.);
      const double needed = edge_bytes + cell_bytes + snapshot_bytes;
      // the smallest over the ranks: they all refuse, or none
      const double available = Utilities::MPI::job_supports_mpi() ?
                                 Utilities::MPI::min(available_memory_per_rank(), MPI_COMM_WORLD) :
                                 available_memory_per_rank();
      if (available <= 0. || needed <= available)
        return available > 0. && piece_bytes > 0. ?
                 std::max(1., std::min(1e3, std::floor((available - needed) / piece_bytes))) :
                 1;
      const auto &files    = c.input.graph.files;
      const bool  by_edges = edge_bytes > cell_bytes && !files.empty();
      require(false,
              by_edges ? files.front().parameter :
              study    ? std::string("Convergence/cells") :
                         std::string("Network/cells per unit length"),
              by_edges ? files.front().name : format_number(cells),
              "the run needs about " + format_bytes(needed) + " per MPI rank (" +
                format_number(n.size()) + " edges at ~" + format_bytes(bytes_per_edge) +
                " each, " + format_number(total) + " cells of degree " +
                std::to_string(degree) + " at ~" + format_number(per_cell) + " bytes each" +
                (snapshots ? std::string(", snapshots included") : std::string()) +
                "), more than the " + format_bytes(available) +
                " available (MemAvailable): use fewer cells per unit length, fewer edges or a "
                "lower degree, or run on more machines (MPI ranks)");
      return 1;
    }

    /// One warning line on stderr (rank 0) when an edge is so short that its
    /// cells are over 10 times narrower than 1 / (cells per unit length): the
    /// CFL step follows the narrowest cell, so the whole network steps that
    /// much more often (an edge shorter than half a cell gets one cell of its
    /// length).
    void
    warn_of_short_edges(const Case &c, const double cells)
    {
      const Graph &graph = c.input.graph;
      const auto   n     = cell_counts(graph, cells);
      const double dx    = 1. / cells;
      unsigned int narrowest = 0, count = 0;
      for (unsigned int k = 0; k < n.size(); ++k)
        {
          const double h = graph.edges[k].length / n[k];
          if (h < 0.1 * dx)
            ++count;
          if (h < graph.edges[narrowest].length / n[narrowest])
            narrowest = k;
        }
      if (count == 0 || Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
        return;
      const Edge  &e = graph.edges[narrowest];
      const double h = e.length / n[narrowest];
      std::cerr << "granular_dg: warning: " << e.label << " (" << c.input.where(narrowest)
                << "length = " << format_number(e.length) << ") has cells of width "
                << format_number(h) << ", " << format_number(dx / h)
                << " times narrower than 1/(Network/cells per unit length) = "
                << format_number(dx) << ": the time step of the whole network shrinks by "
                << "that factor"
                << (count > 1 ? " (" + std::to_string(count - 1) +
                                  " more edges are over 10 times narrower too)" :
                                std::string())
                << std::endl;
    }

    /// One warning line on stderr (rank 0) when a vertex cell is narrower
    /// than the edges' CFL step covers (width factor < 2 x CFL number; the
    /// largest CFL number of a study): the time step then also follows the
    /// cell's own bound (NetworkProblem::time_step()).
    void
    warn_of_narrow_vertices(const Case &c, const RunParameters &common)
    {
      double cfl = c.method.cfl;
      for (const double x : common.convergence ? common.convergence_cfl : std::vector<double>())
        cfl = std::max(cfl, x);
      const auto  &vertices = c.input.graph.vertices;
      unsigned int narrowest = 0, count = 0;
      for (unsigned int v = 0; v < vertices.size(); ++v)
        {
          if (vertices[v].narrower_than_step(cfl))
            {
              if (count == 0 || vertices[v].width_factor < vertices[narrowest].width_factor)
                narrowest = v;
              ++count;
            }
        }
      if (count == 0 || Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
        return;
      std::cerr << "granular_dg: warning: "
                << (c.input.graph.is_star() ? std::string("the vertex") : vertices[narrowest].label)
                << " has a cell of width factor " << format_number(vertices[narrowest].width_factor)
                << " < 2 x CFL number = " << format_number(2 * cfl)
                << (count > 1 ? " (and " + std::to_string(count - 1) + " more vertices)" :
                                std::string())
                << ": its update (4.1b) is not monotone at the edges' time step, so the step "
                << "also keeps dt sum max|f'| <= dx_0 there (more steps)" << std::endl;
    }

    void
    Case::bind(ParameterBinding &b, const RunParameters &common,
               const dg::DiscretizationParameters &method)
    {
      // the paper's scheme unless the file says otherwise
      b.set_default("Discretization/degree", "0");
      b.set_default("Discretization/numerical flux", "upwind");
      b.set_default("Time stepping/CFL number", "0.5");
      if (b.reading())
        take_method(common, method);

      b.section("Network");
      b.add("cells per unit length", options.cells_per_unit_length, Patterns::Integer(1),
            "Cells per unit length of edge: the paper's grid level l is 2^l (dx = 2^-l); an "
            "edge of length L gets round(L * this) cells.");
      b.add("edge profiles", profiles,
            Patterns::Selection("auto|" + profile_names.selection()),
            "What a snapshot writes besides solution-NNNN.vtu: per_edge "
            "(profile-NNNN-edge-K.csv, one file per edge), one_file (profile-NNNN.csv with an "
            "edge column), none, or auto: per_edge for a graph of up to " +
              std::to_string(most_edges_with_profiles) +
              " edges, none for a larger one (its VTU holds every edge).");
      b.add("exact solution", exact_name, Patterns::Selection(exact_choices()),
            "Exact solution for the error measurement (L1 over all edges and the vertex cell): "
            "none, initial_data (the data are a stationary state), example_7_1 ... "
            "example_7_5 (Musch, Fjordholm & Risebro Section 7; the graph and data are checked "
            "against the example), smooth_linear (a smooth solution through the vertex), "
            "two_stars (two star vertices joined by an edge, Burgers shocks) or "
            "smooth_two_vertices (a smooth solution through two vertices).");
      b.section("Time stepping");
      // forward Euler is unstable with DG of degree >= 1 at every CFL number
      const auto degrees = common.convergence ? common.convergence_degrees :
                                                std::vector<unsigned int>{method.degree};
      b.add("integrator", options.integrator, integrator_names,
            "auto: forward_euler at degree 0 (exactly the paper's scheme (4.1)) and ssprk3 at "
            "degree >= 1.");
      for (const unsigned int p : degrees)
        if (b.reading())
          require(options.integrator != Integrator::forward_euler || p == 0,
                  "Time stepping/integrator", "forward_euler",
                  "auto or ssprk3 at degree " + std::to_string(p) +
                    " (forward Euler is unstable with DG of degree >= 1)");
      input.bind(b);
      if (!b.reading())
        return;
      options.profiles =
        profiles != "auto" ? profile_names.parse("Network/edge profiles", profiles) :
        input.graph.edges.size() <= most_edges_with_profiles ? Profiles::per_edge :
                                                               Profiles::none;
      // before any edge is discretised (below for initial_data, then by run())
      options.vtu_writers = std::min(cores_per_rank(), require_network_fits(*this, common));
      build_exact_solution(common);
    }

    void
    Case::take_method(const RunParameters &common, const dg::DiscretizationParameters &m)
    {
      if (common.convergence && Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) > 1)
        throw InputError("the network's convergence study (Convergence/enabled = true) runs on "
                         "one MPI rank: run it without mpirun, or set Convergence/enabled = false "
                         "for a single run on several ranks");
      require(m.scheme == dg::TimeScheme::ssp_rk3, "Time stepping/scheme",
              dg::time_scheme_name(m.scheme),
              "ssp_rk3 (the network's vertex coupling runs with Euler or SSP-RK3 stages; "
              "Time stepping/integrator chooses between them)");
      require(m.skip_tolerance == 0, "Time stepping/skip tolerance", m.skip_tolerance,
              "0 here: the network computes every cell of every edge in every step (skipping "
              "quiet cells is built in the DG solver of the 1D scenes, not for the network)");
      require(m.engine != dg::Engine::matrix_free, "Discretization/engine", "matrix_free",
              "auto or line here: the network's edges run in one line engine (EdgeLines)");
      require(!m.skip_at_rest, "Time stepping/skip cells at rest", "true",
              "false here: the network computes every cell of every edge in every step "
              "(skipping cells at rest is built in the 2D DG solver)");
      require(!m.write_modes, "Output/write modes", "true",
              "false here: modes-NNNN.csv is written by the 1D scenes of the DG solver (the "
              "network writes its edges' samples, profile-NNNN-edge-K.csv)");
      method            = m;
      flux              = numerical_flux_names.parse("Discretization/numerical flux", m.flux);
      options.write_vtu = common.write_vtu;
      common.require_format_fits(1); // the edges are 1D
    }

    void
    Case::build_exact_solution(const RunParameters &common)
    {
      if (exact_name == "initial_data")
        {
          std::vector<std::shared_ptr<Function<1>>> f;
          for (const auto &d : input.data)
            f.push_back(d.initial);
          // the vertex values of a stationary state: given, or c_0 of the data
          NetworkProblem<EdgeLaw> stationary(input.graph, laws(), method, options, input.data);
          stationary.initialize();
          exact = std::make_shared<InitialData>(f, stationary.vertex_values());
        }
      else if (exact_name != "none")
        {
          const Example ex = make_example(exact_name);
          check_example(ex, *this, common.final_time);
          exact = ex.exact;
          for (unsigned int k = 0; k < input.data.size(); ++k)
            input.data[k].initial_breakpoints = ex.exact->breakpoints(k, 0.);
        }
    }

    void
    run(const RunParameters &common, const dg::DiscretizationParameters &, const Case &c)
    {
      if (common.convergence)
        require(static_cast<bool>(c.exact), "Network/exact solution", "none",
                "an exact solution: a convergence study measures errors");
      const std::size_t n_edges = c.input.graph.edges.size();
      require(Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) <= n_edges, "MPI ranks",
              Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD),
              "at most the number of edges, " + std::to_string(n_edges) +
                " (each rank computes whole edges)");
      // a study: its finest level, which costs the most
      warn_of_short_edges(c, common.convergence ?
                               double(*std::max_element(common.convergence_cells.begin(),
                                                        common.convergence_cells.end())) :
                               c.options.cells_per_unit_length);
      warn_of_narrow_vertices(c, common);
      if (c.profiles == "auto" && c.options.profiles == Profiles::none &&
          Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
        std::cout << "  no edge profiles: Network/edge profiles = auto writes them for up to "
                  << most_edges_with_profiles << " edges (per_edge or one_file to have them)"
                  << std::endl;
      {
        const auto    n     = edge_cells(c.input.graph, c.options.cells_per_unit_length);
        unsigned long cells = 0;
        for (const unsigned int x : n)
          cells += x;
        require_reasonable_snapshot_count(common, snapshot_bytes(cells, c.method, c.options));
      }
      begin_output(common);
      if (common.convergence)
        run_network_convergence(c.input.graph, c.laws(), c.input.data, c.method, c.options,
                                *c.exact, common);
      else
        run_network(c.input.graph, c.laws(), c.input.data, c.method, c.options, c.exact.get(),
                    common, true);
    }

    const RegisterScene registration(dg::scene_entry<Case>(
      "network",
      "scalar conservation laws u_t + f_k(u)_x = 0 on a network of edges and vertex control "
      "volumes (linear, Burgers, traffic fluxes)",
      numerical_flux_names.selection(), "", run));
  } // namespace
} // namespace granular_dg::network
