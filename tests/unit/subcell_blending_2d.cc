// Unit test of subcell blending in the 2D MatrixFree engine (Limiter/subcell
// blending, dg/blended_cells.h), on linear advection
// u_t + b . grad u = 0, b = (1, 0.5), with the upwind flux, 40 x 40 periodic
// cells of (0, 1)^2, degrees 1-3: a smooth 0.5 sin(2 pi x) sin(2 pi y) + 2
// everywhere but in one cell, which holds a jump in x (the L2 projection of
// a step at the cell's 40 %).
//  - only the jump cell and its four face neighbours are blended: the jump
//    cell by alpha_max, the neighbours by half of it (the smoothing), every
//    other cell by 0, and there the rate is bit for bit the rate without
//    blending;
//  - conservation: the sum of |K| times the rate of the means is 0 to
//    round-off (periodic), with and without blending, and every cell's mean
//    rate is the DG one;
//  - with alpha_max = 1 the jump cell's rate has, over each of its
//    (p + 1)^2 subcells, the mean fv_j + (R_0 - mean_j fv_j): fv_j the
//    first-order upwind finite-volume rate of subcell j from the subcell
//    means (computed here by quadrature of the cell's and its neighbours'
//    polynomials, not by the engine's tables), R_0 the DG rate of the mean.
// Prints yes/no per check and degree; compared exactly.
#include <deal.II/base/mpi.h>
#include <deal.II/base/polynomial.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <granular_dg/dg/dg_operator.h>
#include <granular_dg/equations/skeleton/system.h>

#include <cmath>
#include <iostream>
#include <map>
#include <vector>

using namespace dealii;
using namespace granular_dg;
using Operator2D = dg::DGOperator<2, skeleton::System<2>>;
extern template class granular_dg::dg::DGOperator<2, skeleton::System<2>>;

namespace
{
  constexpr unsigned int n = 40, jump_x = 20, jump_y = 13;
  constexpr double       h = 1. / n, bx = 1., by = 0.5;

  double
  legendre(const unsigned int k, const double x)
  {
    return Polynomials::Legendre(k).value(x);
  }

  /// the modes (m = kx + n1 ky) on the unit cell of f(xi, eta); exact for
  /// a jump at xi = 0.4 (Gauss points on both sides)
  template <typename F>
  std::vector<double>
  project(const unsigned int n1, const F &f)
  {
    std::vector<double> modes(n1 * n1);
    const QGauss<1>     q(12);
    for (unsigned int m = 0; m < n1 * n1; ++m)
      for (const auto &[a, b] : {std::pair{0., 0.4}, std::pair{0.4, 1.}})
        for (unsigned int i = 0; i < q.size(); ++i)
          for (unsigned int k = 0; k < q.size(); ++k)
            {
              const double xi = a + (b - a) * q.point(i)[0], eta = q.point(k)[0];
              modes[m] += (b - a) * q.weight(i) * q.weight(k) * f(xi, eta) *
                          legendre(m % n1, xi) * legendre(m / n1, eta);
            }
    return modes;
  }

  /// the mean of the polynomial with these modes over [x0, x1] x [y0, y1]
  double
  mean(const std::vector<double> &modes, const unsigned int n1, const double x0, const double x1,
       const double y0, const double y1)
  {
    const QGauss<1> q(8);
    double          s = 0;
    for (unsigned int m = 0; m < modes.size(); ++m)
      for (unsigned int i = 0; i < q.size(); ++i)
        for (unsigned int k = 0; k < q.size(); ++k)
          s += q.weight(i) * q.weight(k) * modes[m] *
               legendre(m % n1, x0 + (x1 - x0) * q.point(i)[0]) *
               legendre(m / n1, y0 + (y1 - y0) * q.point(k)[0]);
    return s;
  }

  const char *
  yes(const bool b)
  {
    return b ? "yes" : "no";
  }

  void
  check(const unsigned int degree)
  {
    const unsigned int n1 = degree + 1;
    Triangulation<2>   tria;
    GridGenerator::subdivided_hyper_cube(tria, n, 0., 1., true);
    std::vector<GridTools::PeriodicFacePair<Triangulation<2>::cell_iterator>> pairs;
    GridTools::collect_periodic_faces(tria, 0, 1, 0, pairs);
    GridTools::collect_periodic_faces(tria, 2, 3, 1, pairs);
    tria.add_periodicity(pairs);
    DoFHandler<2> dof_handler(tria);
    dof_handler.distribute_dofs(FESystem<2>(FE_DGQLegendre<2>(degree), 1));
    const MappingQ1<2> mapping;

    const skeleton::System<2> physics(Tensor<1, 2>({bx, by}), skeleton::NumericalFlux::upwind);
    Operator2D                plain(physics, {}), blended(physics, {}), finite_volume(physics, {});
    plain.reinit(mapping, dof_handler);
    blended.set_subcell_blending(0.5);
    blended.reinit(mapping, dof_handler);
    finite_volume.reinit(mapping, dof_handler);
    finite_volume.set_subcell_blending(1.);

    // the state, and each cell's modes by its (ix, iy)
    dg::VectorType u, r_plain, r_blended, r_fv;
    for (auto *v : {&u, &r_plain, &r_blended, &r_fv})
      plain.initialize_vector(*v);
    std::map<std::pair<unsigned int, unsigned int>, std::vector<double>> modes_of;
    std::vector<std::pair<unsigned int, unsigned int>>                   position;
    std::vector<types::global_dof_index> dofs(n1 * n1);
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        const unsigned int ix = std::lround(cell->center()[0] / h - 0.5),
                           iy = std::lround(cell->center()[1] / h - 0.5);
        const auto modes =
          ix == jump_x && iy == jump_y ?
            project(n1, [](const double xi, double) { return xi < 0.4 ? 3. : 1.; }) :
            project(n1, [&](const double xi, const double eta) {
              return 0.5 * std::sin(2 * M_PI * (ix + xi) * h) * std::sin(2 * M_PI * (iy + eta) * h) +
                     2.;
            });
        cell->get_dof_indices(dofs);
        for (unsigned int m = 0; m < n1 * n1; ++m)
          u[dofs[m]] = modes[m];
        modes_of[{ix, iy}] = modes;
        position.emplace_back(ix, iy);
      }
    plain.apply(0., u, r_plain);
    blended.apply(0., u, r_blended);
    finite_volume.apply(0., u, r_fv);

