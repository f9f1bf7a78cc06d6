#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <granular_dg/base/run_parameters.h>
#include <granular_dg/dg/parameters.h>
#include <granular_dg/equations/layered_strip/system.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace granular_dg::layered_strip
{
  using namespace dealii;

  /// The kind of a side of the domain (Boundary conditions/left ... top).
  enum class Side
  {
    periodic,
    outflow,
    wall,
    traction,
    dirichlet
  };

  /// The layered medium: material A (id 0) on the even layers
  /// [origin + 2j l, origin + (2j+1) l), B (id 1) on the odd ones, along x
  /// (vertical strips) or y (horizontal strips); l = 0: A everywhere.
  struct Layers
  {
    double       width     = 0.;
    double       origin    = 0.;
    unsigned int direction = 0;
    Material     A, B;

    template <int dim>
    types::material_id
    id(const Point<dim> &p) const
    {
      if (width <= 0)
        return 0;
      const double s = (p[direction] - nearest_origin()) / width;
      return std::fmod(std::floor(s), 2.) == 0 ? 0 : 1;
    }

    /// origin shifted by whole periods 2 l to within one period of 0 (fmod
    /// is exact): the same layers, and x - origin keeps its digits however
    /// far away the origin was given
    double
    nearest_origin() const
    {
      return std::fmod(origin, 2 * width);
    }

    std::vector<Material>
    table() const
    {
      return width > 0 ? std::vector<Material>{A, B} : std::vector<Material>{A};
    }

    const Material &
    material(const types::material_id id) const
    {
      return id == 0 ? A : B;
    }
  };

  /// (strain or stress, velocity) expressions of a section of the prm.
  struct PrimitiveExpressions
  {
    std::string section;
    std::string strain, stress, velocity;
  };

  /**
   * Everything the layered_strip scene reads from the prm file, parsed and
   * checked once (what depends on the mesh is checked when the scene is
   * built): the law and the layers, the mesh, the sides, the data
   * expressions, the exact or reference solution, the positivity option and
   * the slice.
   */
  struct LayeredParameters
  {
    int                        dim = 1;
    StressLaw                  law = StressLaw::quadratic;
    NumericalFlux              flux = NumericalFlux::local_lax_friedrichs;
    Layers                     layers;
    Point<2>                   lo = Point<2>(0., 0.), hi = Point<2>(1., 1.);
    std::array<unsigned int, 2> cells{{64, 4}};
    /// left, right, bottom, top (2 dim of them once read) and their data
    /// expressions
    std::vector<Side>        sides     = std::vector<Side>(4, Side::outflow);
    std::vector<std::string> side_data = std::vector<std::string>(4, "0");
    double                   periodic_from = 0.;
    PrimitiveExpressions     initial{"Initial condition", "0", "", "0"};
    PrimitiveExpressions     exact{"Exact solution", "0", "", "0"};
    bool                       exact_available = false;
    std::string                reference_file;
    /// Time stepping/final time: the reference file's time must be it
    double                     final_time = 1.;
    bool                       positivity = false;
    /// the line y = slice_y of slice-NNNN.csv (NaN: none)
    double                     slice_y = NAN;

    /// Every entry, declared, read and checked in one place
    /// (ParameterBinding; the defaults are the initial values above).
    void
    bind(ParameterBinding &b, const RunParameters &run,
         const dg::DiscretizationParameters &method);

  private:
    void
    bind_materials(ParameterBinding &b);
    void
    bind_data(ParameterBinding &b, PrimitiveExpressions &e, const std::string &section);
    void
    bind_sides(ParameterBinding &b);
    void
    read_slice(const std::string &text);
  };

  extern const char *const side_label[4];
  const std::string &
  side_name(Side side);
} // namespace granular_dg::layered_strip
