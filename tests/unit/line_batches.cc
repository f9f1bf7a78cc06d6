// Unit test of the line engine's SIMD batches: LineOperator runs
// the interior cells of a line W at a time (W = the SIMD build's width, 8
// lanes of AVX-512 here; 1 in a scalar build, where both paths are one) and
// the rest cell by cell. For every 1D physics with a batched kernel --
// elasticity with the quadratic law, two materials and the impedance flux
// (layered_1d), with the exponential law and the local Lax-Friedrichs flux
// (its SIMD exp is within 2 ulp of std::exp), the column (m = 3/2, gravity: a
// source term) and linear advection on a periodic line -- and degrees 0-4,
// on 37 cells (4 batches and 5 single cells):
//  - the rates with batches equal the rates cell by cell to 1e-14 of their
//    size (the two differ by rounding only: the compiler's fused multiply-adds
//    and the SIMD exp);
//  - a stage written in place (dst = src, as the low-storage schemes do)
//    equals the same stage written to another vector, bit for bit: a batch
//    reads its cells and the next one before it writes.
// Prints yes/no per physics and degree; compared exactly.
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q1.h>

#include <granular_dg/dg/line_operator.h>
#include <granular_dg/equations/column/system.h>
#include <granular_dg/equations/layered_strip/system.h>
#include <granular_dg/equations/skeleton/system.h>

#include "line_test_tools.h"

#include <iostream>
#include <random>
#include <string>

using namespace dealii;
using namespace granular_dg;
using line_test::yes;

namespace
{
  constexpr unsigned int n_cells = 37;

  /// A state: component i of every cell from draw(i), modes decaying with
  /// the degree (a smooth-looking polynomial per cell).
  template <typename Draw>
  void
  fill(dg::VectorType &u, const unsigned int n_components, const unsigned int n_modes,
       const Draw &draw)
  {
    std::mt19937                           gen(11);
    std::uniform_real_distribution<double> r(-1., 1.);
    for (unsigned int c = 0; c < n_cells; ++c)
      for (unsigned int i = 0; i < n_components; ++i)
        for (unsigned int k = 0; k < n_modes; ++k)
          u[(c * n_components + i) * n_modes + k] =
            k == 0 ? draw(i, r(gen)) : 0.1 * draw(i, r(gen)) / (k * k);
  }

  template <typename Physics, typename Draw>
  void
  check(const std::string &name, const Physics &physics, const dg::BoundaryMap<1> &bc,
        const bool periodic, const Draw &draw)
  {
    constexpr unsigned int nc = Physics::n_components;
    for (unsigned int degree = 0; degree <= 4; ++degree)
      {
        Triangulation<1> tria;
        // two materials for the elasticity's layers, one for the others
        line_test::make_line(tria, n_cells, periodic, Physics::n_coefficients == 3);
        DoFHandler<1> dof_handler(tria);
        dof_handler.distribute_dofs(FESystem<1>(FE_DGQLegendre<1>(degree), nc));
        const MappingQ1<1> mapping;

        dg::LineOperator<Physics> batches(physics, bc), cells(physics, bc);
        batches.reinit(mapping, dof_handler);
        cells.reinit(mapping, dof_handler);
        cells.set_simd_batches(false);

        dg::VectorType u, r_batches, r_cells, out_of_place, in_place;
        batches.initialize_vector(u);
        fill(u, nc, degree + 1, draw);
        r_batches = u;
        r_cells   = u;
        batches.apply(0.3, u, r_batches);
        cells.apply(0.3, u, r_cells);
        double size = 0, difference = 0;
        for (unsigned int i = 0; i < u.size(); ++i)
          {
            size       = std::max(size, std::abs(r_cells[i]));
            difference = std::max(difference, std::abs(r_batches[i] - r_cells[i]));
          }

        dg::StageUpdate<> stage;
        stage.gamma  = 0.01;
        out_of_place = u;
        in_place     = u;
        batches.apply_stage(0.3, u, out_of_place, stage);
        batches.apply_stage(0.3, in_place, in_place, stage);
        bool equal = true;
        for (unsigned int i = 0; i < u.size(); ++i)
          equal &= in_place[i] == out_of_place[i];

        std::cout << name << " degree " << degree
                  << ": batches equal cells to 1e-14: " << yes(difference <= 1e-14 * size)
                  << "; in place bitwise equal: " << yes(equal) << '\n';
      }
  }
} // namespace

int
main()
{
  using Elasticity = layered_strip::System<1>;
  const std::vector<layered_strip::Material> layers{{3., 3., 0.3}, {1., 1., 0.3}};
  dg::BoundaryMap<1>                      wall_outflow;
  wall_outflow[0].kind = dg::BoundaryKind::wall;
  wall_outflow[1].kind = dg::BoundaryKind::outflow;
  // strain within the hyperbolic range of both laws, any velocity
  const auto strain_velocity = [](const unsigned int i, const double r) {
    return i == 0 ? 0.05 * r : 0.3 * r;
  };
  check("elasticity quadratic impedance",
        Elasticity(layered_strip::StressLaw::quadratic, layers, layered_strip::NumericalFlux::impedance),
        wall_outflow, false, strain_velocity);
  check("elasticity exponential LLF",
        Elasticity(layered_strip::StressLaw::exponential, layers,
                   layered_strip::NumericalFlux::local_lax_friedrichs),
        wall_outflow, false, strain_velocity);

  column::Parameters column_parameters;
  column_parameters.m       = 1.5;
  column_parameters.gravity = -1.;
  // compressed (u < 0): the sound speed sqrt(3/2 sqrt(-u)) is defined
  check("column m = 3/2", column::System(column_parameters), wall_outflow, false,
        [](const unsigned int i, const double r) { return i == 0 ? -0.3 + 0.2 * r : 0.1 * r; });

  check("advection periodic",
        skeleton::System<1>(Tensor<1, 1>({1.}), skeleton::NumericalFlux::upwind), {}, true,
        [](const unsigned int, const double r) { return r; });
}
