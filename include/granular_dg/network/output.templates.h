#pragma once

/**
 * The network's output (solution-NNNN.vtu through deal.II's DataOutBase with
 * every edge drawn in the plane, in pieces (VtuPieces), under MPI one file
 * per rank and a .pvtu;
 * profile-NNNN-edge-K.csv), a single run on the TimeLoop, and the
 * convergence study: a scene includes this file once and instantiates
 * NetworkProblem<Law>::write_snapshot(), run_network() and
 * run_network_convergence() for its Law.
 */

#include <deal.II/base/data_out_base.h>
#include <deal.II/base/utilities.h>
#include <deal.II/grid/reference_cell.h>

#include <granular_dg/base/convergence_study.h>
#include <granular_dg/base/errors.h>
#include <granular_dg/base/output.h>
#include <granular_dg/base/time_loop.h>
#include <granular_dg/network/network.h>

#include <cmath>
#include <deque>
#include <fstream>
#include <future>
#include <memory>
#include <sstream>
#include <system_error>

namespace granular_dg::network
{
  namespace internal
  {
    inline std::string
    snapshot_name(const std::string &prefix, const unsigned int index, const std::string &suffix)
    {
      return prefix + Utilities::int_to_string(index, 4) + suffix;
    }

    /// A line patch in the plane through the given points with the values of
    /// u, f(u), the edge coordinate and the edge number at each (points of a
    /// DataOutBase patch: n_subdivisions + 1 of them, in order).
    inline DataOutBase::Patch<1, 2>
    line_patch(const std::vector<Point<2>> &points, const std::vector<std::array<double, 4>> &values)
    {
      DataOutBase::Patch<1, 2> patch;
      patch.vertices[0]          = points.front();
      patch.vertices[1]          = points.back();
      patch.n_subdivisions       = points.size() - 1;
      patch.points_are_available = true;
      patch.reference_cell       = ReferenceCells::get_hypercube<1>();
      patch.data.reinit(4 + 2, points.size());
      for (unsigned int j = 0; j < points.size(); ++j)
        {
          for (unsigned int i = 0; i < 4; ++i)
            patch.data(i, j) = values[j][i];
          patch.data(4, j) = points[j][0];
          patch.data(5, j) = points[j][1];
        }
      return patch;
    }

    /// the names of the VTU fields (u, its flux, the coordinate along the
    /// edge, the edge's number: 0 for a vertex)
    inline const std::vector<std::string> vtu_fields{"u", "flux", "x_edge", "edge"};

    inline DataOutBase::VtkFlags
    vtu_flags(const double time, const unsigned int index)
    {
      DataOutBase::VtkFlags flags(time, index);
      flags.print_date_and_time = false;
      flags.compression_level   = DataOutBase::VtkFlags::best_speed;
      return flags;
    }

    /// The pieces of a VTU file (between deal.II's write_vtu_header() and
    /// write_vtu_footer()) of total_points points in all: as few as hold at most
    /// about vtu_piece_points each, so that the writer's buffers (about 110
    /// bytes per point) stay bounded on large graphs, and of equal size (a
    /// piece ends with the edge that fills it). With writers > 1, that many
    /// pieces are compressed at once (write_vtu_main() each into a text of
    /// its own) while the caller samples the next, and written in order:
    /// the same file as one writer's.
    class VtuPieces
    {
    public:
      VtuPieces(std::ostream &out, const DataOutBase::VtkFlags &flags,
                const std::size_t total_points, const unsigned int writers)
        : out(out)
        , first_flags(flags)
        // (the time and cycle as field data of the first piece only)
        , later_flags(vtu_flags(std::numeric_limits<double>::min(),
                                std::numeric_limits<unsigned int>::min()))
        , writers(writers)
        , piece_points(equal_pieces(total_points))
      {}

      /// patch into the current piece, which is written once it is full
      void
      add(DataOutBase::Patch<1, 2> &&patch)
      {
        patch.patch_index = patches.size();
        n_points += patch.data.n_cols();
        patches.push_back(std::move(patch));
        if (n_points >= piece_points)
          write_piece();
      }

