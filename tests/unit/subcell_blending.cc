// Unit test of subcell blending in the line engine (Limiter/subcell
// blending, dg/subcell_blending.h), on linear advection u_t + u_x = 0
// with the upwind flux, 40 periodic cells of (0, 1), degrees 1-4: a smooth
// sine everywhere but in cell 20, which holds a jump (the L2 projection of a
// step at the cell's 40 %).
//  - the tables: the subcell means of the modes and the modes of subcell
//    means are inverse to each other;
//  - only the jump cell and its two neighbours are blended: the jump cell by
//    alpha_max, the neighbours by half of it (the smoothing), every other cell
//    by 0, and there the rate is bit for bit the rate without blending of
//    the cell-by-cell kernel (blended runs go cell by cell; the SIMD batches
//    of unblended runs agree with it to 1e-14, unit/line_batches: on
//    AVX-512 not bit for bit at degree 3);
//  - conservation: the sum of h times the rate of the means is 0 to
//    round-off (periodic), with and without blending;
//  - with alpha_max = 1 the jump cell's rate is the finite-volume rate: its
//    subcell means (of the rate polynomial) are -(F_{j+1/2} - F_{j-1/2})
//    (p + 1) / h, F the upwind flux of the subcell means (computed here by
//    quadrature of the cell's polynomial, not by the engine's tables) inside
//    the cell and of the traces at its faces.
// Prints yes/no per check and degree; compared exactly.
#include <deal.II/base/polynomial.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/tria.h>

#include <granular_dg/dg/line_operator.h>
#include <granular_dg/equations/skeleton/system.h>

#include <cmath>
#include <iostream>
#include <vector>

using namespace dealii;
using namespace granular_dg;

namespace
{
  constexpr unsigned int n_cells = 40, jump_cell = 20;

  /// the modes of f on [0, 1] (orthonormal Legendre: mode k = int f L_k)
  template <typename F>
  std::vector<double>
  project(const unsigned int n_modes, const F &f)
  {
    // Gauss points on both sides of a possible jump at 0.4 (exact then)
    std::vector<double> modes(n_modes);
    const QGauss<1>     q(12);
    for (unsigned int k = 0; k < n_modes; ++k)
      {
        const Polynomials::Legendre L(k);
        for (const auto &[a, b] : {std::pair{0., 0.4}, std::pair{0.4, 1.}})
          for (unsigned int i = 0; i < q.size(); ++i)
            {
              const double x = a + (b - a) * q.point(i)[0];
              modes[k] += (b - a) * q.weight(i) * f(x) * L.value(x);
            }
      }
    return modes;
  }

  /// the mean of the polynomial with these modes over [a, b] of [0, 1]
  double
  mean(const std::vector<double> &modes, const double a, const double b)
  {
    const QGauss<1> q(8);
    double          s = 0;
    for (unsigned int k = 0; k < modes.size(); ++k)
      {
        const Polynomials::Legendre L(k);
        for (unsigned int i = 0; i < q.size(); ++i)
          s += q.weight(i) * modes[k] * L.value(a + (b - a) * q.point(i)[0]);
      }
    return s;
  }

  bool
  alpha_fv_is_one(const dg::LineOperator<skeleton::System<1>> &op)
  {
    return op.blending_factors().at(jump_cell) == 1.;
  }

  const char *
  yes(const bool b)
  {
    return b ? "yes" : "no";
  }

