#pragma once

#include <deal.II/base/function.h>

#include <memory>
#include <vector>

namespace granular_dg::column
{
  /**
   * The exact solution of the linear column (m = 1, G = 0) of Coffey & Gremaud,
   * section 2: in the sliding region (v > 0) behind the pressure front z = t,
   * u solves u_tt - u_zz - u_z = 0 (2.14) and
   * \f[
   *   u(z,t) = u_b e^{-z/2}\Big(\cosh\tfrac{t-z}{2} - \tfrac t2 \int_{z/t}^1
   *     \cosh\tfrac{yt-z}{2}\,\frac{J_1(\frac t2\sqrt{1-y^2})}{\sqrt{1-y^2}}\,dy\Big),
   *   \qquad
   *   v(z,t) = -u_b e^{-t/2} - \int_z^t u_t(y,t)\,dy
   * \f]
   * (u = v = 0 ahead of the front). The velocity first vanishes at the wall
   * (t_s(0) = 3.2529 for u_b = -1); a stopping front z_s(t) then runs behind the
   * pressure front. It is supersonic (speed > 1, the sound speed), so the
   * formulas stay exact ahead of it, and behind it the material is frozen with
   * the strain it had when it stopped: u(z, t) = u(z, t_s(z)), v = 0, where
   * v(z, t_s(z)) = 0. The frozen profile stays stuck (|u_z / u| < 1, the
   * friction can hold it), so it is also the asymptotic profile.
   *
   * The integrands are entire functions of y (J_1(a s)/s and J_0(a s) are even
   * in s = sqrt(1 - y^2)), so fixed Gauss-Legendre rules converge
   * exponentially; u_t is differentiated analytically. Valid for t up to about
   * 20 (the cosh term cancels against the integral: round-off ~ 1e-16 e^{t/2}).
   */
  class LinearColumnSolution
  {
  public:
    explicit LinearColumnSolution(double u_b);

    /// u and v of the sliding-region formulas (no stopping front)
    double sliding_strain(double z, double t) const;
    double sliding_velocity(double z, double t) const;
    double sliding_strain_rate(double z, double t) const; ///< u_t

    /// t_s(z): when the material at z stops (v(z, t_s) = 0, t_s > z); cubic
    /// interpolation in a table with spacing 0.02 whose nodes are solved to
    /// round-off (interpolation error below 1e-8)
    double stop_time(double z) const;
    /// z_s(t): the stopping front at time t (0 before t_s(0))
    double stop_front(double t) const;

    /// The full solution with the frozen region behind the stopping front.
    double strain(double z, double t) const;
    double velocity(double z, double t) const;

    /// Time of the first stop (at the wall).
    double first_stop_time() const { return stop_time(0.); }

    double u_b;

  private:
    /// t_s at z = k * table_spacing, k = 0, 1, ...: extended on demand
    double                      stop_time_at_node(unsigned int k) const;
    static constexpr double     table_spacing = 0.02;
    mutable std::vector<double> stop_time_table;
  };

  /// The exact solution as a Function<1> of (strain, velocity) for error
  /// measurement.
  class LinearColumnFunction : public dealii::Function<1>
  {
  public:
    explicit LinearColumnFunction(double u_b);
    double value(const dealii::Point<1> &p, unsigned int component) const override;
    void   set_time(double t) override;

  private:
    LinearColumnSolution solution;
    double               front = 0.; ///< stop_front at the current time
  };
} // namespace granular_dg::column
