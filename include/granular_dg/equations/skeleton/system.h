#pragma once

/**
 * @file
 * The skeleton scene's physics: linear advection, the smallest complete
 * system (copy this folder to start a new scene; doc/engine.md):
 * \f[
 *   u_t + \nabla\cdot(\mathbf a\, u) = 0,
 * \f]
 * one conserved variable u, a constant velocity a. The flux in direction n
 * is (a.n) u, its one eigenvalue a.n; every finite state is admissible.
 * Numerical fluxes: upwind (the exact Riemann solver) and local
 * Lax-Friedrichs (Rusanov).
 */

#include <deal.II/base/tensor.h>
#include <deal.II/base/vectorization.h>

#include <granular_dg/base/parameters.h>
#include <granular_dg/dg/boundary.h>
#include <granular_dg/dg/numerical_flux.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace granular_dg::skeleton
{
  using namespace dealii;

  /// The numerical fluxes of this physics (Discretization/numerical flux).
  enum class NumericalFlux
  {
    upwind,
    local_lax_friedrichs
  };
  inline const EnumNames<NumericalFlux> numerical_flux_names(
    {{NumericalFlux::upwind, "upwind"},
     {NumericalFlux::local_lax_friedrichs, dg::local_lax_friedrichs_name}});

  template <int dim>
  class System
  {
  public:
    static constexpr unsigned int n_components    = 1;
    /// the component the troubled-cell indicator watches
    /// (Limiter/indicator): u
    static constexpr unsigned int indicator_component = 0;
    static constexpr unsigned int n_coefficients  = 0;
    static constexpr const char  *name            = "linear advection";
    static constexpr bool         has_source_term = false;
    /// one run-time-degree instantiation of the 2D kernels (a fast build;
    /// a production physics leaves this out to get kernels per degree)
    static constexpr int max_compiled_degree = -1;

    template <typename Number>
    using State = Tensor<1, 1, Number>;
    template <typename Number>
    using Flux = Tensor<1, 1, Tensor<1, dim, Number>>;
    template <typename Number>
    using Coefficients = std::array<Number, 0>;

    System(const Tensor<1, dim> &velocity, const NumericalFlux flux)
      : a(velocity)
      , flux_type(flux)
    {}

    Coefficients<double>
    coefficients(const types::material_id) const
    {
      return {};
    }

    static std::vector<std::string>
    component_names()
    {
      return {"u"};
    }

    static std::vector<std::string>
    derived_names()
    {
      return {};
    }

    std::vector<double>
    derived(const State<double> &, const Coefficients<double> &) const
    {
      return {};
    }

    template <typename Number>
    Flux<Number>
    flux(const State<Number> &U, const Coefficients<Number> &) const
    {
      Flux<Number> F;
      for (int d = 0; d < dim; ++d)
        F[0][d] = a[d] * U[0];
      return F;
    }

    template <typename Number>
    Number
    max_wave_speed(const State<Number> &, const Coefficients<Number> &) const
    {
      return Number(a.norm());
    }

    /// F* . n of the run's numerical flux
    template <typename Number>
    State<Number>
    numerical_flux(const State<Number> &U_m, const State<Number> &U_p,
                   const Tensor<1, dim, Number> &n, const Coefficients<Number> &a_m,
                   const Coefficients<Number> &a_p) const
    {
      if (flux_type == NumericalFlux::local_lax_friedrichs)
        return dg::local_lax_friedrichs(*this, U_m, U_p, n, a_m, a_p);
      Number an = 0.;
      for (int d = 0; d < dim; ++d)
        an += a[d] * n[d];
      // the upwind state: U_m where a.n > 0, U_p elsewhere
      State<Number> F;
      F[0] = an * compare_and_apply_mask<SIMDComparison::greater_than>(an, Number(0.), U_m[0],
                                                                        U_p[0]);
      return F;
    }

    /// outflow: U_p = U_m; dirichlet: U_p = g (inflow data)
    template <typename Number>
    State<Number>
    boundary_state(const dg::BoundaryKind kind, const State<Number> &U_m,
                   const Tensor<1, dim, Number> &, const State<Number> &g,
                   const Coefficients<Number> &) const
    {
      return kind == dg::BoundaryKind::dirichlet ? g : U_m;
    }

    void
    eigenvectors(const State<double> &, const Tensor<1, dim> &, const Coefficients<double> &,
                 Tensor<2, 1> &L, Tensor<2, 1> &R) const
    {
      L[0][0] = R[0][0] = 1.;
    }

    double
    energy(const State<double> &U, const Coefficients<double> &) const
    {
      return 0.5 * U[0] * U[0];
    }

    std::string
    admissibility_violation(const State<double> &U, const Coefficients<double> &) const
    {
      return std::isfinite(U[0]) ? "" : "state is not finite";
    }

  private:
    Tensor<1, dim> a;
    NumericalFlux  flux_type;
  };
} // namespace granular_dg::skeleton
