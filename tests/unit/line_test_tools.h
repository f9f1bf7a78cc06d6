#pragma once

// What the unit tests of the 1D engine's SIMD batches share: the line of
// cells they run on, and yes/no for their output.

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <vector>

namespace line_test
{
  using namespace dealii;

  inline const char *
  yes(const bool b)
  {
    return b ? "yes" : "no";
  }

  /// n_cells cells on [0, 3] (boundary ids 0 and 1), periodic if asked; with
  /// two_materials every third cell has material 1 (the elasticity's layers).
  inline void
  make_line(Triangulation<1> &tria, const unsigned int n_cells, const bool periodic,
            const bool two_materials)
  {
    GridGenerator::subdivided_hyper_cube(tria, n_cells, 0., 3., true);
    if (periodic)
      {
        std::vector<GridTools::PeriodicFacePair<Triangulation<1>::cell_iterator>> pairs;
        GridTools::collect_periodic_faces(tria, 0, 1, 0, pairs);
        tria.add_periodicity(pairs);
      }
    for (const auto &cell : tria.active_cell_iterators())
      cell->set_material_id(two_materials && cell->index() % 3 == 0 ? 1 : 0);
  }
} // namespace line_test
