#pragma once

#include <granular_dg/equations/hopper/radial_field.h>

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace granular_dg::hopper
{
  /**
   * A sharp change of the wall angle (Fig. 8): an upper hopper of half-angle
   * Theta_w carrying its radial field, a lower hopper of half-angle theta_w
   * with its own apex, both sharing the wall corner Q = (R_0, -Theta_w) =
   * (r_0, -theta_w). Lengths are in units of r_0, the lower apex is the
   * origin, z points up the common axis: x = r sin theta, z = r cos theta;
   * the upper apex is at z = z_u = cos theta_w - R_0 cos Theta_w with
   * R_0 = sin theta_w / sin Theta_w.
   *
   * The initial data on Gamma_0 = {r = r_0, |theta| <= theta_w}: a point
   * (r_0, theta) is (R, Theta) in upper coordinates, where the radial field
   * is R T(Theta) (per unit rho g); its in-plane components are rotated to
   * the lower frame by a = Theta - theta (rotate_stress(), psi -> psi + a).
   * Theta_w = theta_w is the radial field itself.
   */
  class Transition
  {
  public:
    Transition(const RadialField &upper, const MohrCoulomb &material, double theta_w);

    double Theta_w() const { return upper.theta_w(); }
    double theta_w() const { return lower_angle; }
    double upper_apex_z() const { return z_u; }

    /// (R, Theta) of the lower point (r, theta)
    std::pair<double, double> upper_coordinates(double r, double theta) const;

    /// (T_rr, T_rt, T_tt) in the lower frame at (r_0, theta) per unit rho g r_0
    std::array<double, 3> initial_stress(double theta) const;

    /// Whether the data on Gamma_0 are admissible for the marching scheme:
    /// at n_samples points of [0, theta_w] the Sokolovskii angle of the full
    /// rotated tensor satisfies |psi| < pi/4 - delta/2 (then T_tt is the
    /// closure's root h(T_rr, T_rt)) and T_rr > 0. Reports the worst point.
    struct Check
    {
      bool                  ok = true;
      double                theta = 0;    ///< where |psi| is largest (or the first failure)
      std::array<double, 3> stress{};     ///< (T_rr, T_rt, T_tt) there
      double                max_abs_psi = 0;
      std::string           reason;
    };
    Check check(unsigned int n_samples = 2001) const;

  private:
    const RadialField &upper;
    MohrCoulomb        material;
    double             lower_angle;
    double             z_u;
  };

  /// One row of the Fig. 9 scan: for the upper angle Theta_w, the radial
  /// field's max psi (and where), psi'(Theta_w), lambda_max = cot(pi/4 -
  /// delta/2 - max psi) and the characteristic bound arctan(1/lambda_max)
  /// of a steeper transition (curve C: theta_w >= Theta_w - bound), and the
  /// range [lo, hi] of lower angles whose rotated data on Gamma_0 pass
  /// Transition::check() (NaN when there is none). Angles in degrees.
  struct ScanRow
  {
    double Theta_w, max_psi, theta_of_max_psi, dpsi_wall, lambda_max, bound, theta_min_C, lo, hi;
  };

  struct ScanResult
  {
    std::vector<ScanRow> rows;
    /// upper angle where psi stops being monotone (psi'(Theta_w) = 0), deg
    double monotone_up_to = NAN;
    /// upper angle where max psi = pi/4 - delta/2 (no steeper transition
    /// left, curve C meets theta_w = Theta_w), deg
    double zero_transition_at = NAN;
    /// first scanned upper angle without a radial field (NaN if none)
    double no_radial_field_from = NAN;
  };

  /// The scan of Fig. 9 for Theta_w = from, from + step, ..., to (degrees);
  /// the two critical angles are refined with TOMS 748 to 1e-9 deg.
  ScanResult
  scan_transitions(Geometry geometry, const MohrCoulomb &material, double from, double to,
                   double step);
} // namespace granular_dg::hopper
