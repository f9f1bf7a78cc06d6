// Unit tests of the hopper physics (include/granular_dg/equations/
// hopper/system.h, radial_field.h, transition.h), wedge and cone,
// delta = 32.1 deg, Phi = 11.7 deg. Every "error" line must be ~0 (the
// .output holds zeros; numdiff -a 1e-7: the finite-difference Jacobian is
// accurate to ~1e-10 for |psi| <= 0.9 (pi/4 - delta/2)); the "flag" lines are exact 0/1 facts.
//  - closure (9) against the Sokolovskii form (8) on the branch |psi| < eps;
//    the passive-branch caveat: for eps < psi < pi/4 |T_rt/T_rr| < tan(delta)
//    holds but h(T_rr, T_rt) is the other root;
//  - eigenvalues of F' (central differences) against eq. (13) and the
//    closed form -cot(eps - psi), cot(eps + psi); eigenvectors (1, -lambda)
//    (A R = R Lambda, L R = I);
//  - the Roe matrix of section 5: A (U+ - U-) = F(U+) - F(U-) exactly, its
//    eigenvalues (the flux's speed) against those of the explicit matrix,
//    and Roe(U, U) = F'(U);
//  - numerical fluxes: consistency and conservation;
//  - the wall state: T_rt = -mu T_tt exactly (1e-14), outgoing
//    characteristic kept; the symmetry state (T_rr, -T_rt);
//  - no NaN for states outside the cone; admissibility messages;
//  - rotation: psi' = psi + a, invariants kept;
//  - the radial field is a steady state of the scaled PDE (and decays like
//    e^{-tau} in the unscaled one): |d_theta F(U_r) - G(U_r)| ~ 0, which
//    checks the sources (7)/(11) against the BVP (16) (derived separately).
#include <granular_dg/equations/hopper/radial_field.h>
#include <granular_dg/equations/hopper/system.h>
#include <granular_dg/equations/hopper/transition.h>

#include <cstdio>
#include <random>

using namespace granular_dg;
using namespace granular_dg::hopper;

namespace
{
  using State = System::State<double>;

  void
  print(const char *what, const double value)
  {
    std::printf("%-62s %.3e\n", what, std::abs(value) < 1e-300 ? 0. : value);
  }

  void
  flag(const char *what, const bool value)
  {
    std::printf("%-62s %d\n", what, value ? 1 : 0);
  }

  Tensor<2, 2>
  jacobian(const System &sys, const State &U)
  {
    // fourth-order central differences
    Tensor<2, 2> A;
    const double h = 1e-5 * std::abs(U[0]);
    for (unsigned int j = 0; j < 2; ++j)
      {
        auto F = [&](const double d) {
          State V = U;
          V[j] += d;
          return sys.flux(V, {});
        };
        const auto F2 = F(2 * h), F1 = F(h), Fm1 = F(-h), Fm2 = F(-2 * h);
        for (unsigned int i = 0; i < 2; ++i)
          A[i][j] = (-F2[i][0] + 8 * F1[i][0] - 8 * Fm1[i][0] + Fm2[i][0]) / (12 * h);
      }
    return A;
  }
} // namespace

