#pragma once

#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/tensor.h>

#include <granular_dg/dg/modal_layout.h>

#include <array>
#include <cmath>
#include <vector>

namespace granular_dg::dg
{
  /**
   * The Gauss quadrature of the operators (p + 2 points per direction on the
   * axis-parallel cells of a ModalLayout) with the Legendre values there: the
   * one implementation of what both engines need besides their kernels:
   * L2 projection, integrals of the components and of pointwise densities,
   * and error norms against a Function. Sums run cell by cell over the
   * locally owned cells, points in tensor order, then over the MPI ranks.
   */
  template <int dim>
  class CellQuadrature
  {
  public:
    void
    reinit(const ModalLayout<dim> &layout)
    {
      cells                  = &layout;
      const unsigned int n1d = layout.degree() + 1;
      const QGauss<1>    q(n1d + 1);
      n_q_1d = q.size();
      xi.resize(n_q_1d);
      w.resize(n_q_1d);
      basis.resize(n_q_1d);
      for (unsigned int i = 0; i < n_q_1d; ++i)
        {
          xi[i]    = q.point(i)[0];
          w[i]     = q.weight(i);
          basis[i] = legendre_values(n1d, xi[i]);
        }
    }

    unsigned int
    n_points() const
    {
      return dim == 1 ? n_q_1d : n_q_1d * n_q_1d;
    }

    /// the weight of point q on the unit cell
    double
    weight(const unsigned int q) const
    {
      return dim == 1 ? w[q] : w[q % n_q_1d] * w[q / n_q_1d];
    }

    /// |K| of owned cell c
    double
    measure(const unsigned int c) const
    {
      double m = cells->extent(c, 0);
      for (int d = 1; d < dim; ++d)
        m *= cells->extent(c, d);
      return m;
    }

    Point<dim>
    point(const unsigned int c, const unsigned int q) const
    {
      Point<dim> x = cells->cell(c)->vertex(0);
      for (int d = 0; d < dim; ++d)
        x[d] += cells->extent(c, d) * xi[d == 0 ? q % n_q_1d : q / n_q_1d];
      return x;
    }

    /// the 1D Gauss points and the Legendre values there (basis(i)[k] = L_k(xi_i))
    unsigned int
    n_points_1d() const
    {
      return n_q_1d;
    }
    const std::vector<double> &
    basis_1d(const unsigned int i) const
    {
      return basis[i];
    }

    /// all components at point q of owned cell c
    template <int n_components, typename VectorType>
    Tensor<1, n_components>
    state(const VectorType &u, const unsigned int c, const unsigned int q) const
    {
      Tensor<1, n_components> U;
      const auto              L = values_at(q);
      for (unsigned int i = 0; i < n_components; ++i)
        U[i] = cells->value(u, c, i, L);
      return U;
    }

    /// L2 projection of f (orthonormal modes: u_m = sum_q w_q phi_m(x_q) f(x_q))
    template <typename VectorType>
    void
    project(const Function<dim> &f, VectorType &dst) const
    {
      const unsigned int n1d = cells->degree() + 1;
      for (unsigned int c = 0; c < cells->n_owned(); ++c)
        for (unsigned int i = 0; i < cells->n_components(); ++i)
          for (unsigned int m = 0; m < cells->n_modes(); ++m)
            {
              double sum = 0;
              for (unsigned int q = 0; q < n_points(); ++q)
                {
                  double phi = basis[q % n_q_1d][m % n1d];
                  if constexpr (dim == 2)
                    phi *= basis[q / n_q_1d][m / n1d];
                  sum += weight(q) * phi * f.value(point(c, q), i);
                }
              dst.local_element(cells->index(c, i, m)) = sum;
            }
    }

    /// The integral of every component: |K| times the mean (mode 0) per cell
    /// (collective).
    template <typename VectorType>
    std::vector<double>
    integrals(const VectorType &u) const
    {
      std::vector<double> sums(cells->n_components(), 0.);
      for (unsigned int i = 0; i < sums.size(); ++i)
        sums[i] = Utilities::MPI::sum(local_integral(u, i), u.get_mpi_communicator());
      return sums;
    }

    /// This rank's part of integrals() of component i (no reduction).
    template <typename VectorType>
    double
    local_integral(const VectorType &u, const unsigned int i) const
    {
      double sum = 0;
      for (unsigned int c = 0; c < cells->n_owned(); ++c)
        sum += measure(c) * u.local_element(cells->index(c, i, 0));
      return sum;
    }

    /// sum over cells and points of |K| w_q density(c, q) (collective)
    template <typename Density>
    double
    integrate(const Density &density, const MPI_Comm comm) const
    {
      double sum = 0;
      for (unsigned int c = 0; c < cells->n_owned(); ++c)
        for (unsigned int q = 0; q < n_points(); ++q)
          sum += measure(c) * weight(q) * density(c, q);
      return Utilities::MPI::sum(sum, comm);
    }

    /// L1, L2 and Linf of (u - exact) per component (collective)
    template <int n_components, typename VectorType>
    std::vector<std::array<double, 3>>
    errors(const VectorType &u, const Function<dim> &exact) const
    {
      std::vector<std::array<double, 3>> e(n_components, {{0., 0., 0.}});
      for (unsigned int c = 0; c < cells->n_owned(); ++c)
        for (unsigned int q = 0; q < n_points(); ++q)
          {
            const auto       U  = state<n_components>(u, c, q);
            const Point<dim> x  = point(c, q);
            const double     hw = measure(c) * weight(q);
            for (unsigned int i = 0; i < n_components; ++i)
              {
                const double diff = std::abs(U[i] - exact.value(x, i));
                e[i][0] += hw * diff;
                e[i][1] += hw * diff * diff;
                e[i][2] = std::max(e[i][2], diff);
              }
          }
      const MPI_Comm comm = u.get_mpi_communicator();
      for (auto &ei : e)
        {
          ei[0] = Utilities::MPI::sum(ei[0], comm);
          ei[1] = std::sqrt(Utilities::MPI::sum(ei[1], comm));
          ei[2] = Utilities::MPI::max(ei[2], comm);
        }
      return e;
    }

  private:
    std::array<const double *, dim>
    values_at(const unsigned int q) const
    {
      if constexpr (dim == 1)
        return {{basis[q].data()}};
      else
        return {{basis[q % n_q_1d].data(), basis[q / n_q_1d].data()}};
    }

    const ModalLayout<dim>          *cells  = nullptr;
    unsigned int                     n_q_1d = 1;
    std::vector<double>              xi, w;
    std::vector<std::vector<double>> basis;
  };
} // namespace granular_dg::dg
