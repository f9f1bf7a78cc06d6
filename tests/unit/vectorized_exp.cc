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
// And shift_lanes up and down (a lane permute at the native
// width) against the lane-by-lane shift, and cell_major_batch,
// for_cell_major_batches, store_cell_major and load_cell_major (masked
// permutes at width 8)
// against the cell-after-cell layout, for 1-10 values per cell, at the
// native width, 4, 2 and 1.
#include <deal.II/base/vectorization.h>

#include <granular_dg/base/vectorized_math.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <utility>

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
    const auto up   = granular_dg::shift_lanes<true>(x, -7.25);
    const auto down = granular_dg::shift_lanes<false>(x, 9.5);
    bool       ok   = up[0] == -7.25 && down[width - 1] == 9.5;
    for (unsigned int l = 1; l < width; ++l)
      ok = ok && up[l] == x[l - 1] && down[l - 1] == x[l];
    return ok;
  }

  /// the batches of cell_major_batch() one after the other: entry l n + k
  /// must be x[k][l]
  template <std::size_t width, unsigned int n>
  bool
  cell_major_agrees()
  {
    VectorizedArray<double, width> x[n];
    for (unsigned int k = 0; k < n; ++k)
      for (unsigned int l = 0; l < width; ++l)
        x[k][l] = 100. * k + l;
    bool ok = true;
    for (unsigned int j = 0; j < n; ++j)
      {
        const auto b = granular_dg::cell_major_batch(x, j);
        for (unsigned int e = 0; e < width; ++e)
          {
            const unsigned int f = j * width + e;
            ok = ok && b[e] == x[f % n][f / n];
          }
      }
    // the same batches through for_cell_major_batches()
    granular_dg::for_cell_major_batches(x, [&](const unsigned int j, const auto &b) {
      for (unsigned int e = 0; e < width; ++e)
        ok = ok && b[e] == x[(j * width + e) % n][(j * width + e) / n];
    });
    // the layout stored: store_cell_major()
    double out[width * n];
    granular_dg::store_cell_major(x, out);
    for (unsigned int f = 0; f < width * n; ++f)
      ok = ok && out[f] == x[f % n][f / n];
    // and back: load_cell_major()
    double in[width * n];
    for (unsigned int f = 0; f < width * n; ++f)
      in[f] = x[f % n][f / n];
    VectorizedArray<double, width> y[n];
    granular_dg::load_cell_major(in, y);
    for (unsigned int k = 0; k < n; ++k)
      for (unsigned int l = 0; l < width; ++l)
        ok = ok && y[k][l] == x[k][l];
    return ok;
  }

  template <std::size_t width, unsigned int... n>
  bool
  cell_major_agrees_for(std::integer_sequence<unsigned int, n...>)
  {
    return (cell_major_agrees<width, n + 1>() && ...);
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
  std::printf("shift_lanes moves every lane up or down by one: %s\n",
              shift ? "yes" : "NO");
  const auto values = std::make_integer_sequence<unsigned int, 10>();
  const bool cells  = cell_major_agrees_for<W>(values) && cell_major_agrees_for<4>(values) &&
                     cell_major_agrees_for<2>(values) && cell_major_agrees_for<1>(values);
  std::printf("cell_major_batch, store_cell_major, load_cell_major: the cell-after-cell "
              "layout (1-10 values): %s\n",
              cells ? "yes" : "NO");
  return wide <= 2. && unit <= 2. && same && special && lanes && shift && cells ? 0 : 1;
}
