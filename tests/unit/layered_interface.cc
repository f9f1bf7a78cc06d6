// Unit tests of the interface-aware (impedance) flux of the elasticity
// physics across a material interface, both stress laws, dim 1, 2:
//  - a stationary contact (eps jumps, u.n and sigma continuous) produces the
//    flux of (u, sigma) itself on both sides: no spurious wave is emitted
//    (the local Lax-Friedrichs flux on (eps, m) does emit one: its defect is
//    printed as a yes/no against 1e-3);
//  - the interface state obeys each side's characteristic relation,
//    sigma* - sigma_m = Z_m (u* - u_m) and sigma* - sigma_p = -Z_p (u* - u_p),
//    so u* and sigma* are one state seen from both sides;
//  - conservation: F*(U_m, U_p, n; a_m, a_p) = -F*(U_p, U_m, -n; a_p, a_m);
//  - for one material and the linear law (beta = 0) the flux is the exact
//    Godunov flux of linear acoustics, F.n average - R|Lambda|L (U_p - U_m)/2.
// Every error line must be ~0 (numdiff, absolute tolerance 1e-7).
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
  const Material         soft{1.0, 1.0, 0.3}, stiff{3.0, 3.0, 0.3};
  const Sys              sys(law, soft);
  const auto             a_m = Sys::coefficients_of(soft), a_p = Sys::coefficients_of(stiff);
  std::mt19937           gen(7);
  std::uniform_real_distribution<double> r(-0.3, 0.3);

  // strain with sigma(eps; a) = s (Newton; sigma is monotone in the range)
  const auto strain_of = [&](const double s, const auto &a) {
    double eps = 0;
    for (unsigned int it = 0; it < 50; ++it)
      eps -= (sys.stress(eps, a) - s) / sys.stress_derivative(eps, a);
    return eps;
  };
  const auto normal_velocity = [](const auto &U, const Tensor<1, dim> &n, const double rho) {
    double un = 0;
    for (int d = 0; d < dim; ++d)
      un += U[1 + d] * n[d];
    return un / rho;
  };

  double e_contact = 0, e_relations = 0, e_conservation = 0, e_godunov = 0, llf_defect = 0;
  for (unsigned int sample = 0; sample < 20; ++sample)
    {
      Tensor<1, dim> n;
      for (int d = 0; d < dim; ++d)
        n[d] = r(gen) + (d == 0 ? 1. : 0.);
      n /= n.norm();

      // stationary contact: common stress s and velocity w, strains differ
      const double                      s = r(gen) + 0.35;
      Tensor<1, dim>                    w;
      typename Sys::template State<double> U, V;
      for (int d = 0; d < dim; ++d)
        w[d] = r(gen);
      U[0] = strain_of(s, a_m);
      V[0] = strain_of(s, a_p);
      for (int d = 0; d < dim; ++d)
        {
          U[1 + d] = soft.rho * w[d];
          V[1 + d] = stiff.rho * w[d];
        }
      const auto F = sys.with_numerical_flux(NumericalFlux::impedance).numerical_flux(U, V, n, a_m, a_p);
      e_contact    = std::max(e_contact, std::abs(F[0] + w * n));
      for (int d = 0; d < dim; ++d)
        e_contact = std::max(e_contact, std::abs(F[1 + d] + s * n[d]));
      const auto G = sys.with_numerical_flux(NumericalFlux::local_lax_friedrichs).numerical_flux(U, V, n, a_m, a_p);
      llf_defect   = std::max(llf_defect, std::abs(G[0] + w * n));

      // random states on both sides of the interface
      for (unsigned int c = 0; c < nc; ++c)
        {
          U[c] = r(gen) + (c == 0 ? 0.35 : 0.);
          V[c] = r(gen) + (c == 0 ? 0.35 : 0.);
        }
      const auto   Fa     = sys.with_numerical_flux(NumericalFlux::impedance).numerical_flux(U, V, n, a_m, a_p);
      const auto   Fb     = sys.with_numerical_flux(NumericalFlux::impedance).numerical_flux(V, U, -n, a_p, a_m);
      const double u_star = -Fa[0];
      double       s_star = 0;
      for (int d = 0; d < dim; ++d)
        s_star -= Fa[1 + d] * n[d];
      const double Z_m = soft.rho * sys.max_wave_speed(U, a_m);
      const double Z_p = stiff.rho * sys.max_wave_speed(V, a_p);
      const double u_m = normal_velocity(U, n, soft.rho), u_p = normal_velocity(V, n, stiff.rho);
      e_relations = std::max({e_relations,
                              std::abs(s_star - sys.stress(U[0], a_m) - Z_m * (u_star - u_m)),
                              std::abs(s_star - sys.stress(V[0], a_p) + Z_p * (u_star - u_p))});
      for (unsigned int c = 0; c < nc; ++c)
        e_conservation = std::max(e_conservation, std::abs(Fa[c] + Fb[c]));
    }

  // one linear material: the exact Godunov flux of linear acoustics
  const Material lin{2.0, 2.0, 0.0};
  const Sys      sys_lin(StressLaw::quadratic, lin);
  const auto     a = Sys::coefficients_of(lin);
  for (unsigned int sample = 0; sample < 20; ++sample)
    {
      Tensor<1, dim> n;
      for (int d = 0; d < dim; ++d)
        n[d] = r(gen) + (d == 0 ? 1. : 0.);
      n /= n.norm();
      typename Sys::template State<double> U, V;
      for (unsigned int c = 0; c < nc; ++c)
        {
          U[c] = r(gen);
          V[c] = r(gen);
        }
      const auto    F = sys_lin.with_numerical_flux(NumericalFlux::impedance).numerical_flux(U, V, n, a, a);
      Tensor<2, nc> L, R;
      sys_lin.eigenvectors(U, n, a, L, R);
      const double c  = sys_lin.max_wave_speed(U, a);
      const auto   Fm = sys_lin.flux(U, a), Fp = sys_lin.flux(V, a);
      for (unsigned int i = 0; i < nc; ++i)
        {
          double upwind = 0.5 * (Fm[i] * n + Fp[i] * n);
          for (unsigned int k = 0; k < nc; ++k)
            {
              const double abs_lambda = (k == 0 || k == nc - 1) ? c : 0.;
              double       alpha      = 0;
              for (unsigned int j = 0; j < nc; ++j)
                alpha += L[k][j] * (V[j] - U[j]);
              upwind -= 0.5 * R[i][k] * abs_lambda * alpha;
            }
          e_godunov = std::max(e_godunov, std::abs(F[i] - upwind));
        }
    }
  std::printf("%s dim=%d stationary contact flux error %.1e\n", law_name, dim, e_contact);
  std::printf("%s dim=%d characteristic relations error %.1e\n", law_name, dim, e_relations);
  std::printf("%s dim=%d conservation error %.1e\n", law_name, dim, e_conservation);
  std::printf("%s dim=%d linear Godunov flux error %.1e\n", law_name, dim, e_godunov);
  std::printf("%s dim=%d LLF emits a wave at a stationary contact (defect > 1e-3): %s\n",
              law_name, dim, llf_defect > 1e-3 ? "yes" : "no");
}

int
main()
{
  check<1>(StressLaw::quadratic, "quadratic");
  check<1>(StressLaw::exponential, "exponential");
  check<2>(StressLaw::quadratic, "quadratic");
  check<2>(StressLaw::exponential, "exponential");
}
