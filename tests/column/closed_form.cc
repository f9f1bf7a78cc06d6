// Checks of the exact solution of the linear column (m = 1, G = 0; Coffey & Gremaud,
// section 2) in include/granular_dg/equations/column/closed_form.h,
// against the problem it solves, not against itself:
//  - the wall condition u(0, t) = u_b and the front value u(t, t) = u_b e^{-t/2};
//  - the PDE u_tt - u_zz - u_z = 0 (2.14) by central differences (h = 1e-3:
//    residual ~ h^2 u'''' ~ 1e-7);
//  - the analytic u_t against a central difference of u;
//  - the system u_t = v_z and v_t - u_z = u (2.12)-(2.13) with sgn(v) = 1;
//  - the velocity at the front v(z, z) = -u_b e^{-z/2} (Rankine-Hugoniot);
//  - the first stop at the wall against an independent computation with
//    SciPy (quad + brentq on the same formulas, differentiating u by central
//    differences): t_s(0) = 3.2528877612, and z_s(8) = 6.92303434;
//  - the interpolated stop time against a direct root at an off-node point;
//  - the frozen profile stays stuck: |u_z/u| < 1 (friction can hold it).
#include <granular_dg/equations/column/closed_form.h>

#include <cmath>
#include <cstdio>

using namespace granular_dg::column;

int
main()
{
  const double               u_b = -1.;
  const LinearColumnSolution s(u_b);
  const double               h = 1e-3;

  for (const double t : {1., 2., 4.})
    {
      std::printf("t = %g: u(0,t) - u_b = %.1e\n", t, s.sliding_strain(0., t) - u_b);
      std::printf("t = %g: u(t,t) - u_b e^(-t/2) = %.1e\n", t,
                  s.sliding_strain(t, t) - u_b * std::exp(-0.5 * t));
      std::printf("t = %g: v(t,t) + u_b e^(-t/2) = %.1e\n", t,
                  s.sliding_velocity(t, t) + u_b * std::exp(-0.5 * t));
    }

  double pde = 0, rate = 0, mass = 0, momentum = 0;
  for (const double t : {1., 2.5, 4.})
    for (const double z : {0.2 * t, 0.5 * t, 0.8 * t})
      {
        const double u   = s.sliding_strain(z, t);
        const double utt = (s.sliding_strain(z, t + h) - 2 * u + s.sliding_strain(z, t - h)) / (h * h);
        const double uzz = (s.sliding_strain(z + h, t) - 2 * u + s.sliding_strain(z - h, t)) / (h * h);
        const double uz  = (s.sliding_strain(z + h, t) - s.sliding_strain(z - h, t)) / (2 * h);
        const double ut  = (s.sliding_strain(z, t + h) - s.sliding_strain(z, t - h)) / (2 * h);
        const double vz  = (s.sliding_velocity(z + h, t) - s.sliding_velocity(z - h, t)) / (2 * h);
        const double vt  = (s.sliding_velocity(z, t + h) - s.sliding_velocity(z, t - h)) / (2 * h);
        pde      = std::max(pde, std::abs(utt - uzz - uz));
        rate     = std::max(rate, std::abs(s.sliding_strain_rate(z, t) - ut));
        mass     = std::max(mass, std::abs(ut - vz));
        momentum = std::max(momentum, std::abs(vt - uz - u));
      }
  // the .output holds 0: numdiff's absolute tolerance 1e-5 bounds these
  std::printf("max |u_tt - u_zz - u_z| = %.1e\n", pde);
  std::printf("max |u_t - (u(t+h) - u(t-h))/2h| = %.1e\n", rate);
  std::printf("max |u_t - v_z| = %.1e\n", mass);
  std::printf("max |v_t - u_z - u| = %.1e\n", momentum);

  std::printf("first stop at the wall t_s(0) = %.10f\n", s.first_stop_time());
  // the value tests/column/point_error.py compares the shipped column with
  std::printf("u(3, 4) = %.12f (still sliding: t_s(3) = %.4f)\n", s.strain(3., 4.),
              s.stop_time(3.));
  // off-node point: the interpolation against the direct root of v(z, t) = 0
  const double z = 1.2345, ts = s.stop_time(z);
  std::printf("v(z, t_s(z)) at z = %g (interpolated t_s) = %.1e\n", z, s.sliding_velocity(z, ts));
  double ratio = 0;
  for (double y = 0.1; y < 6; y += 0.3)
    {
      const double u  = s.strain(y, 8.);
      const double uz = (s.strain(y + h, 8.) - s.strain(y - h, 8.)) / (2 * h);
      ratio           = std::max(ratio, std::abs(uz / u));
    }
  std::printf("frozen profile at t = 8 (z_s = %.4f): max |u_z/u| < 1: %s\n", s.stop_front(8.),
              ratio < 1 ? "yes" : "no");
}
