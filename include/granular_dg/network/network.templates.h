#pragma once

/**
 * The members of NetworkProblem<Law> but its output (output.templates.h): a
 * scene includes this file once and instantiates them for its Law.
 */

#include <deal.II/base/quadrature_lib.h>

#include <granular_dg/base/errors.h>
#include <granular_dg/base/output.h>
#include <granular_dg/dg/solution_transfer.h>
#include <granular_dg/network/network.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <optional>

namespace granular_dg::network
{
  template <typename Law>
  NetworkProblem<Law>::NetworkProblem(const Graph &graph, std::vector<Law> edge_laws,
                                           const dg::DiscretizationParameters &m,
                                           const NetworkOptions &o, std::vector<EdgeData> edge_data,
                                           const ExactSolution *exact, const std::string &scene)
    : net(graph)
    , laws(std::move(edge_laws))
    , method(m)
    , options(o)
    , data(std::move(edge_data))
    , exact(exact)
    , scene(scene)
  {
    AssertThrow(data.size() == net.edges.size() && laws.size() == net.edges.size(),
                ExcMessage("one EdgeData and one law per edge"));
    h_min      = 1e300;
    edge_cells = network::edge_cells(net, options.cells_per_unit_length);
    for (unsigned int k = 0; k < net.edges.size(); ++k)
      {
        edge_h.push_back(net.edges[k].length / edge_cells[k]);
        h_min = std::min(h_min, edge_h.back());
      }
    ranks = std::make_unique<EdgePartition>(net, edge_cells, MPI_COMM_WORLD);

    // this rank's edges in one line engine, in the partition's order
    local_edge.assign(net.edges.size(), -1);
    std::vector<Law>          local_laws;
    std::vector<unsigned int> cells;
    std::vector<double>       sizes;
    for (const unsigned int k : ranks->edges())
      {
        local_edge[k] = local_laws.size();
        local_laws.push_back(laws[k]);
        cells.push_back(edge_cells[k]);
        sizes.push_back(edge_h[k]);
      }
    const EdgeMethod edge_method{method.degree,    method.limiter,
                                 method.tvb_M,     method.indicator,
                                 method.indicator_threshold, method.blending_max()};
    lines = std::make_unique<EdgeLines<Law>>(edge_method, std::move(local_laws), cells, sizes);
    for (const unsigned int k : ranks->edges())
      for (const unsigned int side : {0u, 1u})
        lines->kind(local(k), side) = net.edges[k].vertex_at(side) ? EndKind::vertex :
                                      net.edges[k].far_end == FarEnd::dirichlet ?
                                                                     EndKind::dirichlet :
                                                                     EndKind::outflow;

    auto ends = net.all_vertex_ends();
    for (unsigned int v = 0; v < net.vertices.size(); ++v)
      {
        double width = 0;
        for (const auto &end : ends[v])
          width += 0.5 * edge_h[end.edge];
        junctions.emplace_back(net, laws, v, std::move(ends[v]),
                               net.vertices[v].width_factor * width);
      }

    // the admissible ranges (Law::admissible_range(), vertex_range())
    for (const auto &j : junctions)
      {
        Bounded b{{{-INFINITY, INFINITY}}, {}};
        for (const auto &end : j.ends())
          {
            const auto r = widened(laws[end.edge].vertex_range(end.incoming),
                                   laws[end.edge].admissible_range());
            if (r[0] > b.range[0])
              b.range[0] = r[0], b.end[0] = end;
            if (r[1] < b.range[1])
              b.range[1] = r[1], b.end[1] = end;
          }
        vertex_range.push_back(b);
      }
    for (const unsigned int k : ranks->edges())
      if (const auto r = widened(laws[k].admissible_range()); std::isfinite(r[0]) || std::isfinite(r[1]))
        bounded_edges.emplace_back(k, r);

    // the end faces of this rank's edges at vertices and with far-end data
    for (const unsigned int k : ranks->edges())
      for (const unsigned int side : {0u, 1u})
        if (net.edges[k].vertex_at(side))
          vertex_faces.emplace_back(2 * local(k) + side,
                                    side == 0 ? net.edges[k].from : net.edges[k].to);
        else
          {
            free_faces.emplace_back(k, side);
            if (net.edges[k].far_end == FarEnd::dirichlet)
              data_faces.emplace_back(k, side);
          }
    // edges that share their far-end data next to each other: far_end_data()
    // evaluates each function once per point and time
    std::stable_sort(data_faces.begin(), data_faces.end(), [&](const auto &a, const auto &b) {
      return std::make_pair(data[a.first].far_end.get(), far_end_point(a)) <
             std::make_pair(data[b.first].far_end.get(), far_end_point(b));
    });
    // where the trace of each end of this rank's vertices comes from (a
    // vertex not cut has all its edges here)
    std::vector<bool> here(net.vertices.size(), false);
    for (const unsigned int v : ranks->vertices())
      here[v] = true;
    vertex_ends.first.assign(1, 0);
    for (unsigned int v = 0; v < net.vertices.size(); ++v)
      {
        const auto &ends = junctions[v].ends();
        for (unsigned int i = 0; here[v] && i < ends.size(); ++i)
          {
            // (an end without a slot is on an edge of this rank)
            const int          slot  = ranks->slot(v, i);
            const unsigned int k     = ends[i].edge;
            const bool         owned = ranks->owns_edge(k);
            const std::size_t  cell =
              owned ? lines->index(local(k), ends[i].incoming ? edge_cells[k] - 1 : 0) : 0;
            vertex_ends.face.push_back(slot >= 0 ? -1 - long(slot) :
                                                   long(2 * local(k) + ends[i].incoming));
            vertex_ends.at_end.push_back(ends[i].incoming);
            if (owned)
              owned_ends.push_back({v, cell});
          }
        vertex_ends.first.push_back(vertex_ends.face.size());
      }
    exchanged.assign(ranks->n_slots(), 0.);
    exchanged_flux.assign(ranks->n_slots(), 0.);
    for (const unsigned int v : ranks->vertices())
      {
        without_volume = without_volume || junctions[v].width() == 0;
        if (net.vertices[v].narrower_than_step(method.cfl))
          {
            narrow_vertices.push_back(v);
            for (auto i = vertex_ends.first[v]; i < vertex_ends.first[v + 1]; ++i)
              narrow_cut = narrow_cut || vertex_ends.face[i] < 0;
          }
      }
    double narrow[2] = {double(narrow_vertices.size()), double(narrow_cut)};
    ranks->max(narrow, 2);
    narrow_anywhere = narrow[0] > 0;
    narrow_cut      = narrow[1] > 0;
    u.vertices.assign(net.vertices.size(), 0.);
    vertex_u0.assign(net.vertices.size(), 0.);
    u.edges.assign(lines->size(), 0.);
  }

