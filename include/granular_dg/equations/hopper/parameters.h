#pragma once

#include <deal.II/base/parameter_handler.h>

#include <granular_dg/base/parameters.h>
#include <granular_dg/base/run_parameters.h>
#include <granular_dg/dg/parameters.h>
#include <granular_dg/equations/hopper/system.h>

namespace granular_dg::hopper
{
  using namespace dealii;

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
  /// Hopper, Physics, Hopper output, Scan): each entry declared, read and
  /// checked in bind() (ParameterBinding; the defaults are the initial values
  /// here), angles as given in degrees.
  struct Parameters
  {
    Mode         mode         = Mode::march;
    Geometry     geometry     = Geometry::cone;
    double       upper_angle  = 30.;
    double       lower_angle  = 30.;
    double       r0           = 1.;
    unsigned int cells        = 400;
    double       perturbation = 0.;

    double    internal_friction_angle = 32.1;
    double    wall_friction_angle     = 11.7;
    double    rho                     = 790.;
    double    g                       = 9.81;
    Variables variables               = Variables::scaled;

    unsigned int radial_points      = 61;
    unsigned int sample_points      = 401;
    unsigned int field_theta_points = 101;
    unsigned int field_rows         = 120;
    double       upper_region       = 0.5;
    unsigned int step_interval      = 1;

    double scan_from = 2., scan_to = 45., scan_step = 0.5;

    /// derived once read: the half-angles Theta_w, theta_w in radians and
    /// the material of the two friction angles
    double      Theta_w = 30. * deg, theta_w = 30. * deg;
    MohrCoulomb material;

    void
    bind(ParameterBinding &b, const RunParameters &run,
         const dg::DiscretizationParameters &method);

  private:
    void
    bind_output(ParameterBinding &b);
    void
    bind_scan(ParameterBinding &b);
  };
} // namespace granular_dg::hopper
