#pragma once

/**
 * @file
 * Steady stress field of a Mohr-Coulomb material flowing under gravity in a
 * wedge (d = 2) or conical (d = 3) hopper, after Gremaud & Matthews (seed
 * 003). The derivation is in doc/hopper.md; the equation numbers below are
 * the paper's.
 *
 * Geometry: polar (wedge) or spherical (cone, axisymmetric) coordinates
 * (r, theta) with the apex at r = 0 and theta measured from the downward
 * pointing axis of the hopper, |theta| <= theta_w; gravity is -g e_z with
 * e_r = (sin theta, cos theta) in (x, z). Stresses are compressive positive.
 *
 * Balance of forces (5) (cone) and (10) (wedge), the yield condition (4)
 *   (T_rr - T_tt)^2 + 4 T_rt^2 = s^2 (T_rr + T_tt)^2,   s = sin(delta),
 * and for the cone the Haar-von Karman closure T_pp = (1 + s)(T_rr + T_tt)/2.
 * With tau = -ln(r/r0) (r = r0 e^{-tau}: tau is the time-like variable,
 * increasing down the hopper) the r-derivative is d_r = -(1/r) d_tau and the
 * balance laws become (6) (the OCR'd "d_r" there is d_tau)
 *   d_tau U + d_theta F(U) = G(tau, theta, U),
 *   U = (T_rr, T_rt),   F(U) = -(T_rt, T_tt),   T_tt = h(T_rr, T_rt).
 *
 * Closure (9), the passive root of (4) for T_tt:
 *   h(a, b) = alpha a + sqrt(beta a^2 + gamma b^2),
 *   alpha = (1 + s^2)/(1 - s^2), beta = 4 s^2/(1 - s^2)^2, gamma = -4/(1 - s^2).
 * The square root is real iff |T_rt/T_rr| <= tan(delta); in the Sokolovskii
 * variables (8) T_rr = sigma(1 - s cos 2psi), T_tt = sigma(1 + s cos 2psi),
 * T_rt = -sigma s sin 2psi this root is the physical T_tt iff
 * |psi| <= eps := pi/4 - delta/2 (for eps < |psi| < pi/4, still passive, the
 * other root is, and |T_rt/T_rr| < tan(delta) again: test psi of the full
 * tensor for data that come with their own T_tt, e.g. rotated data).
 *
 * Variables (Physics/variables):
 *  - scaled:   U = T/(rho g r). A radial (Jenike) field T = r T(theta) is a
 *              steady state of the scaled system; the sources do not depend
 *              on tau:  G = L(theta) U + U + (cos theta, -sin theta);
 *  - unscaled: U = T/(rho g r0), the paper's form (7)/(11):
 *              G = L(theta) U + e^{-tau} (cos theta, -sin theta).
 * with the linear part (h = T_tt, c_t = cot theta)
 *   wedge (11): L U = (T_rr - h, 2 T_rt),
 *   cone   (7): L U = ((3-s)/2 T_rr + c_t T_rt - (3+s)/2 h,
 *                      3 T_rt + c_t ((1-s)/2 h - (1+s)/2 T_rr)).
 *
 * Eigenvalues of F'(U) (13), in the Sokolovskii angle of the state:
 *   lambda_1 = -cot(eps - psi) < 0 < lambda_2 = cot(eps + psi),
 * right eigenvectors (1, -lambda_i) (the (1, lambda_i) printed with (13) are
 * those of -F'). Strictly hyperbolic iff |psi| < eps, i.e. iff
 * |T_rt/T_rr| < tan(delta) on the passive branch; |lambda| -> infinity at the
 * limit, where a characteristic becomes tangent to r = const.
 *
 * Roe matrix (section 5): A = -[[0, 1], [alpha + beta abar/xbar, gamma bbar/xbar]]
 * with arithmetic means abar, bbar and xbar = (X(U-) + X(U+))/2,
 * X = sqrt(beta a^2 + gamma b^2); exact: A (U+ - U-) = F(U+) - F(U-).
 *
 * Boundary conditions (section 5): symmetry at theta = 0 (T_rr even, T_rt
 * odd: mirror state (T_rr, -T_rt)); wall friction (15) T_rt = -mu T_tt at
 * theta = theta_w, on the yield cone the linear relation T_rr = chi_w T_rt
 * with chi_w = -(1 - s cos 2psi_w)/(s sin 2psi_w),
 * psi_w = (Phi + arcsin(sin Phi / s))/2, tan Phi = mu. The exterior state
 * keeps the outgoing characteristic (lambda_2 > 0) of the interior trace and
 * takes the incoming one from the wall relation: U+ = U- + kappa r_1 with
 * kappa = (chi_w T_rt- - T_rr-)/(1 + chi_w lambda_1).
 *
 * Admissible set: finite, T_rr > 0 and |T_rt/T_rr| < tan(delta) (on the
 * passive branch |psi| < pi/4 - delta/2). Hyperbolicity margin
 * m = 1 - |T_rt|/(T_rr tan delta) > 0.
 */

