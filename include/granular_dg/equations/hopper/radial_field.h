#pragma once

#include <granular_dg/equations/hopper/system.h>

#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace granular_dg::hopper
{
  /// The radial-field BVP has no admissible solution for the parameters.
  class NoRadialField : public std::runtime_error
  {
  public:
    using std::runtime_error::runtime_error;
  };

  /**
   * Jenike's radial stress field T = rho g r T(theta) of a wedge (d = 2) or
   * cone (d = 3) of half-angle theta_w: the BVP (16)-(17)
   *   A(sigma, psi) (sigma', psi')^T = B_d(theta, sigma, psi),
   *   psi(+-theta_w) = +-psi_w,
   * in units of rho g r (sigma even, psi odd). Solved by shooting from the
   * axis: sigma(0) = sigma_0, psi(0) = 0, psi'(0) from the regular limit of
   * the ODE at theta = 0,
   *   psi'(0) = (1 - sigma_0 ((k+1) s - 1))/(k s sigma_0),  k = 2 (d=2), 4 (d=3),
   * integrated with Boost.odeint (Dormand-Prince 5(4), tolerances 1e-13), and
   * sigma_0 found with Boost.Math's TOMS 748 so that psi(theta_w) = psi_w.
   * A shot fails when |psi| reaches the singular value pi/4 + delta/2 (det A
   * = 2 s sigma (s + cos 2psi) = 0) or sigma <= 0. The solution is stored at
   * 2^12 + 1 equidistant nodes with its derivatives and evaluated by cubic
   * Hermite interpolation (error ~ 1e-15).
   */
  class RadialField
  {
  public:
    /// Throws NoRadialField when the shooting finds no admissible solution.
    RadialField(Geometry geometry, const MohrCoulomb &material, double theta_w,
                unsigned int n_intervals = 4096);

    double theta_w() const { return half_angle; }
    /// sigma_0 = sigma(0) per unit rho g r
    double sigma_axis() const { return nodes.front()[0]; }
    /// |psi(theta_w) - psi_w| of the shooting solution
    double shooting_residual() const { return residual; }
    /// max over interval midpoints of |A y' - B| / |B| with y' from the
    /// interpolant: consistency of the stored table with the ODE
    double ode_residual() const;
    /// number of sign changes of the shooting residual in the sigma_0 scan
    unsigned int n_solutions() const { return n_roots; }

    double sigma(double theta) const;
    /// psi(theta), odd in theta
    double psi(double theta) const;
    /// (T_rr, T_rt, T_tt, T_pp) per unit rho g r at theta in [-theta_w, theta_w]
    /// (T_pp: cone Haar-von Karman sigma (1 + s), wedge the mean stress sigma)
    std::array<double, 4> stresses(double theta) const;

    /// max of psi over [0, theta_w] and where it is
    double max_psi() const;
    double theta_of_max_psi() const;
    /// psi'(theta_w): psi is monotone on [0, theta_w] while this is > 0 (and
    /// stops being so, for growing theta_w, when it crosses 0)
    double psi_derivative_at_wall() const;
    /// (pi/4 + delta/2) - max |psi|: > 0 for a nonsingular solution
    double nonsingularity_margin() const;

    /// radial-field.csv: theta, theta_deg, sigma, psi, psi_deg, T_rr, T_rtheta,
    /// T_thetatheta, T_phiphi per unit rho g r, n_points points on [0, theta_w].
    void write_csv(const std::string &filename, unsigned int n_points) const;

    /// sigma', psi' of (16) at (theta, sigma, psi); theta = 0 uses the limit.
    std::array<double, 2> derivative(double theta, double sigma, double psi) const;

  private:
    Geometry    geometry;
    MohrCoulomb material;
    double      half_angle;
    double      residual = 0;
    unsigned int n_roots = 0;
    double       h = 0;
    /// (sigma, psi, sigma', psi') at theta_i = i h
    std::vector<std::array<double, 4>> nodes;

    std::array<double, 2> evaluate(double theta) const;
  };
} // namespace granular_dg::hopper
