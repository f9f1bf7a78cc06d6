#include <granular_dg/base/errors.h>
#include <granular_dg/base/output.h>
#include <granular_dg/base/parameters.h>
#include <granular_dg/equations/layered_strip/parameters.h>

#include <cstdlib>

namespace granular_dg::layered_strip
{
  const char *const side_label[4] = {"left", "right", "bottom", "top"};

  namespace
  {
    const EnumNames<StressLaw> law_names({{StressLaw::quadratic, "quadratic"},
                                          {StressLaw::exponential, "exponential"}});

    const EnumNames<Side> side_names({{Side::periodic, "periodic"},
                                      {Side::outflow, "outflow"},
                                      {Side::wall, "wall"},
                                      {Side::traction, "traction"},
                                      {Side::dirichlet, "dirichlet"}});

    Layers
    parse_layers(ParameterHandler &prm, const int dim)
    {
      Layers    l;
      Material &A = l.A;
      prm.enter_subsection("Physics");
      A.rho  = prm.get_double("density");
      A.K    = prm.get_double("modulus K");
      A.beta = prm.get_double("beta");
      prm.leave_subsection();
      require(A.rho > 0, "Physics/density", A.rho, "must be > 0");
      require(A.K > 0, "Physics/modulus K", A.K, "must be > 0");
      prm.enter_subsection("Layers");
      l.width     = prm.get_double("layer width");
      l.origin    = prm.get_double("origin");
      l.direction = prm.get("orientation") == "vertical" ? 0 : 1;
      l.B         = A;
      l.B.rho     = prm.get_double("density B");
      l.B.K       = prm.get_double("modulus K B");
      prm.leave_subsection();
      require(l.B.rho > 0, "Layers/density B", l.B.rho, "must be > 0");
      require(l.B.K > 0, "Layers/modulus K B", l.B.K, "must be > 0");
      require(dim == 2 || l.direction == 0, "Layers/orientation", "horizontal",
              "vertical in 1D");
      return l;
    }

    PrimitiveExpressions
    parse_expressions(ParameterHandler &prm, const std::string &section)
    {
      PrimitiveExpressions e;
      e.section = section;
      prm.enter_subsection(section);
      e.strain   = prm.get("strain");
      e.velocity = prm.get("velocity");
      e.stress   = section == "Initial condition" ? prm.get("stress") : "";
      prm.leave_subsection();
      return e;
    }

    void
    parse_sides(ParameterHandler &prm, LayeredParameters &p)
    {
      prm.enter_subsection("Boundary conditions");
      for (int b = 0; b < 2 * p.dim; ++b)
        {
          p.sides.push_back(side_names.parse(std::string("Boundary conditions/") + side_label[b],
                                             prm.get(side_label[b])));
          p.side_data.push_back(prm.get(std::string(side_label[b]) + " data"));
        }
      p.periodic_from = prm.get_double("periodic from");
      prm.leave_subsection();
      for (int d = 0; d < p.dim; ++d)
        {
          const Side s0 = p.sides[2 * d], s1 = p.sides[2 * d + 1];
          require((s0 == Side::periodic) == (s1 == Side::periodic),
                  std::string("Boundary conditions/") + side_label[2 * d], side_names.name(s0),
                  std::string("periodic only together with ") + side_label[2 * d + 1] +
                    " = periodic (it is " + side_names.name(s1) + ")");
        }
    }

    void
    parse_outputs(ParameterHandler &prm, LayeredParameters &p)
    {
      prm.enter_subsection("Exact solution");
      p.exact_available = prm.get_bool("available");
      p.reference_file  = Utilities::trim(prm.get("reference file"));
      prm.leave_subsection();
      p.exact = parse_expressions(prm, "Exact solution");
      require(!(p.exact_available && !p.reference_file.empty()), "Exact solution/reference file",
              p.reference_file, "empty when Exact solution/available = true");
      require(p.reference_file.empty() || p.dim == 1, "Exact solution/reference file",
              p.reference_file, "empty in 2D (reference files are 1D)");

      prm.enter_subsection("Limiter");
      p.positivity = prm.get_bool("strain positivity");
      prm.leave_subsection();
      prm.enter_subsection("Output");
      const std::string slice = Utilities::trim(prm.get("slice y"));
      prm.leave_subsection();
      if (slice.empty())
        return;
      char *end = nullptr;
      p.slice_y = std::strtod(slice.c_str(), &end);
      require(p.dim == 2 && end != slice.c_str() && *end == '\0' && p.slice_y >= p.lo[1] &&
                p.slice_y < p.hi[1],
              "Output/slice y", slice,
              "empty, or in 2D a number in [y min, y max) = [" + format_number(p.lo[1]) + ", " +
                format_number(p.hi[1]) + ")");
    }
  } // namespace

  const std::string &
  side_name(const Side side)
  {
    return side_names.name(side);
  }

  void
  LayeredParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Mesh");
    prm.declare_entry("dimension", "1", Patterns::Integer(1, 2), "1 or 2.");
    prm.declare_entry("x min", "0", Patterns::Double(), "Left end of the domain.");
    prm.declare_entry("x max", "1", Patterns::Double(), "Right end of the domain.");
    prm.declare_entry("cells x", "64", Patterns::Integer(1),
                      "Cells in x; with layers across x, an integer number per layer.");
    prm.declare_entry("y min", "0", Patterns::Double(), "Bottom (2D).");
    prm.declare_entry("y max", "1", Patterns::Double(), "Top (2D).");
    prm.declare_entry("cells y", "4", Patterns::Integer(1),
                      "Cells in y (2D); with horizontal layers, an integer number per layer.");
    prm.leave_subsection();

