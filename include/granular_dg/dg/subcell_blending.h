#pragma once

#include <deal.II/base/polynomial.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/lac/full_matrix.h>

#include <granular_dg/dg/limiter.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace granular_dg::dg
{
  using namespace dealii;

  /**
   * The physics-free part of subcell blending on a line of cells (Hennemann,
   * Rueda-Ramirez, Hindenlang & Gassner 2021; Trixi.jl's
   * VolumeIntegralShockCapturingHG): a cell's rate is
   *   (1 - alpha) R_DG + alpha R_FV,
   * R_FV the first-order finite-volume rate of the cell's p + 1 equal
   * subcells, mapped back to the Legendre modes (from_subcells: the
   * polynomial of degree p whose subcell averages are the given ones; with
   * p + 1 subcells the map is one to one). Both rates use the same numerical
   * flux at the cell's faces, so the cell mean changes alike in both and the
   * blend conserves whatever alpha is.
   *
   * alpha comes from the modal energy share E = e_p / sum_k e_k of the
   * physics' indicator variable (the modal_energy indicator of the limiter):
   *   alpha = 1 / (1 + exp(-s / T (E - T))),  s = ln((1 - 1e-4) / 1e-4),
   * T the threshold of the degree (modal_energy_threshold()); alpha below
   * 1e-3 is 0, above 1 - 1e-3 is 1, then at most alpha_max. The engine
   * smooths it as Trixi does: alpha_K = max(alpha_K, alpha_N / 2) over the
   * neighbours N.
   */
  class SubcellBlending
  {
  public:
    static constexpr unsigned int max_modes = 5;
    using Table = std::array<std::array<double, max_modes>, max_modes>;

    /// Tables for n_modes modes; alpha_max in (0, 1] (0: blending off)
    void
    reinit(const unsigned int n_modes, const double largest_alpha)
    {
      alpha_max = largest_alpha;
      threshold = modal_energy_threshold(n_modes - 1);
      // to_subcells[j][k]: the mean of L_k over subcell j of [0, 1]
      FullMatrix<double> A(n_modes, n_modes);
      const QGauss<1>    q(n_modes);
      for (unsigned int k = 0; k < n_modes; ++k)
        {
          const Polynomials::Legendre L(k);
          for (unsigned int j = 0; j < n_modes; ++j)
            for (unsigned int i = 0; i < q.size(); ++i)
              A(j, k) += q.weight(i) * L.value((j + q.point(i)[0]) / n_modes);
        }
      FullMatrix<double> A_inverse(n_modes, n_modes);
      A_inverse.invert(A);
      for (unsigned int j = 0; j < n_modes; ++j)
        for (unsigned int k = 0; k < n_modes; ++k)
          {
            to_subcells[j][k]   = A(j, k);
            from_subcells[k][j] = A_inverse(k, j);
          }
      // the mean is the mean of the subcell means, exactly (conservation)
      for (unsigned int j = 0; j < n_modes; ++j)
        from_subcells[0][j] = 1. / n_modes;
    }

    bool
    enabled() const
    {
      return alpha_max > 0;
    }

    /// The blending factor before smoothing of a cell whose indicator
    /// variable has the modes q[0..n); floor2: the square of the size below
    /// which a cell is round-off (not blended).
    template <unsigned int n>
    double
    raw_factor(const double *q, const double floor2) const
    {
      // (the share E of the limiter's modal_energy indicator, summed in its
      // own order: one shared sum would change the blended runs' rounding;
      // the modes scaled at square_safe_scale(), as there)
      const auto raw = [&](const double s) {
        double total = 0;
        for (unsigned int k = 0; k < n; ++k)
          total += (q[k] * s) * (q[k] * s);
        return std::pair(n < 2 || !(total > floor2 * s * s) ?
                           0. :
                           factor((q[n - 1] * s) * (q[n - 1] * s) / total),
                         total);
      };
      const auto [alpha, total] = raw(1.);
      const double scale        = square_safe_scale(q, n, total);
      return scale == 1. ? alpha : raw(scale).first;
    }

    /// The blending factor before smoothing of a cell whose indicator
    /// variable has the energy share `energy` in its highest modes.
    double
    factor(const double energy) const
    {
      const double alpha = 1. / (1. + std::exp(-sharpness / threshold * (energy - threshold)));
      if (alpha < alpha_min)
        return 0.;
      return std::min(alpha > 1. - alpha_min ? 1. : alpha, alpha_max);
    }

    /// to_subcells[j][k]: mean of mode k over subcell j; from_subcells: its inverse
    Table        to_subcells{}, from_subcells{};
    double       alpha_max = 0, threshold = 0;

  private:
    static constexpr double alpha_min = 1e-3;
    /// s = ln((1 - 1e-4) / 1e-4): alpha = 1e-4 at E = 0 (Hennemann et al., eq. (42))
    static constexpr double sharpness = 9.210240366975849;
  };
} // namespace granular_dg::dg
