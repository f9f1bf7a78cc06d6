#include <granular_dg/base/errors.h>
#include <granular_dg/base/output.h>
#include <granular_dg/base/parameter_binding.h>
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

  } // namespace

  const std::string &
  side_name(const Side side)
  {
    return side_names.name(side);
  }

  void
  LayeredParameters::bind(ParameterBinding &b, const RunParameters &run,
                          const dg::DiscretizationParameters &method)
  {
    final_time = run.final_time;
    if (b.reading())
      flux = numerical_flux_names.parse("Discretization/numerical flux", method.flux);
    b.section("Mesh");
    b.add("dimension", dim, Patterns::Integer(1, 2), "1 or 2.");
    if (b.reading())
      run.require_format_fits(dim);
    b.add("x min", lo[0], Patterns::Double(), "Left end of the domain.");
    b.add("x max", hi[0], Patterns::Double(), "Right end of the domain.")
      .check([this](const double x) { return x > lo[0]; }, "must be > x min");
    b.add("cells x", cells[0], Patterns::Integer(1),
          "Cells in x; with layers across x, an integer number per layer.");
    b.add("y min", lo[1], Patterns::Double(), "Bottom (2D).");
    b.add("y max", hi[1], Patterns::Double(), "Top (2D).")
      .check([this](const double y) { return dim == 1 || y > lo[1]; }, "must be > y min");
    b.add("cells y", cells[1], Patterns::Integer(1),
          "Cells in y (2D); with horizontal layers, an integer number per layer.");
    if (b.reading() && dim == 1)
      for (const auto &[name, value] : {std::pair<std::string, std::string>{"y min", format_number(lo[1])},
                                        {"y max", format_number(hi[1])},
                                        {"cells y", std::to_string(cells[1])}})
        require(parameter_origin("Mesh/" + name).empty(), "Mesh/" + name, value,
                "unset in 1D (Mesh/dimension = 1)");
    bind_materials(b);
    bind_data(b, initial, "Initial condition");
    bind_sides(b);

    b.section("Output");
    b.add("slice y", "", Patterns::Anything(),
          "2D: write slice-NNNN.csv (strain, stress, velocity along the line y = this value) "
          "at every output time; empty: none.",
          [this](const std::string &text) { read_slice(text); });
    b.section("Limiter");
    b.add("strain positivity", positivity, Patterns::Bool(),
          "Scale the higher strain modes after every stage so that eps >= 0 at the Gauss "
          "points and face centres of every cell with a non-negative mean (Zhang-Shu). The "
          "paper's scheme keeps eps >= 0; the exact solutions have small tensile tails (eps < "
          "0), so this is off by default.");

    b.section("Exact solution");
    b.add("available", exact_available, Patterns::Bool(),
          "Whether the expressions below are the exact solution; then errors are reported and "
          "convergence studies are possible.");
    bind_data(b, exact, "Exact solution");
    b.add("reference file", reference_file, Patterns::Anything(),
          "1D: a modes-NNNN.csv of a finer run (Output/write modes = true) as the reference "
          "solution at the final time, instead of the expressions (errors in summary.json).");
    reference_file = Utilities::trim(reference_file);
    if (!b.reading())
      return;
    require(!(exact_available && !reference_file.empty()), "Exact solution/reference file",
            reference_file, "empty when Exact solution/available = true");
    require(reference_file.empty() || dim == 1, "Exact solution/reference file", reference_file,
            "empty in 2D (reference files are 1D)");
  }

  void
  LayeredParameters::bind_materials(ParameterBinding &b)
  {
    b.section("Physics");
    b.add("stress law", law, law_names,
          "quadratic: sigma = K eps + beta K^2 eps^2 (eq. (1.4) of the central-upwind paper on "
          "layered elasticity; linear for beta = 0); exponential: sigma = exp(K eps) - 1 "
          "(1.5).");
    Material &A = layers.A, &B = layers.B;
    b.add("density", A.rho, Patterns::Double(),
          "rho > 0 of material A (the homogeneous medium, or the even layers).")
      .check([](const double rho) { return rho > 0; }, "must be > 0");
    b.add("modulus K", A.K, Patterns::Double(), "K > 0 of material A.")
      .check([](const double K) { return K > 0; }, "must be > 0");
    b.add("beta", A.beta, Patterns::Double(),
          "Nonlinearity of the quadratic law (both materials).");
    B.beta = A.beta;

    b.section("Layers");
    b.add("layer width", layers.width, Patterns::Double(0),
          "l >= 0: material A on [origin + 2jl, origin + (2j+1)l), B on the others; every "
          "interface must be a mesh face. 0: homogeneous (material A everywhere).");
    b.add("origin", layers.origin, Patterns::Double(), "Where the first A layer starts.");
    b.add("orientation", "vertical", Patterns::Selection("vertical|horizontal"),
          "vertical: the material varies with x (strips x = const in 2D); horizontal: with y "
          "(2D only).",
          [this](const std::string &text) {
            layers.direction = text == "vertical" ? 0 : 1;
            require(dim == 2 || layers.direction == 0, "Layers/orientation", text,
                    "vertical in 1D");
          });
    b.add("density B", B.rho, Patterns::Double(), "rho > 0 of material B.")
      .check([](const double rho) { return rho > 0; }, "must be > 0");
    b.add("modulus K B", B.K, Patterns::Double(), "K > 0 of material B.")
      .check([](const double K) { return K > 0; }, "must be > 0");
  }

  void
  LayeredParameters::bind_data(ParameterBinding &b, PrimitiveExpressions &e,
                               const std::string &section)
  {
    const bool initial_condition = section == "Initial condition";
    e.section                    = section;
    b.section(section);
    b.add("strain", e.strain, Patterns::Anything(),
          initial_condition ? "eps(x[,y]) as an expression (constant pi)." : "eps(x[,y],t).");
    if (initial_condition)
      b.add("stress", e.stress, Patterns::Anything(),
            "sigma(x[,y]) instead of the strain (empty: use the strain); the strain follows "
            "from each material's law.");
    b.add("velocity", e.velocity, Patterns::Anything(),
          initial_condition ? "u(x[,y]) in 1D, 'u; v' in 2D." : "u(x[,y],t) ('u; v' in 2D).");
  }

  void
  LayeredParameters::bind_sides(ParameterBinding &b)
  {
    b.section("Boundary conditions");
    for (unsigned int k = 0; k < 4; ++k)
      {
        const std::string side = side_label[k];
        b.add(side, sides[k], side_names,
              "Kind of the " + side +
                " boundary (bottom/top: 2D only). periodic pairs with the opposite side; "
                "outflow: transmissive; wall: a wall moving with the velocity in the data; "
                "traction: prescribed stress; dirichlet: prescribed strain and velocity.");
        b.add(side + " data", side_data[k], Patterns::Anything(),
              "Expressions in x[,y],t separated by ';': wall: velocity (dim values); traction: "
              "sigma; dirichlet: strain; velocity.");
      }
    b.add("periodic from", periodic_from, Patterns::Double(0),
          "t_p > 0: left and right become periodic at t = t_p (the run to t_p goes to "
          "Output/directory/before-periodic, the rest continues from its final state); 0: "
          "never.");
    if (!b.reading())
      return;
    // the 2D entries, set in 1D, would be ignored
    for (unsigned int k = 2; dim == 1 && k < 4; ++k)
      {
        const std::string side = std::string("Boundary conditions/") + side_label[k];
        require(parameter_origin(side).empty(), side, side_names.name(sides[k]),
                "unset in 1D (bottom and top are the sides of a 2D strip)");
        require(parameter_origin(side + " data").empty(), side + " data", side_data[k],
                "unset in 1D (bottom and top are the sides of a 2D strip)");
      }
    sides.resize(2 * dim);
    side_data.resize(2 * dim);
    for (int d = 0; d < dim; ++d)
      {
        // (the periodic side named, its partner's side said)
        const int p = sides[2 * d] == Side::periodic ? 2 * d : 2 * d + 1, q = 4 * d + 1 - p;
        require((sides[p] == Side::periodic) == (sides[q] == Side::periodic),
                std::string("Boundary conditions/") + side_label[p], side_names.name(sides[p]),
                std::string("periodic only together with ") + side_label[q] +
                  " = periodic (it is " + side_names.name(sides[q]) + ")");
      }
  }

  void
  LayeredParameters::read_slice(const std::string &text)
  {
    const std::string slice = Utilities::trim(text);
    if (slice.empty())
      return;
    char *end = nullptr;
    slice_y   = std::strtod(slice.c_str(), &end);
    require(dim == 2 && end != slice.c_str() && *end == '\0' && slice_y >= lo[1] &&
              slice_y < hi[1],
            "Output/slice y", slice,
            "empty, or in 2D a number in [y min, y max) = [" + format_number(lo[1]) + ", " +
              format_number(hi[1]) + ")");
  }
} // namespace granular_dg::layered_strip