    prm.enter_subsection("Physics");
    prm.declare_entry("stress law", "quadratic", law_names.pattern(),
                      "quadratic: sigma = K eps + beta K^2 eps^2 (eq. (1.4) of the central-upwind paper on layered elasticity; "
                      "linear for beta = 0); exponential: sigma = exp(K eps) - 1 (1.5).");
    prm.declare_entry("density", "1", Patterns::Double(),
                      "rho > 0 of material A (the homogeneous medium, or the even layers).");
    prm.declare_entry("modulus K", "1", Patterns::Double(), "K > 0 of material A.");
    prm.declare_entry("beta", "0", Patterns::Double(),
                      "Nonlinearity of the quadratic law (both materials).");
    prm.leave_subsection();

    prm.enter_subsection("Layers");
    prm.declare_entry("layer width", "0", Patterns::Double(0),
                      "l >= 0: material A on [origin + 2jl, origin + (2j+1)l), B on the "
                      "others; every interface must be a mesh face. 0: homogeneous "
                      "(material A everywhere).");
    prm.declare_entry("origin", "0", Patterns::Double(), "Where the first A layer starts.");
    prm.declare_entry("orientation", "vertical", Patterns::Selection("vertical|horizontal"),
                      "vertical: the material varies with x (strips x = const in 2D); "
                      "horizontal: with y (2D only).");
    prm.declare_entry("density B", "1", Patterns::Double(), "rho > 0 of material B.");
    prm.declare_entry("modulus K B", "1", Patterns::Double(), "K > 0 of material B.");
    prm.leave_subsection();

    prm.enter_subsection("Initial condition");
    prm.declare_entry("strain", "0", Patterns::Anything(),
                      "eps(x[,y]) as an expression (constant pi).");
    prm.declare_entry("stress", "", Patterns::Anything(),
                      "sigma(x[,y]) instead of the strain (empty: use the strain); the "
                      "strain follows from each material's law.");
    prm.declare_entry("velocity", "0", Patterns::Anything(),
                      "u(x[,y]) in 1D, 'u; v' in 2D.");
    prm.leave_subsection();

    prm.enter_subsection("Boundary conditions");
    for (const char *side : side_label)
      {
        prm.declare_entry(side, "outflow", side_names.pattern(),
                          std::string("Kind of the ") + side +
                            " boundary (bottom/top: 2D only). periodic pairs with "
                            "the opposite side; outflow: transmissive; wall: a wall "
                            "moving with the velocity in the data; traction: "
                            "prescribed stress; dirichlet: prescribed strain and "
                            "velocity.");
        prm.declare_entry(std::string(side) + " data", "0", Patterns::Anything(),
                          "Expressions in x[,y],t separated by ';': wall: velocity "
                          "(dim values); traction: sigma; dirichlet: strain; velocity.");
      }
    prm.declare_entry("periodic from", "0", Patterns::Double(0),
                      "t_p > 0: left and right become periodic at t = t_p (the run to "
                      "t_p goes to Output/directory/before-periodic, the rest continues "
                      "from its final state); 0: never.");
    prm.leave_subsection();

    prm.enter_subsection("Output");
    prm.declare_entry("slice y", "", Patterns::Anything(),
                      "2D: write slice-NNNN.csv (strain, stress, velocity along the line "
                      "y = this value) at every output time; empty: none.");
    prm.leave_subsection();

    prm.enter_subsection("Limiter");
    prm.declare_entry("strain positivity", "false", Patterns::Bool(),
                      "Scale the higher strain modes after every stage so that eps >= 0 "
                      "at the Gauss points and face centres of every cell with a "
                      "non-negative mean (Zhang-Shu). The paper's scheme keeps eps >= 0; "
                      "the exact solutions have small tensile tails (eps < 0), so this is "
                      "off by default.");
    prm.leave_subsection();

    prm.enter_subsection("Exact solution");
    prm.declare_entry("available", "false", Patterns::Bool(),
                      "Whether the expressions below are the exact solution; then "
                      "errors are reported and convergence studies are possible.");
    prm.declare_entry("strain", "0", Patterns::Anything(), "eps(x[,y],t).");
    prm.declare_entry("velocity", "0", Patterns::Anything(), "u(x[,y],t) ('u; v' in 2D).");
    prm.declare_entry("reference file", "", Patterns::Anything(),
                      "1D: a modes-NNNN.csv of a finer run (Output/write modes = true) "
                      "as the reference solution at the final time, instead of the "
                      "expressions (errors in summary.json).");
    prm.leave_subsection();
  }


  void
  LayeredParameters::parse(ParameterHandler &prm, const RunParameters &run,
                           const dg::DiscretizationParameters &method)
  {
    final_time = run.final_time;
    prm.enter_subsection("Mesh");
    dim = prm.get_integer("dimension");
    run.require_format_fits(dim);
    lo  = Point<2>(prm.get_double("x min"), prm.get_double("y min"));
    hi  = Point<2>(prm.get_double("x max"), prm.get_double("y max"));
    cells = {{static_cast<unsigned int>(prm.get_integer("cells x")),
              static_cast<unsigned int>(prm.get_integer("cells y"))}};
    prm.leave_subsection();
    prm.enter_subsection("Physics");
    law = law_names.parse("Physics/stress law", prm.get("stress law"));
    prm.leave_subsection();
    layers = parse_layers(prm, dim);
    flux = numerical_flux_names.parse("Discretization/numerical flux", method.flux);
    require(hi[0] > lo[0], "Mesh/x max", hi[0], "must be > x min");
    require(dim == 1 || hi[1] > lo[1], "Mesh/y max", hi[1], "must be > y min");
    parse_sides(prm, *this);
    initial = parse_expressions(prm, "Initial condition");
    parse_outputs(prm, *this);
  }
} // namespace granular_dg::layered_strip
