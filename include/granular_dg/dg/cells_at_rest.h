#pragma once

#include <deal.II/base/array_view.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/partitioner.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/matrix_free/matrix_free.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <tuple>
#include <vector>

namespace granular_dg::dg
{
  /**
   * The cell and face batches of the MatrixFree engine that a time step
   * computes when cells at rest are left out (Time stepping/skip cells at
   * rest; doc/engine.md, "Cells at rest").
   *
   * A cell is at rest when every Legendre coefficient of component i has
   * |u| <= tolerance * scale_i, scale_i the largest |coefficient| of
   * component i in the whole domain now (tolerance 0: the coefficients are
   * exactly zero, the physics' rest state). A cell that is not at rest is
   * loud, and so is every cell with a face on a boundary that has data (the
   * data may switch on at any time). A step computes the loud cells and every
   * cell within `reach` face neighbours of one (the step's stages times the
   * reach of one stage), so that no change arrives unseen; the others keep
   * their values in every stage (rate zero). A cell batch is computed when
   * one of its lanes is, a face batch when a cell on either side of one of
   * its lanes is. The wave-speed scan takes the rest state's speed for a
   * batch whose lanes are all at rest, and the admissibility scan leaves out
   * the batches the step leaves out.
   *
   * The neighbours come from the triangulation (periodic ones included), so
   * that a face that MatrixFree stores on the other rank still counts; under
   * MPI the flags of ghost cells are exchanged once per layer of the reach.
   * The decisions depend only on the cells' flags, so any number of ranks
   * computes the same cells.
   */
  template <int dim, typename VA>
  class CellsAtRest
  {
  public:
    using VectorType = dealii::LinearAlgebra::distributed::Vector<double>;

    CellsAtRest(const double tolerance, const unsigned int reach)
      : tolerance(tolerance)
      , reach(reach)
    {}

    /// The tables for data's cells and faces; `data_boundary(id)` says
    /// whether boundary id has data (its cells are always loud).
    template <typename DataBoundary>
    void
    reinit(const dealii::MatrixFree<dim, double, VA> &data,
           const dealii::DoFHandler<dim> &dof_handler, const DataBoundary &data_boundary);

    /// Find the cells at rest in u and the batches the next step computes.
    void
    find(const VectorType &u);

    /// whether the step computes cell batch b
    bool
    cell_batch(const unsigned int b) const
    {
      return computed_cell_batch[b];
    }

    /// whether every lane of cell batch b is at rest
    bool
    cell_batch_at_rest(const unsigned int b) const
    {
      return rest_cell_batch[b];
    }

    /// The runs [begin, end) of locally owned vector entries of the cells
    /// the step computes, and of those it leaves out.
    const std::vector<std::pair<unsigned int, unsigned int>> &
    computed_entries() const
    {
      return computed_runs;
    }
    const std::vector<std::pair<unsigned int, unsigned int>> &
    left_out_entries() const
    {
      return left_out_runs;
    }

    /// whether the step computes (inner or boundary) face batch f
    bool
    face_batch(const unsigned int f) const
    {
      return computed_face_batch[f];
    }

    /// owned cell updates left out so far, and all owned cell updates (a
    /// step counts once)
    std::pair<double, double>
    updates() const
    {
      return {skipped_updates, all_updates};
    }

    void
    set_updates(const std::pair<double, double> &counts)
    {
      std::tie(skipped_updates, all_updates) = counts;
    }

    /// Count a computed step (its batches as found last).
    void
    count_step()
    {
      skipped_updates += skipped_now;
      all_updates += n_owned;
    }

    std::size_t
    memory_consumption() const
    {
      const auto n = [](const auto &v) { return v.capacity() * sizeof(v[0]); };
      return n(neighbours) + n(neighbour_start) + n(dof_start) + n(component_of_dof) +
             n(always_loud) + n(cell_lanes) + n(face_lanes) + n(computed_cell_batch) +
             n(rest_cell_batch) + n(computed_face_batch) + n(cell_max) + n(computed_cell) +
             n(computed_runs) + n(left_out_runs) + flags.memory_consumption() +
             next.memory_consumption();
    }

  private:
    /// one layer of the reach: next = flags or a neighbour's flag
    void
    grow();