    // blending factors (owned cells in active_cell_iterators() order), and
    // the rates of unblended cells; the mean rate of every cell
    const auto &alpha        = blended.blending_factors();
    bool        factors_ok   = alpha.size() == n * n;
    bool        unblended_eq = true, means_eq = true;
    unsigned int k = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        const auto [ix, iy] = position[k];
        const unsigned int distance =
          std::abs(int(ix) - int(jump_x)) + std::abs(int(iy) - int(jump_y));
        const double expected = distance == 0 ? 0.5 : distance == 1 ? 0.25 : 0.;
        factors_ok &= k < alpha.size() && alpha[k] == expected;
        cell->get_dof_indices(dofs);
        for (unsigned int m = 0; m < n1 * n1; ++m)
          if (expected == 0 || m == 0)
            {
              unblended_eq &= r_blended[dofs[m]] == r_plain[dofs[m]];
              means_eq &= r_fv[dofs[m]] == r_plain[dofs[m]];
            }
        ++k;
      }
    std::cout << "degree " << degree << ": blending factors 0.5 at the jump, 0.25 beside it, "
              << "0 elsewhere: " << yes(factors_ok)
              << "; unblended cells' rates and all mean rates bitwise unchanged: "
              << yes(unblended_eq && means_eq) << '\n';

    // conservation: sum_K |K| d(mean_K)/dt = 0 (periodic)
    const auto total = [&](const dg::VectorType &r) {
      double s = 0, size = 0;
      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          cell->get_dof_indices(dofs);
          s += h * h * r[dofs[0]];
          size += h * h * std::abs(r[dofs[0]]);
        }
      return std::abs(s) / size;
    };
    std::cout << "degree " << degree << ": |sum |K| dmean/dt| / sum ||K| dmean/dt| < 1e-14 "
              << "plain / blended / finite volume: " << yes(total(r_plain) < 1e-14) << ' '
              << yes(total(r_blended) < 1e-14) << ' ' << yes(total(r_fv) < 1e-14) << '\n';

    // alpha = 1 in the jump cell: subcell means of its rate
    const auto &cell_modes = modes_of[{jump_x, jump_y}];
    const auto &left       = modes_of[{jump_x - 1, jump_y}];
    const auto &below      = modes_of[{jump_x, jump_y - 1}];
    const auto  sub        = [&](const std::vector<double> &m, const int jx, const int jy) {
      return mean(m, n1, double(jx) / n1, double(jx + 1) / n1, double(jy) / n1,
                  double(jy + 1) / n1);
    };
    std::vector<double> rate(n1 * n1), fv(n1 * n1);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (std::lround(cell->center()[0] / h - 0.5) == jump_x &&
          std::lround(cell->center()[1] / h - 0.5) == jump_y)
        {
          cell->get_dof_indices(dofs);
          for (unsigned int m = 0; m < n1 * n1; ++m)
            rate[m] = r_fv[dofs[m]];
        }
    double fv_mean = 0;
    for (unsigned int jy = 0; jy < n1; ++jy)
      for (unsigned int jx = 0; jx < n1; ++jx)
        {
          // upwind (b > 0): the flux through a subcell face is b_d times
          // the mean of the subcell before it
          const double here = sub(cell_modes, jx, jy);
          const double west = jx > 0 ? sub(cell_modes, jx - 1, jy) : sub(left, n1 - 1, jy);
          const double south = jy > 0 ? sub(cell_modes, jx, jy - 1) : sub(below, jx, n1 - 1);
          fv[jx + n1 * jy]   = -(bx * (here - west) + by * (here - south)) * n1 / h;
          fv_mean += fv[jx + n1 * jy] / (n1 * n1);
        }
    double worst = 0, scale = 0;
    for (unsigned int jy = 0; jy < n1; ++jy)
      for (unsigned int jx = 0; jx < n1; ++jx)
        {
          const double expected = fv[jx + n1 * jy] + (rate[0] - fv_mean);
          worst = std::max(worst, std::abs(sub(rate, jx, jy) - expected));
          scale = std::max(scale, std::abs(expected));
        }
    std::cout << "degree " << degree
              << ": alpha = 1: the rate's subcell means are the FV rates plus the DG mean's "
                 "correction within 1e-12 relative: "
              << yes(worst <= 1e-12 * scale) << '\n';
  }
} // namespace

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  for (unsigned int degree = 1; degree <= 3; ++degree)
    check(degree);
}
