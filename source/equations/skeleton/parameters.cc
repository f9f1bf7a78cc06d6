#include <granular_dg/base/errors.h>
#include <granular_dg/base/parameter_binding.h>
#include <granular_dg/base/parameters.h>
#include <granular_dg/equations/skeleton/parameters.h>

namespace granular_dg::skeleton
{
  void
  SkeletonParameters::bind(ParameterBinding &b, const RunParameters &run,
                           const dg::DiscretizationParameters &)
  {
    b.section("Mesh");
    b.add("dimension", dim, Patterns::Integer(1, 2), "1 or 2.");
    if (b.reading())
      run.require_format_fits(dim);
    b.add("cells", cells, Patterns::Integer(1),
          "Cells per direction of the unit interval or square.");
    b.add("periodic", periodic, Patterns::Bool(),
          "Periodic in every direction; false: inflow (the exact solution) where a.n < 0, "
          "outflow elsewhere.");
    b.section("Physics");
    b.add("velocity", "1; 0", Patterns::Anything(),
          "The advection velocity a: 'a_x; a_y' (a_y unused in 1D).",
          [this](const std::string &text) { read_velocity(text); });
    b.section("Initial condition");
    b.add("u", initial, Patterns::Anything(),
          "u(x[,y], 0); the exact solution is u(x - a t) (periodically continued).");
  }

  void
  SkeletonParameters::read_velocity(const std::string &text)
  {
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
  }
} // namespace granular_dg::skeleton
