// The linear stability limits of the CFL number of every Time stepping/scheme
// with upwind DG of degree p = 0-4 (Legendre modes), computed here from the
// schemes as the program runs them, against the table it enforces
// (dg::cfl_limit). Fourier analysis of u_t + u_x = 0: on one cell of the
// reference size 2 the semi-discrete operator of the mode exp(i j theta) is
// S(theta) = diag(2k+1) (D - 1 1^T + exp(-i theta) s 1^T) with
// D_km = (P_m, P_k') and s_k = (-1)^k; the step
// multiplies an eigenvector by R(nu z), z an eigenvalue of S, R the
// scheme's stability function: one step of the scheme (dg::SSPRK3 or
// dg::LowStorageRK with deal.II's coefficients) applied to y' = z y. The limit
// is the largest nu with |R(nu z)| <= 1 for all z (bisection), printed to 4
// digits. Also printed: the order of each scheme read off R (the first k with
// R's k-th Taylor coefficient != 1/k!), and whether the enforced table is
// within [0.98, 1] of the computed limits.
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/lac/lapack_full_matrix.h>

#include <granular_dg/dg/parameters.h>
#include <granular_dg/dg/time_integrator.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

using namespace granular_dg;
using dealii::LAPACKFullMatrix;
using cplx = std::complex<double>;

namespace
{
  /// The test equation y' = z y, y = (Re, Im) in a vector of two values,
  /// as the program's integrators see an operator.
  struct TestOperator
  {
    cplx z;
    void
    apply(double, const dg::VectorType &src, dg::VectorType &dst) const
    {
      const double re = src(0), im = src(1);
      dst(0)          = z.real() * re - z.imag() * im;
      dst(1)          = z.imag() * re + z.real() * im;
    }
    void
    apply_stage(double t, const dg::VectorType &src, dg::VectorType &dst,
                const dg::StageUpdate<> &s) const
    {
      dg::VectorType rate(src);
      apply(t, src, rate);
      for (unsigned int i = 0; i < 2; ++i)
        dst(i) = dg::stage_value(s, src(i), s.old ? (*s.old)(i) : 0., rate(i));
    }
  };

  /// R(z) of the scheme: one step of the program's integrator from y = 1
  /// with dt = 1.
  cplx
  amplification(const dg::TimeScheme scheme, const cplx z)
  {
    dg::VectorType u(2);
    u(0)            = 1.;
    const auto hook = [](dg::VectorType &, double, double) {};
    if (scheme == dg::TimeScheme::ssp_rk3)
      dg::SSPRK3<>().step(TestOperator{z}, u, 0., 1., hook);
    else
      dg::LowStorageRK(scheme).step(TestOperator{z}, u, 0., 1., hook);
    return cplx(u(0), u(1));
  }

  double
  legendre(const unsigned int k, const double x, const bool derivative)
  {
    double p0 = 1., p1 = x, d0 = 0., d1 = 1.;
    if (k == 0)
      return derivative ? 0. : 1.;
    for (unsigned int n = 1; n < k; ++n)
      {
        const double p2 = ((2 * n + 1) * x * p1 - n * p0) / (n + 1);
        const double d2 = d0 + (2 * n + 1) * p1;
        p0 = p1, p1 = p2, d0 = d1, d1 = d2;
      }
    return derivative ? d1 : p1;
  }

  /// The eigenvalues of S(theta) for degree p.
  std::vector<cplx>
  symbol_eigenvalues(const unsigned int p, const double theta)
  {
    const unsigned int       n = p + 1;
    const dealii::QGauss<1> gauss(n + 2);
    // the complex n x n matrix as the real 2n x 2n [[Re, -Im], [Im, Re]]:
    // its eigenvalues are those of S and their conjugates (|R| is the same)
    LAPACKFullMatrix<double> A(2 * n, 2 * n);
    const cplx               e = std::exp(cplx(0., -theta));
    for (unsigned int k = 0; k < n; ++k)
      for (unsigned int m = 0; m < n; ++m)
        {
          double d = 0.;
          for (unsigned int q = 0; q < gauss.size(); ++q)
            {
              const double x = 2. * gauss.point(q)[0] - 1.;
              d += 2. * gauss.weight(q) * legendre(m, x, false) * legendre(k, x, true);
            }
          const cplx s = (2. * k + 1.) * (d - 1. + e * (k % 2 ? -1. : 1.));
          A(k, m)         = s.real();
          A(k, m + n)     = -s.imag();
          A(k + n, m)     = s.imag();
          A(k + n, m + n) = s.real();
        }
    A.compute_eigenvalues();
    std::vector<cplx> z;
    for (unsigned int i = 0; i < 2 * n; ++i)
      z.push_back(A.eigenvalue(i));
    return z;
  }

  double
  stability_limit(const dg::TimeScheme scheme, const unsigned int p)
  {
    std::vector<cplx> z;
    for (unsigned int t = 0; t <= 400; ++t)
      for (const cplx &zi : symbol_eigenvalues(p, 2. * M_PI * t / 400.))
        z.push_back(zi);
    double lo = 0., hi = 4.;
    for (unsigned int it = 0; it < 50; ++it)
      {
        const double nu     = 0.5 * (lo + hi);
        bool         stable = true;
        for (const cplx &zi : z)
          stable = stable && std::abs(amplification(scheme, nu * zi)) <= 1. + 1e-13;
        (stable ? lo : hi) = nu;
      }
    return lo;
  }

  /// The order of accuracy of R: R(h) - exp(h) = O(h^{order+1}), from the
  /// Taylor coefficients of R by finite differences in the complex plane.
  unsigned int
  order(const dg::TimeScheme scheme)
  {
    // Taylor coefficients by the discrete Cauchy integral on |z| = rho
    const unsigned int N = 64;
    const double       rho = 0.5;
    double             factorial = 1.;
    for (unsigned int k = 0; k < 10; ++k)
      {
        cplx coefficient = 0.;
        for (unsigned int j = 0; j < N; ++j)
          {
            const cplx z = rho * std::exp(cplx(0., 2. * M_PI * j / N));
            coefficient += amplification(scheme, z) / std::pow(z, k) / double(N);
          }
        if (k > 0)
          factorial *= k;
        if (std::abs(coefficient.real() * factorial - 1.) > 1e-9)
          return k - 1;
      }
    return 9;
  }
} // namespace

int
main(int argc, char **argv)
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const dg::TimeScheme schemes[] = {dg::TimeScheme::ssp_rk3, dg::TimeScheme::lsrk_3_3,
                                    dg::TimeScheme::lsrk_5_4, dg::TimeScheme::lsrk_7_4,
                                    dg::TimeScheme::lsrk_9_5};
  bool table_ok = true;
  for (const auto scheme : schemes)
    {
      std::printf("%-9s order %u, CFL limits p = 0-4:", dg::time_scheme_name(scheme).c_str(),
                  order(scheme));
      for (unsigned int p = 0; p <= 4; ++p)
        {
          const double limit    = stability_limit(scheme, p);
          const double enforced = dg::cfl_limit(scheme, p);
          table_ok = table_ok && enforced <= limit && enforced >= 0.98 * limit;
          std::printf(" %.4f", limit);
        }
      std::printf("\n");
    }
  std::printf("enforced table within [0.98, 1] of the computed limits: %s\n",
              table_ok ? "yes" : "NO");
  return table_ok ? 0 : 1;
}
