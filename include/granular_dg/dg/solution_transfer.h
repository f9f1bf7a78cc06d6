#pragma once

#include <deal.II/distributed/tria_base.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/grid/cell_id.h>

#include <granular_dg/base/checkpoint.h>
#include <granular_dg/base/errors.h>
#include <granular_dg/dg/operator.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
#include <utility>
#include <vector>

/**
 * The solution of a checkpoint, cell by cell (doc/program.md,
 * "Checkpoints"). The cells are stored in p4est's forest order (trees in
 * p4est's order, cells in Morton order within a tree), which does not depend
 * on the partition: p4est gives every rank a contiguous run of that order,
 * rank r's after rank r - 1's, so each rank writes and reads its own cells
 * as one piece of a shared block, at an offset that an exclusive scan of the
 * cell counts gives. A record is the cell's CellId and its values; reading
 * checks the CellId. A mesh that is not spread over ranks (the 1D scenes)
 * has every cell on every rank: rank 0 writes them, every rank reads them.
 */
namespace granular_dg::dg
{
  namespace internal
  {
    /// A cell's place in the forest order: (tree, Morton index of its
    /// child indices, padded to 30 levels). The coarse cell id of a CellId
    /// is the p4est tree's index on a p4est mesh (deal.II's
    /// coarse_cell_index_to_coarse_cell_id()) and the coarse cell's index on
    /// others.
    using ForestKey = std::pair<std::uint64_t, std::uint64_t>;

    template <int dim>
    ForestKey
    forest_key(const CellId &id)
    {
      static_assert(dim <= 2, "the Morton index holds 30 levels of 2D children");
      constexpr unsigned int max_levels = 30;
      const auto             children   = id.get_child_indices();
      if (children.size() > max_levels)
        throw RunError("checkpoint: cell " + id.to_string() + " is refined beyond 30 levels");
      std::uint64_t morton = 0;
      for (unsigned int i = 0; i < children.size(); ++i)
        morton |= std::uint64_t(children[i]) << (dim * (max_levels - 1 - i));
      return {id.get_coarse_cell_id(), morton};
    }

    /// Whether the mesh is spread over MPI ranks (each cell owned by one).
    template <int dim>
    bool
    is_distributed(const Triangulation<dim> &tria)
    {
      return dynamic_cast<const parallel::TriangulationBase<dim> *>(&tria) != nullptr;
    }

    /// This rank's owned cells in forest order.
    template <int dim>
    std::vector<typename DoFHandler<dim>::active_cell_iterator>
    owned_cells_in_forest_order(const DoFHandler<dim> &dof_handler)
    {
      std::vector<std::pair<ForestKey, typename DoFHandler<dim>::active_cell_iterator>> cells;
      for (const auto &cell : dof_handler.active_cell_iterators())
        if (cell->is_locally_owned())
          cells.emplace_back(forest_key<dim>(cell->id()), cell);
      std::sort(cells.begin(), cells.end(),
                [](const auto &a, const auto &b) { return a.first < b.first; });
      std::vector<typename DoFHandler<dim>::active_cell_iterator> sorted;
      sorted.reserve(cells.size());
      for (const auto &c : cells)
        sorted.push_back(c.second);
      return sorted;
    }

    /// Check that the ranks' runs of cells follow each other in forest
    /// order (what p4est promises), so the pieces make one ordered block.
    template <int dim>
    void
    require_rank_order(const std::vector<typename DoFHandler<dim>::active_cell_iterator> &cells,
                       const MPI_Comm                                                     comm)
    {
      const unsigned int n = Utilities::MPI::n_mpi_processes(comm);
      if (n == 1)
        return;
      std::array<std::uint64_t, 5> mine{};
      if (!cells.empty())
        {
          const auto first = forest_key<dim>(cells.front()->id());
          const auto last  = forest_key<dim>(cells.back()->id());
          mine = {{1, first.first, first.second, last.first, last.second}};
        }
      std::vector<std::uint64_t> all(5 * n);
      MPI_Allgather(mine.data(), 5, MPI_UINT64_T, all.data(), 5, MPI_UINT64_T, comm);
      ForestKey last{0, 0};
      bool      any = false;
      for (unsigned int r = 0; r < n; ++r)
        if (all[5 * r] == 1)
          {
            const ForestKey first{all[5 * r + 1], all[5 * r + 2]};
            if (any && !(last < first))
              throw RunError("checkpoint: the cells of MPI rank " + std::to_string(r) +
                             " do not follow those of the ranks before it in p4est's order");
            last = {all[5 * r + 3], all[5 * r + 4]};
            any  = true;
          }
    }
  } // namespace internal