  template <typename Law>
  NetworkProblem<Law>::~NetworkProblem() = default;

  template <typename Law>
  unsigned int
  NetworkProblem<Law>::n_stages() const
  {
    const bool euler = options.integrator == Integrator::forward_euler ||
                       (options.integrator == Integrator::automatic && method.degree == 0);
    return euler ? 1 : dg::SSPRK3<NetworkState>::n_stages;
  }

  template <typename Law>
  unsigned long
  NetworkProblem<Law>::n_dofs() const
  {
    // the edges' modes and the vertex values
    return net.vertices.size() + n_cells() * (method.degree + 1);
  }

  template <typename Law>
  unsigned long
  NetworkProblem<Law>::n_cells() const
  {
    return std::accumulate(edge_cells.begin(), edge_cells.end(), 0ul);
  }

  template <typename Law>
  EvolutionInfo
  NetworkProblem<Law>::info() const
  {
    EvolutionInfo i;
    i.scene    = scene;
    i.physics  = Law::name;
    i.dim      = 1;
    i.degree   = method.degree;
    i.n_cells  = n_cells();
    i.n_dofs   = n_dofs();
    i.h_min    = h_min;
    i.n_stages = n_stages();
    i.snapshot_files = options.profiles == Profiles::per_edge ? "solution.pvd, profile-NNNN-edge-K.csv" :
                       options.profiles == Profiles::one_file ? "solution.pvd, profile-NNNN.csv" :
                                                             "solution.pvd";
    const std::string integrator = n_stages() == 1 ? "forward_euler" : "ssprk3";
    std::string vertices;
    if (net.is_star())
      vertices = std::to_string(junctions[0].ends().size()) + " vertex ends, vertex width " +
                 format_number(junctions[0].width());
    else
      vertices = std::to_string(net.vertices.size()) + " vertices";
    i.description = std::to_string(net.edges.size()) + " edges, " + vertices + ", " +
                    std::to_string(i.n_cells) + " cells, " + std::to_string(i.n_dofs) +
                    " DoFs, degree " + std::to_string(method.degree) + ", " + integrator +
                    (ranks->parallel() ? "; " + ranks->describe() : "");
    i.method.add("engine", "line");
    i.method.add("numerical_flux", laws.front().flux_name());
    i.method.add("limiter", method.limiter_name);
    if (method.blending_max() > 0)
      i.method.add("subcell_blending", method.blending_max());
    i.method.add("scheme", integrator);
    i.method.add("n_edges", static_cast<long long>(net.edges.size()));
    i.bytes_per_snapshot = snapshot_bytes(i.n_cells, method, options);
    return i;
  }

  template <typename Law>
  double
  NetworkProblem<Law>::trace(const unsigned int k, const bool at_end, const NetworkState &s) const
  {
    return lines->trace(s.edges.data(), local(k), at_end);
  }

  template <typename Law>
  double
  NetworkProblem<Law>::initialize()
  {
    const QGauss<1>     quad(method.degree + 3);
    std::vector<double> moments(method.degree + 1), pieces;
    for (const unsigned int k : ranks->edges())
      {
        const double h = edge_h[k];
        data[k].initial->set_time(0.);
        for (unsigned int c = 0; c < edge_cells[k]; ++c)
          {
            const double x0 = c * h;
            std::fill(moments.begin(), moments.end(), 0.);
            // split at the known jumps first, then refine adaptively
            pieces.assign({x0, x0 + h});
            for (const double b : data[k].initial_breakpoints)
              if (b > x0 && b < x0 + h)
                pieces.push_back(b);
            std::sort(pieces.begin(), pieces.end());
            for (unsigned int p = 0; p + 1 < pieces.size(); ++p)
              add_cell_moments(*data[k].initial, lines->legendre(), quad, x0, h, pieces[p],
                               pieces[p + 1], moments);
            for (unsigned int m = 0; m <= method.degree; ++m)
              u.edges[lines->index(local(k), c) + m] = moments[m] / h;
          }
      }
    // the limiter sees the vertex values as the neighbours of the edge ends
    exchange_traces(u);
    fill_traces(u);
    for (const unsigned int v : ranks->vertices())
      {
        const auto &given = net.vertices[v].initial_value;
        u.vertices[v]     = given ? *given : balance_at(v, 0.);
        vertex_u0[v]  = u.vertices[v];
      }
    set_end_states(0.);
    lines->limit(u.edges.data());
    exchange_traces(u);
    fill_traces(u);
    for (const unsigned int v : ranks->vertices())
      if (!net.vertices[v].initial_value || junctions[v].width() == 0)
        u.vertices[v] = balance_at(v, 0.);
    t      = 0.;
    inflow = 0.;
    balance.mass0 = mass();
    const double l1 = l1_norm();
    balance.scale = l1 > 0 ? l1 : 1.;
    tv0 = tv_max = total_variation();
    u00          = u.vertices.empty() ? 0. : vertex_values()[0];
    return 0.;
  }

  template <typename Law>
  Inadmissible
  NetworkProblem<Law>::failure(const double time, const int k, const double x, const double value,
                               const std::string &reason) const
  {
    Inadmissible f;
    f.time   = time;
    f.where  = k >= 0     ? net.edges[k].label + " x = " + format_number(x) :
               net.is_star() ? std::string("vertex") :
                               net.vertices[-1 - k].label;
    f.names  = {"u"};
    f.state  = {value};
    f.reason = reason;
    return f;
  }

