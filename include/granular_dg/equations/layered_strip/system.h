#pragma once

/**
 * @file
 * Nonlinear elasticity in (possibly layered) media, after LeVeque & Yong (2003)
 * and Kurganov & Pollack:
 * \f[
 *   \varepsilon_t - \nabla\cdot\mathbf u = 0, \qquad
 *   (\rho\mathbf u)_t - \nabla\sigma(\varepsilon) = 0,
 * \f]
 * with strain \f$\varepsilon\f$, velocity \f$\mathbf u\f$ (dim components),
 * density \f$\rho\f$ and modulus \f$K\f$, and one of the stress-strain laws
 *   - (1.4) quadratic: \f$\sigma = K\varepsilon + \beta K^2\varepsilon^2\f$
 *           (linear for \f$\beta = 0\f$),
 *   - (1.5) exponential: \f$\sigma = e^{K\varepsilon} - 1\f$.
 *
 * Conserved variables U = (eps, m_1..m_dim), m = rho u. The flux in direction
 * n is F(U) n = (-u.n, -sigma n). Its eigenvalues are -c, 0 (dim-1 times),
 * +c with the sound speed c = sqrt(sigma'(eps)/rho); right eigenvectors
 * r_(+-) = (1, -+Z n), r_0 = (0, t) with the impedance Z = rho c.
 *
 * Admissible set: finite states with sigma'(eps) > 0 (the system is
 * hyperbolic); for law (1.4) with beta > 0 that is eps > -1/(2 beta K).
 *
 * The material is per cell: coefficients a = (rho, K, beta) from the cell's
 * material_id (layers of a layered medium), so that every function below
 * takes the coefficients of the cell (or of each side of a face).
 */

#include <deal.II/base/tensor.h>
#include <deal.II/base/vectorization.h>

#include <granular_dg/base/parameters.h>
#include <granular_dg/base/vectorized_math.h>
#include <granular_dg/dg/boundary.h>
#include <granular_dg/dg/numerical_flux.h>

