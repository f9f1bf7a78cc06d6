#pragma once

#include <deal.II/base/polynomial.h>
#include <deal.II/base/tensor.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <cmath>
#include <vector>

namespace granular_dg::dg
{
  using namespace dealii;

  enum class LimiterType
  {
    none,
    componentwise,
    characteristic
  };

  /**
   * TVB minmod limiter on the Legendre modes of FE_DGQLegendre (Cockburn &
   * Shu). Per direction d, the cell's 1D expansion through the cell centre
   * gives the jumps to its face values, u(face+) - ubar and ubar - u(face-);
   * if minmod_TVB of either against the neighbour differences of averages
   * changes it, the cell is troubled: its modes other than the average are
   * replaced by the limited linear slope per direction. Cell averages (and so
   * conservation) are never touched. In characteristic mode the jumps are
   * transformed with the left eigenvectors of the flux Jacobian in direction
   * d at the cell average, limited field by field, and transformed back.
   *
   * Works on the vector's local storage through index tables built once; the
   * neighbours' averages of ghost cells are read from ghost entries.
   */
  template <int dim, typename Physics>
  class ModalLimiter
  {
  public:
    static constexpr unsigned int n_components = Physics::n_components;
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    ModalLimiter(const Physics &physics, LimiterType type, double tvb_M)
      : physics(physics)
      , type(type)
      , M(tvb_M)
    {}

    void
    reinit(const DoFHandler<dim> &dof_handler);

    /// Limit in place; returns the number of troubled (modified) cells on this
    /// rank.
    unsigned int
    apply(VectorType &solution) const;

    /// Troubled flags of the last apply(), one per locally owned active cell
    /// in the order of dof_handler.active_cell_iterators().
    const std::vector<unsigned char> &
    troubled_cells() const
    {
      return troubled;
    }

    LimiterType
    get_type() const
    {
      return type;
    }

  private:
    const Physics physics;
    LimiterType   type;
    double        M;

    unsigned int n_modes_1d = 1;
    /// local vector index of (cell, component, mode) = dof_index[(cell*n_comp+c)*n_modes + mode]
    std::vector<unsigned int> dof_index;
    /// neighbour cell (index into the owned+ghost table) per (cell, face), or -1
    std::vector<int>          neighbor;
    std::vector<double>       cell_h; // per owned cell, per direction
    unsigned int              n_owned = 0;
    unsigned int              n_modes = 1;
    /// L_k(1) and L_k(0) of the orthonormal Legendre polynomials, L_0
    std::vector<double>       value_at_1, value_at_0;
    double                    L0 = 1.;
    /// mode index of the 1D degree-k mode in direction d: k * stride[d]
    std::array<unsigned int, dim> stride;

    mutable std::vector<unsigned char> troubled;
  };
} // namespace granular_dg::dg
