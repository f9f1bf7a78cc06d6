#pragma once

#include <deal.II/base/partitioner.h>
#include <deal.II/base/point.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <array>
#include <memory>
#include <type_traits>
#include <vector>

namespace granular_dg::dg
{
  using namespace dealii;

  /**
   * f(std::integral_constant<unsigned int, n>()) for n = n_modes_1d, the
   * number of Legendre modes per direction (degree + 1, 1-5): the cell loops
   * compiled per degree, so that the compiler unrolls the mode and point
   * loops (line operator, limiter, friction projection).
   */
  template <typename F>
  decltype(auto)
  with_n_modes(const unsigned int n_modes_1d, const F &f)
  {
    AssertThrow(n_modes_1d >= 1 && n_modes_1d <= 5,
                ExcMessage("the DG kernels support degrees 0-4"));
    switch (n_modes_1d)
      {
        case 1:
          return f(std::integral_constant<unsigned int, 1>());
        case 2:
          return f(std::integral_constant<unsigned int, 2>());
        case 3:
          return f(std::integral_constant<unsigned int, 3>());
        case 4:
          return f(std::integral_constant<unsigned int, 4>());
        default:
          return f(std::integral_constant<unsigned int, 5>());
      }
  }

  /// L_0(xi), ..., L_{n-1}(xi): the orthonormal Legendre polynomials on
  /// [0, 1], the 1D shape functions of FE_DGQLegendre (evaluated as deal.II
  /// evaluates them, so that point values agree with FEValues').
  std::vector<double>
  legendre_values(unsigned int n, double xi);

  /**
   * Where the Legendre modes of FE_DGQLegendre live in a solution vector, cell
   * by cell, and who the neighbours are: the index tables behind the modal
   * limiter and every cell-local post-stage operation (friction projection,
   * positivity scaling). Cells are numbered 0..n_owned()-1 for the locally
   * owned ones in the order of active_cell_iterators(), then the ghost
   * neighbours that some owned cell touches.
   *
   * Mode m of a cell is the tensor-product index m = sum_d k_d stride(d) of
   * the 1D degrees k_d; mode 0 is the cell average (the orthonormal L_0 = 1 on
   * the unit cell). index() is the global DoF index until localize() turns the
   * table into local indices of the partitioner of the owned and locally
   * relevant DoFs: address owned cells in any vector of the run with
   * local_element() (the owned range is the same in MatrixFree's vectors) and
   * read ghost neighbours from with_ghosts(vector). In a serial run local and
   * global indices coincide and with_ghosts() is the vector itself.
   */
  template <int dim>
  class ModalLayout
  {
  public:
    void
    reinit(const DoFHandler<dim> &dof_handler);

    /// Turn the index table into local indices of the owned and locally
    /// relevant DoFs of dof_handler (the ghost neighbours' DoFs included).
    void
    localize(const DoFHandler<dim> &dof_handler, MPI_Comm comm);

    /// u with the ghost neighbours' entries in the localized numbering: u
    /// itself in serial, otherwise a copy with exchanged ghost values (made
    /// on first use and kept until release_ghosts()).
    const LinearAlgebra::distributed::Vector<double> &
    with_ghosts(const LinearAlgebra::distributed::Vector<double> &u) const;

    /// Free the copy of with_ghosts() (a full vector): for users that need
    /// it rarely (diagnostics at output times), so that a run whose limiter
    /// does not limit holds no such copy between them.
    void
    release_ghosts() const
    {
      ghosted.reinit(0);
    }

    unsigned int n_owned() const { return n_owned_cells; }
    unsigned int n_cells() const { return cells.size(); }
    unsigned int n_components() const { return n_comp; }
    unsigned int degree() const { return n_modes_1d - 1; }
    unsigned int n_modes() const { return n_modes_cell; }
    unsigned int stride(const unsigned int d) const { return strides[d]; }

    /// vector index of (cell, component, mode): global, or local after localize()
    types::global_dof_index
    index(const unsigned int cell, const unsigned int component, const unsigned int mode) const
    {
      return dof_index[(cell * n_comp + component) * n_modes_cell + mode];
    }

    /// the neighbour across face f (0..2dim-1, deal.II numbering), or -1 at a
    /// non-periodic boundary
    int
    neighbor(const unsigned int cell, const unsigned int f) const
    {
      return neighbors[cell * 2 * dim + f];
    }

    /// boundary id of face f of an owned cell (meaningful where neighbor() < 0)
    types::boundary_id
    boundary_id(const unsigned int cell, const unsigned int f) const
    {
      return boundary_ids[cell * 2 * dim + f];
    }

    const typename DoFHandler<dim>::active_cell_iterator &
    cell(const unsigned int c) const { return cells[c]; }

    double extent(const unsigned int c, const unsigned int d) const { return extents[c * dim + d]; }

    /// L_k(1) and L_k(0) of the 1D orthonormal Legendre polynomials on [0, 1]
    double value_at_1(const unsigned int k) const { return at_1[k]; }
    double value_at_0(const unsigned int k) const { return at_0[k]; }

    /// Component i of cell c (a local index, see localize()) at the point
    /// whose 1D Legendre values in direction d are L[d][0..degree]: the sum
    /// over the modes m of u_m prod_d L[d][k_d(m)]. The one point evaluation
    /// of modal fields in the program.
    template <typename VectorType>
    double
    value(const VectorType &u, const unsigned int c, const unsigned int i,
          const std::array<const double *, dim> &L) const
    {
      double sum = 0;
      for (unsigned int m = 0; m < n_modes_cell; ++m)
        {
          double phi = L[0][m % n_modes_1d];
          if constexpr (dim == 2)
            phi *= L[1][m / n_modes_1d];
          sum += u.local_element(index(c, i, m)) * phi;
        }
      return sum;
    }

    /// 1D: component i of cell c at reference coordinate xi in [0, 1].
    template <typename VectorType>
    double
    value(const VectorType &u, const unsigned int c, const unsigned int i, const double xi) const
    {
      static_assert(dim == 1, "value(u, c, i, xi) is the 1D form");
      const auto L = legendre_values(n_modes_1d, xi);
      return value(u, c, i, {{L.data()}});
    }

    /// bytes of the tables and of the ghosted copy (with_ghosts())
    std::size_t
    memory_consumption() const
    {
      return cells.capacity() * sizeof(cells[0]) + dof_index.capacity() * sizeof(dof_index[0]) +
             neighbors.capacity() * sizeof(int) +
             boundary_ids.capacity() * sizeof(types::boundary_id) +
             (extents.capacity() + at_1.capacity() + at_0.capacity()) * sizeof(double) +
             ghosted.memory_consumption();
    }

  private:
    unsigned int n_comp = 1, n_modes_1d = 1, n_modes_cell = 1, n_owned_cells = 0;
    std::array<unsigned int, dim>                               strides;
    std::vector<typename DoFHandler<dim>::active_cell_iterator> cells;
    std::vector<types::global_dof_index>                        dof_index;
    std::vector<int>                                            neighbors;
    std::vector<types::boundary_id>                             boundary_ids;
    std::vector<double>                                         extents;
    std::vector<double>                                         at_1, at_0;
    bool                                                        has_ghosts = false;
    std::shared_ptr<const Utilities::MPI::Partitioner>          partitioner;
    mutable LinearAlgebra::distributed::Vector<double>          ghosted;
  };
} // namespace granular_dg::dg