int
main()
{
  const MohrCoulomb mc(32.1 * deg, 11.7 * deg);
  const double      s = mc.s(), c = mc.c(), eps = mc.hyperbolic_limit();
  std::mt19937      gen(7);
  std::uniform_real_distribution<double> unit(0., 1.);

  for (const auto geometry : {Geometry::wedge, Geometry::cone})
    {
      const char *gname = geometry == Geometry::wedge ? "wedge" : "cone";
      std::printf("--- %s\n", gname);
      const System sys(geometry, Variables::scaled, mc);

      double e_closure = 0, e_fd = 0, e_13 = 0, e_cot = 0, e_vec = 0, e_inv = 0, e_roe = 0,
             e_roe_eig = 0, e_roe_same = 0, e_cons = 0, e_consv = 0, e_wall = 0, e_out = 0,
             e_rot = 0, e_inv_rot = 0;
      bool wall_admissible = true;
      for (unsigned int k = 0; k < 200; ++k)
        {
          // a random admissible state from Sokolovskii variables
          const double sigma = 0.2 + 2 * unit(gen);
          const double psi   = (2 * unit(gen) - 1) * 0.9 * eps;
          const auto   T     = sokolovskii_stresses(sigma, psi, s);
          const State  U({T[0], T[1]});
          e_closure = std::max(e_closure, std::abs(sys.h(U[0], U[1]) - T[2]) / sigma);
          e_closure = std::max(e_closure, std::abs(sys.psi(U) - psi));

          // eigenvalues
          const auto         A = jacobian(sys, U);
          const auto         l = sys.eigenvalues(U);
          const double tr = A[0][0] + A[1][1], det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
          const double disc = std::sqrt(tr * tr / 4 - det);
          const double fd[2] = {tr / 2 - disc, tr / 2 + disc};
          const double a = U[0], b = U[1];
          const double eq13[2] = {-std::tan(mc.delta) -
                                    std::sqrt((s * a - c * b) / (s * a + c * b)) / c,
                                  std::tan(mc.delta) +
                                    std::sqrt((s * a + c * b) / (s * a - c * b)) / c};
          const double cot[2] = {-1. / std::tan(eps - psi), 1. / std::tan(eps + psi)};
          for (unsigned int i = 0; i < 2; ++i)
            {
              e_fd  = std::max(e_fd, std::abs(l[i] - fd[i]) / std::abs(l[i]));
              e_13  = std::max(e_13, std::abs(l[i] - eq13[i]) / std::abs(l[i]));
              e_cot = std::max(e_cot, std::abs(l[i] - cot[i]) / std::abs(l[i]));
            }
          Tensor<2, 2> L, R;
          sys.eigenvectors(U, Tensor<1, 1>({1.}), {}, L, R);
          for (unsigned int i = 0; i < 2; ++i)
            for (unsigned int j = 0; j < 2; ++j)
              {
                double AR = 0, LR = 0;
                for (unsigned int m = 0; m < 2; ++m)
                  {
                    AR += A[i][m] * R[m][j];
                    LR += L[i][m] * R[m][j];
                  }
                e_vec = std::max(e_vec, std::abs(AR - R[i][j] * l[j]) / std::abs(l[j]));
                e_inv = std::max(e_inv, std::abs(LR - (i == j ? 1. : 0.)));
              }

          // the Roe matrix with a second admissible state
          const double sigma2 = 0.2 + 2 * unit(gen);
          const double psi2   = (2 * unit(gen) - 1) * 0.97 * eps;
          const auto   T2     = sokolovskii_stresses(sigma2, psi2, s);
          const State  V({T2[0], T2[1]});
          const double xbar =
            0.5 * (std::sqrt(mc.beta() * a * a + mc.gamma() * b * b) +
                   std::sqrt(mc.beta() * V[0] * V[0] + mc.gamma() * V[1] * V[1]));
          Tensor<2, 2> Roe;
          Roe[0][1] = -1;
          Roe[1][0] = -(mc.alpha() + mc.beta() * 0.5 * (a + V[0]) / xbar);
          Roe[1][1] = -mc.gamma() * 0.5 * (b + V[1]) / xbar;
          const auto FU = sys.flux(U, {}), FV = sys.flux(V, {});
          for (unsigned int i = 0; i < 2; ++i)
            e_roe = std::max(e_roe, std::abs(Roe[i][0] * (V[0] - U[0]) + Roe[i][1] * (V[1] - U[1]) -
                                             (FV[i][0] - FU[i][0])));
          const double rtr = Roe[1][1], rdet = -Roe[0][1] * Roe[1][0];
          const double rdisc = std::sqrt(rtr * rtr / 4 - rdet);
          const auto   rl    = sys.roe_eigenvalues(U, V);
          e_roe_eig = std::max({e_roe_eig, std::abs(rl[0] - (rtr / 2 - rdisc)),
                                std::abs(rl[1] - (rtr / 2 + rdisc))});
          const auto same = sys.roe_eigenvalues(U, U);
          e_roe_same = std::max({e_roe_same, std::abs(same[0] - l[0]), std::abs(same[1] - l[1])});

          // fluxes
          for (const auto type : {NumericalFlux::local_lax_friedrichs,
                                  NumericalFlux::roe_lax_friedrichs})
            for (const double nx : {-1., 1.})
              {
                const System       flux_sys(geometry, Variables::scaled, mc, type);
                const Tensor<1, 1> n({nx});
                const auto         Fs = flux_sys.numerical_flux(U, U, n, {}, {});
                const auto         Fa = flux_sys.numerical_flux(U, V, n, {}, {});
                const auto         Fb = flux_sys.numerical_flux(V, U, -n, {}, {});
                for (unsigned int i = 0; i < 2; ++i)
                  {
                    e_cons  = std::max(e_cons, std::abs(Fs[i] - FU[i][0] * nx));
                    e_consv = std::max(e_consv, std::abs(Fa[i] + Fb[i]));
                  }
              }

          // the wall state
          const State  W    = sys.wall_state(U);
          const double T_tt = sys.h(W[0], W[1]);
          e_wall = std::max(e_wall, std::abs(W[1] + mc.mu() * T_tt) / std::abs(W[1]));
          e_out  = std::max(e_out, std::abs(L[1][0] * (W[0] - U[0]) + L[1][1] * (W[1] - U[1])) /
                                    std::abs(U[0]));
          wall_admissible &= sys.admissibility_violation(W, {}).empty();

          // rotation of the full tensor
          const double angle = (2 * unit(gen) - 1) * 0.3;
          const auto   Tr    = rotate_stress(T[0], T[1], T[2], angle);
          e_rot = std::max(e_rot, std::abs(sokolovskii_angle(Tr[0], Tr[1], Tr[2]) - (psi + angle)));
          e_inv_rot =
            std::max({e_inv_rot, std::abs(Tr[0] + Tr[2] - T[0] - T[2]) / sigma,
                      std::abs(std::pow(Tr[0] - Tr[2], 2) + 4 * Tr[1] * Tr[1] -
                               s * s * std::pow(Tr[0] + Tr[2], 2)) /
                        (sigma * sigma)});
        }
      print("closure (9) vs Sokolovskii (8), psi(U)", e_closure);
      print("eigenvalues vs finite-difference Jacobian (rel)", e_fd);
      print("eigenvalues vs eq. (13) (rel)", e_13);
      print("eigenvalues vs -cot(eps - psi), cot(eps + psi) (rel)", e_cot);
      print("eigenvectors (1, -lambda): A R - R Lambda (rel)", e_vec);
      print("L R - I", e_inv);
      print("Roe matrix: A (U+ - U-) - (F(U+) - F(U-))", e_roe);
      print("Roe eigenvalues vs explicit Roe matrix", e_roe_eig);
      print("Roe(U, U) eigenvalues vs F'(U)", e_roe_same);
      print("numerical fluxes: consistency", e_cons);
      print("numerical fluxes: conservation", e_consv);
      print("wall state: T_rt + mu T_tt (rel)", e_wall);
      print("wall state: outgoing characteristic kept (rel)", e_out);
      flag("wall states of admissible states are admissible", wall_admissible);
      print("rotation: psi' - (psi + a)", e_rot);
      print("rotation: trace and yield condition kept", e_inv_rot);

      {
        const State U({1., 0.3});
        const State S = sys.boundary_state(System::symmetry, U, Tensor<1, 1>({-1.}),
                                           State(), {});
        flag("symmetry state (T_rr, -T_rt)", S[0] == 1. && S[1] == -0.3);
      }
      {
        // the passive-branch caveat: eps < psi < pi/4 passes the ratio test
        // but is on the other root of (4)
        const double psi = 0.5 * (eps + M_PI / 4);
        const auto   T   = sokolovskii_stresses(1., psi, s);
        const State  U({T[0], T[1]});
        flag("eps < psi < pi/4: |T_rt/T_rr| < tan(delta)",
             std::abs(T[1] / T[0]) < std::tan(mc.delta));
        flag("eps < psi < pi/4: h(T_rr, T_rt) != T_tt (other branch)",
             std::abs(sys.h(U[0], U[1]) - T[2]) > 1e-3);
        flag("eps < psi < pi/4: full-tensor |psi| >= eps detects it",
             std::abs(sokolovskii_angle(T[0], T[1], T[2])) >= eps);
      }
      {
        // outside the cone: finite values, a message
        const State U({1., -0.8});
        const auto  F = sys.flux(U, {});
        const auto  H = sys.numerical_flux(U, State({1., 0.1}), Tensor<1, 1>({1.}), {}, {});
        flag("outside the cone: flux, speed, Roe flux finite",
             std::isfinite(F[1][0]) && std::isfinite(sys.max_wave_speed(U, {})) &&
               std::isfinite(H[0]) && std::isfinite(H[1]));
        flag("outside the cone: admissibility_violation says so",
             sys.admissibility_violation(U, {}).find("loss of hyperbolicity") == 0);
        flag("T_rr <= 0 is inadmissible",
             !sys.admissibility_violation(State({-1., 0.}), {}).empty());
        flag("NaN is inadmissible",
             !sys.admissibility_violation(State({NAN, 0.}), {}).empty());
      }

      // the radial field is a steady state of the scaled system and
      // e^{-tau} U_r one of the unscaled system
      const RadialField field(geometry, mc, 30 * deg);
      const System      unscaled(geometry, Variables::unscaled, mc);
      double            e_steady = 0, e_unscaled = 0;
      for (unsigned int k = 1; k < 60; ++k)
        {
          const double theta = 30 * deg * k / 60., dh = 1e-5;
          auto         U_r   = [&](const double t) {
            const auto T = field.stresses(t);
            return State({T[0], T[1]});
          };
          const auto Fp = sys.flux(U_r(theta + dh), {}), Fm = sys.flux(U_r(theta - dh), {});
          const auto G  = sys.source(U_r(theta), Point<1>(theta), 0., {});
          const double tau = 0.7, f = std::exp(-tau);
          const auto   Gu  = unscaled.source(State(f * U_r(theta)), Point<1>(theta), tau, {});
          for (unsigned int i = 0; i < 2; ++i)
            {
              const double dF = (Fp[i][0] - Fm[i][0]) / (2 * dh);
              e_steady        = std::max(e_steady, std::abs(dF - G[i]));
              // d_tau U = -U for U = e^{-tau} U_r
              e_unscaled = std::max(e_unscaled, std::abs(-f * U_r(theta)[i] + f * dF - Gu[i]));
            }
        }
      print("radial field: |d_theta F(U_r) - G(U_r)| (scaled)", e_steady);
      print("radial field: d_tau U + d_theta F - G (unscaled)", e_unscaled);
      print("radial field: shooting residual", field.shooting_residual());
      print("radial field: ODE residual of the table", field.ode_residual());
      // the same field through the BVP's wall condition: T_rt = -mu T_tt
      const auto Tw = field.stresses(30 * deg);
      print("radial field: T_rt + mu T_tt at the wall (rel)", (Tw[1] + mc.mu() * Tw[2]) / Tw[2]);
      print("radial field: T_rr - chi_w T_rt at the wall (rel)",
            (Tw[0] - mc.chi_wall() * Tw[1]) / Tw[0]);

      // a transition to the same angle is the radial field itself
      const Transition same(field, mc, 30 * deg);
      double           e_same = 0;
      for (const double theta : {0., 10 * deg, 29 * deg, 30 * deg})
        {
          const auto T = same.initial_stress(theta);
          const auto R = field.stresses(theta);
          for (unsigned int i = 0; i < 3; ++i)
            e_same = std::max(e_same, std::abs(T[i] - R[i]));
        }
      print("transition Theta_w = theta_w: initial data = radial field", e_same);
      // rotated data: psi_lower = psi_upper + (Theta - theta)
      const Transition steeper(field, mc, 25 * deg);
      double           e_psi = 0;
      for (const double theta : {5 * deg, 15 * deg, 25 * deg})
        {
          const auto   T     = steeper.initial_stress(theta);
          const double Theta = steeper.upper_coordinates(1., theta).second;
          e_psi = std::max(e_psi, std::abs(sokolovskii_angle(T[0], T[1], T[2]) -
                                           (field.psi(Theta) + Theta - theta)));
        }
      print("transition 30 -> 25: psi_l - (psi_u + Theta - theta)", e_psi);
      flag("transition 30 -> 25: corner maps to the upper wall",
           std::abs(steeper.upper_coordinates(1., 25 * deg).second - 30 * deg) < 1e-14);
    }
  return 0;
}
