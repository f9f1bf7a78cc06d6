#pragma once

#include <granular_dg/dg/scene_data.h>
#include <granular_dg/equations/column/friction.h>
#include <granular_dg/equations/column/parameters.h>
#include <granular_dg/equations/column/system.h>

#include <memory>
#include <string>

namespace granular_dg::column
{
  /**
   * What the column measures along the way and at the end: the fronts (the
   * pressure front, the strain and velocity behind it, the stopping front),
   * energy, friction and wall work, stuck cells and their multipliers,
   * critical loadings, history.csv and sgn-map.csv at the sample interval,
   * the Rankine-Hugoniot check of the front, and the final strain against
   * Janssen's profile and the stationary problem (4.1)-(4.2)
   * (final-profile.csv). directory empty: no files (convergence studies);
   * friction: the stage operation whose stuck cells it reports.
   */
  std::shared_ptr<dg::SceneHooks<1>>
  make_diagnostics(const System &system, const ColumnParameters &prm, double final_time,
                   const std::string &directory, const FrictionHooks &friction);
} // namespace granular_dg::column
