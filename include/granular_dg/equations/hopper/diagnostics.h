#pragma once

#include <granular_dg/base/output.h>
#include <granular_dg/dg/scene_data.h>
#include <granular_dg/equations/hopper/parameters.h>
#include <granular_dg/equations/hopper/radial_field.h>
#include <granular_dg/equations/hopper/system.h>

#include <memory>
#include <string>

namespace granular_dg::hopper
{
  /**
   * What the march measures: per step the hyperbolicity margin and the
   * difference to the lower hopper's radial field (hopper-steps.csv), per
   * output tau the stresses T/r in Pa/m (stress-NNNN.csv) and the monitors
   * in timeseries.csv, at the end the whole marched field in physical
   * coordinates (hopper-field.vtu/.pvd/.csv, unless Output/write vtu is
   * false). directory empty: no files.
   */
  std::shared_ptr<dg::SceneHooks<1>>
  make_diagnostics(const Parameters &p, const System &physics,
                   std::shared_ptr<const RadialField> lower,
                   std::shared_ptr<const RadialField> upper, const std::string &directory,
                   double tau_end, unsigned int degree, bool write_vtu);

  /// The entries of a radial field for summary.json, keys with prefix.
  void
  add_radial_diagnostics(JsonObject &d, const std::string &prefix, const RadialField &f);
} // namespace granular_dg::hopper
