// granular_dg::exp on VectorizedArray (base/vectorized_math.h) against
// std::exp: the largest error in units in the last place over 10^6
// arguments spread over the whole finite range and 10^6 in [-1, 1], at the
// native width and at width 1 (the same value in every lane and width), and
// the special values (0, +-inf, NaN, overflow, subnormal results). The test
// fails itself (exit 1) if an error exceeds 2 ulp or a special value is wrong.
// Also the lane tests all_finite and all_positive of the admissibility
// checks (one SIMD compare at the native width): a special value (NaN, +-inf,
// +-0, subnormal, DBL_MAX, ...) in one lane and 1 in the others, in every
// lane, at the native width, 4 and 1, against std::isfinite and > 0.
// And shift_lanes_up (a lane permute at the native width) against the
// lane-by-lane shift, at the native width, 4, 2 and 1.
#include <deal.II/base/vectorization.h>

#include <granular_dg/base/vectorized_math.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

using dealii::VectorizedArray;

namespace
{
  double
  ulp_error(const double value, const double exact)
  {
    if (value == exact)
      return 0.;
    const double ulp = std::nextafter(std::abs(exact), std::numeric_limits<double>::infinity()) -
                       std::abs(exact);
    return std::abs(value - exact) / ulp;
  }

  /// the largest error in ulp over n arguments uniform in [lo, hi]
  template <std::size_t width>
  double
  max_error(const double lo, const double hi, const unsigned int n, bool &same_in_width_1)
  {
    std::mt19937_64                        rng(42);
    std::uniform_real_distribution<double> u(lo, hi);
    double                                 worst = 0.;
    for (unsigned int i = 0; i < n / width; ++i)
      {
        VectorizedArray<double, width> x;
        for (unsigned int v = 0; v < width; ++v)
          x[v] = u(rng);
        const auto e = granular_dg::exp(x);
        for (unsigned int v = 0; v < width; ++v)
          {
            worst = std::max(worst, ulp_error(e[v], std::exp(x[v])));
            const VectorizedArray<double, 1> x1(x[v]);
            same_in_width_1 = same_in_width_1 && granular_dg::exp(x1)[0] == e[v];
          }
      }
    return worst;
  }
  /// whether all_finite and all_positive agree with the lane-by-lane test
  /// for every special value in every lane
  template <std::size_t width>
  bool
  lane_tests_agree()
  {
    const double inf     = std::numeric_limits<double>::infinity();
    const double values[] = {std::nan(""), inf, -inf, 0., -0., -1., 1., 4.9e-324, -4.9e-324,
                             std::numeric_limits<double>::max(), -std::numeric_limits<double>::max()};
    bool agree = true;
    for (const double s : values)
      for (unsigned int lane = 0; lane < width; ++lane)
        {
          VectorizedArray<double, width> x(1.);
          x[lane] = s;
          agree &= granular_dg::all_finite(x) == bool(std::isfinite(s));
          agree &= granular_dg::all_positive(x) == (s > 0.);
        }
    return agree;
  }
} // namespace

namespace
{
  template <std::size_t width>
  bool
  shift_agrees()
  {
    VectorizedArray<double, width> x;
    for (unsigned int l = 0; l < width; ++l)
      x[l] = 1.5 + l;
    const auto y  = granular_dg::shift_lanes_up(x, -7.25);
    bool       ok = y[0] == -7.25;
    for (unsigned int l = 1; l < width; ++l)
      ok = ok && y[l] == x[l - 1];
    return ok;
  }
} // namespace

int
main()
{
  constexpr std::size_t W    = VectorizedArray<double>::size();
  bool                  same = true;
  const double          wide = max_error<W>(-745., 709.7, 1000000, same);
  const double          unit = max_error<W>(-1., 1., 1000000, same);
  std::printf("max error over [-745, 709.7]: %s 2 ulp\n", wide <= 2. ? "within" : "ABOVE");
  std::printf("max error over [-1, 1]: %s 2 ulp\n", unit <= 2. ? "within" : "ABOVE");
  std::printf("every lane equal to width 1: %s\n", same ? "yes" : "NO");
  std::fprintf(stderr, "width %u: %.3f ulp, %.3f ulp\n", unsigned(W), wide, unit);

  const double inf = std::numeric_limits<double>::infinity();
  const double cases[] = {0., -0., 1., -1., 709.78, 709.79, 800., -inf, inf, -744.4, -745.2,
                          -1000., 1e-300, -1e-17};
  bool special = true;
  for (const double x : cases)
    {
      const double e = granular_dg::exp(VectorizedArray<double, W>(x))[0];
      const bool   ok = ulp_error(e, std::exp(x)) <= 2. || (std::isinf(e) && std::isinf(std::exp(x)));
      special = special && ok;
      std::printf("exp(%g) = %.17g %s\n", x, e, ok ? "ok" : "WRONG");
    }
  const double nan = granular_dg::exp(VectorizedArray<double, W>(std::nan("")))[0];
  special          = special && std::isnan(nan);
  std::printf("exp(NaN) is NaN: %s\n", std::isnan(nan) ? "yes" : "NO");

  const bool lanes = lane_tests_agree<W>() && lane_tests_agree<4>() && lane_tests_agree<1>();
  std::printf("all_finite, all_positive agree with std::isfinite, > 0 in every lane: %s\n",
              lanes ? "yes" : "NO");
  const bool shift = shift_agrees<W>() && shift_agrees<4>() && shift_agrees<2>() &&
                     shift_agrees<1>();
  std::printf("shift_lanes_up moves every lane up by one: %s\n", shift ? "yes" : "NO");
  return wide <= 2. && unit <= 2. && same && special && lanes && shift ? 0 : 1;
}
