#include <granular_dg/base/errors.h>
#include <granular_dg/base/output.h>
#include <granular_dg/base/parameter_binding.h>
#include <granular_dg/equations/hopper/parameters.h>

#include <cmath>

namespace granular_dg::hopper
{
  namespace
  {
    bool
    angle(const double degrees)
    {
      return degrees > 0 && degrees < 90;
    }
  } // namespace

  void
  Parameters::bind(ParameterBinding &b, const RunParameters &run,
                   const dg::DiscretizationParameters &)
  {
    if (b.reading())
      run.require_format_fits(1);
    b.section("Hopper");
    b.add("mode", mode, mode_names,
          "march: solve down the hopper in tau = -ln(r/r0); radial: only write the radial "
          "(Jenike) field radial-field.csv; scan: the admissibility scan of Fig. 9 "
          "(fig9-scan.csv) over the upper half-angles of subsection Scan.");
    if (b.reading())
      require(!run.resume || mode == Mode::march, "Checkpoint/resume", "true",
              "false in Hopper/mode = " + mode_names.name(mode) +
                " (it has no time loop to continue)");
    b.add("geometry", geometry, geometry_names,
          "wedge (plane, d = 2) or cone (axisymmetric, d = 3).");
    b.add("upper half-angle", upper_angle, Patterns::Double(),
          "Theta_w in degrees, in (0, 90): the hopper above the transition, carrying its "
          "radial field.")
      .check(angle, "an angle in degrees in (0, 90)");
    b.add("lower half-angle", lower_angle, Patterns::Double(),
          "theta_w in degrees, in (0, 90): the hopper that is marched (equal to the upper "
          "one: radial-field preservation).")
      .check(angle, "an angle in degrees in (0, 90)");
    Theta_w = upper_angle * deg;
    theta_w = lower_angle * deg;
    b.add("initial radius", r0, Patterns::Double(),
          "r0 in m: the radius of the wall corner (the initial arc Gamma_0) in the lower "
          "hopper, > 0. Only scales coordinates and T.")
      .check([](const double r) { return r > 0; }, "must be > 0 (m)");
    b.add("cells", cells, Patterns::Integer(1), "N: cells in theta on (0, theta_w).");
    b.add("initial perturbation", perturbation, Patterns::Double(),
          "delta_p: the initial T_rr is multiplied by 1 + delta_p, |delta_p| < 0.5 (0: none). "
          "A test of the linear stability of the radial field (doc/hopper.md).")
      .check([](const double d) { return std::abs(d) < 0.5; },
             "a relative amplitude in (-0.5, 0.5)");

    b.section("Physics");
    b.add("internal friction angle", internal_friction_angle, Patterns::Double(),
          "delta in degrees, in (0, 90).")
      .check(angle, "an angle in degrees in (0, 90)");
    b.add("wall friction angle", wall_friction_angle, Patterns::Double(),
          "Phi in degrees (mu = tan Phi), in [0, delta).")
      .check([this](const double Phi) { return Phi >= 0 && Phi < internal_friction_angle; },
             "an angle in degrees in [0, internal friction angle = " +
               format_number(internal_friction_angle) +
               ") (the passive wall state needs sin Phi < sin delta)");
    if (b.reading())
      material = MohrCoulomb(internal_friction_angle * deg, wall_friction_angle * deg);
    b.add("density", rho, Patterns::Double(), "rho in kg/m^3, > 0.")
      .check([](const double r) { return r > 0; }, "must be > 0");
    b.add("gravity", g, Patterns::Double(), "g in m/s^2, > 0.")
      .check([](const double x) { return x > 0; }, "must be > 0");
    b.add("variables", variables, variables_names,
          "scaled: U = T/(rho g r), the radial field is a steady state; unscaled: U = T/(rho g "
          "r0) with the tau-dependent gravity source e^{-tau} of the paper's (7)/(11).");
    bind_output(b);
    bind_scan(b);
  }

  void
  Parameters::bind_output(ParameterBinding &b)
  {
    b.section("Hopper output");
    b.add("radial field points", radial_points, Patterns::Integer(2),
          "Rows of radial-field.csv (equidistant on [0, theta_w]).");
    b.add("sample points", sample_points, Patterns::Integer(2),
          "Equidistant theta points of stress-NNNN.csv (T/r in Pa/m per output tau).");
    b.add("field theta points", field_theta_points, Patterns::Integer(2),
          "Theta points per half of hopper-field.vtu (the marched field in physical "
          "coordinates).");
    b.add("field rows", field_rows, Patterns::Integer(1), "Rows (tau values) of hopper-field.vtu.");
    b.add("upper region", upper_region, Patterns::Double(0),
          "hopper-field.vtu also shows the upper hopper's radial field from Gamma_0 up to R = "
          "R_0 + this * r0 (0: none).");
    b.add("step series interval", step_interval, Patterns::Integer(0),
          "Write margin and radial-field difference to hopper-steps.csv every this many steps "
          "(0: never).");
  }

  void
  Parameters::bind_scan(ParameterBinding &b)
  {
    // checked only when they are used
    const bool scan = mode == Mode::scan;
    b.section("Scan");
    b.add("upper half-angle from", scan_from, Patterns::Double(),
          "First Theta_w of the Fig. 9 scan, degrees.")
      .check([&](const double a) { return !scan || angle(a); }, "an angle in degrees in (0, 90)");
    b.add("upper half-angle to", scan_to, Patterns::Double(),
          "Last Theta_w of the scan, degrees (the scan stops at the first angle without a "
          "radial field).")
      .check([&](const double a) { return !scan || (a >= scan_from && a < 90); },
             "an angle in degrees in [upper half-angle from, 90)");
    b.add("upper half-angle step", scan_step, Patterns::Double(),
          "Step of the scan, degrees, > 0.")
      .check([&](const double d) { return !scan || d > 0; }, "must be > 0");
  }
} // namespace granular_dg::hopper
