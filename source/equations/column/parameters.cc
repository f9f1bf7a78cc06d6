#include <granular_dg/base/errors.h>
#include <granular_dg/base/output.h>
#include <granular_dg/base/parameter_binding.h>
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
  ColumnParameters::bind(ParameterBinding &b, const RunParameters &run,
                         const dg::DiscretizationParameters &)
  {
    if (b.reading())
      run.require_format_fits(1);
    b.section("Physics");
    b.add("stress exponent m", physics.m, Patterns::Double(),
          "m >= 1 in sigma(u) = max(0, -u|u|^(m-1)) (2.2): 1 (linear), 3/2, 2.")
      .check([](const double m) { return m >= 1; }, "m >= 1");
    b.add("wall strain", u_b, Patterns::Double(),
          "u_b < 0: the strain imposed at z = 0 (2.5); the wall stress is sigma_b = |u_b|^m.")
      .check([](const double u) { return u < 0; }, "u_b < 0 (compression)");
    b.add("gravity", physics.gravity, Patterns::Double(),
          "G >= 0 (2.4): 0 for the horizontal cylinder of the paper's experiments, > 0 for a "
          "vertical column.")
      .check([](const double g) { return g >= 0; }, "G >= 0");
    b.add("regularisation strain", physics.u_star, Patterns::Double(),
          "u* >= 0 of the Lipschitz-regularised law (3.5): sigma is continued linearly beyond "
          "|u| > u*. 0: off.")
      .check([](const double u) { return u >= 0; }, "u* >= 0 (0: off)");
    b.add("friction", physics.friction, friction_names,
          "projection: the implicit per-cell step of the paper (section 3); explicit_sign: "
          "naive explicit source with sgn(v) of the current state; explicit_smooth: naive "
          "explicit source with v/sqrt(v^2 + delta^2); none: no friction (the p-system).");
    b.add("friction stage weights", "consistent", Patterns::Selection("consistent|printed"),
          "The weights of the friction projection in the three SSP-RK3 stages: consistent "
          "(dt, dt/4, 2dt/3: those of the explicit part, so that a stuck state stays stuck) or "
          "printed (dt, dt/2, dt as printed in Coffey & Gremaud, for comparison).",
          [this](const std::string &text) { printed_weights = text == "printed"; });
    b.add("smoothing", physics.smoothing, Patterns::Double(),
          "delta > 0 of the smoothed sgn (friction = explicit_smooth).")
      .check([](const double d) { return d > 0; }, "delta > 0");

    b.section("Mesh");
    b.add("length", length, Patterns::Double(),
          "L > 0: the column is (0, L); choose it so that the disturbance never reaches z = L "
          "(summary.json: disturbance_extent).")
      .check([](const double l) { return l > 0; }, "L > 0");
    b.add("cells", cells, Patterns::Integer(1), "Number of cells.");
    b.add("far end", "outflow", Patterns::Selection("outflow|wall"),
          "The end z = L: outflow (a semi-infinite column) or wall (a closed bottom at rest, "
          "for a vertical column under gravity).",
          [this](const std::string &text) { closed_end = text == "wall"; });

    b.section("Diagnostics");
    b.add("sample interval", sample_dt, Patterns::Double(0),
          "Time between the rows of history.csv and sgn-map.csv (0: final time / 400).");
    b.add("front threshold", threshold, Patterns::Double(0),
          "The disturbed region is where |u| > threshold |u_b|.");
    b.add("probe position", probe, Patterns::Double(0),
          "z of the strain probe in history.csv (drift of stuck material).")
      .check([this](const double z) { return z <= length; },
             "a height in [0, Mesh/length = " + format_number(length) + "]");
    b.add("closed form", closed_form, Patterns::Bool(),
          "Compare with the exact solution of the linear case (m = 1, G = 0, section 2; final "
          "time <= 20): errors in timeseries.csv and summary.json, and convergence studies.")
      .check(
        [this](const bool on) {
          return !on || (physics.m == 1 && physics.gravity == 0 && physics.u_star == 0 &&
                         physics.friction == FrictionTreatment::projection);
        },
        "only for the linear law m = 1 without gravity or regularisation, with friction = "
        "projection")
      .check([&](const bool on) { return !on || run.final_time <= 20; },
             "final time <= 20 (it is " + format_number(run.final_time) +
               "; the closed form loses accuracy to round-off beyond)");
    b.add("write sgn map", write_sgn_map, Patterns::Bool(),
          "Write sgn-map.csv (friction multiplier per cell and sample).");
  }
} // namespace granular_dg::column
