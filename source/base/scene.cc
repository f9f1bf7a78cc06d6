#include <granular_dg/base/scene.h>

#include <algorithm>
#include <stdexcept>

namespace granular_dg
{
  namespace
  {
    std::vector<Scene> &
    registry()
    {
      // a function-local static: initialised before the first registration,
      // whatever the order of the translation units
      static std::vector<Scene> scenes;
      return scenes;
    }
  } // namespace

  RegisterScene::RegisterScene(Scene scene)
  {
    auto &scenes = registry();
    if (find_registered_scene(scene.name))
      throw std::logic_error("two scenes are called '" + scene.name + "'");
    scenes.push_back(std::move(scene));
    std::sort(scenes.begin(), scenes.end(),
              [](const Scene &a, const Scene &b) { return a.name < b.name; });
  }

  const std::vector<Scene> &
  registered_scenes()
  {
    return registry();
  }

  const Scene *
  find_registered_scene(const std::string &name)
  {
    for (const auto &s : registry())
      if (s.name == name)
        return &s;
    return nullptr;
  }

  std::string
  scene_names()
  {
    std::string s;
    for (const auto &scene : registry())
      s += (s.empty() ? "" : "|") + scene.name;
    return s;
  }
} // namespace granular_dg
