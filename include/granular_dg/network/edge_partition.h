#pragma once

#include <deal.II/base/mpi.h>

#include <granular_dg/base/evolution.h>
#include <granular_dg/network/graph.h>

#include <optional>
#include <string>
#include <vector>

namespace granular_dg::network
{
  /**
   * The network's edges spread over the MPI ranks, and the communication the
   * vertex coupling needs.
   *
   * The edges are split by a graph partition of their adjacency (two edges
   * are adjacent when they meet at a vertex), weighted by their cells:
   * METIS through deal.II's SparsityTools::partition, computed on rank 0 and
   * broadcast. A vertex is updated by every rank that owns one of its edges;
   * a vertex whose edges lie on several ranks is "cut". Before a vertex
   * needs its traces, exchange() shares the traces of the cut vertices' ends
   * in one MPI_Allreduce over a buffer with one slot per such end (each slot
   * written by one rank, the others adding 0), so every rank sees the same
   * traces bit for bit and the solution does not depend on the number of
   * ranks. On one rank nothing is cut and nothing is communicated.
   */
  class EdgePartition
  {
  public:
    /// cells[k]: the cells of edge k (the partition's weights).
    EdgePartition(const Graph &graph, const std::vector<unsigned int> &cells, MPI_Comm comm);

    unsigned int rank() const { return my_rank; }
    unsigned int n_ranks() const { return ranks; }
    bool         parallel() const { return ranks > 1; }
    MPI_Comm     communicator() const { return comm; }

    bool owns_edge(unsigned int k) const { return edge_owner[k] == my_rank; }
    /// the rank of edge k
    unsigned int owner(unsigned int k) const { return edge_owner[k]; }
    /// the edges of this rank, in increasing order
    const std::vector<unsigned int> &edges() const { return own_edges; }
    /// the vertices with an end on an edge of this rank, in increasing order
    const std::vector<unsigned int> &vertices() const { return local; }
    /// The rank that reports vertex v (the owner of its first end's edge):
    /// its value enters sums over the network once.
    bool reports_vertex(unsigned int v) const { return vertex_reporter[v] == my_rank; }
    /// vertices whose edges lie on more than one rank
    unsigned int n_cut_vertices() const { return n_cut; }
    /// whether a cut vertex has no control volume (its value then follows
    /// the traces and needs them after the limiter, too)
    bool has_cut_vertex_without_volume() const { return cut_without_volume; }

    /// The slot of the i-th end of vertex v in the exchange buffer, or -1
    /// when the vertex is not cut.
    int slot(unsigned int v, unsigned int i) const { return end_slot[v][i]; }
    /// the ends of all cut vertices: the size of the exchange buffer
    unsigned int n_slots() const { return slots; }

    /// The ends of this rank's edges at cut vertices: (slot, edge, at x = L).
    struct SentEnd
    {
      unsigned int slot, edge;
      bool         at_end;
    };
    const std::vector<SentEnd> &sent_ends() const { return sent; }

    /// buffer (one entry per slot, this rank's written, the rest 0) summed
    /// over the ranks in place: one MPI_Allreduce (none on one rank).
    void exchange(std::vector<double> &buffer) const;

    /// In-place reductions over the ranks (no-ops on one rank).
    void sum(double *values, unsigned int n) const;
    void min(double *values, unsigned int n) const;
    void max(double *values, unsigned int n) const;
    double sum(double x) const { sum(&x, 1); return x; }
    double min(double x) const { min(&x, 1); return x; }
    double max(double x) const { max(&x, 1); return x; }

    /// Collective: when some rank has a failure, every rank throws the one
    /// of the lowest such rank (an Inadmissible, or a RunError with the
    /// message error); otherwise returns.
    void agree(const std::optional<Inadmissible> &failure,
               const std::optional<std::string> &error) const;

    /// "4 edges on 2 ranks: 2, 2 edges, 1 cut vertex" (for the log).
    std::string describe() const;

  private:
    MPI_Comm                          comm;
    unsigned int                      my_rank = 0, ranks = 1;
    std::vector<unsigned int>         edge_owner, own_edges, local, vertex_reporter;
    std::vector<std::vector<int>>     end_slot;
    std::vector<SentEnd>              sent;
    unsigned int                      n_cut = 0, slots = 0;
    bool                              cut_without_volume = false;
  };
} // namespace granular_dg::network