#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/vectorization.h>

#include <granular_dg/dg/boundary.h>
#include <granular_dg/dg/limiter.h>
#include <granular_dg/base/parameters.h>
#include <granular_dg/dg/numerical_flux.h>

#include <array>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace granular_dg::hopper
{
  /// One degree in radians (the prm gives angles in degrees).
  constexpr double deg = M_PI / 180.;

  using namespace dealii;

  enum class Geometry
  {
    wedge, ///< d = 2, balance (10), sources (11)
    cone   ///< d = 3, axisymmetric, balance (5), sources (7)
  };

  enum class Variables
  {
    scaled,  ///< U = T/(rho g r): the radial field is a steady state
    unscaled ///< U = T/(rho g r0): the paper's (6)-(7)
  };

  /// Material constants: angle of internal friction delta and of wall
  /// friction Phi (tan Phi = mu), and what follows from them.
  struct MohrCoulomb
  {
    double delta = 0.;
    double Phi   = 0.;

    MohrCoulomb() = default;
    MohrCoulomb(const double delta, const double Phi)
      : delta(delta)
      , Phi(Phi)
    {}

    double s() const { return std::sin(delta); }
    double c() const { return std::cos(delta); }
    double mu() const { return std::tan(Phi); }
    /// alpha, beta, gamma of h(a, b) = alpha a + sqrt(beta a^2 + gamma b^2)
    double alpha() const { return (1 + s() * s()) / (c() * c()); }
    double beta() const { return 4 * s() * s() / (c() * c() * c() * c()); }
    double gamma() const { return -4 / (c() * c()); }
    /// pi/4 - delta/2: the hyperbolicity limit of |psi|
    double hyperbolic_limit() const { return M_PI / 4 - delta / 2; }
    /// pi/4 + delta/2: the radial-field BVP (16) is singular beyond it
    double singular_limit() const { return M_PI / 4 + delta / 2; }
    /// psi at the wall theta = +theta_w (16)-(17)
    double psi_wall() const { return 0.5 * (Phi + std::asin(std::sin(Phi) / s())); }
    /// T_rr = chi_w T_rt at the wall (section 5)
    double chi_wall() const
    {
      const double p = psi_wall();
      return -(1 - s() * std::cos(2 * p)) / (s() * std::sin(2 * p));
    }
  };

  /// Stress tensor components (T_rr, T_rt, T_tt, T_pp) from the Sokolovskii
  /// variables (8).
  inline std::array<double, 4>
  sokolovskii_stresses(const double sigma, const double psi, const double s)
  {
    return {{sigma * (1 - s * std::cos(2 * psi)), -sigma * s * std::sin(2 * psi),
             sigma * (1 + s * std::cos(2 * psi)), sigma * (1 + s)}};
  }

  /// The Sokolovskii angle of a full in-plane tensor (T_rr, T_rt, T_tt) at
  /// yield: 2 psi = atan2(-2 T_rt, T_tt - T_rr), |psi| <= pi/2.
  inline double
  sokolovskii_angle(const double T_rr, const double T_rt, const double T_tt)
  {
    return 0.5 * std::atan2(-2 * T_rt, T_tt - T_rr);
  }

  /// Rotate the in-plane components of a stress tensor from the frame
  /// (e_R, e_Theta) of the polar angle Theta to that of theta at the same
  /// point: T' = Q^T T Q with Q = [[cos a, sin a], [-sin a, cos a]],
  /// a = Theta - theta. Returns (T_rr, T_rt, T_tt) in the new frame;
  /// psi' = psi + a (doc/hopper.md).
  inline std::array<double, 3>
  rotate_stress(const double T_rr, const double T_rt, const double T_tt, const double a)
  {
    const double c = std::cos(a), s = std::sin(a);
    // columns of Q: e_r = c e_R - s e_Theta, e_theta = s e_R + c e_Theta
    const double rr = c * c * T_rr - 2 * c * s * T_rt + s * s * T_tt;
    const double rt = c * s * T_rr + (c * c - s * s) * T_rt - c * s * T_tt;
    const double tt = s * s * T_rr + 2 * c * s * T_rt + c * c * T_tt;
    return {{rr, rt, tt}};
  }

  /// The numerical fluxes of the march (Discretization/numerical flux).
  enum class NumericalFlux
  {
    roe_lax_friedrichs,  ///< Lax-Friedrichs with the Roe matrix' spectral radius
    local_lax_friedrichs ///< Rusanov
  };
  inline const EnumNames<NumericalFlux> numerical_flux_names(
    {{NumericalFlux::roe_lax_friedrichs, "roe_lax_friedrichs"},
     {NumericalFlux::local_lax_friedrichs, dg::local_lax_friedrichs_name}});

  /**
   * The physics policy of the marching problem (doc/engine.md), 1D in theta.
   */
  class System
  {
  public:
    static constexpr int          dim             = 1;
    static constexpr unsigned int n_components    = 2;
    /// the component the troubled-cell indicator watches
    /// (Limiter/indicator): T_rr
    static constexpr unsigned int indicator_component = 0;
    static constexpr unsigned int n_coefficients  = 0;
    static constexpr const char  *name            = "Mohr-Coulomb hopper stress (passive state)";
    static constexpr bool         has_source_term = true;
    /// theta = 0: the mirror state (T_rt odd)
    static constexpr dg::BoundaryKind symmetry = dg::physics_boundary_kind(0);
    /// theta = theta_w: Coulomb friction T_rr = chi_w T_rt (section 5)
    static constexpr dg::BoundaryKind friction_wall = dg::physics_boundary_kind(1);

    template <typename Number>
    using State = Tensor<1, n_components, Number>;
    template <typename Number>
    using Flux = Tensor<1, n_components, Tensor<1, dim, Number>>;
    template <typename Number>
    using Coefficients = std::array<Number, n_coefficients>;

    System(const Geometry geometry, const Variables variables, const MohrCoulomb &material,
           const NumericalFlux flux = NumericalFlux::roe_lax_friedrichs)
      : flux_type(flux)
      , geometry(geometry)
      , variables(variables)
      , material(material)
      , s(material.s())
      , tan_delta(std::tan(material.delta))
      , alpha(material.alpha())
      , beta(material.beta())
      , gamma(material.gamma())
      , chi_w(material.chi_wall())
    {}

    Coefficients<double>
    coefficients(const types::material_id) const
    {
      return {};
    }

    static std::vector<std::string>
    component_names()
    {
      return {"T_rr", "T_rtheta"};
    }

    static std::vector<std::string>
    derived_names()
    {
      return {"T_thetatheta", "T_phiphi", "psi_deg", "hyperbolicity_margin"};
    }

    /// T_tt, T_pp (cone: Haar-von Karman; wedge: the mean stress sigma, a
    /// convention that enters no equation), psi in degrees and the margin.
    std::vector<double>
    derived(const State<double> &U, const Coefficients<double> &) const
    {
      const double T_tt = h(U[0], U[1]);
      return {T_tt, phiphi(U[0], T_tt), psi(U) * 180. / M_PI, hyperbolicity_margin(U)};
    }

    double
    phiphi(const double T_rr, const double T_tt) const
    {
      return (geometry == Geometry::cone ? 0.5 * (1 + s) : 0.5) * (T_rr + T_tt);
    }

    /// X^2 = beta a^2 + gamma b^2 >= 0 iff |b/a| <= tan(delta)
    template <typename Number>
    Number
    root_argument(const Number &a, const Number &b) const
    {
      return beta * a * a + gamma * b * b;
    }

    /// X = sqrt(beta a^2 + gamma b^2), clamped at 0: never a NaN (states
    /// outside are caught by admissibility_violation()).
    template <typename Number>
    Number
    root(const Number &a, const Number &b) const
    {
      return std::sqrt(std::max(root_argument(a, b), Number(0.)));
    }

    /// A floor for X in the eigenvalues, 1e-6 of its value at T_rt = 0:
    /// speeds stay finite (|lambda| <~ 1e6) for states at or beyond the
    /// hyperbolicity limit, which the admissibility check then reports.
    template <typename Number>
    Number
    root_floor(const Number &a) const
    {
      return Number(1e-6 * std::sqrt(beta)) * std::abs(a) + Number(1e-300);
    }

    /// The closure (9): T_tt = h(T_rr, T_rt) on the passive branch.
    template <typename Number>
    Number
    h(const Number &a, const Number &b) const
    {
      return alpha * a + root(a, b);
    }

    /// Sokolovskii angle of a state (passive branch).
    double
    psi(const State<double> &U) const
    {
      return sokolovskii_angle(U[0], U[1], h(U[0], U[1]));
    }

    /// 1 - |T_rt|/(T_rr tan delta): > 0 iff strictly hyperbolic (T_rr > 0).
    double
    hyperbolicity_margin(const State<double> &U) const
    {
      return 1. - std::abs(U[1]) / (std::abs(U[0]) * tan_delta);
    }

    template <typename Number>
    Flux<Number>
    flux(const State<Number> &U, const Coefficients<Number> &) const
    {
      Flux<Number> F;
      F[0][0] = -U[1];
      F[1][0] = -h(U[0], U[1]);
      return F;
    }

    /// Eigenvalues (lambda_1, lambda_2) of F'(U) = -[[0, 1], [h_a, h_b]]:
    /// lambda = -mu with mu^2 - h_b mu - h_a = 0.
    template <typename Number>
    std::array<Number, 2>
    eigenvalues(const State<Number> &U) const
    {
      const Number X   = std::max(root(U[0], U[1]), root_floor(U[0]));
      const Number h_a = alpha + beta * U[0] / X;
      const Number h_b = gamma * U[1] / X;
      return eigenvalues_of(h_a, h_b);
    }

    /// Eigenvalues of the Roe matrix of (U_m, U_p) (section 5).
    template <typename Number>
    std::array<Number, 2>
    roe_eigenvalues(const State<Number> &U_m, const State<Number> &U_p) const
    {
      const Number xbar = std::max(Number(0.5) * (root(U_m[0], U_m[1]) + root(U_p[0], U_p[1])),
                                   root_floor(Number(0.5) * (U_m[0] + U_p[0])));
      const Number h_a = alpha + beta * Number(0.5) * (U_m[0] + U_p[0]) / xbar;
      const Number h_b = gamma * Number(0.5) * (U_m[1] + U_p[1]) / xbar;
      return eigenvalues_of(h_a, h_b);
    }

    template <typename Number>
    Number
    max_wave_speed(const State<Number> &U, const Coefficients<Number> &) const
    {
      const auto l = eigenvalues(U);
      return std::max(std::abs(l[0]), std::abs(l[1]));
    }

    /// The numerical flux of the run: Lax-Friedrichs with the Roe matrix'
    /// spectral radius, or Rusanov.
    template <typename Number>
    State<Number>
    numerical_flux(const State<Number>           &U_m,
                   const State<Number>           &U_p,
                   const Tensor<1, dim, Number>  &n,
                   const Coefficients<Number>    &a_m,
                   const Coefficients<Number>    &a_p) const
    {
      if (flux_type != NumericalFlux::roe_lax_friedrichs)
        return dg::local_lax_friedrichs(*this, U_m, U_p, n, a_m, a_p);
      // Lax-Friedrichs with the spectral radius of the Roe matrix
      const auto   l      = roe_eigenvalues(U_m, U_p);
      const Number lambda = std::max(std::abs(l[0]), std::abs(l[1]));
      const auto   F_m = flux(U_m, a_m), F_p = flux(U_p, a_p);
      State<Number> F;
      for (unsigned int c = 0; c < n_components; ++c)
        F[c] = Number(0.5) * (F_m[c][0] + F_p[c][0]) * n[0] +
               Number(0.5) * lambda * (U_m[c] - U_p[c]);
      return F;
    }

    /// Exterior states: symmetry (theta = 0) mirrors T_rt; friction_wall is
    /// the wall at theta = theta_w (normal +1) through the
    /// characteristic boundary state of section 5; outflow copies.
    template <typename Number>
    State<Number>
    boundary_state(const dg::BoundaryKind        kind,
                   const State<Number>          &U_m,
                   const Tensor<1, dim, Number> &,
                   const State<Number>          &,
                   const Coefficients<Number>   &) const
    {
      State<Number> U_p = U_m;
      switch (kind)
        {
          case dg::BoundaryKind::outflow:
            break;
          case symmetry:
            U_p[1] = -U_m[1];
            break;
          case friction_wall:
            U_p = wall_state(U_m);
            break;
          default:
            AssertThrow(false, ExcMessage("hopper: boundary kinds are symmetry, "
                                          "friction_wall and outflow"));
        }
      return U_p;
    }

    /// The wall state of section 5: U+ = U- + kappa r_1 (the outgoing
    /// characteristic u_2 of U- kept, r_1 = (1, -lambda_1) the incoming
    /// direction, lambda_1 < 0 at the right wall) on T_rr = chi_w T_rt.
    template <typename Number>
    State<Number>
    wall_state(const State<Number> &U_m) const
    {
      const Number lambda_1 = eigenvalues(U_m)[0];
      // a frictionless wall (Phi = 0, chi_w = -inf): the limit T_rt+ = 0
      const Number kappa = std::isinf(chi_w) ?
                             U_m[1] / lambda_1 :
                             (chi_w * U_m[1] - U_m[0]) / (Number(1.) + chi_w * lambda_1);
      State<Number> U_p;
      U_p[0] = U_m[0] + kappa;
      U_p[1] = U_m[1] - kappa * lambda_1;
      return U_p;
    }

    /// What the friction wall tells the limiter (dg::ModalLimiter): the
    /// incoming characteristic (lambda_i n < 0) at the wall is set by the
    /// wall relation, its value U_b = wall_state(U_face) (the outgoing part of
    /// the cell's trace kept); the ghost cell reflects the cell through it,
    /// ghost - avg = 2 (U_b - avg). The outgoing field gets no information
    /// from the wall and takes the interior difference. Symmetry keeps the
    /// default: its mirror state is the exact average of the mirror cell.
    std::optional<dg::LimiterBoundary<n_components>>
    limiter_boundary(const dg::BoundaryKind kind, const State<double> &avg,
                     const State<double> &face_value, const Tensor<1, dim> &n,
                     const State<double> &, const Coefficients<double> &,
                     const Tensor<2, n_components> *L) const
    {
      if (kind != friction_wall)
        return std::nullopt;
      const State<double>                D = 2. * (wall_state(face_value) - avg);
      dg::LimiterBoundary<n_components> b;
      if (L != nullptr)
        {
          b.difference  = (*L) * D;
          const auto l  = eigenvalues(avg);
          for (unsigned int i = 0; i < n_components; ++i)
            b.known[i] = l[i] * n[0] < 0;
        }
      else
        {
          b.difference = D;
          b.known.fill(true);
        }
      return b;
    }

    /// What source() needs of the position theta (the optional
    /// source_position() of doc/engine.md: the line engine evaluates it once
    /// per quadrature point instead of once per point and stage).
    template <typename Number>
    struct Position
    {
      Number cos_theta, sin_theta;
      Number cot_theta; ///< cone only (0 for the wedge)
    };

    template <typename Number>
    Position<Number>
    source_position(const Point<dim, Number> &x) const
    {
      const Number theta = x[0];
      return {std::cos(theta), std::sin(theta),
              geometry == Geometry::cone ? Number(1.) / std::tan(theta) : Number(0.)};
    }

    /// G(tau, theta, U); x[0] = theta, t = tau.
    template <typename Number>
    State<Number>
    source(const State<Number> &U, const Point<dim, Number> &x, const double tau,
           const Coefficients<Number> &coefficients) const
    {
      return source(U, source_position(x), tau, coefficients);
    }

    /// G at a position of source_position().
    template <typename Number>
    State<Number>
    source(const State<Number> &U, const Position<Number> &x, const double tau,
           const Coefficients<Number> &) const
    {
      const Number &a = U[0], &b = U[1];
      const Number  T_tt  = h(a, b);
      const double  scale = variables == Variables::scaled ? 1. : 0.;
      const double  w     = variables == Variables::scaled ? 1. : std::exp(-tau);
      State<Number> G;
      if (geometry == Geometry::wedge)
        {
          G[0] = a - T_tt;
          G[1] = Number(2.) * b;
        }
      else
        {
          const Number &cot = x.cot_theta;
          G[0] = Number(0.5 * (3 - s)) * a + cot * b - Number(0.5 * (3 + s)) * T_tt;
          G[1] = Number(3.) * b + cot * (Number(0.5 * (1 - s)) * T_tt - Number(0.5 * (1 + s)) * a);
        }
      G[0] += scale * a + w * x.cos_theta;
      G[1] += scale * b - w * x.sin_theta;
      return G;
    }

    /// Eigenvectors of n F'(U): R = [r_1 | r_2], r_i = (1, -lambda_i), L = R^{-1}.
    void
    eigenvectors(const State<double> &U, const Tensor<1, dim> &, const Coefficients<double> &,
                 Tensor<2, n_components> &L, Tensor<2, n_components> &R) const
    {
      const auto l = eigenvalues(U);
      R[0][0] = R[0][1] = 1.;
      R[1][0]           = -l[0];
      R[1][1]           = -l[1];
      L = invert(R);
    }

    /// Whether U is admissible: admissibility_violation(U, a) == "" without
    /// building the message (the check of every stage).
    bool
    is_admissible(const State<double> &U, const Coefficients<double> &) const
    {
      return std::isfinite(U[0]) && std::isfinite(U[1]) && U[0] > 0 &&
             hyperbolicity_margin(U) > 0;
    }

    /// "" when U is admissible, otherwise the failed test.
    std::string
    admissibility_violation(const State<double> &U, const Coefficients<double> &) const
    {
      if (!std::isfinite(U[0]) || !std::isfinite(U[1]))
        return "state is not finite";
      if (!(U[0] > 0))
        {
          std::ostringstream s;
          s.precision(6);
          s << "T_rr = " << U[0] << " <= 0: not a compressive passive state";
          return s.str();
        }
      const double m = hyperbolicity_margin(U);
      if (!(m > 0))
        {
          std::ostringstream s;
          s.precision(6);
          s << "loss of hyperbolicity: |T_rtheta/T_rr| = " << std::abs(U[1] / U[0])
            << " >= tan(delta) = " << tan_delta << " (margin " << m
            << "; on the passive branch |psi| reaches pi/4 - delta/2 = "
            << material.hyperbolic_limit() * 180 / M_PI << " deg)";
          return s.str();
        }
      return "";
    }

    /// No energy for the stress problem: 0 (the generic time series column).
    double
    energy(const State<double> &, const Coefficients<double> &) const
    {
      return 0.;
    }

    const MohrCoulomb &
    mohr_coulomb() const
    {
      return material;
    }

    Geometry
    get_geometry() const
    {
      return geometry;
    }

    Variables
    get_variables() const
    {
      return variables;
    }

  private:
    template <typename Number>
    static std::array<Number, 2>
    eigenvalues_of(const Number &h_a, const Number &h_b)
    {
      const Number d = std::sqrt(std::max(h_b * h_b + Number(4.) * h_a, Number(0.)));
      // mu = (h_b +- d)/2, lambda = -mu: lambda_1 = -(h_b + d)/2 < 0
      return {{Number(-0.5) * (h_b + d), Number(0.5) * (d - h_b)}};
    }

    NumericalFlux flux_type;
    Geometry    geometry;
    Variables   variables;
    MohrCoulomb material;
    double      s, tan_delta, alpha, beta, gamma, chi_w;
  };
} // namespace granular_dg::hopper
