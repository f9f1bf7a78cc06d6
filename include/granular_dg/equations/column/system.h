#pragma once

/**
 * @file
 * A granular column with Coulomb wall friction: the dynamical Janssen model of
 * Coffey & Gremaud, in nondimensional Lagrangian form on z > 0:
 * \f[
 *   u_t - v_z = 0, \qquad
 *   v_t + \sigma(u)_z - G \in -\operatorname{sgn}(v)\,\sigma(u),
 *   \qquad \sigma(u) = \max\{0, -u|u|^{m-1}\},
 * \f]
 * (2.3)-(2.4), (2.2) with the strain u (u < 0 is compression), the velocity v,
 * the stress sigma >= 0 (granular matter carries no tension), gravity G (0 for
 * the horizontal cylinder of the paper's experiments) and the maximal monotone
 * graph sgn (sgn(0) = [-1, 1]): a differential inclusion. The wall load
 * u(0, t) = u_b (2.5) drives the column from rest (2.6).
 *
 * Conserved variables U = (u, v), flux F(U) = (-v, sigma(u)). The Jacobian
 * [[0, -1], [sigma'(u), 0]] has the eigenvalues -c, +c with
 * c = sqrt(-sigma'(u)) = sqrt(m |u|^(m-1)) for u < 0 (c = 0 for u > 0: a
 * vacuum-like state, and for m > 1 also at u = 0, where strict hyperbolicity is
 * lost), right eigenvectors r_(-+) = (1, +-c).
 *
 * Optionally sigma is replaced by the Lipschitz-regularised law (3.5): linear
 * continuation of sigma beyond |u| = u*, which makes the semi-discrete
 * inclusion well posed (Lemma 3.1).
 *
 * The stored energy Sigma(u) = int_0^u -sigma = |u|^(m+1)/(m+1) (u < 0) makes
 * E = v^2/2 + Sigma(u) a convex entropy with E_t + (v sigma)_z = G v - |v| sigma.
 *
 * The friction is not part of the explicit operator in the paper's method:
 * it is solved implicitly per cell and stage (column/friction.h). The naive
 * alternatives evaluate it explicitly in source(): sgn(v) of the current
 * state, or a smoothed sgn, v / sqrt(v^2 + delta^2).
 */

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/vectorization.h>