  template <typename Law>
  void
  NetworkProblem<Law>::check_initial_state(const double time)
  {
    NetworkState s = u;
    bounds         = {-INFINITY, INFINITY};
    try
      {
        post_stage_checks(s, time, true, true);
      }
    catch (Inadmissible &f)
      {
        f.initial = true;
        throw;
      }
  }

  template <typename Law>
  void
  NetworkProblem<Law>::fill_traces(const NetworkState &s) const
  {
    end_traces.resize(vertex_ends.face.size());
    for (std::size_t i = 0; i < end_traces.size(); ++i)
      {
        const long face = vertex_ends.face[i];
        end_traces[i]   = face < 0 ? exchanged[-1 - face] :
                                     lines->trace(s.edges.data(), face / 2, face % 2);
      }
  }

  template <typename Law>
  void
  NetworkProblem<Law>::exchange_traces(const NetworkState &s) const
  {
    if (ranks->n_cut_vertices() == 0)
      return;
    const auto &sent = ranks->sent_ends();
    exchanged.assign(exchanged.size(), 0.);
    for (const auto &end : sent)
      exchanged[end.slot] = trace(end.edge, end.at_end, s);
    ranks->exchange(exchanged);
  }

  template <typename Law>
  double
  NetworkProblem<Law>::balance_at(const unsigned int v, const double time) const
  {
    const double *traces = traces_at(v);
    if (!ranks->parallel())
      return junctions[v].balance(traces, time);
    try
      {
        return junctions[v].balance(traces, time);
      }
    catch (const RunError &e)
      {
        if (!pending_error)
          pending_error = e.what();
        return NAN;
      }
  }

  template <typename Law>
  std::vector<double>
  NetworkProblem<Law>::vertex_values() const
  {
    if (!ranks->parallel())
      return u.vertices;
    std::vector<double> all(u.vertices.size(), 0.);
    for (const unsigned int v : ranks->vertices())
      if (ranks->reports_vertex(v))
        all[v] = u.vertices[v];
    ranks->sum(all.data(), all.size());
    return all;
  }

  template <typename Law>
  double
  NetworkProblem<Law>::far_end_inflow() const
  {
    // inflow at x = 0, outflow at x = L
    double sum = 0;
    for (const auto &[k, side] : free_faces)
      {
        const double F = lines->boundary_flux(2 * local(k) + side);
        sum += side == 0 ? F : -F;
      }
    return sum;
  }

  template <typename Law>
  double
  NetworkProblem<Law>::vertex_state(const unsigned int v, const NetworkState &s, const double time) const
  {
    return junctions[v].width() > 0 ? s.vertices[v] : balance_at(v, time);
  }

  template <typename Law>
  void
  NetworkProblem<Law>::set_vertex_states(const NetworkState &s, const double time) const
  {
    // vertices without volume follow the traces: shared ones need them
    if (ranks->has_cut_vertex_without_volume())
      exchange_traces(s);
    if (without_volume)
      fill_traces(s);
    for (const unsigned int v : ranks->vertices())
      vertex_u0[v] = vertex_state(v, s, time);
    set_end_states(time);
  }

  template <typename Law>
  const std::vector<double> &
  NetworkProblem<Law>::vertex_rates() const
  {
    // the fluxes of the ends at cut vertices, from the ranks of their edges
    if (ranks->n_cut_vertices() > 0)
      {
        exchanged_flux.assign(exchanged_flux.size(), 0.);
        for (const auto &end : ranks->sent_ends())
          exchanged_flux[end.slot] = lines->boundary_flux(2 * local(end.edge) + end.at_end);
        ranks->exchange(exchanged_flux);
      }
    // Junction::net_outflow() of these fluxes: the same sum in the same order
    rates.resize(junctions.size());
    for (const unsigned int v : ranks->vertices())
      {
        double sum = 0;
        for (auto i = vertex_ends.first[v]; i < vertex_ends.first[v + 1]; ++i)
          {
            const long   face = vertex_ends.face[i];
            const double F =
              face < 0 ? exchanged_flux[-1 - face] : lines->boundary_flux(face);
            sum += vertex_ends.at_end[i] ? -F : F;
          }
        rates[v] = junctions[v].rate(sum);
      }
    stage_inflow.push_back(far_end_inflow());
    return rates;
  }

  template <typename Law>
  void
  NetworkProblem<Law>::set_end_states(const double time) const
  {
    for (const auto &[face, v] : vertex_faces)
      lines->outer_state(face / 2, face % 2) = vertex_u0[v];
    // the far-end data depend on the time only (a step's last stage and the
    // next step's first one share theirs)
    if (time == data_time)
      return;
    data_time = time;
    far_end_data(time, [&](const auto &face, const double g) {
      lines->outer_state(local(face.first), face.second) = g;
    });
  }

  template <typename Law>
  template <typename F>
  void
  NetworkProblem<Law>::far_end_data(const double time, const F &f) const
  {
    // (data_faces are sorted by function and point: each pair evaluated once)
    Function<1>       *function = nullptr;
    double             x = NAN, g = NAN;
    for (const auto &face : data_faces)
      {
        if (data[face.first].far_end.get() != function || far_end_point(face) != x)
          {
            function = data[face.first].far_end.get();
            x        = far_end_point(face);
            function->set_time(time);
            g = function->value(Point<1>(x));
          }
        f(face, g);
      }
  }

  template <typename Law>
  void
  NetworkProblem<Law>::apply_stage(const double time, const NetworkState &src, NetworkState &dst,
                                   const dg::StageUpdate<NetworkState> &s) const
  {
    // the vertex coupling is part of the right-hand side of the network
    StepPhases::Scope scope(phases, StepPhases::operator_apply);
    set_vertex_states(src, time);
    dst.edges.resize(src.edges.size());
    lines->stage(src.edges.data(), dst.edges.data(), s.old ? s.old->edges.data() : nullptr,
                 s.alpha, s.beta, s.gamma);
    const auto &rate = vertex_rates();
    dst.vertices.resize(src.vertices.size());
    for (const unsigned int v : ranks->vertices())
      dst.vertices[v] =
        dg::stage_value(s, src.vertices[v], s.old ? s.old->vertices[v] : 0., rate[v]);
  }