  void
  check(const unsigned int degree)
  {
    const unsigned int nm = degree + 1;
    Triangulation<1>   tria;
    GridGenerator::subdivided_hyper_cube(tria, n_cells, 0., 1., true);
    std::vector<GridTools::PeriodicFacePair<Triangulation<1>::cell_iterator>> pairs;
    GridTools::collect_periodic_faces(tria, 0, 1, 0, pairs);
    tria.add_periodicity(pairs);
    DoFHandler<1> dof_handler(tria);
    dof_handler.distribute_dofs(FESystem<1>(FE_DGQLegendre<1>(degree), 1));
    const MappingQ1<1> mapping;

    const Tensor<1, 1>             velocity({1.});
    const skeleton::System<1>      physics(velocity, skeleton::NumericalFlux::upwind);
    dg::LineOperator<skeleton::System<1>> plain(physics, {}), blended(physics, {}),
      finite_volume(physics, {});
    plain.reinit(mapping, dof_handler);
    // blended runs go cell by cell: compare with the cell-by-cell kernel
    // (the SIMD batches agree with it to 1e-14, unit/line_batches)
    plain.set_simd_batches(false);
    blended.reinit(mapping, dof_handler);
    finite_volume.reinit(mapping, dof_handler);
    blended.set_subcell_blending(0.5);
    finite_volume.set_subcell_blending(1.);

    // the state: sin(2 pi x) + 2, and a jump in the jump cell
    dg::VectorType u, r_plain, r_blended, r_fv;
    plain.initialize_vector(u);
    plain.initialize_vector(r_plain);
    plain.initialize_vector(r_blended);
    plain.initialize_vector(r_fv);
    const double h = 1. / n_cells;
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        const auto modes =
          c == jump_cell ?
            project(nm, [](const double xi) { return xi < 0.4 ? 3. : 1.; }) :
            project(nm, [&](const double xi) { return std::sin(2 * M_PI * (c + xi) * h) + 2.; });
        for (unsigned int k = 0; k < nm; ++k)
          u[c * nm + k] = modes[k];
      }
    plain.apply(0., u, r_plain);
    blended.apply(0., u, r_blended);
    finite_volume.apply(0., u, r_fv);

    // blending factors and the rates of unblended cells
    const auto &alpha        = blended.blending_factors();
    bool        factors_ok   = alpha.size() == n_cells;
    bool        unblended_eq = true;
    for (unsigned int c = 0; c < n_cells && factors_ok; ++c)
      {
        const unsigned int distance = std::abs(int(c) - int(jump_cell));
        const double expected = distance == 0 ? 0.5 : distance == 1 ? 0.25 : 0.;
        factors_ok &= alpha[c] == expected;
        if (expected == 0)
          for (unsigned int k = 0; k < nm; ++k)
            unblended_eq &= r_blended[c * nm + k] == r_plain[c * nm + k];
      }
    std::cout << "degree " << degree << ": blending factors 0.5 at the jump, 0.25 beside it, "
              << "0 elsewhere: " << yes(factors_ok)
              << "; unblended cells' rates bitwise unchanged: " << yes(unblended_eq) << '\n';

    // conservation: sum_c h d(mean_c)/dt = 0 (periodic)
    const auto total = [&](const dg::VectorType &r) {
      double s = 0, size = 0;
      for (unsigned int c = 0; c < n_cells; ++c)
        {
          s += h * r[c * nm];
          size += h * std::abs(r[c * nm]);
        }
      return std::abs(s) / size;
    };
    std::cout << "degree " << degree << ": |sum h dmean/dt| / sum |h dmean/dt| < 1e-14 "
              << "plain / blended / finite volume: " << yes(total(r_plain) < 1e-14) << ' '
              << yes(total(r_blended) < 1e-14) << ' ' << yes(total(r_fv) < 1e-14) << '\n';

    // alpha = 1 in the jump cell: the rate's subcell means are the FV rates
    std::vector<double> cell(nm), rate(nm), left(nm);
    for (unsigned int k = 0; k < nm; ++k)
      {
        cell[k] = u[jump_cell * nm + k];
        left[k] = u[(jump_cell - 1) * nm + k];
        rate[k] = r_fv[jump_cell * nm + k];
      }
    // upwind flux (velocity 1): at the cell's faces the left side's trace
    // (the DG flux), inside the cell the left subcell's mean
    const auto trace_at_1 = [](const std::vector<double> &modes) {
      double s = 0;
      for (unsigned int k = 0; k < modes.size(); ++k)
        s += modes[k] * Polynomials::Legendre(k).value(1.);
      return s;
    };
    double F_minus = trace_at_1(left), worst = 0, scale = 0;
    for (unsigned int j = 0; j < nm; ++j)
      {
        const double F_plus =
          j + 1 < nm ? mean(cell, double(j) / nm, double(j + 1) / nm) : trace_at_1(cell);
        const double fv  = -(F_plus - F_minus) * nm / h;
        const double got = mean(rate, double(j) / nm, double(j + 1) / nm);
        worst            = std::max(worst, std::abs(got - fv));
        scale            = std::max(scale, std::abs(fv));
        F_minus          = F_plus;
      }
    std::cout << "degree " << degree
              << ": alpha = 1: the rate's subcell means are the FV rates within 1e-12 relative: "
              << yes(alpha_fv_is_one(finite_volume) && worst <= 1e-12 * scale) << '\n';
  }
} // namespace

int
main()
{
  for (unsigned int degree = 1; degree <= 4; ++degree)
    check(degree);
}
