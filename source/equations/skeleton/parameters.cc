#include <granular_dg/base/errors.h>
#include <granular_dg/base/parameters.h>
#include <granular_dg/equations/skeleton/parameters.h>

namespace granular_dg::skeleton
{
  void
  SkeletonParameters::declare(ParameterHandler &prm)
  {
    prm.enter_subsection("Mesh");
    prm.declare_entry("dimension", "1", Patterns::Integer(1, 2), "1 or 2.");
    prm.declare_entry("cells", "16", Patterns::Integer(1),
                      "Cells per direction of the unit interval or square.");
    prm.declare_entry("periodic", "true", Patterns::Bool(),
                      "Periodic in every direction; false: inflow (the exact solution) "
                      "where a.n < 0, outflow elsewhere.");
    prm.leave_subsection();
    prm.enter_subsection("Physics");
    prm.declare_entry("velocity", "1; 0", Patterns::Anything(),
                      "The advection velocity a: 'a_x; a_y' (a_y unused in 1D).");
    prm.leave_subsection();
    prm.enter_subsection("Initial condition");
    prm.declare_entry("u", "sin(2*pi*x)", Patterns::Anything(),
                      "u(x[,y], 0); the exact solution is u(x - a t) (periodically "
                      "continued).");
    prm.leave_subsection();
  }

  void
  SkeletonParameters::parse(ParameterHandler &prm, const RunParameters &run,
                            const dg::DiscretizationParameters &)
  {
    prm.enter_subsection("Mesh");
    dim      = prm.get_integer("dimension");
    run.require_format_fits(dim);
    cells    = prm.get_integer("cells");
    periodic = prm.get_bool("periodic");
    prm.leave_subsection();
    prm.enter_subsection("Physics");
    const std::string text = prm.get("velocity");
    prm.leave_subsection();
    const auto v = split_expressions(text);
    require(v.size() == 2, "Physics/velocity", text, "two numbers 'a_x; a_y'");
    for (unsigned int d = 0; d < 2; ++d)
      {
        char *end   = nullptr;
        velocity[d] = std::strtod(v[d].c_str(), &end);
        require(end != v[d].c_str() && *end == '\0' && std::isfinite(velocity[d]),
                "Physics/velocity", text, "two numbers 'a_x; a_y'");
      }
    require(velocity.norm() > 0, "Physics/velocity", text, "a nonzero velocity");
    prm.enter_subsection("Initial condition");
    initial = prm.get("u");
    prm.leave_subsection();
  }
} // namespace granular_dg::skeleton