    double       tolerance;
    unsigned int reach;
    unsigned int n_owned = 0;
    MPI_Comm     comm    = MPI_COMM_SELF;
    bool         parallel = false;
    /// owned cell -> its face neighbours (owned or ghost), CSR
    std::vector<unsigned int> neighbour_start, neighbours;
    /// owned cell -> its first entry in the solution vector
    std::vector<unsigned int> dof_start;
    std::vector<unsigned int> component_of_dof;
    unsigned int              n_components = 0;
    std::vector<char>         always_loud;
    /// cell batch b, lane v -> owned cell (b * width + v; unused lanes: -1)
    std::vector<int> cell_lanes;
    /// face batch f, lane v -> the cells on its two sides (2 (f width + v)
    /// and the next; -1 where there is none)
    std::vector<int> face_lanes;
    std::vector<char> computed_cell_batch, rest_cell_batch, computed_face_batch;
    /// per owned and ghost cell: 1 when loud (within reach, after grow())
    VectorType flags, next;
    std::vector<char> at_rest;
    std::vector<double> cell_max;
    /// per owned cell in vector order (its entries [c n, (c + 1) n))
    std::vector<char> computed_cell;
    std::vector<std::pair<unsigned int, unsigned int>> computed_runs, left_out_runs;
    double            skipped_now = 0, skipped_updates = 0, all_updates = 0;
  };

  template <int dim, typename VA>
  template <typename DataBoundary>
  void
  CellsAtRest<dim, VA>::reinit(const dealii::MatrixFree<dim, double, VA> &data,
                               const dealii::DoFHandler<dim>             &dof_handler,
                               const DataBoundary                        &data_boundary)
  {
    using namespace dealii;
    const auto &tria         = dof_handler.get_triangulation();
    const auto *parallel_tria = dynamic_cast<const parallel::TriangulationBase<dim> *>(&tria);
    std::shared_ptr<const Utilities::MPI::Partitioner> partitioner;
    if (parallel_tria != nullptr)
      {
        partitioner = parallel_tria->global_active_cell_index_partitioner().lock();
        comm        = parallel_tria->get_communicator();
        parallel    = Utilities::MPI::n_mpi_processes(comm) > 1;
      }
    else
      partitioner = std::make_shared<Utilities::MPI::Partitioner>(tria.n_active_cells());
    const auto local = [&](const auto &cell) -> unsigned int {
      return parallel_tria != nullptr ?
               partitioner->global_to_local(cell->global_active_cell_index()) :
               cell->active_cell_index();
    };
    flags.reinit(partitioner);
    next.reinit(partitioner);
    n_owned = partitioner->locally_owned_size();

    const auto &fe = dof_handler.get_fe();
    n_components   = fe.n_components();
    component_of_dof.resize(fe.n_dofs_per_cell());
    for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
      component_of_dof[i] = fe.system_to_component_index(i).first;

    VectorType probe;
    data.initialize_dof_vector(probe);
    const auto &dofs = *probe.get_partitioner();
    dof_start.assign(n_owned, 0);
    always_loud.assign(n_owned, 0);
    std::vector<std::vector<unsigned int>> adjacent(n_owned);
    std::vector<types::global_dof_index>   indices(fe.n_dofs_per_cell());
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const unsigned int c = local(cell);
          cell->get_dof_indices(indices);
          dof_start[c] = dofs.global_to_local(*std::min_element(indices.begin(), indices.end()));
          for (const unsigned int f : cell->face_indices())
            if (cell->at_boundary(f) && !cell->has_periodic_neighbor(f))
              always_loud[c] |= data_boundary(cell->face(f)->boundary_id()) ? 1 : 0;
            else
              {
                const auto neighbour = cell->neighbor_or_periodic_neighbor(f);
                AssertThrow(neighbour->is_active(),
                            ExcMessage("skipping cells at rest needs a mesh without hanging nodes"));
                adjacent[c].push_back(local(neighbour));
              }
        }
    neighbour_start.assign(1, 0);
    neighbours.clear();
    for (const auto &a : adjacent)
      {
        neighbours.insert(neighbours.end(), a.begin(), a.end());
        neighbour_start.push_back(neighbours.size());
      }