#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace granular_dg::layered_strip
{
  using namespace dealii;

  /// The stress-strain laws (1.4) and (1.5) of the central-upwind paper.
  enum class StressLaw
  {
    quadratic,  ///< (1.4) sigma = K eps + beta K^2 eps^2
    exponential ///< (1.5) sigma = exp(K eps) - 1
  };

  /// The numerical fluxes of elasticity (Discretization/numerical flux).
  enum class NumericalFlux
  {
    local_lax_friedrichs, ///< Rusanov, each side with its own material
    impedance ///< the linearised Godunov flux that keeps u.n and sigma continuous
  };
  inline const EnumNames<NumericalFlux> numerical_flux_names(
    {{NumericalFlux::local_lax_friedrichs, dg::local_lax_friedrichs_name},
     {NumericalFlux::impedance, "impedance"}});

  /// Material data of one layer.
  struct Material
  {
    double rho  = 1.;
    double K    = 1.;
    double beta = 0.;
  };

  /// Positions of the material data in the coefficient array.
  enum Coefficient : unsigned int
  {
    density = 0,
    modulus = 1,
    nonlinearity = 2
  };

  template <int dim>
  class System
  {
  public:
    static constexpr unsigned int n_components    = dim + 1;
    /// the component the troubled-cell indicator watches
    /// (Limiter/indicator): the strain (shocks are strain jumps)
    static constexpr unsigned int indicator_component = 0;
    static constexpr unsigned int n_coefficients  = 3;
    static constexpr const char  *name            = "nonlinear elasticity";
    static constexpr bool         has_source_term = false;
    /// zero strain and velocity are at rest in every layer: sigma(0) = 0,
    /// zero flux and zero numerical flux (Time stepping/skip cells at rest)
    static constexpr bool zero_is_rest_state = true;
    /// Limiter/scheme's name for limiting_variables() (stress and velocity)
    static constexpr const char  *limiting_variables_name = "flux_variables";
    /// a prescribed normal stress g[0] (BoundaryCondition::kind)
    static constexpr dg::BoundaryKind traction = dg::physics_boundary_kind(0);

    template <typename Number>
    using State = Tensor<1, n_components, Number>;
    template <typename Number>
    using Flux = Tensor<1, n_components, Tensor<1, dim, Number>>;
    /// (rho, K, beta) of a cell
    template <typename Number>
    using Coefficients = std::array<Number, n_coefficients>;

    /// materials[id] is the material of the cells with material_id id.
    System(const StressLaw law, std::vector<Material> materials,
           const NumericalFlux flux = NumericalFlux::local_lax_friedrichs)
      : law(law)
      , flux_type(flux)
      , materials(std::move(materials))
    {}

    System(const StressLaw law, const Material &material,
           const NumericalFlux flux = NumericalFlux::local_lax_friedrichs)
      : System(law, std::vector<Material>{material}, flux)
    {}

    /// The same system with another numerical flux.
    System
    with_numerical_flux(const NumericalFlux flux) const
    {
      System s    = *this;
      s.flux_type = flux;
      return s;
    }

    Coefficients<double>
    coefficients(const types::material_id id) const
    {
      AssertThrow(id < materials.size(),
                  ExcMessage("cell material_id " + std::to_string(id) + " has no material (" +
                             std::to_string(materials.size()) + " defined)"));
      const Material &m = materials[id];
      return {{m.rho, m.K, m.beta}};
    }

    static Coefficients<double>
    coefficients_of(const Material &m)
    {
      return {{m.rho, m.K, m.beta}};
    }

    static std::vector<std::string>
    component_names()
    {
      std::vector<std::string> names{"strain"};
      const char *m[] = {"momentum_x", "momentum_y", "momentum_z"};
      for (int d = 0; d < dim; ++d)
        names.emplace_back(m[d]);
      return names;
    }

    /// Quantities written next to the conserved ones: velocity and stress.
    static std::vector<std::string>
    derived_names()
    {
      std::vector<std::string> names;
      const char *v[] = {"velocity_x", "velocity_y", "velocity_z"};
      for (int d = 0; d < dim; ++d)
        names.emplace_back(v[d]);
      names.emplace_back("stress");
      return names;
    }

    std::vector<double>
    derived(const State<double> &U, const Coefficients<double> &a) const
    {
      std::vector<double> out;
      for (int d = 0; d < dim; ++d)
        out.push_back(U[1 + d] / a[density]);
      out.push_back(stress(U[0], a));
      return out;
    }

    template <typename Number>
    Number
    stress(const Number &eps, const Coefficients<Number> &a) const
    {
      const Number &K = a[modulus];
      if (law == StressLaw::quadratic)
        return K * eps + (a[nonlinearity] * K * K) * eps * eps;
      else
        return granular_dg::exp(K * eps) - Number(1.);
    }

    /// The strain of a given stress (the inverse law); NaN where the law
    /// cannot reach sigma (then the initial state is reported inadmissible).
    double
    strain_of_stress(const double sigma, const Coefficients<double> &a) const
    {
      const double K = a[modulus], beta = a[nonlinearity];
      if (law == StressLaw::exponential)
        return sigma > -1. ? std::log1p(sigma) / K : std::nan("");
      if (beta == 0.)
        return sigma / K;
      const double disc = 1. + 4. * beta * sigma;
      return disc >= 0. ? (std::sqrt(disc) - 1.) / (2. * beta * K) : std::nan("");
    }

    /// sigma'(eps)
    template <typename Number>
    Number
    stress_derivative(const Number &eps, const Coefficients<Number> &a) const
    {
      const Number &K = a[modulus];
      if (law == StressLaw::quadratic)
        return K + (2. * a[nonlinearity] * K * K) * eps;
      else
        return K * granular_dg::exp(K * eps);
    }

    /// sigma(eps) and sigma'(eps) together: the same values as stress() and
    /// stress_derivative(), with one exponential for law (1.5).
    template <typename Number>
    std::pair<Number, Number>
    stress_and_derivative(const Number &eps, const Coefficients<Number> &a) const
    {
      if (law == StressLaw::quadratic)
        return {stress(eps, a), stress_derivative(eps, a)};
      const Number e = granular_dg::exp(a[modulus] * eps);
      return {e - Number(1.), a[modulus] * e};
    }

    /// Sigma(eps) = int_0^eps sigma: the stored energy density.
    double
    stored_energy(const double eps, const Coefficients<double> &a) const
    {
      const double K = a[modulus];
      if (law == StressLaw::quadratic)
        return 0.5 * K * eps * eps + a[nonlinearity] * K * K * eps * eps * eps / 3.;
      else
        return (std::exp(K * eps) - 1.) / K - eps;
    }

    /// Total energy density |m|^2/(2 rho) + Sigma(eps).
    double
    energy(const State<double> &U, const Coefficients<double> &a) const
    {
      double m2 = 0;
      for (int d = 0; d < dim; ++d)
        m2 += U[1 + d] * U[1 + d];
      return 0.5 * m2 / a[density] + stored_energy(U[0], a);
    }

    template <typename Number>
    Flux<Number>
    flux(const State<Number> &U, const Coefficients<Number> &a) const
    {
      Flux<Number> F;
      const Number sigma   = stress(U[0], a);
      const Number inv_rho = Number(1.) / a[density];
      for (int d = 0; d < dim; ++d)
        {
          F[0][d]     = -U[1 + d] * inv_rho;
          F[1 + d][d] = -sigma;
        }
      return F;
    }

    /// Sound speed c = sqrt(sigma'/rho); the largest |eigenvalue| in any
    /// direction. Clamped at 0 for non-hyperbolic states (caught by the
    /// admissibility check, never a NaN here).
    template <typename Number>
    Number
    max_wave_speed(const State<Number> &U, const Coefficients<Number> &a) const
    {
      return sound_speed(stress_derivative(U[0], a), a);
    }

    /// c = sqrt(max(sigma'/rho, 0)) from sigma'.
    template <typename Number>
    static Number
    sound_speed(const Number &stress_slope, const Coefficients<Number> &a)
    {
      const Number s = stress_slope / a[density];
      return std::sqrt(std::max(s, Number(0.)));
    }

    /// phi(eps) = int_0^eps c(e) de: the strain part of the Riemann
    /// invariants u.n -+ phi(eps) of the characteristic fields +-c.
    double
    riemann_strain(const double eps, const Coefficients<double> &a) const
    {
      const double K = a[modulus], rho = a[density], beta = a[nonlinearity];
      if (law == StressLaw::exponential)
        return 2. / std::sqrt(K * rho) * std::expm1(0.5 * K * eps);
      if (beta == 0.)
        return std::sqrt(K / rho) * eps;
      const double base = std::max(K + 2. * beta * K * K * eps, 0.);
      return (base * std::sqrt(base) - K * std::sqrt(K)) / (3. * beta * K * K * std::sqrt(rho));
    }

    /// The strain of a value of riemann_strain() (clamped where the law
    /// loses hyperbolicity).
    double
    strain_of_riemann(const double phi, const Coefficients<double> &a) const
    {
      const double K = a[modulus], rho = a[density], beta = a[nonlinearity];
      if (law == StressLaw::exponential)
        return 2. / K * std::log1p(std::max(0.5 * phi * std::sqrt(K * rho), -1. + 1e-300));
      if (beta == 0.)
        return phi / std::sqrt(K / rho);
      const double base = std::max(3. * beta * K * K * std::sqrt(rho) * phi + K * std::sqrt(K), 0.);
      return (std::cbrt(base * base) - K) / (2. * beta * K * K);
    }

    /// The transmissive state: the outgoing Riemann invariant u.n - phi(eps)
    /// (constant along the characteristic +c leaving through the face) of
    /// the interior trace kept, the incoming one u.n + phi(eps) that of the
    /// material at rest (0), the tangential velocity kept. A simple wave that leaves gets U_p = U_m (no
    /// reflection); what would come in from outside is nothing. (U_p = U_m
    /// instead lets the incoming field take the interior's value: at degree
    /// >= 1 a neutral mode of the last cell then grows and reflects the
    /// wave as tension, doc/layered_strip.md.)
    State<double>
    outflow_state(const State<double> &U_m, const Tensor<1, dim> &n,
                  const Coefficients<double> &a) const
    {
      const double rho = a[density];
      double       un  = 0;
      for (int d = 0; d < dim; ++d)
        un += U_m[1 + d] * n[d] / rho;
      const double  phi = 0.5 * (riemann_strain(U_m[0], a) - un);
      State<double> U_p;
      U_p[0] = strain_of_riemann(phi, a);
      for (int d = 0; d < dim; ++d)
        U_p[1 + d] = U_m[1 + d] - rho * (un + phi) * n[d];
      return U_p;
    }

    /// outflow_state() lane by lane of a batch of faces.
    template <typename Number>
    State<Number>
    outflow_state(const State<Number> &U_m, const Tensor<1, dim, Number> &n,
                  const Coefficients<Number> &a) const
    {
      State<Number> U_p;
      for (unsigned int v = 0; v < Number::size(); ++v)
        {
          State<double>        u;
          Tensor<1, dim>       nv;
          Coefficients<double> av;
          for (unsigned int c = 0; c < n_components; ++c)
            u[c] = U_m[c][v];
          for (int d = 0; d < dim; ++d)
            nv[d] = n[d][v];
          for (unsigned int i = 0; i < n_coefficients; ++i)
            av[i] = a[i][v];
          const auto p = outflow_state(u, nv, av);
          for (unsigned int c = 0; c < n_components; ++c)
            U_p[c][v] = p[c];
        }
      return U_p;
    }

    /// Exterior state of a boundary face from the kind and its data g
    /// (dim values of the Function at the point: wall velocity for a wall,
    /// prescribed traction sigma for a traction boundary (first value),
    /// the full exterior state for Dirichlet; outflow: outflow_state()).
    template <typename Number>
    State<Number>
    boundary_state(const dg::BoundaryKind         kind,
                   const State<Number>           &U_m,
                   const Tensor<1, dim, Number>  &normal,
                   const State<Number>           &g,
                   const Coefficients<Number>    &a) const
    {
      const Number &rho = a[density];
      State<Number> U_p = U_m;
      switch (kind)
        {
          case dg::BoundaryKind::outflow:
            U_p = outflow_state(U_m, normal, a);
            break;
          case dg::BoundaryKind::dirichlet:
            U_p = g;
            break;
          case dg::BoundaryKind::wall:
            {
              // mirror state: the Riemann problem with the interior state
              // has u.n = u_wall.n at the wall; g[1..dim] is the wall velocity
              Number un_m = 0, un_w = 0;
              for (int d = 0; d < dim; ++d)
                {
                  un_m += U_m[1 + d] * normal[d];
                  un_w += g[1 + d] * normal[d];
                }
              const Number dm = 2. * (rho * un_w - un_m);
              for (int d = 0; d < dim; ++d)
                U_p[1 + d] += dm * normal[d];
              break;
            }
          case traction:
            {
              // sigma(eps_p) = 2 g - sigma(eps_m) so that the average is g;
              // solved with the linearisation at eps_m
              const Number s_m = stress(U_m[0], a);
              U_p[0] += 2. * (g[0] - s_m) / stress_derivative(U_m[0], a);
              break;
            }
          default:
            AssertThrow(false, ExcMessage("elasticity knows outflow, dirichlet, wall and "
                                          "traction boundaries"));
        }
      return U_p;
    }

    /// Interface-aware flux: the linearised Godunov (acoustic) state with
    /// impedances Z_m, Z_p that makes u.n and sigma continuous; the flux is
    /// evaluated from (u*, sigma*). Returns F* . n.
    template <typename Number>
    State<Number>
    impedance_flux(const State<Number>          &U_m,
                   const State<Number>          &U_p,
                   const Tensor<1, dim, Number> &n,
                   const Coefficients<Number>   &a_m,
                   const Coefficients<Number>   &a_p) const
    {
      // sigma and sigma' of each side from one evaluation of the law
      const auto [s_m, ds_m] = stress_and_derivative(U_m[0], a_m);
      const auto [s_p, ds_p] = stress_and_derivative(U_p[0], a_p);
      const Number Z_m       = a_m[density] * sound_speed(ds_m, a_m);
      const Number Z_p       = a_p[density] * sound_speed(ds_p, a_p);
      Number       un_m = 0, un_p = 0;
      for (int d = 0; d < dim; ++d)
        {
          un_m += U_m[1 + d] * n[d];
          un_p += U_p[1 + d] * n[d];
        }
      un_m /= a_m[density];
      un_p /= a_p[density];
      const Number inv = Number(1.) / (Z_m + Z_p);
      const Number u_star = (Z_m * un_m + Z_p * un_p + s_p - s_m) * inv;
      const Number s_star = (Z_p * s_m + Z_m * s_p + Z_m * Z_p * (un_p - un_m)) * inv;
      State<Number> F;
      F[0] = -u_star;
      for (int d = 0; d < dim; ++d)
        F[1 + d] = -s_star * n[d];
      return F;
    }

    /// The numerical flux of the run (the impedance flux or Rusanov).
    template <typename Number>
    State<Number>
    numerical_flux(const State<Number>            &U_m,
                   const State<Number>            &U_p,
                   const Tensor<1, dim, Number>   &n,
                   const Coefficients<Number>     &a_m,
                   const Coefficients<Number>     &a_p) const
    {
      if (flux_type == NumericalFlux::impedance)
        return impedance_flux(U_m, U_p, n, a_m, a_p);
      return dg::local_lax_friedrichs(*this, U_m, U_p, n, a_m, a_p);
    }

    /// Left (rows of L) and right (columns of R) eigenvectors of the flux
    /// Jacobian in direction n at U; L R = I. Order: -c, 0.., +c.
    template <typename Number>
    void
    eigenvectors(const State<Number>               &U,
                 const Tensor<1, dim, Number>      &n,
                 const Coefficients<Number>        &a,
                 Tensor<2, n_components, Number>   &L,
                 Tensor<2, n_components, Number>   &R) const
    {
      const Number Z = a[density] * max_wave_speed(U, a);
      L = Tensor<2, n_components, Number>();
      R = Tensor<2, n_components, Number>();
      // lambda = -c: r = (1, Z n), l = (1/2, n/(2Z))
      // lambda = +c: r = (1, -Z n), l = (1/2, -n/(2Z))
      const unsigned int last = n_components - 1;
      R[0][0] = R[0][last] = 1.;
      L[0][0] = L[last][0] = 0.5;
      for (int d = 0; d < dim; ++d)
        {
          R[1 + d][0]    = Z * n[d];
          R[1 + d][last] = -Z * n[d];
          L[0][1 + d]    = 0.5 * n[d] / Z;
          L[last][1 + d] = -0.5 * n[d] / Z;
        }
      if constexpr (dim == 2)
        {
          // zero eigenvalue: tangential momentum t = (-n_y, n_x)
          R[1][1] = L[1][1] = -n[1];
          R[2][1] = L[1][2] = n[0];
        }
    }

    /// The variables of the flux_variables limiter: W = (sigma, u), which are
    /// continuous across material interfaces (the conserved eps and m jump).
    State<double>
    limiting_variables(const State<double> &U, const Coefficients<double> &a) const
    {
      State<double> W;
      W[0] = stress(U[0], a);
      for (int d = 0; d < dim; ++d)
        W[1 + d] = U[1 + d] / a[density];
      return W;
    }

    /// dW/dU = diag(sigma'(eps), 1/rho, ..).
    template <typename Number>
    Tensor<2, n_components, Number>
    limiting_jacobian(const State<Number> &U, const Coefficients<Number> &a) const
    {
      Tensor<2, n_components, Number> J;
      J[0][0] = stress_derivative(U[0], a);
      for (int d = 0; d < dim; ++d)
        J[1 + d][1 + d] = 1. / a[density];
      return J;
    }

    /// Whether U is admissible (admissibility_violation() words why not);
    /// with VectorizedArray: in every lane.
    template <typename Number>
    bool
    is_admissible(const State<Number> &U, const Coefficients<Number> &a) const
    {
      for (unsigned int c = 0; c < n_components; ++c)
        if (!all_finite(U[c]))
          return false;
      // sigma' > 0 and a finite stress (the exponential law can overflow)
      const auto [s, ds] = stress_and_derivative(U[0], a);
      return all_positive(ds) && all_finite(s);
    }

    std::string
    admissibility_violation(const State<double> &U, const Coefficients<double> &a) const
    {
      for (unsigned int c = 0; c < n_components; ++c)
        if (!std::isfinite(U[c]))
          return "state is not finite";
      const double sp = stress_derivative(U[0], a);
      if (!(sp > 0.))
        return "loss of hyperbolicity: sigma'(eps) = " + std::to_string(sp) +
               " <= 0";
      if (!std::isfinite(stress(U[0], a)))
        return "stress is not finite";
      return "";
    }

    const std::vector<Material> &
    material_table() const
    {
      return materials;
    }

  private:
    StressLaw             law;
    NumericalFlux         flux_type;
    std::vector<Material> materials;
  };
} // namespace granular_dg::layered_strip
