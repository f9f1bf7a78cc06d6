#pragma once

/**
 * @file
 * Scalar conservation laws on the edges of a star network, after Musch,
 * Fjordholm & Risebro, "Well-posedness theory for nonlinear scalar
 * conservation laws on networks", Networks and Heterogeneous Media 17 (2022)
 * (Musch, Fjordholm & Risebro 2022; arXiv 2102.06400). On every edge k
 * \f[
 *   u^k_t + f^k(u^k)_x = 0, \qquad x \in (0, L_k),  \qquad (1.2), (2.1)
 * \f]
 * with x running in the direction of the edge: an ingoing edge ends at the
 * vertex (x = L_k), an outgoing edge starts there (x = 0), a roundabout
 * (loop) does both. The edges are coupled by the vertex; weak solutions
 * satisfy the Rankine-Hugoniot condition (2.5)
 *   sum_{k in} f^k(u^k(vertex-)) = sum_{k out} f^k(u^k(vertex+)).
 *
 * One scalar unknown u (n_components = 1). The flux of an edge is one of
 *   - linear:  f(u) = a u                            (Example 7.3)
 *   - burgers: f(u) = u^2 / 2                        (Examples 7.1, 7.4, 7.5)
 *   - traffic: f(u) = alpha f_0(u / alpha), f_0(u) = 4 u (1 - u), i.e.
 *              f(u) = 4 u (1 - u / alpha)            (Example 7.2)
 * The characteristic speed ("eigenvalue") is f'(u): a, u and 4 - 8 u / alpha.
 * Linear flux is monotone; Burgers' is convex with its minimum at 0, the
 * traffic flux concave with its maximum (the road capacity alpha) at
 * u = alpha / 2. The paper's theory (Sections 5, 6) covers monotone fluxes;
 * the examples only visit the increasing branches (u >= 0 for Burgers,
 * u <= alpha / 2 for traffic).
 *
 * Numerical fluxes F(u_l, u_r) (left and right state in edge direction):
 *   - upwind: Engquist-Osher, F = f^+(u_l) + f^-(u_r) with
 *     f^+(u) = f(c) + int_c^u max(f', 0), f^-(u) = int_c^u min(f', 0) and c
 *     the extremum (0 for Burgers, alpha/2 for traffic). For a monotone
 *     increasing f it is the upwind flux f(u_l) of the paper (Section 5);
 *   - godunov: the exact Riemann solver's flux (= upwind for monotone f);
 *   - local_lax_friedrichs: (f(u_l) + f(u_r))/2 - lambda/2 (u_r - u_l),
 *     lambda = max(|f'(u_l)|, |f'(u_r)|), for comparison: it is monotone but
 *     has other discrete stationary states at the vertex (Definition 4.4).
 * All three are monotone (nondecreasing in u_l, nonincreasing in u_r) under
 * the CFL condition (4.7) dt max|f'| <= dx / 2.
 *
 * Admissible set: finite states. (Traffic densities outside [0, alpha] are
 * unphysical but the flux is defined there; at degree 0 the scheme is
 * monotone and keeps u in the range of the data by Proposition 4.11.)
 *
 * Every edge has its own System object (its flux law and parameters): one
 * DGOperator per edge and mesh, so there are no per-cell coefficients
 * (n_coefficients = 0). A flux that varied inside an edge would use them.
 */

#include <deal.II/base/tensor.h>
#include <deal.II/base/vectorization.h>

#include <granular_dg/base/parameters.h>
#include <granular_dg/dg/boundary.h>
#include <granular_dg/dg/numerical_flux.h>

