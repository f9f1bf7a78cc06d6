// Linear stability of the radial field under the DG discretisation of the
// hopper (doc/hopper.md, "Why the wedge's error grows and the cone's
// decays"). In the scaled variables U = T/(rho g r) the radial field U_r is
// a steady state of d_tau U = R(U) (the semi-discrete DG operator, LLF with
// the Roe speed, no limiter); a perturbation v obeys d_tau v = J v with
// J = R'(Pi U_r). The Jacobian is built column by column with central
// differences of DGOperator::apply(), its spectrum by LAPACK. Printed per
// geometry and mesh: the largest real part of the spectrum (the asymptotic
// growth rate of a perturbation; relative to the field, since U is already
// divided by r) and the decay of the slowest mode over the paper's
// tau = ln 20. Compared with numdiff -a 5e-3 (the rates converge with the
// mesh to about that; the sign is the claim).
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_dgq.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <granular_dg/dg/cell_quadrature.h>
#include <granular_dg/dg/dg_operator.h>
#include <granular_dg/equations/hopper/radial_field.h>
#include <granular_dg/equations/hopper/system.h>

#include <complex>
#include <cstdio>

using namespace granular_dg;
using namespace granular_dg::hopper;

namespace
{
  class Radial : public Function<1>
  {
  public:
    explicit Radial(const RadialField &f)
      : Function<1>(2)
      , field(f)
    {}
    double
    value(const Point<1> &x, const unsigned int c) const override
    {
      return field.stresses(x[0])[c];
    }

  private:
    const RadialField &field;
  };

  std::complex<double>
  rightmost(const Geometry geometry, const unsigned int cells, const unsigned int degree)
  {
    const MohrCoulomb mc(32.1 * deg, 11.7 * deg);
    const double      theta_w = 30 * deg;
    const RadialField field(geometry, mc, theta_w);
    const System      physics(geometry, Variables::scaled, mc);

    Triangulation<1> tria;
    GridGenerator::subdivided_hyper_rectangle(tria, std::vector<unsigned int>{cells},
                                              Point<1>(0.), Point<1>(theta_w), true);
    for (const auto &cell : tria.active_cell_iterators())
      cell->set_material_id(0);
    const FESystem<1> fe(FE_DGQLegendre<1>(degree), 2);
    DoFHandler<1>     dof_handler(tria);
    dof_handler.distribute_dofs(fe);
    const MappingQ1<1> mapping;
    dg::BoundaryMap<1> boundary;
    boundary[0].kind = System::symmetry;
    boundary[1].kind = System::friction_wall;
    dg::DGOperator<1, System> op(physics, boundary);
    op.reinit(mapping, dof_handler);
    dg::ModalLayout<1> layout;
    layout.reinit(dof_handler);
    dg::CellQuadrature<1> quadrature;
    quadrature.reinit(layout);

    dg::VectorType U, V, Rp, Rm;
    op.initialize_vector(U);
    op.initialize_vector(V);
    op.initialize_vector(Rp);
    op.initialize_vector(Rm);
    quadrature.project(Radial(field), U);

    const unsigned int  n = U.size();
    LAPACKFullMatrix<double> J(n, n);
    const double        eta = 1e-7;
    for (unsigned int j = 0; j < n; ++j)
      {
        V = U;
        V(j) += eta;
        op.apply(0., V, Rp);
        V(j) -= 2 * eta;
        op.apply(0., V, Rm);
        for (unsigned int i = 0; i < n; ++i)
          J(i, j) = (Rp(i) - Rm(i)) / (2 * eta);
      }
    J.compute_eigenvalues();
    std::complex<double> best(-1e300, 0.);
    for (unsigned int i = 0; i < n; ++i)
      if (J.eigenvalue(i).real() > best.real())
        best = J.eigenvalue(i);
    return best;
  }
} // namespace

int
main()
{
  for (const auto geometry : {Geometry::wedge, Geometry::cone})
    for (const unsigned int degree : {1u, 2u})
      for (const unsigned int cells : {50u, 100u})
        {
          const auto kappa = rightmost(geometry, cells, degree);
          std::printf("%-5s P%u N = %3u: rightmost eigenvalue %+.4f %+.4f i, growth over "
                      "tau = ln 20: %.4f\n",
                      geometry == Geometry::wedge ? "wedge" : "cone", degree, cells,
                      kappa.real(), std::abs(kappa.imag()), std::exp(kappa.real() * std::log(20.)));
        }
  return 0;
}
