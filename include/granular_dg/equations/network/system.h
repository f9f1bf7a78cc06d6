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
 * Admissible set (admissible_range()): the densities 0 <= u <= alpha of a
 * traffic road (empty to jammed: beyond, f < 0 and cars would drive
 * backwards), every finite u for the linear and Burgers' laws. The vertex
 * value u_0 enters the numerical flux at each edge end (vertex_range()): a
 * road into the vertex takes it as its downstream state, so u_0 <= alpha of
 * every such road (else its flux into the vertex turns negative); a road out
 * of it takes, with the upwind and Godunov fluxes, only the demand
 * min(u_0, alpha/2), so there a queue above its alpha (of a wider road) is
 * its capacity. The single vertex value of the paper's scheme (4.1b) cannot
 * go on where a junction fills beyond a road into it (the network engine
 * stops the run there; doc/network.md).
 *
 * EdgeLaw is what the network engine (granular_dg/network/network.h) asks of
 * the physics of an edge: its flux law with the method's numerical flux.
 */

#include <deal.II/base/vectorization.h>

#include <granular_dg/base/parameters.h>
#include <granular_dg/dg/numerical_flux.h>

#include <array>
#include <cmath>
#include <sstream>
#include <string>
#include <type_traits>

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

  namespace internal
  {
    /// x, not fused with the arithmetic that uses it (a * b + c into one
    /// fma). The sums of the Engquist-Osher and Lax-Friedrichs fluxes take
    /// their terms through it where GCC, compiling the law that branches on
    /// its kind at run time, kept them apart (the branch's join lay between
    /// them): a law fixed at compile time (with_fixed_law()) then rounds as
    /// that one, and the network's results stay the same to the bit. An
    /// empty asm statement (GCC and Clang on x86; elsewhere the compiler
    /// decides).
    template <typename Number>
    DEAL_II_ALWAYS_INLINE inline Number
    unfused(Number x)
    {
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
      if constexpr (std::is_same_v<Number, double>)
        asm("" : "+x"(x));
      else
        asm("" : "+x"(x.data));
#endif
      return x;
    }
  } // namespace internal

  /// A flux law with its parameters. Kind: FluxLaw, or
  /// std::integral_constant<FluxLaw, K> for the law K fixed at compile time
  /// (with_fixed_law(): the same operations, without a branch on the law in
  /// every evaluation).
  template <typename Kind>
  class BasicFluxFunction
  {
  public:
    /// speed: a of the linear flux; alpha: the capacity scale of the traffic flux
    BasicFluxFunction(const FluxLaw law = FluxLaw::burgers, const double speed = 1., const double alpha = 1.)
      : kind(law)
      , advection_speed(speed)
      , capacity(alpha)
      , inverse_alpha(1. / alpha)
      , eight_over_alpha(8. / alpha)
    {}

    /// the law of f fixed at compile time (f.law() == K)
    template <FluxLaw K>
    BasicFluxFunction<std::integral_constant<FluxLaw, K>>
    fixed() const
    {
      AssertDimension(int(law()), int(K));
      return {*this, {}};
    }

    FluxLaw law() const { return FluxLaw(kind); }
    /// the same law with the same parameters (-0 is not 0: a speed's sign
    /// enters the fluxes)
    bool
    operator==(const BasicFluxFunction &g) const
    {
      const auto same = [](const double a, const double b) {
        return a == b && std::signbit(a) == std::signbit(b);
      };
      return law() == g.law() && same(advection_speed, g.advection_speed) && same(capacity, g.capacity);
    }
    double  speed() const { return advection_speed; }
    double  alpha() const { return capacity; }

    template <typename Number>
    DEAL_II_ALWAYS_INLINE inline Number
    value(const Number &u) const
    {
      switch (law())
        {
          case FluxLaw::linear:
            return advection_speed * u;
          case FluxLaw::burgers:
            return 0.5 * u * u;
          default:
            return 4. * u * (Number(1.) - u * inverse_alpha);
        }
    }

    /// f'(u), the characteristic speed
    template <typename Number>
    DEAL_II_ALWAYS_INLINE inline Number
    derivative(const Number &u) const
    {
      switch (law())
        {
          case FluxLaw::linear:
            return Number(advection_speed);
          case FluxLaw::burgers:
            return u;
          default:
            return Number(4.) - u * eight_over_alpha;
        }
    }

    /// The increasing part f^+ of the Engquist-Osher splitting f = f^+ + f^-
    template <typename Number>
    DEAL_II_ALWAYS_INLINE inline Number
    increasing_part(const Number &u) const
    {
      switch (law())
        {
          case FluxLaw::linear:
            return std::max(advection_speed, 0.) * u;
          case FluxLaw::burgers:
            return value(std::max(u, Number(0.)));
          default:
            return value(std::min(u, Number(0.5 * capacity)));
        }
    }

    /// The decreasing part f^- (f^-(c) = 0 at the extremum c)
    template <typename Number>
    DEAL_II_ALWAYS_INLINE inline Number
    decreasing_part(const Number &u) const
    {
      switch (law())
        {
          case FluxLaw::linear:
            return std::min(advection_speed, 0.) * u;
          case FluxLaw::burgers:
            return internal::unfused(value(std::min(u, Number(0.))));
          default:
            return value(std::max(u, Number(0.5 * capacity))) - capacity;
        }
    }

    /// Engquist-Osher flux; the upwind flux f(u_l) for increasing f
    template <typename Number>
    DEAL_II_ALWAYS_INLINE inline Number
    engquist_osher(const Number &u_l, const Number &u_r) const
    {
      return internal::unfused(increasing_part(u_l)) + decreasing_part(u_r);
    }

    /// Godunov flux: min of f over [u_l, u_r] if u_l <= u_r, else the max
    /// over [u_r, u_l]; in closed form for the convex and concave laws.
    template <typename Number>
    DEAL_II_ALWAYS_INLINE inline Number
    godunov(const Number &u_l, const Number &u_r) const
    {
      switch (law())
        {
          case FluxLaw::linear:
            return engquist_osher(u_l, u_r);
          case FluxLaw::burgers:
            return std::max(value(std::max(u_l, Number(0.))), value(std::min(u_r, Number(0.))));
          default:
            return std::min(value(std::min(u_l, Number(0.5 * capacity))),
                            value(std::max(u_r, Number(0.5 * capacity))));
        }
    }

    template <typename Number>
    DEAL_II_ALWAYS_INLINE inline Number
    lax_friedrichs(const Number &u_l, const Number &u_r) const
    {
      const Number lambda =
        std::max(std::abs(derivative(u_l)), std::abs(derivative(u_r)));
      return 0.5 * (internal::unfused(value(u_l)) + internal::unfused(value(u_r))) -
             internal::unfused((0.5 * lambda) * (u_r - u_l));
    }

    /// The numerical flux F(u_l, u_r) in the direction of the edge.
    template <typename Number>
    DEAL_II_ALWAYS_INLINE inline Number
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

    /// [0, alpha] for traffic, the whole line otherwise
    std::array<double, 2>
    admissible_range() const
    {
      if (law() == FluxLaw::traffic)
        return {{0., capacity}};
      return {{-INFINITY, INFINITY}};
    }

    /// "burgers f = u^2/2", for messages and output headers
    std::string
    describe() const
    {
      std::ostringstream s;
      if (law() == FluxLaw::linear)
        s << "linear f = " << advection_speed << " u";
      else if (law() == FluxLaw::burgers)
        s << "burgers f = u^2/2";
      else
        s << "traffic f = 4 u (1 - u/" << capacity << ")";
      return s.str();
    }

  private:
    template <typename>
    friend class BasicFluxFunction;
    template <typename Other>
    BasicFluxFunction(const BasicFluxFunction<Other> &g, const Kind k)
      : kind(k)
      , advection_speed(g.advection_speed)
      , capacity(g.capacity)
      , inverse_alpha(g.inverse_alpha)
      , eight_over_alpha(g.eight_over_alpha)
    {}

    Kind kind;
    /// a of the linear flux, alpha of the traffic flux (the road capacity)
    double advection_speed, capacity;
    /// 1 / alpha and 8 / alpha, divided once: a division in the kernels'
    /// flux is not hoisted out of their loops (it sits in a branch of the law)
    double inverse_alpha, eight_over_alpha;
  };
  using FluxFunction = BasicFluxFunction<FluxLaw>;

  /// The physics of one edge for the network engine (NetworkProblem<Law>):
  /// the flux law f and the numerical flux F of the method. Kind as for
  /// BasicFluxFunction; EdgeLaw is the one the engine stores per edge.
  template <typename Kind>
  struct BasicEdgeLaw
  {
    BasicFluxFunction<Kind> f;
    NumericalFlux           type = NumericalFlux::upwind;

    static constexpr const char *name = "scalar conservation law";

    bool
    operator==(const BasicEdgeLaw &l) const
    {
      return f == l.f && type == l.type;
    }

    template <typename Number>
    DEAL_II_ALWAYS_INLINE inline Number
    value(const Number &u) const
    {
      return f.value(u);
    }

    /// f'(u), the characteristic speed
    template <typename Number>
    DEAL_II_ALWAYS_INLINE inline Number
    derivative(const Number &u) const
    {
      return f.derivative(u);
    }

    /// F(u_l, u_r) in the direction of the edge
    template <typename Number>
    DEAL_II_ALWAYS_INLINE inline Number
    flux(const Number &u_l, const Number &u_r) const
    {
      return f.numerical_flux(type, u_l, u_r);
    }

    /// the states the law admits, [lo, hi] (infinite where unbounded)
    std::array<double, 2>
    admissible_range() const
    {
      return f.admissible_range();
    }

    /// The vertex values u_0 for which the flux through a vertex end of the
    /// edge (incoming: its end, u_0 the right state) is physical: the
    /// admissible range, but at the start of a traffic road the upwind and
    /// Godunov fluxes take the demand min(u_0, alpha/2) and admit any u_0 >= 0.
    std::array<double, 2>
    vertex_range(const bool incoming) const
    {
      auto r = admissible_range();
      if (!incoming && f.law() == FluxLaw::traffic && type != NumericalFlux::local_lax_friedrichs)
        r[1] = INFINITY;
      return r;
    }

    std::string
    describe() const
    {
      return f.describe();
    }

    std::string
    flux_name() const
    {
      return numerical_flux_names.name(type);
    }
  };
  using EdgeLaw = BasicEdgeLaw<FluxLaw>;

  /// body(l) with l the law of edge law fixed at compile time (the network
  /// engine's kernels: evaluations without a branch on the flux law; the
  /// same values to the bit). The engine's default for other laws calls
  /// body(law).
  template <typename Body>
  DEAL_II_ALWAYS_INLINE inline void
  with_fixed_law(const EdgeLaw &law, Body &&body)
  {
    const auto as = [&](auto kind) {
      constexpr FluxLaw K = decltype(kind)::value;
      body(BasicEdgeLaw<std::integral_constant<FluxLaw, K>>{law.f.template fixed<K>(), law.type});
    };
    switch (law.f.law())
      {
        case FluxLaw::linear:
          return as(std::integral_constant<FluxLaw, FluxLaw::linear>());
        case FluxLaw::burgers:
          return as(std::integral_constant<FluxLaw, FluxLaw::burgers>());
        default:
          return as(std::integral_constant<FluxLaw, FluxLaw::traffic>());
      }
  }
} // namespace granular_dg::network
