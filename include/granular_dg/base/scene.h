#pragma once

#include <deal.II/base/parameter_handler.h>

#include <functional>
#include <string>
#include <vector>

namespace granular_dg
{
  /**
   * A scene of the program: a name (`set scene = NAME` in a prm file), a
   * one-line description, its parameter declarations and its run function.
   * A scene registers itself with a static RegisterScene object in one of its
   * own source files, so that a new scene is a new folder and nothing else:
   *
   *   namespace { const RegisterScene registration(make_scene()); }
   *
   * The program links every scene (CMake puts the whole library into the
   * executable).
   */
  struct Scene
  {
    std::string name;
    std::string description;
    /// declare every parameter of the scene (base and dg sections included)
    std::function<void(dealii::ParameterHandler &)> declare;
    /// run the scene with the parsed parameters
    std::function<void(dealii::ParameterHandler &)> run;
  };

  /// Every registered scene, sorted by name.
  const std::vector<Scene> &
  registered_scenes();

  /// The scene called name, or nullptr.
  const Scene *
  find_registered_scene(const std::string &name);

  /// "a|b|c": the names of the registered scenes.
  std::string
  scene_names();

  /// Registers a scene when the program starts.
  struct RegisterScene
  {
    explicit RegisterScene(Scene scene);
  };
} // namespace granular_dg