  template <typename Law>
  std::pair<double, double>
  NetworkProblem<Law>::range_of_step(const double time, const double dt) const
  {
    double lo = INFINITY, hi = -INFINITY;
    for (const unsigned int v : ranks->vertices())
      {
        lo = std::min(lo, u.vertices[v]);
        hi = std::max(hi, u.vertices[v]);
      }
    const internal::Scan edges = internal::scan<true>(u.edges);
    lo               = std::min(lo, edges.lo);
    hi               = std::max(hi, edges.hi);
    for (const double s : {time, time + 0.5 * dt, time + dt})
      far_end_data(s, [&](const auto &, const double g) {
        lo = std::min(lo, g);
        hi = std::max(hi, g);
      });
    return {ranks->min(lo), ranks->max(hi)};
  }

  template <typename Law>
  void
  NetworkProblem<Law>::check_maximum_principle(const NetworkState &s, const double stage_time,
                                               const double lo_s, const double hi_s)
  {
    const auto [lo, hi] = bounds;
    const double tol    = 1e-12 * (hi - lo + std::max(std::abs(lo), std::abs(hi)));
    // [lo_s, hi_s]: the range of s.edges (degree 0: the means only); else
    // the cell to report
    if (lo_s >= lo - tol && hi_s <= hi + tol)
      return;
    for (const unsigned int k : ranks->edges())
      for (unsigned int c = 0; c < edge_cells[k]; ++c)
        {
          const double v = s.edges[lines->index(local(k), c)];
          if (v < lo - tol || v > hi + tol)
            throw failure(stage_time, int(k), (c + 0.5) * edge_h[k], v,
                          "maximum principle violated: u outside [" + format_number(lo) +
                            ", " + format_number(hi) +
                            "], the range of the cell averages, vertex values and "
                            "far-end data at the start of the step (degree 0 is monotone "
                            "only up to its CFL limit; CFL number " +
                            format_number(method.cfl) + ")");
        }
  }

  template <typename Law>
  void
  NetworkProblem<Law>::post_stage(NetworkState &s, const double stage_time, const bool last)
  {
    {
      StepPhases::Scope scope(phases, StepPhases::limiter);
      // (the limiter's neighbours at the edge ends: the vertex values)
      if (lines->limits())
        {
          set_vertex_states(s, stage_time);
          lines->limit(s.edges.data());
        }
      if (ranks->has_cut_vertex_without_volume())
        exchange_traces(s);
      if (without_volume)
        fill_traces(s);
      for (const unsigned int v : ranks->vertices())
        if (junctions[v].width() == 0)
          s.vertices[v] = balance_at(v, stage_time);
    }
    StepPhases::Scope scope(phases, StepPhases::admissibility);
    post_stage_checks(s, stage_time, last && method.degree > 0);
  }

  template <typename Law>
  void
  NetworkProblem<Law>::post_stage_checks(const NetworkState &s, const double stage_time,
                                         const bool means, const bool initial)
  {
    const bool principle =
      method.degree == 0 && std::isfinite(bounds.first) && std::isfinite(bounds.second);
    if (principle)
      {
        // a vertex is a neighbour of its edge ends: its (stage) value is a
        // value the edges may take on
        for (const unsigned int v : ranks->vertices())
          {
            bounds.first  = std::min(bounds.first, s.vertices[v]);
            bounds.second = std::max(bounds.second, s.vertices[v]);
          }
        bounds = {ranks->min(bounds.first), ranks->max(bounds.second)};
      }
    // every rank checks its part, then all report the first failure
    std::optional<Inadmissible> found;
    try
      {
        local_checks(s, stage_time, principle, means, initial);
      }
    catch (const Inadmissible &f)
      {
        found = f;
      }
    std::optional<std::string> error;
    std::swap(error, pending_error);
    ranks->agree(found, error);
  }

  template <typename Law>
  void
  NetworkProblem<Law>::local_checks(const NetworkState &s, const double stage_time,
                                    const bool principle, const bool means,
                                    const bool initial)
  {
    for (const unsigned int v : ranks->vertices())
      if (!std::isfinite(s.vertices[v]))
        throw failure(stage_time, -1 - int(v), 0., s.vertices[v], "vertex value is not finite");
    // (non-finite values fail this test too, and are reported as such below)
    const internal::Scan edges = principle ? internal::scan<true>(s.edges) : internal::scan<false>(s.edges);
    // At degree 0 the update of an edge is monotone under its CFL limit
    // (the maximum principle checks it): its means stay within its
    // initial and far-end data and the values of its vertices, which are
    // checked every stage. The means of higher degrees: after every step.
    check_admissible_ranges(s, stage_time, edges.finite && means, initial);
    if (principle && edges.finite)
      check_maximum_principle(s, stage_time, edges.lo, edges.hi);
    if (edges.finite)
      return;
    // non-finite far-end data are the cause where there are any
    for (const auto &face : data_faces)
      if (const double g = lines->outer_state(local(face.first), face.second); !std::isfinite(g))
        throw failure(stage_time, int(face.first), far_end_point(face), g,
                      "far-end data not finite at t = " + format_number(data_time));
    // else: the first cell whose modes are not finite
    for (const unsigned int k : ranks->edges())
      for (unsigned int c = 0; c < edge_cells[k]; ++c)
        for (unsigned int m = 0; m <= method.degree; ++m)
          if (!std::isfinite(s.edges[lines->index(local(k), c) + m]))
            throw failure(stage_time, int(k), (c + 0.5) * edge_h[k],
                          s.edges[lines->index(local(k), c)], "state is not finite");
  }