      /// the last piece (an empty one if there was none), and every piece
      /// still being compressed
      void
      finish()
      {
        if (!patches.empty() || n_pieces == 0)
          write_piece();
        while (!compressing.empty())
          write_oldest();
      }

    private:
      /// the points of each of the fewest pieces of total_points points with
      /// at most vtu_piece_points each (at least 1)
      static std::size_t
      equal_pieces(const std::size_t total_points)
      {
        const std::size_t pieces = (total_points + vtu_piece_points - 1) / vtu_piece_points;
        return pieces <= 1 ? std::max<std::size_t>(1, total_points) :
                             (total_points + pieces - 1) / pieces;
      }

      void
      write_piece()
      {
        const DataOutBase::VtkFlags &flags = n_pieces == 0 ? first_flags : later_flags;
        if (writers == 1)
          DataOutBase::write_vtu_main(patches, vtu_fields, {}, flags, out);
        else
          {
            if (compressing.size() == writers)
              write_oldest();
            const auto piece = std::make_shared<const Patches>(std::move(patches));
            try
              {
                compressing.push_back(std::async(std::launch::async, [piece, flags]() {
                  std::ostringstream text;
                  DataOutBase::write_vtu_main(*piece, vtu_fields, {}, flags, text);
                  return text.str();
                }));
              }
            catch (const std::system_error &)
              {
                // (no thread to be had) the pieces before it, then this one
                while (!compressing.empty())
                  write_oldest();
                DataOutBase::write_vtu_main(*piece, vtu_fields, {}, flags, out);
              }
          }
        patches.clear();
        n_points = 0;
        ++n_pieces;
      }

      void
      write_oldest()
      {
        out << compressing.front().get();
        compressing.pop_front();
      }

      using Patches = std::vector<DataOutBase::Patch<1, 2>>;
      std::ostream                         &out;
      const DataOutBase::VtkFlags           first_flags, later_flags;
      const unsigned int                    writers;
      const std::size_t                     piece_points;
      Patches                               patches;
      std::size_t                           n_points = 0, n_pieces = 0;
      std::deque<std::future<std::string>>  compressing;
    };
  } // namespace internal

  template <typename Law>
  void
  NetworkProblem<Law>::write_vtu(const std::string &directory, const std::string &name,
                                 const unsigned int index, const double time,
                                 const std::vector<double> &vertices) const
  {
    // one patch per edge through all its sample points (the points of a
    // face appear twice, once with each cell's trace: the patch has a line
    // of length 0 there), then one of 2 points per vertex, in pieces
    // (VtuPieces)
    const GraphDrawing embed(net);
    const auto         flags    = internal::vtu_flags(time, index);
    std::size_t        n_points = 0;
    for (const unsigned int k : ranks->edges())
      n_points += std::size_t(edge_cells[k]) * vtu_points();
    for (unsigned int v = 0; v < net.vertices.size(); ++v)
      n_points += ranks->reports_vertex(v) ? 2 : 0;
    write_to_file(directory + "/" + name, [&](std::ostream &out) {
      DataOutBase::write_vtu_header(out, flags);
      internal::VtuPieces                pieces(out, flags, n_points, options.vtu_writers);
      std::vector<Point<2>>              points;
      std::vector<std::array<double, 4>> values;
      for (unsigned int k = 0; k < net.edges.size(); ++k)
        if (ranks->owns_edge(k))
          {
            points.clear();
            values.clear();
            for (const auto &[x, value] : sample_edge(k, vtu_points()))
              {
                const auto p = embed(k, x);
                points.emplace_back(p[0], p[1]);
                values.push_back({{value, laws[k].value(value), x, double(k + 1)}});
              }
            pieces.add(internal::line_patch(points, values));
          }
      // every vertex this rank reports: a patch of length 0 with its value
      // (edge number 0)
      for (unsigned int v = 0; v < net.vertices.size(); ++v)
        if (ranks->reports_vertex(v))
          {
            const Point<2> &p = embed.vertex(v);
            pieces.add(internal::line_patch(
              {p, p}, {{{vertices[v], 0., 0., 0.}}, {{vertices[v], 0., 0., 0.}}}));
          }
      // (a rank without edges or vertices writes one empty piece)
      pieces.finish();
      DataOutBase::write_vtu_footer(out);
    });
  }