#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace granular_dg::network
{
  using namespace dealii;

  /// The numerical fluxes of scalar laws (Discretization/numerical flux).
  enum class NumericalFlux
  {
    upwind,              ///< Engquist-Osher
    godunov,             ///< the exact Riemann solver's flux
    local_lax_friedrichs ///< Rusanov
  };
  inline const EnumNames<NumericalFlux> numerical_flux_names(
    {{NumericalFlux::upwind, "upwind"},
     {NumericalFlux::godunov, "godunov"},
     {NumericalFlux::local_lax_friedrichs, dg::local_lax_friedrichs_name}});

  /// The flux laws of the examples.
  enum class FluxLaw
  {
    linear,  ///< f = a u
    burgers, ///< f = u^2 / 2
    traffic  ///< f = 4 u (1 - u / alpha)
  };
  /// Their names in the prm and in CSV graph files.
  inline const EnumNames<FluxLaw> flux_law_names({{FluxLaw::linear, "linear"},
                                                  {FluxLaw::burgers, "burgers"},
                                                  {FluxLaw::traffic, "traffic"}});

  /// A flux law with its parameters.
  struct FluxFunction
  {
    FluxLaw law   = FluxLaw::burgers;
    double  speed = 1.; ///< a of the linear flux
    double  alpha = 1.; ///< capacity scaling of the traffic flux

    template <typename Number>
    Number
    value(const Number &u) const
    {
      switch (law)
        {
          case FluxLaw::linear:
            return speed * u;
          case FluxLaw::burgers:
            return 0.5 * u * u;
          default:
            return 4. * u * (Number(1.) - u * (1. / alpha));
        }
    }

    /// f'(u), the characteristic speed
    template <typename Number>
    Number
    derivative(const Number &u) const
    {
      switch (law)
        {
          case FluxLaw::linear:
            return Number(speed);
          case FluxLaw::burgers:
            return u;
          default:
            return Number(4.) - u * (8. / alpha);
        }
    }

    /// The increasing part f^+ of the Engquist-Osher splitting f = f^+ + f^-
    template <typename Number>
    Number
    increasing_part(const Number &u) const
    {
      switch (law)
        {
          case FluxLaw::linear:
            return std::max(speed, 0.) * u;
          case FluxLaw::burgers:
            return value(std::max(u, Number(0.)));
          default:
            return value(std::min(u, Number(0.5 * alpha)));
        }
    }

    /// The decreasing part f^- (f^-(c) = 0 at the extremum c)
    template <typename Number>
    Number
    decreasing_part(const Number &u) const
    {
      switch (law)
        {
          case FluxLaw::linear:
            return std::min(speed, 0.) * u;
          case FluxLaw::burgers:
            return value(std::min(u, Number(0.)));
          default:
            return value(std::max(u, Number(0.5 * alpha))) - alpha;
        }
    }

    /// Engquist-Osher flux; the upwind flux f(u_l) for increasing f
    template <typename Number>
    Number
    engquist_osher(const Number &u_l, const Number &u_r) const
    {
      return increasing_part(u_l) + decreasing_part(u_r);
    }

    /// Godunov flux: min of f over [u_l, u_r] if u_l <= u_r, else the max
    /// over [u_r, u_l]; in closed form for the convex and concave laws.
    template <typename Number>
    Number
    godunov(const Number &u_l, const Number &u_r) const
    {
      switch (law)
        {
          case FluxLaw::linear:
            return engquist_osher(u_l, u_r);
          case FluxLaw::burgers:
            return std::max(value(std::max(u_l, Number(0.))), value(std::min(u_r, Number(0.))));
          default:
            return std::min(value(std::min(u_l, Number(0.5 * alpha))),
                            value(std::max(u_r, Number(0.5 * alpha))));
        }
    }

    template <typename Number>
    Number
    lax_friedrichs(const Number &u_l, const Number &u_r) const
    {
      const Number lambda =
        std::max(std::abs(derivative(u_l)), std::abs(derivative(u_r)));
      return 0.5 * (value(u_l) + value(u_r)) - (0.5 * lambda) * (u_r - u_l);
    }

    /// The numerical flux F(u_l, u_r) in the direction of the edge.
    template <typename Number>
    Number
    numerical_flux(const NumericalFlux type, const Number &u_l, const Number &u_r) const
    {
      switch (type)
        {
          case NumericalFlux::upwind:
            return engquist_osher(u_l, u_r);
          case NumericalFlux::godunov:
            return godunov(u_l, u_r);
          default:
            return lax_friedrichs(u_l, u_r);
        }
    }

    /// "burgers f = u^2/2", for messages and output headers
    std::string
    describe() const
    {
      std::ostringstream s;
      if (law == FluxLaw::linear)
        s << "linear f = " << speed << " u";
      else if (law == FluxLaw::burgers)
        s << "burgers f = u^2/2";
      else
        s << "traffic f = 4 u (1 - u/" << alpha << ")";
      return s.str();
    }
  };

  /// The physics policy of one edge (the contract is in doc/engine.md).
  class System
  {
  public:
    static constexpr unsigned int n_components    = 1;
    /// the component the troubled-cell indicator watches
    /// (Limiter/indicator): u
    static constexpr unsigned int indicator_component = 0;
    static constexpr unsigned int n_coefficients  = 0;
    static constexpr const char  *name            = "scalar conservation law";
    static constexpr bool         has_source_term = false;

    template <typename Number>
    using State = Tensor<1, 1, Number>;
    template <typename Number>
    using Flux = Tensor<1, 1, Tensor<1, 1, Number>>;
    template <typename Number>
    using Coefficients = std::array<Number, 0>;

    explicit System(const FluxFunction &f = {},
                    const NumericalFlux flux = NumericalFlux::upwind)
      : f(f)
      , flux_type(flux)
    {}

    const FluxFunction &
    flux_function() const
    {
      return f;
    }

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
      return {"flux"};
    }

    std::vector<double>
    derived(const State<double> &U, const Coefficients<double> &) const
    {
      return {f.value(U[0])};
    }

    /// The L2 entropy u^2/2 (the "energy" column of the engine).
    double
    energy(const State<double> &U, const Coefficients<double> &) const
    {
      return 0.5 * U[0] * U[0];
    }

    template <typename Number>
    Flux<Number>
    flux(const State<Number> &U, const Coefficients<Number> &) const
    {
      Flux<Number> F;
      F[0][0] = f.value(U[0]);
      return F;
    }

    template <typename Number>
    Number
    max_wave_speed(const State<Number> &U, const Coefficients<Number> &) const
    {
      return std::abs(f.derivative(U[0]));
    }

    /// F* . n on a face with normal n = +-1: F(U_m, U_p) for n = +1, the
    /// face's left state being the interior one, and -F(U_p, U_m) for n = -1.
    template <typename Number>
    State<Number>
    numerical_flux(const State<Number>          &U_m,
                   const State<Number>          &U_p,
                   const Tensor<1, 1, Number>   &n,
                   const Coefficients<Number>   &,
                   const Coefficients<Number>   &) const
    {
      // exact selection: n is exactly +-1 in 1D
      const Number left  = compare_and_apply_mask<SIMDComparison::greater_than>(
        n[0], Number(0.), U_m[0], U_p[0]);
      const Number right = compare_and_apply_mask<SIMDComparison::greater_than>(
        n[0], Number(0.), U_p[0], U_m[0]);
      State<Number> F;
      F[0] = n[0] * f.numerical_flux(flux_type, left, right);
      return F;
    }

    /// outflow: U_p = U_m (zero gradient, the paper's "zero Neumann");
    /// dirichlet: U_p = g (far-end inflow data, or the vertex value).
    template <typename Number>
    State<Number>
    boundary_state(const dg::BoundaryKind       kind,
                   const State<Number>         &U_m,
                   const Tensor<1, 1, Number>  &,
                   const State<Number>         &g,
                   const Coefficients<Number>  &) const
    {
      return kind == dg::BoundaryKind::dirichlet ? g : U_m;
    }

    void
    eigenvectors(const State<double> &, const Tensor<1, 1> &, const Coefficients<double> &,
                 Tensor<2, 1> &L, Tensor<2, 1> &R) const
    {
      L[0][0] = R[0][0] = 1.;
    }

    std::string
    admissibility_violation(const State<double> &U, const Coefficients<double> &) const
    {
      return std::isfinite(U[0]) ? "" : "state is not finite";
    }

  private:
    FluxFunction  f;
    NumericalFlux flux_type;
  };
} // namespace granular_dg::network
