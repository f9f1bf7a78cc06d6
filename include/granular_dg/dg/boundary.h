#pragma once

#include <deal.II/base/function.h>
#include <deal.II/base/types.h>

#include <map>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>

namespace granular_dg::dg
{
  /// How a boundary face gets its exterior state. The physics turns the kind
  /// and the boundary data g (a Function of x and t with one value per
  /// component) into the exterior state U_p in boundary_state(); the
  /// numerical flux does the rest. What g means is the physics' business.
  /// The engine knows the generic kinds below (periodic boundaries are mesh
  /// faces, not kinds); a physics declares its own with
  /// physics_boundary_kind() (a traction boundary, a symmetry line, a
  /// friction wall).
  enum class BoundaryKind : unsigned int
  {
    outflow,   ///< transmissive: what leaves leaves (the physics says how)
    dirichlet, ///< U_p = g
    wall,      ///< mirror state of a wall moving with the velocity in g
    /// the kinds a physics declares (physics_boundary_kind()), named here so
    /// that a switch over a physics' kinds lists enumerators
    physics_0 = 16,
    physics_1,
    physics_2,
    physics_3
  };

  /// The i-th boundary kind of a physics (distinct from the generic ones),
  /// i < 4.
  constexpr BoundaryKind
  physics_boundary_kind(const unsigned int i)
  {
    return static_cast<BoundaryKind>(static_cast<unsigned int>(BoundaryKind::physics_0) + i);
  }

  template <int dim>
  struct BoundaryCondition
  {
    BoundaryKind                           kind = BoundaryKind::outflow;
    std::shared_ptr<dealii::Function<dim>> data;
  };

  template <int dim>
  using BoundaryMap = std::map<dealii::types::boundary_id, BoundaryCondition<dim>>;

  namespace internal
  {
    template <typename Physics, typename State, typename Coefficients, typename = void>
    struct has_is_admissible : std::false_type
    {};
    template <typename Physics, typename State, typename Coefficients>
    struct has_is_admissible<
      Physics, State, Coefficients,
      std::void_t<decltype(std::declval<const Physics &>().is_admissible(
        std::declval<const State &>(), std::declval<const Coefficients &>()))>> : std::true_type
    {};
  } // namespace internal

  /// The admissibility test of a state: the physics' cheap is_admissible(U, a)
  /// when it has one (then admissibility_violation() only words the
  /// failure), otherwise admissibility_violation(U, a) == "".
  template <typename Physics, typename State, typename Coefficients>
  bool
  admissible(const Physics &physics, const State &U, const Coefficients &a)
  {
    if constexpr (internal::has_is_admissible<Physics, State, Coefficients>::value)
      return physics.is_admissible(U, a);
    else
      return physics.admissibility_violation(U, a).empty();
  }
} // namespace granular_dg::dg
