#include <granular_dg/base/errors.h>
#include <granular_dg/base/output.h>
#include <granular_dg/equations/hopper/parameters.h>

#include <cmath>

namespace granular_dg::hopper
{
  void
  Parameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Hopper");
    prm.declare_entry("mode", "march", mode_names.pattern(),
                      "march: solve down the hopper in tau = -ln(r/r0); radial: only "
                      "write the radial (Jenike) field radial-field.csv; scan: the "
                      "admissibility scan of Fig. 9 (fig9-scan.csv) over the upper "
                      "half-angles of subsection Scan.");
    prm.declare_entry("geometry", "cone", geometry_names.pattern(),
                      "wedge (plane, d = 2) or cone (axisymmetric, d = 3).");
    prm.declare_entry("upper half-angle", "30", Patterns::Double(),
                      "Theta_w in degrees, in (0, 90): the hopper above the transition, "
                      "carrying its radial field.");
    prm.declare_entry("lower half-angle", "30", Patterns::Double(),
                      "theta_w in degrees, in (0, 90): the hopper that is marched "
                      "(equal to the upper one: radial-field preservation).");
    prm.declare_entry("initial radius", "1", Patterns::Double(),
                      "r0 in m: the radius of the wall corner (the initial arc Gamma_0) "
                      "in the lower hopper, > 0. Only scales coordinates and T.");
    prm.declare_entry("cells", "400", Patterns::Integer(1),
                      "N: cells in theta on (0, theta_w).");
    prm.declare_entry("initial perturbation", "0", Patterns::Double(),
                      "delta_p: the initial T_rr is multiplied by 1 + delta_p, |delta_p| < "
                      "0.5 (0: none). A test of the linear stability of the radial field "
                      "(doc/hopper.md).");
    prm.leave_subsection();

    prm.enter_subsection("Physics");
    prm.declare_entry("internal friction angle", "32.1", Patterns::Double(),
                      "delta in degrees, in (0, 90).");
    prm.declare_entry("wall friction angle", "11.7", Patterns::Double(),
                      "Phi in degrees (mu = tan Phi), in [0, delta).");
    prm.declare_entry("density", "790", Patterns::Double(), "rho in kg/m^3, > 0.");
    prm.declare_entry("gravity", "9.81", Patterns::Double(), "g in m/s^2, > 0.");
    prm.declare_entry("variables", "scaled", variables_names.pattern(),
                      "scaled: U = T/(rho g r), the radial field is a steady state; "
                      "unscaled: U = T/(rho g r0) with the tau-dependent gravity "
                      "source e^{-tau} of the paper's (7)/(11).");
    prm.leave_subsection();

    prm.enter_subsection("Hopper output");
    prm.declare_entry("radial field points", "61", Patterns::Integer(2),
                      "Rows of radial-field.csv (equidistant on [0, theta_w]).");
    prm.declare_entry("sample points", "401", Patterns::Integer(2),
                      "Equidistant theta points of stress-NNNN.csv (T/r in Pa/m per "
                      "output tau).");
    prm.declare_entry("field theta points", "101", Patterns::Integer(2),
                      "Theta points per half of hopper-field.vtu (the marched field in "
                      "physical coordinates).");
    prm.declare_entry("field rows", "120", Patterns::Integer(1),
                      "Rows (tau values) of hopper-field.vtu.");
    prm.declare_entry("upper region", "0.5", Patterns::Double(0),
                      "hopper-field.vtu also shows the upper hopper's radial field from "
                      "Gamma_0 up to R = R_0 + this * r0 (0: none).");
    prm.declare_entry("step series interval", "1", Patterns::Integer(0),
                      "Write margin and radial-field difference to hopper-steps.csv "
                      "every this many steps (0: never).");
    prm.leave_subsection();

