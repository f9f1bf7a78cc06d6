#pragma once

#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <string>
#include <vector>

namespace granular_dg
{
  /// A scene: a name, a one-line description, its parameter declarations
  /// (besides the common ones) and its run function. main() dispatches on the
  /// name given by `set scene = NAME` in the prm file.
  struct Scene
  {
    std::string                                     name;
    std::string                                     description;
    std::string                                     fluxes; ///< "a|b" for Discretization/numerical flux
    std::function<void(dealii::ParameterHandler &)> declare;
    std::function<void(dealii::ParameterHandler &)> run;
  };

  const std::vector<Scene> &
  all_scenes();

  namespace elasticity
  {
    Scene
    scene();
  }

  namespace column
  {
    Scene
    scene();
  }

  namespace network
  {
    Scene
    scene();
  }

  namespace hopper
  {
    Scene
    scene();
  }
} // namespace granular_dg
