// Unit test of the limiter's SIMD batches: in 1D with every cell
// examined, ModalLimiter analyses W interior cells at once (W = the SIMD
// build's width, 8 lanes of AVX-512 here; 1 in a scalar build, where both
// paths are one): jumps, neighbour differences, the characteristic or
// flux-variable transform on VectorizedArray, then per lane the TVB test and,
// for a troubled lane, its new modes from what the batch computed. For each 1D physics and limiter the
// program uses -- elasticity (quadratic law, two materials) in its
// flux_variables, elasticity (exponential law) and the column (m = 3/2)
// characteristic, periodic advection componentwise -- at degrees 1-4 on 37
// cells, half of them smooth and half rough, so that both outcomes occur:
//  - the troubled flags with batches equal those cell by cell;
//  - the limited states are bitwise equal.
// And the batch's TVB test (internal::tvb_keeps_lanes) against the scalar one
// (tvb_keeps) on every combination of special values of the jump and the two
// differences (NaN, +-inf, +-0, equal magnitudes, both signs) and M h^2 in
// {0, 1}, packed into lanes.
// Prints the number of troubled cells and yes/no; compared exactly.
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>

#include <granular_dg/dg/limiter.h>
#include <granular_dg/dg/limiter.templates.h>
#include <granular_dg/dg/operator.h>
#include <granular_dg/equations/column/system.h>
#include <granular_dg/equations/layered_strip/system.h>
#include <granular_dg/equations/skeleton/system.h>

#include "line_test_tools.h"

#include <iostream>
#include <limits>
#include <random>
#include <string>

using namespace dealii;
using namespace granular_dg;
using line_test::yes;

namespace
{
  constexpr unsigned int n_cells = 37;

  /// A state: cell averages draw(i, s) of a smooth profile s; in the cells
  /// c % 4 < 2 a slope of a tenth of the central difference of the averages
  /// and no higher modes (the TVB test passes but near extrema), in the
  /// others random higher modes (it mostly fails).
  template <typename Draw>
  void
  fill(dg::VectorType &u, const unsigned int n_components, const unsigned int n_modes,
       const Draw &draw)
  {
    std::mt19937                           gen(5);
    std::uniform_real_distribution<double> r(-1., 1.);
    const double                           h = 1. / n_cells;
    for (unsigned int c = 0; c < n_cells; ++c)
      for (unsigned int i = 0; i < n_components; ++i)
        for (unsigned int k = 0; k < n_modes; ++k)
          {
            const auto average = [&](const double cell) {
              return draw(i, std::sin(2. * M_PI * (cell + 0.5) * h + i));
            };
            double value;
            if (k == 0)
              value = average(c);
            else if (c % 4 < 2)
              value = k == 1 ? 0.1 * (average(c + 1.) - average(c - 1.)) : 0.;
            else
              value = 0.3 * draw(i, r(gen)) / k;
            u[(c * n_components + i) * n_modes + k] = value;
          }
  }

  template <typename Physics, typename Draw>
  void
  check(const std::string &name, const Physics &physics, const dg::LimiterType type,
        const dg::BoundaryMap<1> &bc, const bool periodic, const Draw &draw)
  {
    constexpr unsigned int nc = Physics::n_components;
    for (unsigned int degree = 1; degree <= 4; ++degree)
      {
        Triangulation<1> tria;
        // two materials for the elasticity's layers, one for the others
        line_test::make_line(tria, n_cells, periodic, Physics::n_coefficients == 3);
        DoFHandler<1> dof_handler(tria);
        dof_handler.distribute_dofs(FESystem<1>(FE_DGQLegendre<1>(degree), nc));

        dg::ModalLimiter<1, Physics> batches(physics, type, 0., bc), cells(physics, type, 0., bc);
        batches.reinit(dof_handler);
        cells.reinit(dof_handler);
        cells.set_simd_batches(false);

        dg::VectorType u(dof_handler.n_dofs());
        fill(u, nc, degree + 1, draw);
        dg::VectorType u_batches = u, u_cells = u;
        const unsigned int n_batches = batches.apply(u_batches, 0.), n_cells_troubled = cells.apply(u_cells, 0.);
        bool equal = n_batches == n_cells_troubled &&
                     batches.troubled_cells() == cells.troubled_cells() &&
                     batches.n_flagged() == cells.n_flagged();
        for (unsigned int i = 0; i < u.size(); ++i)
          equal &= u_batches[i] == u_cells[i];
        std::cout << name << " degree " << degree << ": troubled " << n_cells_troubled << " of "
                  << n_cells << "; batches equal cells bitwise: " << yes(equal) << '\n';
      }
  }

  /// Whether tvb_keeps_lanes() equals tvb_keeps() on every combination.
  bool
  tvb_lanes_agree()
  {
    using VA             = VectorizedArray<double>;
    const double inf     = std::numeric_limits<double>::infinity();
    const double v[]     = {std::nan(""), -inf, -2., -1., -0.5, -0., 0., 0.5, 1., 2., inf};
    std::vector<std::array<double, 4>> cases;
    for (const double a : v)
      for (const double b : v)
        for (const double c : v)
          for (const double Mh2 : {0., 1.})
            cases.push_back({{a, b, c, Mh2}});
    bool agree = true;
    for (std::size_t first = 0; first < cases.size(); first += VA::size())
      {
        VA a(0.), b(0.), c(0.), Mh2(0.);
        for (unsigned int l = 0; l < VA::size() && first + l < cases.size(); ++l)
          {
            a[l]   = cases[first + l][0];
            b[l]   = cases[first + l][1];
            c[l]   = cases[first + l][2];
            Mh2[l] = cases[first + l][3];
          }
        const VA keeps = dg::internal::tvb_keeps_lanes(a, b, c, Mh2);
        for (unsigned int l = 0; l < VA::size(); ++l)
          agree &= (keeps[l] != 0.) == dg::internal::tvb_keeps(a[l], b[l], c[l], Mh2[l]);
      }
    return agree;
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
  const auto strain_velocity = [](const unsigned int i, const double r) {
    return i == 0 ? 0.05 * r : 0.3 * r;
  };
  check("elasticity quadratic flux_variables",
        Elasticity(layered_strip::StressLaw::quadratic, layers, layered_strip::NumericalFlux::impedance),
        dg::LimiterType::physics_variables, wall_outflow, false, strain_velocity);
  check("elasticity exponential characteristic",
        Elasticity(layered_strip::StressLaw::exponential, layers,
                   layered_strip::NumericalFlux::local_lax_friedrichs),
        dg::LimiterType::characteristic, wall_outflow, false, strain_velocity);

  column::Parameters column_parameters;
  column_parameters.m       = 1.5;
  column_parameters.gravity = -1.;
  check("column m = 3/2 characteristic", column::System(column_parameters),
        dg::LimiterType::characteristic, wall_outflow, false,
        [](const unsigned int i, const double r) { return i == 0 ? -0.3 + 0.2 * r : 0.1 * r; });

  check("advection periodic componentwise",
        skeleton::System<1>(Tensor<1, 1>({1.}), skeleton::NumericalFlux::upwind),
        dg::LimiterType::componentwise, {}, true,
        [](const unsigned int, const double r) { return r; });

  std::cout << "TVB test of the batches equals limit_cell()'s on special values: "
            << yes(tvb_lanes_agree()) << '\n';
}
