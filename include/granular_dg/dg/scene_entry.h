#pragma once

#include <granular_dg/base/parameter_binding.h>
#include <granular_dg/base/run_parameters.h>
#include <granular_dg/base/scene.h>
#include <granular_dg/dg/parameters.h>

#include <functional>
#include <string>

namespace granular_dg::dg
{
  /**
   * The registry entry of a DG scene: its parameters are the run's
   * (RunParameters), the method's (DiscretizationParameters with the
   * numerical fluxes and limiting variables its physics offers) and its own
   * (SceneParameters::bind(ParameterBinding &, run, method): every entry once,
   * with its field, pattern, documentation and checks); run gets all three,
   * read and checked:
   *
   *   const RegisterScene registration(dg::scene_entry<MyParameters>(
   *     "name", "description", my_flux_names.selection(), "", run));
   */
  template <typename SceneParameters>
  Scene
  scene_entry(const std::string &name, const std::string &description, const std::string &fluxes,
              const std::string &physics_variables,
              const std::function<void(const RunParameters &, const DiscretizationParameters &,
                                       const SceneParameters &)> &run)
  {
    Scene s;
    s.name        = name;
    s.description = description;
    s.declare     = [=](ParameterHandler &prm) {
      RunParameters::declare(prm);
      DiscretizationParameters::declare(prm, fluxes, physics_variables);
      ParameterBinding b(prm, ParameterBinding::Mode::declare);
      SceneParameters().bind(b, RunParameters(), DiscretizationParameters());
    };
    s.run = [=](ParameterHandler &prm) {
      RunParameters common;
      common.parse(prm);
      DiscretizationParameters method;
      method.parse(prm, common, physics_variables);
      SceneParameters p;
      {
        ParameterBinding b(prm, ParameterBinding::Mode::read);
        p.bind(b, common, method);
      }
      run(common, method, p);
    };
    return s;
  }
} // namespace granular_dg::dg
