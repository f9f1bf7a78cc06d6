#pragma once

#include <deal.II/base/parameter_handler.h>

#include <granular_dg/base/parameters.h>
#include <granular_dg/base/run_parameters.h>
#include <granular_dg/dg/parameters.h>
#include <granular_dg/equations/hopper/system.h>

namespace granular_dg::hopper
{
  using namespace dealii;

  constexpr double deg = M_PI / 180.;

  /// What a hopper run does (Hopper/mode).
  enum class Mode
  {
    march,
    radial,
    scan
  };
  inline const EnumNames<Mode>      mode_names({{Mode::march, "march"},
                                         {Mode::radial, "radial"},
                                         {Mode::scan, "scan"}});
  inline const EnumNames<Geometry>  geometry_names({{Geometry::wedge, "wedge"},
                                             {Geometry::cone, "cone"}});
  inline const EnumNames<Variables> variables_names({{Variables::scaled, "scaled"},
                                              {Variables::unscaled, "unscaled"}});

  /// Everything the hopper scene reads from the prm file (subsections
  /// Hopper, Physics, Hopper output, Scan), parsed and checked once.
  struct Parameters
  {
    Mode         mode;
    Geometry     geometry;
    Variables    variables;
    MohrCoulomb  material;
    double       rho, g, r0, perturbation;
    double       Theta_w, theta_w; // radians
    unsigned int cells;
    unsigned int radial_points, sample_points, field_theta_points, field_rows,
      step_interval;
    double       upper_region;
    double       scan_from, scan_to, scan_step;

    static void
    declare(ParameterHandler &prm);
    void
    parse(ParameterHandler &prm, const RunParameters &run,
          const dg::DiscretizationParameters &method);
  };
} // namespace granular_dg::hopper
