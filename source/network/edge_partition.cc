#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>

#include <granular_dg/base/errors.h>
#include <granular_dg/network/edge_partition.h>

#include <algorithm>
#include <numeric>

namespace granular_dg::network
{
  namespace
  {
    /// Contiguous runs of edges with about equal cells (when METIS leaves a
    /// rank without edges, which it may do on tiny graphs).
    std::vector<unsigned int>
    contiguous_split(const std::vector<unsigned int> &cells, const unsigned int ranks)
    {
      const double total = std::accumulate(cells.begin(), cells.end(), 0.);
      std::vector<unsigned int> owner(cells.size());
      double                    before = 0;
      for (unsigned int k = 0; k < cells.size(); ++k)
        {
          // the rank of the edge's middle cell, but never fewer edges left
          // than ranks still to fill
          const unsigned int by_cells = static_cast<unsigned int>((before + 0.5 * cells[k]) / total * ranks);
          const unsigned int by_count = ranks - std::min<unsigned int>(ranks, cells.size() - k);
          owner[k] = std::min(ranks - 1, std::max(by_cells, by_count));
          if (k > 0)
            owner[k] = std::max(owner[k], owner[k - 1]);
          owner[k] = std::min(owner[k], k > 0 ? owner[k - 1] + 1 : 0u);
          before += cells[k];
        }
      return owner;
    }

    /// METIS on the edges' adjacency, weighted by cells.
    std::vector<unsigned int>
    metis_split(const Graph &graph, const std::vector<unsigned int> &cells,
                const unsigned int ranks)
    {
      const unsigned int     n = graph.edges.size();
      DynamicSparsityPattern dsp(n, n);
      for (const auto &ends : graph.all_vertex_ends())
        for (const auto &a : ends)
          for (const auto &b : ends)
            if (a.edge != b.edge)
              dsp.add(a.edge, b.edge);
      SparsityPattern sparsity;
      sparsity.copy_from(dsp);
      std::vector<unsigned int> owner(n, 0);
      SparsityTools::partition(sparsity, cells, ranks, owner, SparsityTools::Partitioner::metis);
      std::vector<unsigned int> count(ranks, 0);
      for (const unsigned int r : owner)
        ++count[r];
      if (std::find(count.begin(), count.end(), 0u) != count.end())
        return contiguous_split(cells, ranks);
      return owner;
    }
  } // namespace

  EdgePartition::EdgePartition(const Graph &graph, const std::vector<unsigned int> &cells,
                               const MPI_Comm comm)
    : comm(comm)
    // (unit tests may run without MPI_Init: one rank)
    , my_rank(Utilities::MPI::job_supports_mpi() ? Utilities::MPI::this_mpi_process(comm) : 0)
    , ranks(Utilities::MPI::job_supports_mpi() ? Utilities::MPI::n_mpi_processes(comm) : 1)
    , edge_owner(graph.edges.size(), 0)
  {
    if (ranks > graph.edges.size())
      throw InputError("the network has " + std::to_string(graph.edges.size()) +
                       " edges and cannot be spread over " + std::to_string(ranks) +
                       " MPI ranks: run it on at most " + std::to_string(graph.edges.size()) +
                       " ranks");
    if (ranks > 1)
      {
        if (my_rank == 0)
          edge_owner = metis_split(graph, cells, ranks);
        edge_owner = Utilities::MPI::broadcast(comm, edge_owner, 0);
      }
    for (unsigned int k = 0; k < graph.edges.size(); ++k)
      if (edge_owner[k] == my_rank)
        own_edges.push_back(k);

    const auto ends = graph.all_vertex_ends();
    vertex_reporter.resize(ends.size());
    end_slot.resize(ends.size());
    for (unsigned int v = 0; v < ends.size(); ++v)
      {
        vertex_reporter[v] = edge_owner[ends[v].front().edge];
        bool mine = false, cut = false;
        for (const auto &end : ends[v])
          {
            mine |= edge_owner[end.edge] == my_rank;
            cut |= edge_owner[end.edge] != vertex_reporter[v];
          }
        if (mine)
          local.push_back(v);
        end_slot[v].assign(ends[v].size(), -1);
        if (!cut)
          continue;
        ++n_cut;
        cut_without_volume |= graph.vertices[v].width_factor == 0;
        for (unsigned int i = 0; i < ends[v].size(); ++i)
          {
            end_slot[v][i] = slots;
            if (edge_owner[ends[v][i].edge] == my_rank)
              sent.push_back({slots, ends[v][i].edge, ends[v][i].incoming});
            ++slots;
          }
      }
  }

  void
  EdgePartition::exchange(std::vector<double> &buffer) const
  {
    if (ranks > 1 && !buffer.empty())
      MPI_Allreduce(MPI_IN_PLACE, buffer.data(), buffer.size(), MPI_DOUBLE, MPI_SUM, comm);
  }

  void
  EdgePartition::sum(double *values, const unsigned int n) const
  {
    if (ranks > 1)
      MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_SUM, comm);
  }

  void
  EdgePartition::min(double *values, const unsigned int n) const
  {
    if (ranks > 1)
      MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_MIN, comm);
  }

  void
  EdgePartition::max(double *values, const unsigned int n) const
  {
    if (ranks > 1)
      MPI_Allreduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_MAX, comm);
  }

  void
  EdgePartition::agree(const std::optional<Inadmissible> &failure,
                       const std::optional<std::string> &error) const
  {
    if (ranks == 1)
      {
        if (error)
          throw RunError(*error);
        if (failure)
          throw *failure;
        return;
      }
    const bool         failed = failure || error;
    const unsigned int first  = Utilities::MPI::min(failed ? my_rank : ranks, comm);
    if (first == ranks)
      return;
    // the failing rank's report, field by field
    const bool run_error = Utilities::MPI::broadcast(comm, bool(error), first);
    if (run_error)
      throw RunError(Utilities::MPI::broadcast(comm, error.value_or(""), first));
    Inadmissible f = failure.value_or(Inadmissible{});
    f.time         = Utilities::MPI::broadcast(comm, f.time, first);
    f.initial      = Utilities::MPI::broadcast(comm, f.initial, first);
    f.where        = Utilities::MPI::broadcast(comm, f.where, first);
    f.names        = Utilities::MPI::broadcast(comm, f.names, first);
    f.state        = Utilities::MPI::broadcast(comm, f.state, first);
    f.reason       = Utilities::MPI::broadcast(comm, f.reason, first);
    throw f;
  }

  std::string
  EdgePartition::describe() const
  {
    std::vector<unsigned int> count(ranks, 0);
    for (const unsigned int r : edge_owner)
      ++count[r];
    std::string s = std::to_string(edge_owner.size()) + " edges on " + std::to_string(ranks) +
                    " MPI ranks (";
    for (unsigned int r = 0; r < ranks; ++r)
      s += (r ? ", " : "") + std::to_string(count[r]);
    return s + " edges), " + std::to_string(n_cut) + " cut vertices";
  }
} // namespace granular_dg::network
