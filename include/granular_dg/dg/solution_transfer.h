#pragma once

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/grid/cell_id.h>

#include <granular_dg/base/checkpoint.h>
#include <granular_dg/base/errors.h>
#include <granular_dg/dg/operator.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace granular_dg::dg
{
  /// The solution cell by cell, keyed by CellId (partition independent):
  /// rank 0 gets every cell, sorted by key, the other ranks "".
  /// Collective.
  template <int dim>
  std::string
  save_cell_values(const DoFHandler<dim> &dof_handler, const VectorType &u)
  {
    using Key                        = CellId::binary_type;
    const unsigned int n             = dof_handler.get_fe().n_dofs_per_cell();
    const std::size_t  record        = sizeof(Key) + n * sizeof(double);
    std::vector<types::global_dof_index> dofs(n);
    std::string                          mine;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const Key key = cell->id().template to_binary<dim>();
          mine.append(reinterpret_cast<const char *>(&key), sizeof(Key));
          cell->get_dof_indices(dofs);
          for (const auto i : dofs)
            {
              const double v = u(i);
              mine.append(reinterpret_cast<const char *>(&v), sizeof(double));
            }
        }
    const MPI_Comm comm = u.get_mpi_communicator();
    const auto     all  = gather_bytes(comm, mine);
    if (Utilities::MPI::this_mpi_process(comm) != 0)
      return "";
    std::vector<std::pair<Key, const char *>> cells;
    for (const auto &part : all)
      for (std::size_t o = 0; o + record <= part.size(); o += record)
        {
          Key key;
          std::memcpy(&key, part.data() + o, sizeof(Key));
          cells.emplace_back(key, part.data() + o);
        }
    std::sort(cells.begin(), cells.end(),
              [](const auto &a, const auto &b) { return a.first < b.first; });
    ByteWriter w;
    w.io(static_cast<std::uint64_t>(cells.size()));
    w.io(n);
    for (const auto &c : cells)
      w.bytes.append(c.second, record);
    return w.bytes;
  }

  /// Set the owned cells of u from what save_cell_values() wrote.
  template <int dim>
  void
  load_cell_values(const DoFHandler<dim> &dof_handler, const std::string &bytes,
                   VectorType &u)
  {
    using Key = CellId::binary_type;
    ByteReader    r(bytes);
    std::uint64_t n_cells = 0;
    unsigned int  n       = 0;
    r.io(n_cells);
    r.io(n);
    const std::size_t record = sizeof(Key) + n * sizeof(double);
    if (n != dof_handler.get_fe().n_dofs_per_cell() ||
        n_cells != dof_handler.get_triangulation().n_global_active_cells() ||
        bytes.size() != sizeof(std::uint64_t) + sizeof(unsigned int) + n_cells * record)
      throw RunError("the checkpoint's solution does not fit this mesh (" +
                     std::to_string(n_cells) + " cells of " + std::to_string(n) + " DoFs)");
    const char *first = bytes.data() + sizeof(std::uint64_t) + sizeof(unsigned int);
    auto        key_of = [&](const std::size_t i) {
      Key key;
      std::memcpy(&key, first + i * record, sizeof(Key));
      return key;
    };
    std::vector<types::global_dof_index> dofs(n);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const Key   key = cell->id().template to_binary<dim>();
          std::size_t lo = 0, hi = n_cells;
          while (lo < hi)
            {
              const std::size_t mid = (lo + hi) / 2;
              if (key_of(mid) < key)
                lo = mid + 1;
              else
                hi = mid;
            }
          if (lo == n_cells || key_of(lo) != key)
            throw RunError("the checkpoint has no values for cell " + cell->id().to_string());
          const char *values = first + lo * record + sizeof(Key);
          cell->get_dof_indices(dofs);
          for (unsigned int i = 0; i < n; ++i)
            std::memcpy(&u(dofs[i]), values + i * sizeof(double), sizeof(double));
        }
  }
} // namespace granular_dg::dg