  template <typename Law>
  void
  NetworkProblem<Law>::write_profiles(const std::string &directory, const unsigned int index,
                                      const double time, const Samples &profile,
                                      const std::vector<double> &vertices) const
  {
    if (options.profiles == Profiles::one_file)
      {
        std::vector<std::string> header{"edge", "x", "u", "flux"};
        if (exact)
          header.push_back("exact");
        CsvWriter csv;
        csv.open(directory + "/" + internal::snapshot_name("profile-", index, ".csv"), header,
                 "time = " + format_number(time) + "\n# edge: the edge's place in the graph "
                 "(1, 2, ...), x its coordinate");
        for (unsigned int k = 0; k < net.edges.size(); ++k)
          for (const auto &[x, value] : profile[k])
            {
              std::vector<double> row{double(k + 1), x, value, laws[k].value(value)};
              if (exact)
                row.push_back(exact->value(k, x, time));
              csv.row(row);
            }
        return;
      }
    for (unsigned int k = 0; k < net.edges.size(); ++k)
      {
        const Edge              &e = net.edges[k];
        std::vector<std::string> header{"x", "u", "flux"};
        if (exact)
          header.push_back("exact");
        std::ostringstream comment;
        comment << "time = " << format_number(time) << "\n# " << e.label << ": "
                << net.describe(k) << ", length " << format_number(e.length) << ", "
                << laws[k].describe();
        if (net.is_star())
          comment << "; vertex value " << format_number(vertices[0]);
        for (const unsigned int v : {e.from, e.to})
          if (!net.is_star() && v != free_end)
            comment << "; " << net.vertices[v].label << " value " << format_number(vertices[v]);
        CsvWriter csv;
        csv.open(directory + "/" +
                   internal::snapshot_name("profile-", index, "-edge-" + std::to_string(k + 1) + ".csv"),
                 header, comment.str());
        for (const auto &[x, value] : profile[k])
          {
            std::vector<double> row{x, value, laws[k].value(value)};
            if (exact)
              row.push_back(exact->value(k, x, time));
            csv.row(row);
          }
      }
  }

  template <typename Law>
  SnapshotFiles
  NetworkProblem<Law>::write_snapshot(const std::string &directory, const unsigned int index,
                                      const double time)
  {
    // the profiles gathered on rank 0, which writes them; the VTU in one
    // file on one rank, else in one piece per rank and a .pvtu record by
    // rank 0
    const auto vertices = vertex_values();
    const bool vtu = options.write_vtu, profiles = options.profiles != Profiles::none;
    const bool one_file = vtu && !ranks->parallel();
    if (profiles)
      {
        const Samples profile = gathered_sample(profile_points());
        if (ranks->rank() == 0)
          write_profiles(directory, index, time, profile, vertices);
      }
    SnapshotFiles files;
    if (profiles)
      files.main_file = internal::snapshot_name("profile-", index,
                                                options.profiles == Profiles::one_file ?
                                                  ".csv" :
                                                  "-edge-*.csv");
    if (!vtu)
      return files;
    const std::string base = internal::snapshot_name("solution-", index, "");
    if (one_file)
      {
        write_vtu(directory, base + ".vtu", index, time, vertices);
        files.pvd_entry = files.main_file = base + ".vtu";
        return files;
      }
    const auto piece = [&](const unsigned int r) {
      return base + "." + Utilities::int_to_string(r, 4) + ".vtu";
    };
    write_vtu(directory, piece(ranks->rank()), index, time, vertices);
    if (ranks->rank() == 0)
      {
        std::vector<std::string> pieces;
        for (unsigned int r = 0; r < ranks->n_ranks(); ++r)
          {
            pieces.push_back(piece(r));
            record_output_file(directory, pieces.back());
          }
        std::ostringstream record;
        DataOutBase::write_pvtu_record(record, pieces, internal::vtu_fields, {},
                                       internal::vtu_flags(time, index));
        write_pvtu(directory + "/" + base + ".pvtu", record.str());
      }
    files.pvd_entry = files.main_file = base + ".pvtu";
    return files;
  }