    prm.enter_subsection("Scan");
    prm.declare_entry("upper half-angle from", "2", Patterns::Double(),
                      "First Theta_w of the Fig. 9 scan, degrees.");
    prm.declare_entry("upper half-angle to", "45", Patterns::Double(),
                      "Last Theta_w of the scan, degrees (the scan stops at the first "
                      "angle without a radial field).");
    prm.declare_entry("upper half-angle step", "0.5", Patterns::Double(),
                      "Step of the scan, degrees, > 0.");
    prm.leave_subsection();
  }

  void
  Parameters::parse(ParameterHandler &prm, const RunParameters &run,
                    const dg::DiscretizationParameters &)
  {
    Parameters &p = *this;
    run.require_format_fits(1);
    prm.enter_subsection("Hopper");
    p.mode     = mode_names.parse("Hopper/mode", prm.get("mode"));
    p.geometry = geometry_names.parse("Hopper/geometry", prm.get("geometry"));
    const double upper = prm.get_double("upper half-angle");
    const double lower = prm.get_double("lower half-angle");
    p.r0               = prm.get_double("initial radius");
    p.cells            = prm.get_integer("cells");
    p.perturbation     = prm.get_double("initial perturbation");
    prm.leave_subsection();
    require(std::abs(p.perturbation) < 0.5, "Hopper/initial perturbation", p.perturbation,
            "a relative amplitude in (-0.5, 0.5)");
    require(upper > 0 && upper < 90, "Hopper/upper half-angle", upper,
            "an angle in degrees in (0, 90)");
    require(lower > 0 && lower < 90, "Hopper/lower half-angle", lower,
            "an angle in degrees in (0, 90)");
    require(p.r0 > 0, "Hopper/initial radius", p.r0, "must be > 0 (m)");
    p.Theta_w = upper * deg;
    p.theta_w = lower * deg;

    prm.enter_subsection("Physics");
    const double delta = prm.get_double("internal friction angle");
    const double Phi   = prm.get_double("wall friction angle");
    p.rho              = prm.get_double("density");
    p.g                = prm.get_double("gravity");
    p.variables        = variables_names.parse("Physics/variables", prm.get("variables"));
    prm.leave_subsection();
    require(delta > 0 && delta < 90, "Physics/internal friction angle", delta,
            "an angle in degrees in (0, 90)");
    require(Phi >= 0 && Phi < delta, "Physics/wall friction angle", Phi,
            "an angle in degrees in [0, internal friction angle = " + format_number(delta) +
              ") (the passive wall state needs sin Phi < sin delta)");
    require(p.rho > 0, "Physics/density", p.rho, "must be > 0");
    require(p.g > 0, "Physics/gravity", p.g, "must be > 0");
    p.material = MohrCoulomb(delta * deg, Phi * deg);

    prm.enter_subsection("Hopper output");
    p.radial_points      = prm.get_integer("radial field points");
    p.sample_points      = prm.get_integer("sample points");
    p.field_theta_points = prm.get_integer("field theta points");
    p.field_rows         = prm.get_integer("field rows");
    p.upper_region       = prm.get_double("upper region");
    p.step_interval      = prm.get_integer("step series interval");
    prm.leave_subsection();

    prm.enter_subsection("Scan");
    p.scan_from = prm.get_double("upper half-angle from");
    p.scan_to   = prm.get_double("upper half-angle to");
    p.scan_step = prm.get_double("upper half-angle step");
    prm.leave_subsection();
    if (p.mode == Mode::scan)
      {
        require(p.scan_from > 0 && p.scan_from < 90, "Scan/upper half-angle from",
                p.scan_from, "an angle in degrees in (0, 90)");
        require(p.scan_to >= p.scan_from && p.scan_to < 90, "Scan/upper half-angle to",
                p.scan_to, "an angle in degrees in [upper half-angle from, 90)");
        require(p.scan_step > 0, "Scan/upper half-angle step", p.scan_step, "must be > 0");
      }
    require(!run.resume || p.mode == Mode::march, "Checkpoint/resume", "true",
            "false in Hopper/mode = " + mode_names.name(p.mode) +
              " (it has no time loop to continue)");
  }
} // namespace granular_dg::hopper