#include <granular_dg/base/vectorized_math.h>
#include <granular_dg/dg/boundary.h>
#include <granular_dg/dg/numerical_flux.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace granular_dg::column
{
  using namespace dealii;

  /// How the friction term -sgn(v) sigma(u) enters the scheme.
  enum class FrictionTreatment
  {
    projection,      ///< implicit per cell and stage (the paper's steps 1-4)
    explicit_sign,   ///< naive: explicit source with sgn(v) of the current state
    explicit_smooth, ///< naive: explicit source with v / sqrt(v^2 + delta^2)
    none             ///< no friction: the p-system
  };

  struct Parameters
  {
    double            m             = 1.;  ///< exponent of the stress law
    double            gravity       = 0.;  ///< G
    double            u_star        = 0.;  ///< regularisation (3.5) beyond |u| > u*; 0 = off
    FrictionTreatment friction      = FrictionTreatment::projection;
    double            smoothing     = 1e-2; ///< delta of the smoothed sgn
  };

  class System
  {
  public:
    static constexpr unsigned int n_components    = 2;
    /// the component the troubled-cell indicator watches
    /// (Limiter/indicator): the strain (its jumps are the fronts)
    static constexpr unsigned int indicator_component = 0;
    static constexpr unsigned int n_coefficients  = 0;
    static constexpr const char  *name            = "granular column with Coulomb wall friction";
    static constexpr bool         has_source_term = true;

    template <typename Number>
    using State = Tensor<1, n_components, Number>;
    template <typename Number>
    using Flux = Tensor<1, n_components, Tensor<1, 1, Number>>;
    template <typename Number>
    using Coefficients = std::array<Number, 0>;

    explicit System(const Parameters &p)
      : p(p)
      , law(p.m == 1.  ? Law::linear :
            p.m == 1.5 ? Law::three_halves :
            p.m == 2.  ? Law::square :
                         Law::general)
    {}

    const Parameters &
    parameters() const
    {
      return p;
    }

    Coefficients<double>
    coefficients(types::material_id) const
    {
      return {};
    }

    static std::vector<std::string>
    component_names()
    {
      return {"strain", "velocity"};
    }

    static std::vector<std::string>
    derived_names()
    {
      return {"stress"};
    }

    std::vector<double>
    derived(const State<double> &U, const Coefficients<double> &) const
    {
      return {stress(U[0])};
    }

    /// sigma(u) of (2.2), or of the regularised law (3.5) when u* > 0.
    template <typename Number>
    Number
    stress(const Number &u) const
    {
      // compression w = max(-u, 0); sigma = w^m
      const Number w = std::max(-u, Number(0.));
      if (p.u_star > 0)
        {
          const double s_star  = std::pow(p.u_star, p.m);
          const double ds_star = p.m * std::pow(p.u_star, p.m - 1.);
          return compare_and_apply_mask<SIMDComparison::greater_than>(
            w, Number(p.u_star), s_star + ds_star * (w - p.u_star), power(w));
        }
      return power(w);
    }

    /// -sigma'(u) >= 0 (the square of the sound speed).
    template <typename Number>
    Number
    minus_stress_derivative(const Number &u) const
    {
      Number w = std::max(-u, Number(0.));
      if (p.u_star > 0)
        w = std::min(w, Number(p.u_star));
      switch (law)
        {
          case Law::linear:
            // sigma = -u for u <= 0: the left derivative at u = 0 is -1
            return compare_and_apply_mask<SIMDComparison::less_than_or_equal>(
              u, Number(0.), Number(1.), Number(0.));
          case Law::three_halves:
            return 1.5 * std::sqrt(w);
          case Law::square:
            return 2. * w;
          default:
            return p.m * std::pow(w, p.m - 1.);
        }
    }

    /// Sound speed c = sqrt(-sigma'(u)).
    template <typename Number>
    Number
    sound_speed(const Number &u) const
    {
      return std::sqrt(minus_stress_derivative(u));
    }

    /// Sigma(u) = int_0^u -sigma, the stored energy (regularised law: of sigma*).
    double
    stored_energy(const double u) const
    {
      const double w = std::max(-u, 0.);
      if (p.u_star > 0 && w > p.u_star)
        {
          const double s_star  = std::pow(p.u_star, p.m);
          const double ds_star = p.m * std::pow(p.u_star, p.m - 1.);
          const double d       = w - p.u_star;
          return std::pow(p.u_star, p.m + 1.) / (p.m + 1.) + s_star * d + 0.5 * ds_star * d * d;
        }
      return std::pow(w, p.m + 1.) / (p.m + 1.);
    }

    double
    energy(const State<double> &U, const Coefficients<double> &) const
    {
      return 0.5 * U[1] * U[1] + stored_energy(U[0]);
    }

    template <typename Number>
    Flux<Number>
    flux(const State<Number> &U, const Coefficients<Number> &) const
    {
      Flux<Number> F;
      F[0][0] = -U[1];
      F[1][0] = stress(U[0]);
      return F;
    }

    template <typename Number>
    Number
    max_wave_speed(const State<Number> &U, const Coefficients<Number> &) const
    {
      return sound_speed(U[0]);
    }

    /// G, plus the friction when it is treated explicitly (naive variants).
    template <typename Number>
    State<Number>
    source(const State<Number> &U, const Point<1, Number> &, double,
           const Coefficients<Number> &) const
    {
      State<Number> S;
      S[1] = Number(p.gravity);
      if (p.friction == FrictionTreatment::explicit_sign)
        {
          const Number sgn = compare_and_apply_mask<SIMDComparison::greater_than>(
            U[1], Number(0.), Number(1.),
            compare_and_apply_mask<SIMDComparison::less_than>(U[1], Number(0.), Number(-1.),
                                                              Number(0.)));
          S[1] -= sgn * stress(U[0]);
        }
      else if (p.friction == FrictionTreatment::explicit_smooth)
        S[1] -= U[1] / std::sqrt(U[1] * U[1] + Number(p.smoothing * p.smoothing)) *
                stress(U[0]);
      return S;
    }

    /// Dirichlet (the wall load): prescribed strain g[0], velocity from the
    /// interior, so that the load enters through the numerical flux;
    /// wall: a closed end at rest, the mirror state v_p = -v_m;
    /// outflow: U_p = U_m.
    template <typename Number>
    State<Number>
    boundary_state(const dg::BoundaryKind kind, const State<Number> &U_m,
                   const Tensor<1, 1, Number> &, const State<Number> &g,
                   const Coefficients<Number> &) const
    {
      State<Number> U_p = U_m;
      if (kind == dg::BoundaryKind::dirichlet)
        U_p[0] = g[0];
      else if (kind == dg::BoundaryKind::wall)
        U_p[1] = -U_m[1];
      else
        AssertThrow(kind == dg::BoundaryKind::outflow,
                    ExcMessage("the column knows dirichlet (wall load), wall and outflow "
                               "boundaries"));
      return U_p;
    }

    /// Rusanov (local Lax-Friedrichs), the column's one numerical flux.
    template <typename Number>
    State<Number>
    numerical_flux(const State<Number> &U_m,
                   const State<Number> &U_p, const Tensor<1, 1, Number> &n,
                   const Coefficients<Number> &a_m, const Coefficients<Number> &a_p) const
    {
      return dg::local_lax_friedrichs(*this, U_m, U_p, n, a_m, a_p);
    }

    /// Eigenvectors at U in direction n (order -c, +c); the sound speed is
    /// floored so that the decomposition stays defined at rest (c = 0).
    template <typename Number>
    void
    eigenvectors(const State<Number> &U, const Tensor<1, 1, Number> &n,
                 const Coefficients<Number> &, Tensor<2, 2, Number> &L,
                 Tensor<2, 2, Number> &R) const
    {
      const Number c  = std::max(sound_speed(U[0]), Number(1e-6));
      const Number cn = c * n[0];
      // A n = [[0, -n], [sigma' n, 0]], eigenvalues -+c: r = (1, +-c n)
      R[0][0] = R[0][1] = 1.;
      R[1][0]           = cn;
      R[1][1]           = -cn;
      L[0][0] = L[1][0] = 0.5;
      L[0][1]           = 0.5 / cn;
      L[1][1]           = -0.5 / cn;
    }

    /// Whether U is finite (with VectorizedArray: in every lane).
    template <typename Number>
    bool
    is_admissible(const State<Number> &U, const Coefficients<Number> &) const
    {
      return all_finite(U[0]) && all_finite(U[1]);
    }

    std::string
    admissibility_violation(const State<double> &U, const Coefficients<double> &) const
    {
      if (!std::isfinite(U[0]) || !std::isfinite(U[1]))
        return "state is not finite";
      return "";
    }

  private:
    template <typename Number>
    Number
    power(const Number &w) const
    {
      // the paper's laws without pow(), which costs as much as the rest of a
      // flux evaluation
      switch (law)
        {
          case Law::linear:
            return w;
          case Law::three_halves:
            return w * std::sqrt(w);
          case Law::square:
            return w * w;
          default:
            // w^m with w >= 0; pow(0, m) = 0 for m > 0
            return std::pow(w, p.m);
        }
    }

    /// the exponent m, decided once: the laws of the paper without pow()
    enum class Law : unsigned char
    {
      linear,       ///< m = 1
      three_halves, ///< m = 3/2
      square,       ///< m = 2
      general
    };

    Parameters p;
    Law        law;
  };
} // namespace granular_dg::column
