#include <granular_dg/base/errors.h>
#include <granular_dg/base/output.h>
#include <granular_dg/base/parameters.h>
#include <granular_dg/equations/column/parameters.h>

namespace granular_dg::column
{
  namespace
  {
    const EnumNames<FrictionTreatment> friction_names(
      {{FrictionTreatment::projection, "projection"},
       {FrictionTreatment::explicit_sign, "explicit_sign"},
       {FrictionTreatment::explicit_smooth, "explicit_smooth"},
       {FrictionTreatment::none, "none"}});
  } // namespace

  void
  ColumnParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Physics");
    prm.declare_entry("stress exponent m", "1", Patterns::Double(),
                      "m >= 1 in sigma(u) = max(0, -u|u|^(m-1)) (2.2): 1 (linear), 3/2, 2.");
    prm.declare_entry("wall strain", "-1", Patterns::Double(),
                      "u_b < 0: the strain imposed at z = 0 (2.5); the wall stress is "
                      "sigma_b = |u_b|^m.");
    prm.declare_entry("gravity", "0", Patterns::Double(),
                      "G >= 0 (2.4): 0 for the horizontal cylinder of the paper's "
                      "experiments, > 0 for a vertical column.");
    prm.declare_entry("regularisation strain", "0", Patterns::Double(),
                      "u* >= 0 of the Lipschitz-regularised law (3.5): sigma is continued "
                      "linearly beyond |u| > u*. 0: off.");
    prm.declare_entry("friction", "projection", friction_names.pattern(),
                      "projection: the implicit per-cell step of the paper (section 3); "
                      "explicit_sign: naive explicit source with sgn(v) of the current "
                      "state; explicit_smooth: naive explicit source with "
                      "v/sqrt(v^2 + delta^2); none: no friction (the p-system).");
    prm.declare_entry("friction stage weights", "consistent",
                      Patterns::Selection("consistent|printed"),
                      "The weights of the friction projection in the three SSP-RK3 "
                      "stages: consistent (dt, dt/4, 2dt/3: those of the explicit part, "
                      "so that a stuck state stays stuck) or printed (dt, dt/2, dt as "
                      "printed in Coffey & Gremaud, for comparison).");
    prm.declare_entry("smoothing", "0.01", Patterns::Double(),
                      "delta > 0 of the smoothed sgn (friction = explicit_smooth).");
    prm.leave_subsection();

    prm.enter_subsection("Mesh");
    prm.declare_entry("length", "40", Patterns::Double(),
                      "L > 0: the column is (0, L); choose it so that the disturbance "
                      "never reaches z = L (summary.json: disturbance_extent).");
    prm.declare_entry("cells", "1600", Patterns::Integer(1), "Number of cells.");
    prm.declare_entry("far end", "outflow", Patterns::Selection("outflow|wall"),
                      "The end z = L: outflow (a semi-infinite column) or wall (a closed "
                      "bottom at rest, for a vertical column under gravity).");
    prm.leave_subsection();

    prm.enter_subsection("Diagnostics");
    prm.declare_entry("sample interval", "0", Patterns::Double(0),
                      "Time between the rows of history.csv and sgn-map.csv "
                      "(0: final time / 400).");
    prm.declare_entry("front threshold", "1e-3", Patterns::Double(0),
                      "The disturbed region is where |u| > threshold |u_b|.");
    prm.declare_entry("probe position", "0.5", Patterns::Double(0),
                      "z of the strain probe in history.csv (drift of stuck material).");
    prm.declare_entry("closed form", "false", Patterns::Bool(),
                      "Compare with the exact solution of the linear case (m = 1, G = 0, "
                      "section 2; final time <= 20): errors in timeseries.csv and "
                      "summary.json, and convergence studies.");
    prm.declare_entry("write sgn map", "true", Patterns::Bool(),
                      "Write sgn-map.csv (friction multiplier per cell and sample).");
    prm.leave_subsection();
  }

  void
  ColumnParameters::parse(ParameterHandler &prm, const RunParameters &run,
                          const dg::DiscretizationParameters &)
  {
    const double final_time = run.final_time;
    run.require_format_fits(1);
    ColumnParameters &p = *this;
    prm.enter_subsection("Physics");
    p.physics.m         = prm.get_double("stress exponent m");
    p.u_b               = prm.get_double("wall strain");
    p.physics.gravity   = prm.get_double("gravity");
    p.physics.u_star    = prm.get_double("regularisation strain");
    p.physics.friction  = friction_names.parse("Physics/friction", prm.get("friction"));
    p.physics.smoothing = prm.get_double("smoothing");
    p.printed_weights   = prm.get("friction stage weights") == "printed";
    prm.leave_subsection();
    require(p.physics.m >= 1, "Physics/stress exponent m", p.physics.m, "m >= 1");
    require(p.u_b < 0, "Physics/wall strain", p.u_b, "u_b < 0 (compression)");
    require(p.physics.gravity >= 0, "Physics/gravity", p.physics.gravity, "G >= 0");
    require(p.physics.u_star >= 0, "Physics/regularisation strain", p.physics.u_star,
            "u* >= 0 (0: off)");
    require(p.physics.smoothing > 0, "Physics/smoothing", p.physics.smoothing, "delta > 0");

    prm.enter_subsection("Mesh");
    p.length = prm.get_double("length");
    p.cells  = prm.get_integer("cells");
    p.closed_end = prm.get("far end") == "wall";
    prm.leave_subsection();
    require(p.length > 0, "Mesh/length", p.length, "L > 0");

    prm.enter_subsection("Diagnostics");
    p.sample_dt     = prm.get_double("sample interval");
    p.threshold     = prm.get_double("front threshold");
    p.probe         = prm.get_double("probe position");
    p.closed_form   = prm.get_bool("closed form");
    p.write_sgn_map = prm.get_bool("write sgn map");
    prm.leave_subsection();
    require(p.probe <= p.length, "Diagnostics/probe position", p.probe,
            "a height in [0, Mesh/length = " + format_number(p.length) + "]");
    if (p.closed_form)
      {
        require(p.physics.m == 1 && p.physics.gravity == 0 && p.physics.u_star == 0 &&
                  p.physics.friction == FrictionTreatment::projection,
                "Diagnostics/closed form", "true",
                "only for the linear law m = 1 without gravity or regularisation, with "
                "friction = projection");
        require(final_time <= 20, "Diagnostics/closed form", "true",
                "final time <= 20 (it is " + format_number(final_time) +
                  "; the closed form loses accuracy to round-off beyond)");
      }
  }
} // namespace granular_dg::column