  template <typename Law>
  void
  NetworkProblem<Law>::check_admissible_ranges(const NetworkState &s, const double stage_time,
                                               const bool means, const bool initial) const
  {
    // After a stage only the upper bounds: a traffic vertex value or mean
    // above alpha is a junction that overfills (the single vertex value's
    // limit), while the paper's time step does not keep the value of a
    // vertex without inflow at u_0 >= 0 (doc/network.md): the scheme's
    // undershoot, not a state the model cannot hold. (NaN is not outside:
    // the finiteness checks report it.)
    const auto outside = [initial](const double x, const std::array<double, 2> &r) {
      return (initial && x < r[0]) || x > r[1];
    };
    const auto interval = [](const std::array<double, 2> &r) {
      return "[" + format_number(r[0]) + ", " + format_number(r[1]) + "]";
    };
    const auto admitted = [&](const unsigned int k) {
      return interval(laws[k].admissible_range()) + ", the states " + net.edges[k].label + " (" +
             laws[k].describe() + ") admits";
    };
    for (const auto &face : data_faces)
      {
        const double g = lines->outer_state(local(face.first), face.second);
        const auto   r = widened(laws[face.first].admissible_range());
        if (g < r[0] || g > r[1])
          throw failure(stage_time, int(face.first), far_end_point(face), g,
                        "far-end data at t = " + format_number(data_time) + " outside " +
                          admitted(face.first));
      }
    const unsigned int stride = lines->n_modes();
    for (unsigned int i = 0; means && i < bounded_edges.size(); ++i)
      {
        const auto &[k, range] = bounded_edges[i];
        const double      *mean = s.edges.data() + lines->index(local(k), 0);
        const unsigned int n    = edge_cells[k];
        // the edge's range of means first (two chains each: no long one)
        double       lo0 = mean[0], hi0 = mean[0], lo1 = mean[0], hi1 = mean[0];
        unsigned int c = 1;
        for (; c + 1 < n; c += 2)
          {
            const double a = mean[c * stride], b = mean[(c + 1) * stride];
            lo0 = std::min(lo0, a), hi0 = std::max(hi0, a);
            lo1 = std::min(lo1, b), hi1 = std::max(hi1, b);
          }
        if (c < n)
          lo0 = std::min(lo0, mean[c * stride]), hi0 = std::max(hi0, mean[c * stride]);
        if (!outside(std::min(lo0, lo1), range) && !outside(std::max(hi0, hi1), range))
          continue;
        for (unsigned int cell = 0; cell < n; ++cell)
          if (outside(mean[cell * stride], range))
            throw failure(stage_time, int(k), (cell + 0.5) * edge_h[k], mean[cell * stride],
                          "cell mean outside " + admitted(k));
      }
    // (after the edges: a vertex's initial value balances their traces)
    for (const unsigned int v : ranks->vertices())
      if (const Bounded &b = vertex_range[v]; outside(s.vertices[v], b.range))
        {
          const EdgeEnd &end = b.end[s.vertices[v] > b.range[1]];
          // (an initial value the program found, not one the user gave;
          // the net outflow grows with u_0 for monotone fluxes)
          std::string found;
          if (initial && !net.vertices[v].initial_value)
            found = std::string(junctions[v].width() > 0 ?
                                  "; it is the discrete stationary value of the edges' "
                                  "initial traces (Definition 4.4), so" :
                                  "; it balances the fluxes of the edges' initial traces, so") +
                    " at every value in that range " +
                    (s.vertices[v] > b.range[1] ? "more flows in than out" :
                                                  "less flows in than out") +
                    (junctions[v].width() > 0 ?
                       " (an initial value starts the run: Network/vertex initial value)" :
                       "");
          throw failure(stage_time, -1 - int(v), 0., s.vertices[v],
                        "vertex value outside " +
                          interval(laws[end.edge].vertex_range(end.incoming)) +
                          ", where the flux at the " + (end.incoming ? "end" : "start") +
                          " of " + net.edges[end.edge].label + " (" +
                          laws[end.edge].describe() + ") is physical" + found);
        }
  }

  template <typename Law>
  double
  NetworkProblem<Law>::time_step(const double time)
  {
    // the vertex value at each vertex end of this rank's edges
    face_values.resize(2 * lines->n_edges());
    for (const auto &[face, v] : vertex_faces)
      face_values[face] = u.vertices[v];
    const double speed_over_h = lines->max_speed_over_h(u.edges.data(), face_values.data());
    if (!narrow_anywhere)
      return method.time_step(ranks->max(speed_over_h), "t", time);
    // (one reduction for both rates)
    double rates[2] = {speed_over_h, narrow_vertex_rate()};
    ranks->max(rates, 2);
    const double dt = method.time_step(rates[0], "t", time);
    return dt * rates[1] > 1 ? 1 / rates[1] : dt;
  }

  template <typename Law>
  double
  NetworkProblem<Law>::narrow_vertex_rate() const
  {
    // (a monotone flux F(u_l, u_r) changes with u_0 by at most the largest
    // |f'| between u_0 and the trace: at one of them for the convex and
    // concave laws)
    if (narrow_cut)
      exchange_traces(u);
    double rate = 0;
    for (const unsigned int v : narrow_vertices)
      {
        const auto  &ends = junctions[v].ends();
        const double u0   = u.vertices[v];
        double       sum  = 0;
        for (auto i = vertex_ends.first[v]; i < vertex_ends.first[v + 1]; ++i)
          {
            const long   face = vertex_ends.face[i];
            const double tr   = face < 0 ? exchanged[-1 - face] :
                                           lines->trace(u.edges.data(), face / 2, face % 2);
            const Law   &f    = laws[ends[i - vertex_ends.first[v]].edge];
            sum += std::max(std::abs(f.derivative(u0)), std::abs(f.derivative(tr)));
          }
        rate = std::max(rate, sum / junctions[v].width());
      }
    return rate;
  }

  template <typename Law>
  void
  NetworkProblem<Law>::advance(const double time, const double dt)
  {
    t = time;
    stage_inflow.clear();
    if (method.degree == 0)
      bounds = range_of_step(t, dt);
    // the new state into last_good, then swapped with u: u keeps the last
    // good state until the step is done, without a copy (store())
    if (n_stages() == 1)
      {
        dg::ForwardEuler<NetworkState>().step(
          *this, u, t, dt,
          [&](NetworkState &s, double stage_time, double) { post_stage(s, stage_time, true); },
          &last_good);
        inflow += dt * stage_inflow[0];
      }
    else
      {
        unsigned int stage = 0;
        rk3.step(
          *this, u, t, dt,
          [&](NetworkState &s, const double stage_time, const double) {
            post_stage(s, stage_time, ++stage == n_stages());
          },
          &last_good);
        // the Butcher weights of the Shu-Osher SSPRK3: 1/6, 1/6, 2/3
        inflow += dt * (stage_inflow[0] / 6. + stage_inflow[1] / 6. + 2. * stage_inflow[2] / 3.);
      }
    u.swap(last_good);
    last_good_swapped = true;
    t += dt;
  }