  /// The solution into a checkpoint payload: the number of cells and of
  /// values per cell in w's bytes, this rank's records (CellId, values) as
  /// its piece of a shared block. Collective.
  template <int dim>
  void
  save_cell_values(const DoFHandler<dim> &dof_handler, const VectorType &u, ByteWriter &w)
  {
    using Key                 = CellId::binary_type;
    const unsigned int n      = dof_handler.get_fe().n_dofs_per_cell();
    const MPI_Comm     comm   = u.get_mpi_communicator();
    const bool distributed    = internal::is_distributed(dof_handler.get_triangulation());
    const bool writes         = distributed || Utilities::MPI::this_mpi_process(comm) == 0;
    auto cells = std::make_shared<const std::vector<typename DoFHandler<dim>::active_cell_iterator>>(
      internal::owned_cells_in_forest_order(dof_handler));
    if (distributed)
      internal::require_rank_order<dim>(*cells, comm);
    w.io(static_cast<std::uint64_t>(dof_handler.get_triangulation().n_global_active_cells()));
    w.io(n);
    // the records are made as the checkpoint writes them (u must not change
    // until then): bytes [offset, offset + size) from the records they cross
    const std::size_t record = sizeof(Key) + n * sizeof(double);
    const auto        fill = [cells, &u, n, record](const std::uint64_t offset,
                                                   const std::uint64_t size, char *out) {
      std::vector<char>                    bytes(record);
      std::vector<types::global_dof_index> dofs(n);
      for (std::uint64_t r = offset / record; r * record < offset + size; ++r)
        {
          const auto &cell = (*cells)[r];
          const Key   key  = cell->id().template to_binary<dim>();
          std::memcpy(bytes.data(), &key, sizeof(Key));
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < n; ++i)
            {
              const double v = u(dofs[i]);
              std::memcpy(bytes.data() + sizeof(Key) + i * sizeof(double), &v, sizeof(double));
            }
          const std::uint64_t first = std::max(offset, r * record);
          const std::uint64_t end   = std::min(offset + size, (r + 1) * record);
          std::memcpy(out + (first - offset), bytes.data() + (first - r * record), end - first);
        }
    };
    w.shared(SharedPiece{writes ? cells->size() * record : 0, fill});
  }

  /// Set the owned cells of u from what save_cell_values() wrote, reading
  /// only this rank's records. Collective.
  template <int dim>
  void
  load_cell_values(const DoFHandler<dim> &dof_handler, ByteReader &r, VectorType &u)
  {
    using Key             = CellId::binary_type;
    std::uint64_t n_cells = 0;
    unsigned int  n       = 0;
    r.io(n_cells);
    r.io(n);
    const std::size_t record = sizeof(Key) + n * sizeof(double);
    if (n != dof_handler.get_fe().n_dofs_per_cell() ||
        n_cells != dof_handler.get_triangulation().n_global_active_cells() ||
        r.shared_size() != n_cells * record)
      throw RunError("the checkpoint's solution does not fit this mesh (" +
                     std::to_string(n_cells) + " cells of " + std::to_string(n) + " DoFs)");
    const auto     cells = internal::owned_cells_in_forest_order(dof_handler);
    std::uint64_t  first = 0, count = cells.size();
    const MPI_Comm comm = u.get_mpi_communicator();
    if (internal::is_distributed(dof_handler.get_triangulation()) &&
        Utilities::MPI::n_mpi_processes(comm) > 1)
      MPI_Exscan(&count, &first, 1, MPI_UINT64_T, MPI_SUM, comm);
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      first = 0;
    const std::string                    bytes = r.shared(first * record, count * record);
    std::vector<types::global_dof_index> dofs(n);
    std::string                          wrong;
    for (std::size_t c = 0; c < cells.size() && wrong.empty(); ++c)
      {
        const char *p   = bytes.data() + c * record;
        const Key   key = cells[c]->id().template to_binary<dim>();
        if (std::memcmp(p, &key, sizeof(Key)) != 0)
          wrong = "the checkpoint's record " + std::to_string(first + c) +
                  " is not that of cell " + cells[c]->id().to_string();
        cells[c]->get_dof_indices(dofs);
        for (unsigned int i = 0; i < n; ++i)
          std::memcpy(&u(dofs[i]), p + sizeof(Key) + i * sizeof(double), sizeof(double));
      }
    // (every rank stops together)
    if (Utilities::MPI::n_mpi_processes(comm) > 1 &&
        Utilities::MPI::max(static_cast<int>(!wrong.empty()), comm) > 0 && wrong.empty())
      wrong = "another MPI rank found a checkpoint record of the wrong cell";
    if (!wrong.empty())
      throw RunError(wrong);
  }
} // namespace granular_dg::dg