  template <typename Law>
  RunResult
  run_network(const Graph &graph, std::vector<Law> laws, const std::vector<EdgeData> &data,
              const dg::DiscretizationParameters &method, const NetworkOptions &options,
              const ExactSolution *exact, const RunParameters &params, const bool write_files,
              const std::string &scene)
  {
    NetworkProblem<Law> p(graph, std::move(laws), method, options, data, exact, scene);
    TimeLoop       loop(p, params, write_files);
    return loop.run();
  }

  namespace internal
  {
    /// "level" of a number of cells per unit length (log2 when a power of 2)
    inline double
    level_of(const double cells)
    {
      const double l = std::log2(cells);
      return std::abs(l - std::round(l)) < 1e-12 ? std::round(l) : l;
    }
  } // namespace internal

  template <typename Law>
  void
  run_network_convergence(const Graph &graph, const std::vector<Law> &laws,
                          const std::vector<EdgeData> &data,
                          const dg::DiscretizationParameters &method,
                          const NetworkOptions &options, const ExactSolution &exact,
                          const RunParameters &params)
  {
    StudyColumns columns;
    columns.values = {"level", "cells_per_unit_length", "dx", "dofs", "cfl", "time_steps",
                      "l1_error", "l1_error_edges", "l1_error_vertex", "l2_error", "linf_error",
                      "mass_balance_residual_max", "mass_step_residual_max", "cpu_time_s",
                      "wall_time_s"};
    for (unsigned int k = 0; k < graph.edges.size(); ++k)
      columns.values.push_back("l1_error_edge_" + std::to_string(k + 1));
    columns.rated         = {{"l1_error", "eoc"}};
    columns.table_comment = "L1 error over all edges and the vertex cell at t = " +
                            format_number(params.final_time) + " against " + exact.name() +
                            "; eoc = log2(e(l-1)/e(l)) per level";
    columns.rates_comment = "L1 error rate of the two finest meshes";
    columns.printed       = {"degree", "cfl", "level", "dofs", "time_steps", "l1_error", "eoc",
                             "l1_error_vertex", "cpu_time_s"};
    const auto one_run = [&](const unsigned int i, const unsigned int cells) {
      const auto     m        = method.for_study(params, i);
      NetworkOptions o        = options;
      o.cells_per_unit_length = cells;
      NetworkProblem<Law> p(graph, laws, m, o, data, &exact);
      const RunResult     r = TimeLoop(p, params, false).run();
      const auto          e = p.errors(exact, r.final_time);
      std::vector<double> row{internal::level_of(cells), double(cells), p.min_cell_size(),
                              double(p.n_dofs()), m.cfl, double(r.n_steps), e.l1, e.l1_edges,
                              e.l1_vertex, e.l2, e.linf, p.mass_balance().max_residual,
                              p.mass_balance().max_step, r.time_loop_cpu_s, r.wall_time_s};
      row.insert(row.end(), e.l1_per_edge.begin(), e.l1_per_edge.end());
      return StudyRow{p.min_cell_size(), row};
    };
    JsonObject summary;
    summary.add("scene", "network");
    summary.add("mode", "convergence study");
    summary.add("dim", 1ll);
    summary.add("exact_solution", exact.name());
    summary.add("cells_per_unit_length",
                std::vector<double>(params.convergence_cells.begin(),
                                    params.convergence_cells.end()));
    run_convergence_study(columns, params, one_run, summary);
  }
} // namespace granular_dg::network
