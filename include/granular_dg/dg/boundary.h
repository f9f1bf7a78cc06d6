#pragma once

#include <deal.II/base/function.h>
#include <deal.II/base/types.h>

#include <map>
#include <memory>

namespace granular_dg::dg
{
  /// How a boundary face gets its exterior state. The physics turns the kind
  /// and the boundary data g (a Function of x and t with one value per
  /// component) into the exterior state U_p in boundary_state(); the
  /// numerical flux does the rest. What g means is the physics' business.
  enum class BoundaryKind
  {
    outflow,   ///< U_p = U_m (transmissive)
    dirichlet, ///< U_p = g
    wall,      ///< mirror state of a wall moving with the velocity in g
    traction,  ///< prescribed normal stress g[0]
    symmetry,  ///< mirror state of a symmetry line (even/odd components)
    custom     ///< a physics-specific condition (e.g. a friction wall)
  };

  template <int dim>
  struct BoundaryCondition
  {
    BoundaryKind                           kind = BoundaryKind::outflow;
    std::shared_ptr<dealii::Function<dim>> data;
  };

  template <int dim>
  using BoundaryMap = std::map<dealii::types::boundary_id, BoundaryCondition<dim>>;
} // namespace granular_dg::dg
