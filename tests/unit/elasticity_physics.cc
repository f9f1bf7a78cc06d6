// Unit tests of the elasticity physics (include/granular_dg/equations/
// layered_strip/system.h), for both stress laws and dim = 1, 2:
//  - flux consistency: F*(U, U, n) = F(U) n for the LLF and impedance fluxes;
//  - conservation: F*(U_m, U_p, n) = -F*(U_p, U_m, -n);
//  - eigenvalues: the flux Jacobian by central differences, A = dF.n/dU,
//    satisfies A R = R diag(-c, 0.., c) and L R = I with the physics' own
//    eigenvectors and c = sqrt(sigma'(eps)/rho);
//  - sigma' and the stored energy against differences of sigma.
// Every line prints an error that must be ~0 (the .output holds zeros,
// compared with numdiff at an absolute tolerance of 1e-7).
#include <granular_dg/equations/layered_strip/system.h>

#include <cstdio>
#include <random>

using namespace granular_dg;
using namespace granular_dg::layered_strip;

template <int dim>
void
check(const StressLaw law, const char *law_name)
{
  using Sys = System<dim>;
  constexpr unsigned int nc = Sys::n_components;
  const Material         mat{2.0, 2.0, 0.3};
  const Sys              sys(law, mat);
  const auto             a = Sys::coefficients_of(mat);
  std::mt19937           gen(42);
  std::uniform_real_distribution<double> r(-0.3, 0.3);

  double e_consistency = 0, e_conservation = 0, e_eigen = 0, e_inverse = 0,
         e_speed = 0, e_derivative = 0;
  for (unsigned int sample = 0; sample < 20; ++sample)
    {
      typename Sys::template State<double> U, V;
      for (unsigned int c = 0; c < nc; ++c)
        {
          U[c] = r(gen);
          V[c] = r(gen);
        }
      Tensor<1, dim> n;
      for (int d = 0; d < dim; ++d)
        n[d] = r(gen) + (d == 0 ? 1. : 0.);
      n /= n.norm();

      const auto F = sys.flux(U, a);
      for (const auto type : {NumericalFlux::local_lax_friedrichs,
                              NumericalFlux::impedance})
        {
          const auto Fs = sys.with_numerical_flux(type).numerical_flux(U, U, n, a, a);
          const auto Fa = sys.with_numerical_flux(type).numerical_flux(U, V, n, a, a);
          const auto Fb = sys.with_numerical_flux(type).numerical_flux(V, U, -n, a, a);
          for (unsigned int c = 0; c < nc; ++c)
            {
              e_consistency = std::max(e_consistency, std::abs(Fs[c] - F[c] * n));
              e_conservation = std::max(e_conservation, std::abs(Fa[c] + Fb[c]));
            }
        }

      // Jacobian of F(U).n by central differences
      Tensor<2, nc> A;
      const double  h = 1e-6;
      for (unsigned int j = 0; j < nc; ++j)
        {
          auto Up = U, Um = U;
          Up[j] += h;
          Um[j] -= h;
          const auto Fp = sys.flux(Up, a), Fm = sys.flux(Um, a);
          for (unsigned int i = 0; i < nc; ++i)
            A[i][j] = (Fp[i] * n - Fm[i] * n) / (2 * h);
        }
      Tensor<2, nc> L, R;
      sys.eigenvectors(U, n, a, L, R);
      const double c = std::sqrt(sys.stress_derivative(U[0], a) / mat.rho);
      e_speed        = std::max(e_speed, std::abs(sys.max_wave_speed(U, a) - c));
      for (unsigned int k = 0; k < nc; ++k)
        {
          const double lambda = k == 0 ? -c : (k == nc - 1 ? c : 0.);
          for (unsigned int i = 0; i < nc; ++i)
            {
              double AR = 0, LR = 0;
              for (unsigned int j = 0; j < nc; ++j)
                {
                  AR += A[i][j] * R[j][k];
                  LR += L[i][j] * R[j][k];
                }
              e_eigen   = std::max(e_eigen, std::abs(AR - lambda * R[i][k]));
              e_inverse = std::max(e_inverse, std::abs(LR - (i == k ? 1. : 0.)));
            }
        }
      const double eps = U[0];
      e_derivative     = std::max(
        {e_derivative,
         std::abs((sys.stress(eps + h, a) - sys.stress(eps - h, a)) / (2 * h) -
                  sys.stress_derivative(eps, a)),
         std::abs((sys.stored_energy(eps + h, a) - sys.stored_energy(eps - h, a)) / (2 * h) -
                  sys.stress(eps, a))});
    }
  std::printf("%s dim=%d flux consistency error %.1e\n", law_name, dim, e_consistency);
  std::printf("%s dim=%d flux conservation error %.1e\n", law_name, dim, e_conservation);
  std::printf("%s dim=%d wave speed error %.1e\n", law_name, dim, e_speed);
  std::printf("%s dim=%d A R - R Lambda error %.1e\n", law_name, dim, e_eigen);
  std::printf("%s dim=%d L R - I error %.1e\n", law_name, dim, e_inverse);
  std::printf("%s dim=%d stress derivative error %.1e\n", law_name, dim, e_derivative);
}

int
main()
{
  check<1>(StressLaw::quadratic, "quadratic");
  check<1>(StressLaw::exponential, "exponential");
  check<2>(StressLaw::quadratic, "quadratic");
  check<2>(StressLaw::exponential, "exponential");
}
