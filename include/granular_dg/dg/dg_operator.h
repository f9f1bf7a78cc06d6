#pragma once

#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/matrix_free/matrix_free.h>

#include <granular_dg/dg/boundary.h>
#include <granular_dg/dg/numerical_flux.h>

#include <array>
#include <string>

namespace granular_dg::dg
{
  using namespace dealii;
  using VectorType = LinearAlgebra::distributed::Vector<double>;

  /// Where and why a state left the admissible set.
  struct AdmissibilityReport
  {
    bool                 ok = true;
    Point<3>             position; ///< first inadmissible quadrature point
    std::vector<double>  state;
    std::string          reason;
  };

  /**
   * Physics-free explicit DG operator on MatrixFree (after deal.II step-67):
   * dst = M^{-1} ( (F(U), grad v) - <F* . n, v> + (S(U), v) ) for a Physics
   * policy providing n_components, flux(), max_wave_speed(),
   * numerical_flux(type, U_m, U_p, n) and boundary_state(kind, U_m, n, g).
   * The polynomial degree is a run-time value (FEEvaluation degree -1), so one
   * instantiation per (dim, Physics) serves degrees 0-4.
   *
   * The quadrature has degree+2 Gauss points per direction (over-integration
   * of the nonlinear flux). The Legendre basis is orthonormal, so on the
   * affine cells the engine accepts the inverse mass matrix is the diagonal
   * 1/|K|.
   */
  template <int dim, typename Physics>
  class DGOperator
  {
  public:
    static constexpr unsigned int n_components = Physics::n_components;
    using Number = double;
    template <typename T>
    using State = Tensor<1, n_components, T>;

    DGOperator(const Physics &physics, NumericalFlux flux, BoundaryMap<dim> bc);

    void
    reinit(const Mapping<dim> &mapping, const DoFHandler<dim> &dof_handler);

    void
    initialize_vector(VectorType &vector) const;

    /// dst = M^{-1} R(t, src)
    void
    apply(double time, const VectorType &src, VectorType &dst) const;

    /// L2 projection of a Function with n_components components.
    void
    project(const Function<dim> &function, VectorType &dst) const;

    /// max over quadrature points of lambda(U) * sum_d |row_d(J^{-1})|; the
    /// stable step is CFL / this value.
    double
    max_speed_over_h(const VectorType &solution) const;

    /// Integral of every component over the domain.
    std::array<double, n_components>
    integrals(const VectorType &solution) const;

    /// Integral of a pointwise scalar functional of the state (e.g. energy).
    double
    integrate(const VectorType                                     &solution,
              const std::function<double(const State<double> &)> &density) const;

    /// L1, L2 and Linf norms of (solution - exact) for each component.
    std::array<std::array<double, 3>, n_components>
    errors(const VectorType &solution, const Function<dim> &exact) const;

    /// Check every quadrature point (and face point) against the Physics'
    /// admissibility_violation(); the first failure is reported.
    AdmissibilityReport
    check_admissibility(const VectorType &solution) const;

    const MatrixFree<dim, Number> &
    matrix_free() const
    {
      return data;
    }

    const Physics &
    physics() const
    {
      return phys;
    }

  private:
    using VA = VectorizedArray<Number>;

    void
    local_apply_cell(const MatrixFree<dim, Number>               &data,
                     VectorType                                  &dst,
                     const VectorType                            &src,
                     const std::pair<unsigned int, unsigned int> &cell_range) const;
    void
    local_apply_face(const MatrixFree<dim, Number>               &data,
                     VectorType                                  &dst,
                     const VectorType                            &src,
                     const std::pair<unsigned int, unsigned int> &face_range) const;
    void
    local_apply_boundary_face(
      const MatrixFree<dim, Number>               &data,
      VectorType                                  &dst,
      const VectorType                            &src,
      const std::pair<unsigned int, unsigned int> &face_range) const;
    Physics                 phys;
    NumericalFlux           flux_type;
    BoundaryMap<dim>        boundary;
    MatrixFree<dim, Number> data;
    VectorType              inverse_mass_diagonal;
    mutable double          time = 0.;
  };
} // namespace granular_dg::dg
