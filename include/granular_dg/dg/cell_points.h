#pragma once

#include <deal.II/base/quadrature_lib.h>

#include <granular_dg/dg/cell_quadrature.h>
#include <granular_dg/dg/modal_layout.h>

#include <algorithm>
#include <array>
#include <limits>
#include <vector>

namespace granular_dg::dg
{
  /**
   * The points of a cell at which a DG polynomial is checked against a
   * bound: the operator's Gauss points (p + 2 per direction, tensor order)
   * and the face centres, as Legendre tables. What a positivity limiter
   * enforces and a diagnostic of the range of a field reads.
   */
  template <int dim>
  class CellPoints
  {
  public:
    void
    reinit(const ModalLayout<dim> &cells)
    {
      layout = &cells;
      quadrature.reinit(cells);
      const unsigned int n1d = cells.degree() + 1;
      at = {{legendre_values(n1d, 0.), legendre_values(n1d, 0.5), legendre_values(n1d, 1.)}};
    }

    /// the smallest value of component i of owned cell c at the points
    template <typename VectorType>
    double
    min(const VectorType &u, const unsigned int c, const unsigned int i) const
    {
      double                          low = std::numeric_limits<double>::max();
      std::array<const double *, dim> v;
      const unsigned int              n = quadrature.n_points_1d();
      for (unsigned int p = 0; p < quadrature.n_points(); ++p)
        {
          unsigned int r = p;
          for (int d = 0; d < dim; ++d, r /= n)
            v[d] = quadrature.basis_1d(r % n).data();
          low = std::min(low, layout->value(u, c, i, v));
        }
      for (unsigned int f = 0; f < 2 * dim; ++f)
        {
          for (int d = 0; d < dim; ++d)
            v[d] = at[1].data();
          v[f / 2] = (f % 2 == 0 ? at[0] : at[2]).data();
          low      = std::min(low, layout->value(u, c, i, v));
        }
      return low;
    }

    /// Legendre values at xi = 0, 1/2, 1
    const std::vector<double> &
    at_0() const
    {
      return at[0];
    }
    const std::vector<double> &
    at_half() const
    {
      return at[1];
    }
    const std::vector<double> &
    at_1() const
    {
      return at[2];
    }

  private:
    const ModalLayout<dim>            *layout = nullptr;
    CellQuadrature<dim>                quadrature;
    std::array<std::vector<double>, 3> at;
  };
} // namespace granular_dg::dg