  template <typename Law>
  double
  NetworkProblem<Law>::balance_residual() const
  {
    double sums[2] = {local_mass(), inflow};
    ranks->sum(sums, 2);
    return (sums[0] - balance.mass0 - sums[1]) / balance.scale;
  }

  template <typename Law>
  void
  NetworkProblem<Law>::end_of_step(const double, const double, const unsigned long)
  {
    // one reduction for the step's diagnostics
    const auto local = local_sums();
    double     sums[3] = {local[0], inflow, local[1]};
    ranks->sum(sums, 3);
    const double r       = (sums[0] - balance.mass0 - sums[1]) / balance.scale;
    balance.max_residual = std::max(balance.max_residual, std::abs(r));
    balance.max_step     = std::max(balance.max_step, std::abs(r - balance.last));
    balance.last         = r;
    tv_max               = std::max(tv_max, sums[2]);
  }

  template <typename Law>
  void
  NetworkProblem<Law>::store(const Slot slot)
  {
    // (a step leaves u alone and swaps: u is the last good state)
    if (slot == Slot::last_good)
      last_good_swapped = false;
    else
      benchmark_start = u;
  }

  template <typename Law>
  void
  NetworkProblem<Law>::restore(const Slot slot)
  {
    if (slot == Slot::benchmark_start)
      u = benchmark_start;
    else if (last_good_swapped)
      u.swap(last_good);
    last_good_swapped = false;
  }

  template <typename Law>
  double
  NetworkProblem<Law>::mass() const
  {
    return ranks->sum(local_mass());
  }

  template <typename Law>
  double
  NetworkProblem<Law>::local_mass() const
  {
    return local_sums()[0];
  }

  template <typename Law>
  std::array<double, 2>
  NetworkProblem<Law>::local_sums() const
  {
    // mass: the vertices' part, then each edge's (h times its sum of
    // means); TV: the jumps along each edge, then those at the vertices
    double m = 0, tv = 0;
    for (const unsigned int v : ranks->vertices())
      if (ranks->reports_vertex(v))
        m += junctions[v].width() * u.vertices[v];
    internal::add_edge_sums(u.edges.data(), lines->n_modes(), lines->cell_counts(),
                            lines->cell_sizes(), m, tv);
    for (const auto &end : owned_ends)
      tv += std::abs(u.vertices[end.vertex] - u.edges[end.cell]);
    return {{m, tv}};
  }

  template <typename Law>
  double
  NetworkProblem<Law>::l1_norm() const
  {
    double m = 0;
    for (const unsigned int v : ranks->vertices())
      if (ranks->reports_vertex(v))
        m += junctions[v].width() * std::abs(u.vertices[v]);
    for (const unsigned int k : ranks->edges())
      {
      for (unsigned int c = 0; c < edge_cells[k]; ++c)
        m += std::abs(u.edges[lines->index(local(k), c)]) * edge_h[k];
      }
    return ranks->sum(m);
  }

  template <typename Law>
  double
  NetworkProblem<Law>::rh_residual() const
  {
    // every vertex's residual on the rank that reports it, then the
    // largest as on one rank
    exchange_traces(u);
    fill_traces(u);
    std::vector<double> residual(junctions.size(), 0.);
    for (const unsigned int v : ranks->vertices())
      if (ranks->reports_vertex(v))
        residual[v] = -junctions[v].net_outflow(traces_at(v), u.vertices[v]);
    ranks->sum(residual.data(), residual.size());
    double largest = 0;
    for (unsigned int v = 0; v < junctions.size(); ++v)
      if (std::abs(residual[v]) > std::abs(largest) || v == 0)
        largest = residual[v];
    return largest;
  }

  template <typename Law>
  double
  NetworkProblem<Law>::total_variation() const
  {
    return ranks->sum(local_sums()[1]);
  }

  template <typename Law>
  NetworkErrors
  NetworkProblem<Law>::errors(const ExactSolution &solution, const double time) const
  {
    NetworkErrors   e;
    const QGauss<1> quad(2 * method.degree + 8);
    double          l2 = 0;
    e.l1_per_edge.assign(net.edges.size(), 0.);
    for (const unsigned int k : ranks->edges())
      {
        const auto   breaks = solution.breakpoints(k, time);
        const double h      = edge_h[k];
        for (unsigned int c = 0; c < edge_cells[k]; ++c)
          {
            const double        x0 = c * h;
            std::vector<double> pieces{x0, x0 + h};
            for (const double b : breaks)
              if (b > x0 && b < x0 + h)
                pieces.push_back(b);
            std::sort(pieces.begin(), pieces.end());
            for (unsigned int p = 0; p + 1 < pieces.size(); ++p)
              for (unsigned int q = 0; q < quad.size(); ++q)
                {
                  const double w = (pieces[p + 1] - pieces[p]) * quad.weight(q);
                  const double x = pieces[p] + (pieces[p + 1] - pieces[p]) * quad.point(q)[0];
                  const double d = std::abs(lines->value(u.edges.data(), local(k), c, (x - x0) / h) -
                                            solution.value(k, x, time));
                  e.l1_per_edge[k] += w * d;
                  l2 += w * d * d;
                  e.linf = std::max(e.linf, d);
                }
          }
      }
    for (const unsigned int v : ranks->vertices())
      if (ranks->reports_vertex(v))
        {
          const double d0 = std::abs(u.vertices[v] - solution.vertex_value(v, time));
          e.l1_vertex += junctions[v].width() * d0;
          l2 += junctions[v].width() * d0 * d0;
          if (junctions[v].width() > 0)
            e.linf = std::max(e.linf, d0);
        }
    // each edge's error comes from one rank: the sum over the edges is the
    // one of a serial run
    ranks->sum(e.l1_per_edge.data(), e.l1_per_edge.size());
    double sums[2] = {e.l1_vertex, l2};
    ranks->sum(sums, 2);
    e.l1_vertex = sums[0];
    e.linf      = ranks->max(e.linf);
    for (const double l1 : e.l1_per_edge)
      e.l1_edges += l1;
    e.l1 = e.l1_edges + e.l1_vertex;
    e.l2 = std::sqrt(sums[1]);
    return e;
  }

