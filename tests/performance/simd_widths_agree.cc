// The SIMD build against the scalar one (doc/performance.md, "SIMD build").
// The 2D layered strip (two materials in layers of width 1, exponential law,
// impedance flux, walls, a stress pulse off the axis) is advanced by 150
// SSP-RK3 steps twice: with DGOperator<2, System<2>> on the native
// VectorizedArray<double, W> (the program's operator: W = 8 with AVX-512,
// with the kernels compiled per degree), and with
// DGOperator<2, System<2>, 1>, the width of Debian's deal.II (its
// run-time-degree kernels from libdeal.ii). Printed per degree: the
// largest difference of the two states relative to the largest value,
// and whether it is below 1e-12; the test fails (exit 1) if not. The norms
// are printed to 6 digits (numdiff -r 1e-6).
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <granular_dg/dg/cell_quadrature.h>
#include <granular_dg/dg/dg_operator.h>
#include <granular_dg/dg/dg_operator.templates.h>
#include <granular_dg/equations/layered_strip/system.h>

#include <cmath>
#include <cstdio>

using namespace granular_dg;
using namespace granular_dg::layered_strip;

// the program's operator (instantiated in the library)
extern template class granular_dg::dg::DGOperator<2, System<2>>;
extern template struct granular_dg::dg::internal::DGKernels<2, System<2>, 0>;
extern template struct granular_dg::dg::internal::DGKernels<2, System<2>, 1>;
extern template struct granular_dg::dg::internal::DGKernels<2, System<2>, 2>;
extern template struct granular_dg::dg::internal::DGKernels<2, System<2>, 3>;
extern template struct granular_dg::dg::internal::DGKernels<2, System<2>, 4>;
// the scalar operator is only needed here (its run-time-degree kernels)
template class granular_dg::dg::DGOperator<2, System<2>, 1>;
template struct granular_dg::dg::internal::DGKernels<2, System<2>, -1, 1>;

namespace
{
  /// strain and velocity of a pulse at (3, 4) moving to the upper right
  class Pulse : public Function<2>
  {
  public:
    Pulse()
      : Function<2>(3)
    {}
    double
    value(const Point<2> &x, const unsigned int c) const override
    {
      const double g = std::exp(-((x[0] - 3.) * (x[0] - 3.) + (x[1] - 4.) * (x[1] - 4.)) / 2.);
      return c == 0 ? 0.3 * g : (c == 1 ? -0.2 * g : -0.1 * g);
    }
  };

  /// n SSP-RK3 steps of size dt
  template <typename Op>
  void
  advance(const Op &op, dg::VectorType &u, const double dt, const unsigned int n)
  {
    dg::VectorType k, u1;
    op.initialize_vector(k);
    op.initialize_vector(u1);
    for (unsigned int step = 0; step < n; ++step)
      {
        op.apply(0., u, k);
        u1 = u;
        u1.add(dt, k);
        op.apply(0., u1, k);
        u1.sadd(0.25, 0.75, u);
        u1.add(0.25 * dt, k);
        op.apply(0., u1, k);
        u.sadd(1. / 3., 2. / 3., u1);
        u.add(2. / 3. * dt, k);
      }
  }

  bool
  compare(const unsigned int degree)
  {
    Triangulation<2> tria;
    GridGenerator::subdivided_hyper_rectangle(tria, {40u, 8u}, Point<2>(0., 0.),
                                              Point<2>(20., 8.), true);
    for (const auto &cell : tria.active_cell_iterators())
      cell->set_material_id(static_cast<unsigned int>(std::floor(cell->center()[0])) % 2);
    const System<2> physics(StressLaw::exponential, {{4., 4., 0.}, {1., 1., 0.}},
                            NumericalFlux::impedance);
    dg::BoundaryMap<2> boundary;
    for (types::boundary_id b = 0; b < 4; ++b)
      boundary[b].kind = dg::BoundaryKind::wall;

    const FESystem<2> fe(FE_DGQLegendre<2>(degree), 3);
    DoFHandler<2>     dof_handler(tria);
    dof_handler.distribute_dofs(fe);
    const MappingQ1<2> mapping;
    dg::DGOperator<2, System<2>>    native(physics, boundary);
    dg::DGOperator<2, System<2>, 1> scalar(physics, boundary);
    native.reinit(mapping, dof_handler);
    scalar.reinit(mapping, dof_handler);

    dg::ModalLayout<2> layout;
    layout.reinit(dof_handler);
    dg::CellQuadrature<2> quadrature;
    quadrature.reinit(layout);
    dg::VectorType u_native, u_scalar;
    native.initialize_vector(u_native);
    scalar.initialize_vector(u_scalar);
    quadrature.project(Pulse(), u_native);
    u_scalar = u_native;

    const double dt = 0.1 / (2 * degree + 1) / native.max_speed_over_h(u_native, 0.);
    advance(native, u_native, dt, 150);
    advance(scalar, u_scalar, dt, 150);

    dg::VectorType difference = u_native;
    difference -= u_scalar;
    const double relative = difference.linfty_norm() / u_native.linfty_norm();
    const bool   agree    = relative < 1e-12;
    std::printf("P%u, native lanes against 1: |u|_2 = %.6e and %.6e; max difference "
                "relative to max |u| below 1e-12: %s\n",
                degree, u_native.l2_norm(), u_scalar.l2_norm(), agree ? "yes" : "NO");
    std::fprintf(stderr, "P%u: %u lanes against 1 differ by %.3e relative\n", degree,
                 static_cast<unsigned int>(VectorizedArray<double>::size()), relative);
    return agree;
  }
} // namespace

int
main()
{
  bool ok = true;
  for (const unsigned int degree : {1u, 2u, 3u})
    ok = compare(degree) && ok;
  return ok ? 0 : 1;
}