    constexpr unsigned int width = VA::size();
    cell_lanes.assign(data.n_cell_batches() * width, -1);
    for (unsigned int b = 0; b < data.n_cell_batches(); ++b)
      for (unsigned int v = 0; v < data.n_active_entries_per_cell_batch(b); ++v)
        cell_lanes[b * width + v] = local(data.get_cell_iterator(b, v));
    const unsigned int n_faces = data.n_inner_face_batches() + data.n_boundary_face_batches();
    face_lanes.assign(2 * n_faces * width, -1);
    for (unsigned int f = 0; f < n_faces; ++f)
      for (unsigned int v = 0; v < data.n_active_entries_per_face_batch(f); ++v)
        {
          face_lanes[2 * (f * width + v)] = local(data.get_face_iterator(f, v, true).first);
          if (f < data.n_inner_face_batches())
            face_lanes[2 * (f * width + v) + 1] = local(data.get_face_iterator(f, v, false).first);
        }
    computed_cell_batch.assign(data.n_cell_batches(), 1);
    rest_cell_batch.assign(data.n_cell_batches(), 0);
    computed_face_batch.assign(n_faces, 1);
    at_rest.assign(n_owned, 0);
    // the owned entries are the cells' blocks of n_dofs_per_cell, one per cell
    AssertThrow(probe.locally_owned_size() == std::size_t(n_owned) * fe.n_dofs_per_cell(),
                ExcInternalError());
    for (unsigned int c = 0; c < n_owned; ++c)
      AssertThrow(dof_start[c] % fe.n_dofs_per_cell() == 0, ExcInternalError());
    computed_cell.assign(n_owned, 1);
  }

  template <int dim, typename VA>
  void
  CellsAtRest<dim, VA>::find(const VectorType &u)
  {
    using namespace dealii;
    const unsigned int n_dofs = component_of_dof.size();
    // the largest |coefficient| of each component in each cell, and the
    // scale of each component: its largest |coefficient| now
    cell_max.assign(std::size_t(n_owned) * n_components, 0.);
    std::vector<double> scale(n_components, 0.);
    for (unsigned int c = 0; c < n_owned; ++c)
      {
        const double *x = u.begin() + dof_start[c];
        double       *m = cell_max.data() + std::size_t(c) * n_components;
        for (unsigned int i = 0; i < n_dofs; ++i)
          m[component_of_dof[i]] = std::max(m[component_of_dof[i]], std::abs(x[i]));
        for (unsigned int i = 0; i < n_components; ++i)
          scale[i] = std::max(scale[i], m[i]);
      }
    if (parallel)
      {
        const std::vector<double> local_scale = scale;
        Utilities::MPI::max(make_array_view(local_scale), comm, make_array_view(scale));
      }
    for (double &s : scale)
      s *= tolerance;
    for (unsigned int c = 0; c < n_owned; ++c)
      {
        const double *m    = cell_max.data() + std::size_t(c) * n_components;
        bool          rest = !always_loud[c];
        for (unsigned int i = 0; i < n_components; ++i)
          rest = rest && m[i] <= scale[i];
        at_rest[c]             = rest;
        flags.local_element(c) = rest ? 0. : 1.;
      }
    for (unsigned int layer = 0; layer < reach; ++layer)
      grow();
    if (parallel)
      flags.update_ghost_values();

    constexpr unsigned int width = VA::size();
    const auto             loud  = [&](const int c) { return c >= 0 && flags.local_element(c) > 0; };
    skipped_now                  = 0;
    for (unsigned int b = 0; b < computed_cell_batch.size(); ++b)
      {
        bool computed = false, rest = true;
        unsigned int lanes = 0;
        for (unsigned int v = 0; v < width; ++v)
          if (const int c = cell_lanes[b * width + v]; c >= 0)
            {
              computed = computed || loud(c);
              rest     = rest && at_rest[c];
              ++lanes;
            }
        computed_cell_batch[b] = computed;
        rest_cell_batch[b]     = rest;
        if (!computed)
          skipped_now += lanes;
      }
    for (unsigned int f = 0; f < computed_face_batch.size(); ++f)
      {
        bool computed = false;
        for (unsigned int k = 0; k < 2 * width && !computed; ++k)
          computed = loud(face_lanes[2 * f * width + k]);
        computed_face_batch[f] = computed;
      }
    // the vector entries of the cells of computed batches, as runs
    std::fill(computed_cell.begin(), computed_cell.end(), 0);
    for (unsigned int b = 0; b < computed_cell_batch.size(); ++b)
      if (computed_cell_batch[b])
        for (unsigned int v = 0; v < width; ++v)
          if (const int c = cell_lanes[b * width + v]; c >= 0)
            computed_cell[dof_start[c] / n_dofs] = 1;
    computed_runs.clear();
    left_out_runs.clear();
    for (unsigned int k = 0; k < computed_cell.size();)
      {
        unsigned int end = k;
        while (end < computed_cell.size() && computed_cell[end] == computed_cell[k])
          ++end;
        (computed_cell[k] ? computed_runs : left_out_runs).emplace_back(k * n_dofs, end * n_dofs);
        k = end;
      }
  }

  template <int dim, typename VA>
  void
  CellsAtRest<dim, VA>::grow()
  {
    if (parallel)
      flags.update_ghost_values();
    for (unsigned int c = 0; c < n_owned; ++c)
      {
        double f = flags.local_element(c);
        for (unsigned int k = neighbour_start[c]; k < neighbour_start[c + 1] && f == 0.; ++k)
          f = flags.local_element(neighbours[k]);
        next.local_element(c) = f;
      }
    for (unsigned int c = 0; c < n_owned; ++c)
      flags.local_element(c) = next.local_element(c);
  }
} // namespace granular_dg::dg