  template <typename Law>
  double
  NetworkProblem<Law>::l1_distance(const NetworkProblem &other) const
  {
    const QGauss<1> quad(method.degree + 2);
    double          sum = 0;
    for (const unsigned int v : ranks->vertices())
      if (ranks->reports_vertex(v))
        sum += junctions[v].width() * std::abs(u.vertices[v] - other.u.vertices[v]);
    for (const unsigned int k : ranks->edges())
      {
        for (unsigned int c = 0; c < edge_cells[k]; ++c)
          for (unsigned int q = 0; q < quad.size(); ++q)
            sum += quad.weight(q) * edge_h[k] *
                   std::abs(lines->value(u.edges.data(), local(k), c, quad.point(q)[0]) -
                            other.lines->value(other.u.edges.data(), other.local(k), c,
                                               quad.point(q)[0]));
      }
    return ranks->sum(sum);
  }

  template <typename Law>
  std::vector<std::pair<double, double>>
  NetworkProblem<Law>::sample_edge(const unsigned int k, const unsigned int points_per_cell) const
  {
    std::vector<std::pair<double, double>> out;
    out.reserve(edge_cells[k] * points_per_cell);
    for (unsigned int c = 0; c < edge_cells[k]; ++c)
      for (unsigned int j = 0; j < points_per_cell; ++j)
        {
          const double xi = points_per_cell == 1 ? 0.5 : j / double(points_per_cell - 1);
          out.emplace_back(c * edge_h[k] + xi * edge_h[k],
                           lines->value(u.edges.data(), local(k), c, xi));
        }
    return out;
  }

  template <typename Law>
  std::vector<std::vector<std::pair<double, double>>>
  NetworkProblem<Law>::sample(const unsigned int points_per_cell) const
  {
    std::vector<std::vector<std::pair<double, double>>> out(net.edges.size());
    for (const unsigned int k : ranks->edges())
      out[k] = sample_edge(k, points_per_cell);
    return out;
  }

  template <typename Law>
  std::vector<std::vector<std::pair<double, double>>>
  NetworkProblem<Law>::gathered_sample(const unsigned int points_per_cell) const
  {
    auto out = sample(points_per_cell);
    if (!ranks->parallel())
      return out;
    // the pairs of every edge as x_0, u_0, x_1, u_1, ...
    std::vector<std::vector<double>> flat(out.size());
    for (const unsigned int k : ranks->edges())
      for (const auto &[x, value] : out[k])
        flat[k].insert(flat[k].end(), {x, value});
    gather_edge_values(flat);
    for (unsigned int k = 0; k < flat.size(); ++k)
      {
        out[k].resize(flat[k].size() / 2);
        for (std::size_t j = 0; j < out[k].size(); ++j)
          out[k][j] = {flat[k][2 * j], flat[k][2 * j + 1]};
      }
    return out;
  }

  template <typename Law>
  void
  NetworkProblem<Law>::gather_edge_values(std::vector<std::vector<double>> &values) const
  {
    if (!ranks->parallel())
      return;
    // this rank's edges as (k, n, its n values), as bytes (gather_bytes:
    // any size)
    std::vector<double> mine;
    for (const unsigned int k : ranks->edges())
      {
        mine.insert(mine.end(), {double(k), double(values[k].size())});
        mine.insert(mine.end(), values[k].begin(), values[k].end());
      }
    const std::string bytes(reinterpret_cast<const char *>(mine.data()),
                            mine.size() * sizeof(double));
    for (const auto &b : gather_bytes(ranks->communicator(), bytes))
      {
        std::vector<double> part(b.size() / sizeof(double));
        std::memcpy(part.data(), b.data(), b.size());
        for (std::size_t i = 0; i < part.size();)
          {
            const auto k = static_cast<unsigned int>(part[i]);
            const auto n = static_cast<std::size_t>(part[i + 1]);
            values[k].assign(part.begin() + i + 2, part.begin() + i + 2 + n);
            i += 2 + n;
          }
      }
  }

  template <typename Law>
  std::vector<std::string>
  NetworkProblem<Law>::timeseries_names() const
  {
    const bool               vertices = !junctions.empty();
    std::vector<std::string> header{"mass", "mass_balance_residual", "boundary_inflow"};
    if (vertices)
      header.emplace_back("vertex_value");
    header.emplace_back("total_variation");
    if (vertices)
      header.emplace_back("rh_residual");
    if (exact && vertices)
      header.emplace_back("vertex_exact");
    if (exact)
      header.emplace_back("l1_error");
    if (exact && vertices)
      header.emplace_back("l1_error_vertex");
    if (method.blending_max() > 0)
      header.emplace_back("blended_cells");
    return header;
  }

  template <typename Law>
  std::string
  NetworkProblem<Law>::timeseries_comment() const
  {
    const std::string blended =
      method.blending_max() > 0 ? "; blended_cells: cells of all edges with a blending factor > 0" : "";
    if (net.is_star())
      return "mass_balance_residual = |mass - mass(0) - boundary_inflow| / ||u(0)||_L1; "
             "rh_residual = sum_in F - sum_out F at the vertex" +
             blended;
    return "mass_balance_residual = |mass - mass(0) - boundary_inflow| / ||u(0)||_L1; "
           "vertex_value, vertex_exact: at " +
           (junctions.empty() ? std::string("no vertex") : net.vertices[0].label) +
           "; rh_residual = sum_in F - sum_out F at the vertex where it is largest" + blended;
  }

