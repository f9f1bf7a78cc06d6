#pragma once

#include <deal.II/base/tensor.h>
#include <deal.II/base/vectorization.h>

namespace granular_dg::dg
{
  using namespace dealii;

  /// The numerical flux every physics offers (Discretization/numerical
  /// flux); the others are declared by the physics that implements them.
  inline const char *const local_lax_friedrichs_name = "local_lax_friedrichs";

  /// Local Lax-Friedrichs (Rusanov): {F}.n + lambda/2 (U_m - U_p),
  /// lambda = max(|lambda(U_m)|, |lambda(U_p)|), each side with its own
  /// coefficients (blind to a material jump in every other respect).
  template <typename Physics, int dim, int n_components, typename Number, typename Coefficients>
  Tensor<1, n_components, Number>
  local_lax_friedrichs(const Physics                         &physics,
                       const Tensor<1, n_components, Number> &U_m,
                       const Tensor<1, n_components, Number> &U_p,
                       const Tensor<1, dim, Number>          &normal,
                       const Coefficients                    &a_m,
                       const Coefficients                    &a_p)
  {
    const auto   F_m    = physics.flux(U_m, a_m);
    const auto   F_p    = physics.flux(U_p, a_p);
    const Number lambda = std::max(physics.max_wave_speed(U_m, a_m),
                                   physics.max_wave_speed(U_p, a_p));
    Tensor<1, n_components, Number> F;
    for (int c = 0; c < n_components; ++c)
      F[c] = 0.5 * ((F_m[c] + F_p[c]) * normal) +
             (0.5 * lambda) * (U_m[c] - U_p[c]);
    return F;
  }
} // namespace granular_dg::dg