  template <typename Law>
  std::vector<double>
  NetworkProblem<Law>::timeseries_values(const double time)
  {
    const bool          vertices = !junctions.empty();
    std::vector<double> row{mass(), std::abs(balance_residual()), boundary_inflow()};
    if (vertices)
      row.push_back(vertex_values()[0]);
    row.push_back(total_variation());
    if (vertices)
      row.push_back(rh_residual());
    if (exact)
      {
        const auto e = errors(*exact, time);
        if (vertices)
          row.push_back(exact->vertex_value(0, time));
        row.push_back(e.l1);
        if (vertices)
          row.push_back(e.l1_vertex);
      }
    if (method.blending_max() > 0)
      {
        // cells of all edges whose last stage blended in finite volumes
        row.push_back(ranks->sum(double(lines->n_blended_cells())));
      }
    return row;
  }

  template <typename Law>
  template <typename Archive>
  void
  NetworkProblem<Law>::state_io(Archive &ar, std::vector<double> &vertices,
                                std::vector<std::vector<double>> &modes, double &total_inflow)
  {
    // the graph's files first: the parameters name a graph file, not its
    // content, so a file changed since the checkpoint is refused here like
    // a changed parameter (the content hash of each file, in the order read)
    std::vector<std::pair<std::string, std::uint64_t>> files;
    for (const GraphFile &f : net.files)
      files.emplace_back(f.parameter, f.content_hash);
    auto stored = files;
    ar.io(stored);
    for (unsigned int i = 0; i < files.size(); ++i)
      if (i >= stored.size() || stored[i] != files[i])
        throw InputError("cannot resume from the checkpoint: " + net.files[i].parameter + " '" +
                         net.files[i].name +
                         "' changed since the checkpoint was written (its content differs "
                         "from the run's; a resumed run needs the files it started with)");
    // then the graph's size
    std::uint64_t n_vertices = vertices.size(), n_edges = modes.size();
    ar.io(n_vertices);
    ar.io(n_edges);
    if (n_vertices != u.vertices.size() || n_edges != net.edges.size())
      throw RunError("the checkpoint's network has " + std::to_string(n_vertices) +
                     " vertices and " + std::to_string(n_edges) + " edges, this one " +
                     std::to_string(u.vertices.size()) + " and " +
                     std::to_string(net.edges.size()));
    ar.io(total_inflow);
    for (double &v : vertices)
      ar.io(v);
    for (unsigned int k = 0; k < modes.size(); ++k)
      {
        ar.io(modes[k]);
        if (modes[k].size() != edge_cells[k] * (method.degree + 1))
          throw RunError("the checkpoint's network has other edge sizes");
      }
    for (double *x : {&balance.mass0, &balance.scale, &balance.last, &balance.max_residual,
                      &balance.max_step, &tv0, &u00, &tv_max})
      ar.io(*x);
  }

  template <typename Law>
  void
  NetworkProblem<Law>::save(ByteWriter &w)
  {
    // every edge's modes in the order of the graph, on rank 0 (which writes
    // the checkpoint): the file does not depend on the number of ranks
    std::vector<std::vector<double>> modes(net.edges.size());
    for (const unsigned int k : ranks->edges())
      modes[k].assign(u.edges.begin() + lines->index(local(k), 0),
                      u.edges.begin() + lines->index(local(k), edge_cells[k]));
    gather_edge_values(modes);
    auto   vertices     = vertex_values();
    double total_inflow = boundary_inflow();
    if (ranks->rank() == 0)
      state_io(w, vertices, modes, total_inflow);
  }

  template <typename Law>
  void
  NetworkProblem<Law>::load(ByteReader &r)
  {
    // every rank reads the whole state and keeps its edges
    std::vector<double>              vertices(u.vertices.size());
    std::vector<std::vector<double>> modes(net.edges.size());
    double                           total_inflow = 0;
    state_io(r, vertices, modes, total_inflow);
    u.vertices = vertices;
    inflow     = ranks->rank() == 0 ? total_inflow : 0.;
    for (const unsigned int k : ranks->edges())
      std::copy(modes[k].begin(), modes[k].end(), u.edges.begin() + lines->index(local(k), 0));
  }

  template <typename Law>
  void
  NetworkProblem<Law>::finish(const double time, RunResult &result, const bool)
  {
    if (result.status != "completed")
      return;
    JsonObject &d = result.diagnostics;
    d.add("n_edges", static_cast<long long>(net.edges.size()));
    if (net.is_star())
      {
        d.add("n_vertex_ends", static_cast<long long>(junctions[0].ends().size()));
        d.add("vertex_width", junctions[0].width());
      }
    else
      {
        long long ends = 0;
        for (const auto &j : junctions)
          ends += j.ends().size();
        d.add("n_vertices", static_cast<long long>(junctions.size()));
        d.add("n_vertex_ends", ends);
      }
    d.add("integrator", n_stages() == 1 ? "forward_euler" : "ssprk3");
    d.add("cfl", method.cfl);
    d.add("mass_initial", balance.mass0);
    d.add("mass_final", mass());
    d.add("boundary_inflow", boundary_inflow());
    d.add("mass_balance_residual_max", balance.max_residual);
    d.add("mass_step_residual_max", balance.max_step);
    const auto vertices = vertex_values();
    if (!junctions.empty())
      {
        d.add("vertex_value_initial", u00);
        d.add("vertex_value_final", vertices[0]);
        d.add("rh_residual_final", rh_residual());
      }
    if (!net.is_star() && junctions.size() <= 100)
      d.add("vertex_values_final", vertices);
    d.add("total_variation_initial", tv0);
    d.add("total_variation_final", total_variation());
    d.add("total_variation_max", tv_max);
    d.add("cpu_time_loop_s", result.time_loop_cpu_s);
    d.add("dof_updates_per_cpu_s", result.dof_updates_per_cpu_s_per_rank);
    if (!exact)
      return;
    const auto e = errors(*exact, time);
    result.errors.push_back({{e.l1, e.l2, e.linf}});
    result.l2_error = e.l2;
    d.add("exact_solution", exact->name());
    if (!junctions.empty())
      d.add("vertex_exact_final", exact->vertex_value(0, time));
    d.add("l1_error", e.l1);
    d.add("l1_error_edges", e.l1_edges);
    d.add("l1_error_vertex", e.l1_vertex);
    d.add("linf_error", e.linf);
  }
} // namespace granular_dg::network
