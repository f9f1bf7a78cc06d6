#pragma once

/**
 * @file Elementary functions on deal.II's VectorizedArray that stay in SIMD
 * registers. deal.II's std::exp(VectorizedArray) calls std::exp lane by lane;
 * in the 2D strip with the exponential stress law that was 40 % of the
 * operator's time at 8 lanes (doc/performance.md, "SIMD build").
 *
 * exp() takes double (std::exp, unchanged) or VectorizedArray<double, W>:
 * Cody-Waite reduction x = n ln 2 + r, |r| <= ln 2 / 2, the Taylor
 * polynomial of degree 13 for e^r, and the scaling by 2^n in two factors (so that
 * subnormal results and overflow to inf come out as std::exp's). Accuracy:
 * within 2 ulp of std::exp for all finite x (tests/unit/vectorized_exp
 * checks 10^6 arguments and the special values); NaN stays NaN, exp(-inf) = 0,
 * exp(inf) = inf. Every lane is computed alone: the value does not depend on
 * the lane or the width.
 */

#include <deal.II/base/vectorization.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>
#if defined(__AVX__)
#  include <immintrin.h>
#endif

namespace granular_dg
{
  inline double
  exp(const double x)
  {
    return std::exp(x);
  }

  template <std::size_t width>
  dealii::VectorizedArray<double, width>
  exp(const dealii::VectorizedArray<double, width> &x_in)
  {
    using VA = dealii::VectorizedArray<double, width>;
    // beyond these e^x is inf or 0 (std::exp's thresholds, with margin)
    const VA x = std::min(std::max(x_in, VA(-746.)), VA(710.));
    // n = round(x / ln 2) by the 1.5 * 2^52 trick (|x / ln 2| < 2^51)
    const VA shifter(6755399441055744.);
    const VA n = (x * VA(1.4426950408889634073599) + shifter) - shifter;
    // r = x - n ln 2 in two parts (Cephes' C1 + C2 = ln 2)
    const VA r  = (x - n * VA(6.93145751953125e-1)) - n * VA(1.42860682030941723212e-6);
    // e^r by its Taylor polynomial of degree 13 (remainder < 5e-18 relative
    // for |r| <= ln 2 / 2), Horner
    static constexpr double c[] = {1. / 6227020800., 1. / 479001600., 1. / 39916800.,
                                   1. / 3628800.,    1. / 362880.,    1. / 40320.,
                                   1. / 5040.,       1. / 720.,       1. / 120.,
                                   1. / 24.,         1. / 6.,         1. / 2.,
                                   1.,               1.};
    VA e = VA(c[0]);
    for (unsigned int i = 1; i < 14; ++i)
      e = e * r + VA(c[i]);
    // times 2^n = 2^n1 2^n2, each factor a normal double
    VA scale1, scale2;
    for (unsigned int v = 0; v < width; ++v)
      {
        const std::int64_t k  = static_cast<std::int64_t>(n[v]);
        const std::int64_t k1 = k / 2, k2 = k - k1;
        const std::uint64_t b1 = static_cast<std::uint64_t>(k1 + 1023) << 52,
                            b2 = static_cast<std::uint64_t>(k2 + 1023) << 52;
        double f1, f2;
        std::memcpy(&f1, &b1, sizeof(double));
        std::memcpy(&f2, &b2, sizeof(double));
        scale1[v] = f1;
        scale2[v] = f2;
      }
    e = (e * scale1) * scale2;
    // NaN in, NaN out (min/max above replaced it)
    for (unsigned int v = 0; v < width; ++v)
      if (x_in[v] != x_in[v])
        e[v] = x_in[v];
    return e;
  }

  /// Lane tests for the admissibility checks that take double or
  /// VectorizedArray (the line engine's SIMD batches): whether x is finite
  /// in every lane ...
  inline bool
  all_finite(const double x)
  {
    return std::isfinite(x);
  }

  namespace internal
  {
    /// the ordered comparisons of _mm*_cmp_pd (_CMP_EQ_OQ, _CMP_GT_OQ)
    constexpr int equal_to = 0x00, greater_than = 0x1e;
#if defined(__AVX__)
    static_assert(equal_to == _CMP_EQ_OQ && greater_than == _CMP_GT_OQ);
#endif

    /// Whether x > 0 (ordered: false for NaN) holds in every lane when
    /// compare_zero is the ordered "greater than", or x == 0 with the ordered
    /// "equal": one SIMD compare and a test of its mask where VectorizedArray
    /// holds a native register (AVX-512 or AVX), a loop over the lanes
    /// otherwise. (A loop of scalar compares per lane made the elasticity's
    /// admissibility scan 13 % of a layered 1D step.)
    template <int compare_zero, std::size_t width>
    DEAL_II_ALWAYS_INLINE inline bool
    all_lanes_compare_zero(const dealii::VectorizedArray<double, width> &x)
    {
      // (deal.II's conditions for the native specialisations of 8 and 4 lanes)
#if DEAL_II_VECTORIZATION_WIDTH_IN_BITS >= 512 && defined(__AVX512F__)
      if constexpr (width == 8)
        return _mm512_cmp_pd_mask(x.data, _mm512_setzero_pd(), compare_zero) == 0xFF;
#endif
#if DEAL_II_VECTORIZATION_WIDTH_IN_BITS >= 256 && defined(__AVX__)
      if constexpr (width == 4)
        return _mm256_movemask_pd(_mm256_cmp_pd(x.data, _mm256_setzero_pd(), compare_zero)) ==
               0xF;
#endif
      bool ok = true;
      for (unsigned int v = 0; v < width; ++v)
        ok &= compare_zero == greater_than ? x[v] > 0. : x[v] == 0.;
      return ok;
    }
  } // namespace internal

  template <std::size_t width>
  bool
  all_finite(const dealii::VectorizedArray<double, width> &x)
  {
    // x - x is 0 for finite x, NaN for an infinite or NaN x
    return internal::all_lanes_compare_zero<internal::equal_to>(x - x);
  }

  /// ... and whether x > 0 in every lane (false for NaN).
  inline bool
  all_positive(const double x)
  {
    return x > 0.;
  }

  template <std::size_t width>
  bool
  all_positive(const dealii::VectorizedArray<double, width> &x)
  {
    return internal::all_lanes_compare_zero<internal::greater_than>(x);
  }

  /// The lanes of x moved by one lane towards the top (up: (fill, x[0], ...,
  /// x[width - 2])) or the bottom ((x[1], ..., x[width - 1], fill)). One lane
  /// permute where VectorizedArray holds a native register (AVX-512, AVX2):
  /// the states or fluxes of a batch of cells' neighbours from the batch's
  /// own, without the store and wide reload that a lane-by-lane copy
  /// compiles to (a failed store forwarding in every batch of a line engine).
  template <bool up, std::size_t width>
  DEAL_II_ALWAYS_INLINE inline dealii::VectorizedArray<double, width>
  shift_lanes(const dealii::VectorizedArray<double, width> &x, const double fill)
  {
    dealii::VectorizedArray<double, width> r;
#if DEAL_II_VECTORIZATION_WIDTH_IN_BITS >= 512 && defined(__AVX512F__)
    if constexpr (width == 8)
      {
        // alignr(high, low, s): the concatenation (low | high) shifted down by s lanes
        const __m512i v = _mm512_castpd_si512(x.data),
                      f = _mm512_castpd_si512(_mm512_set1_pd(fill));
        if constexpr (up)
          r.data = _mm512_castsi512_pd(_mm512_alignr_epi64(v, f, 7));
        else
          r.data = _mm512_castsi512_pd(_mm512_alignr_epi64(f, v, 1));
        return r;
      }
#endif
#if DEAL_II_VECTORIZATION_WIDTH_IN_BITS >= 256 && defined(__AVX2__)
    if constexpr (width == 4)
      {
        // (x[3], x[0], x[1], x[2]) or (x[1], x[2], x[3], x[0]), then the free lane
        const __m256d f = _mm256_set1_pd(fill);
        if constexpr (up)
          r.data = _mm256_blend_pd(_mm256_permute4x64_pd(x.data, 0x93), f, 0x1);
        else
          r.data = _mm256_blend_pd(_mm256_permute4x64_pd(x.data, 0x39), f, 0x8);
        return r;
      }
#endif
    for (unsigned int l = 0; l < width; ++l)
      r[l] = up ? (l == 0 ? fill : x[l - 1]) : (l + 1 == width ? fill : x[l + 1]);
    return r;
  }

  namespace internal
  {
    /// A lane permute of n registers into one: for each register i, the
    /// lanes it fills (mask[i]) and the lane of register i each takes (lane[i]).
    template <unsigned int n>
    struct LaneSources
    {
      unsigned int  mask[n]    = {};
      long long int lane[n][8] = {};
    };
    /// The cell-major layout of 8 cells of n values, entry f = l n + k (value k
    /// of cell l) in lane f % 8 of batch f / 8, as permutes both ways: batch[j]
    /// gathers batch j from the value registers x[k] (lane l: cell l),
    /// value[k] gathers x[k] from the batches.
    template <unsigned int n>
    struct CellMajorTables
    {
      LaneSources<n> batch[n], value[n];
      constexpr CellMajorTables()
      {
        for (unsigned int f = 0; f < 8 * n; ++f)
          {
            const unsigned int j = f / 8, e = f % 8, l = f / n, k = f % n;
            batch[j].mask[k] |= 1u << e;
            batch[j].lane[k][e] = l;
            value[k].mask[j] |= 1u << l;
            value[k].lane[j][l] = e;
          }
      }
    };
#if DEAL_II_VECTORIZATION_WIDTH_IN_BITS >= 512 && defined(__AVX512F__)
    /// The register the LaneSources s make of the registers source(i), i < n.
    template <unsigned int n, typename Source>
    DEAL_II_ALWAYS_INLINE inline __m512d
    permute_lanes(const LaneSources<n> &s, const Source &source)
    {
      __m512d r = _mm512_setzero_pd();
      for (unsigned int i = 0; i < n; ++i)
        if (s.mask[i] != 0)
          r = _mm512_mask_permutexvar_pd(r, static_cast<__mmask8>(s.mask[i]),
                                         _mm512_loadu_si512(s.lane[i]), source(i));
      return r;
    }
#endif
#if DEAL_II_VECTORIZATION_WIDTH_IN_BITS >= 256 && defined(__AVX2__)
    /// The cell-major layout of 4 cells of n = 2 or 3 values in AVX2
    /// registers: the value registers x[k] (lane l: cell l) from the n
    /// batches b_j of 4 consecutive entries, and back. n = 2: a 2 x 2
    /// transpose of 128-bit halves and of doubles. n = 3: each value register
    /// takes one lane of each batch, in distinct lanes, so two blends and one
    /// lane permute (its own inverse) make it, and the same undo it. Where
    /// deal.II gathers every value (vgatherdpd, slow on AMD) or stores lane
    /// by lane. (Registers by value: an array of them went through the stack
    /// in halves, a failed store forwarding per batch.)
    DEAL_II_ALWAYS_INLINE inline void
    batches_to_values(const __m256d b0, const __m256d b1, __m256d &x0, __m256d &x1)
    {
      const __m256d lo = _mm256_permute2f128_pd(b0, b1, 0x20), // a0 b0 a2 b2
        hi             = _mm256_permute2f128_pd(b0, b1, 0x31); // a1 b1 a3 b3
      x0               = _mm256_unpacklo_pd(lo, hi);
      x1               = _mm256_unpackhi_pd(lo, hi);
    }

    DEAL_II_ALWAYS_INLINE inline void
    batches_to_values(const __m256d b0, const __m256d b1, const __m256d b2, __m256d &x0,
                      __m256d &x1, __m256d &x2)
    {
      // b = (a0 b0 c0 a1), (b1 c1 a2 b2), (c2 a3 b3 c3)
      x0 = _mm256_permute4x64_pd(_mm256_blend_pd(_mm256_blend_pd(b0, b1, 0x4), b2, 0x2),
                                 0x6C); // from a0 a3 a2 a1
      x1 = _mm256_permute_pd(_mm256_blend_pd(_mm256_blend_pd(b1, b0, 0x2), b2, 0x4),
                             0x5); // from b1 b0 b3 b2
      x2 = _mm256_permute4x64_pd(_mm256_blend_pd(_mm256_blend_pd(b2, b1, 0x2), b0, 0x4),
                                 0xC6); // from c2 c1 c0 c3
    }

    /// The inverse of batches_to_values(): batch j of the value registers.
    DEAL_II_ALWAYS_INLINE inline __m256d
    values_to_batch(const __m256d x0, const __m256d x1, const unsigned int j)
    {
      const __m256d lo = _mm256_unpacklo_pd(x0, x1), // a0 b0 a2 b2
        hi             = _mm256_unpackhi_pd(x0, x1); // a1 b1 a3 b3
      return j == 0 ? _mm256_permute2f128_pd(lo, hi, 0x20) : _mm256_permute2f128_pd(lo, hi, 0x31);
    }

    DEAL_II_ALWAYS_INLINE inline __m256d
    values_to_batch(const __m256d x0, const __m256d x1, const __m256d x2, const unsigned int j)
    {
      const __m256d a = _mm256_permute4x64_pd(x0, 0x6C), // a0 a3 a2 a1
        b             = _mm256_permute_pd(x1, 0x5),      // b1 b0 b3 b2
        c             = _mm256_permute4x64_pd(x2, 0xC6); // c2 c1 c0 c3
      return j == 0 ? _mm256_blend_pd(_mm256_blend_pd(a, b, 0x2), c, 0x4) :
             j == 1 ? _mm256_blend_pd(_mm256_blend_pd(b, c, 0x2), a, 0x4) :
                      _mm256_blend_pd(_mm256_blend_pd(c, a, 0x2), b, 0x4);
    }
#endif
  } // namespace internal

  /// Batch j of the values of `width` cells stored cell after cell (cell l's
  /// n values, value k of cell l in x[k][l]): the entries j width ..
  /// (j + 1) width - 1 of that layout, j < n; what deal.II's
  /// vectorized_transpose_and_store() writes for consecutive cells, here in
  /// registers (one masked lane permute per value on AVX-512), so that a
  /// batch update can read it without a store and a wide reload.
  template <unsigned int n, std::size_t width>
  DEAL_II_ALWAYS_INLINE inline dealii::VectorizedArray<double, width>
  cell_major_batch(const dealii::VectorizedArray<double, width> (&x)[n], const unsigned int j)
  {
    dealii::VectorizedArray<double, width> r;
    if constexpr (n == 1)
      return x[0];
#if DEAL_II_VECTORIZATION_WIDTH_IN_BITS >= 512 && defined(__AVX512F__)
    else if constexpr (width == 8)
      {
        static constexpr internal::CellMajorTables<n> tables;
        r.data = internal::permute_lanes(tables.batch[j], [&](const unsigned int k) { return x[k].data; });
        return r;
      }
#endif
#if DEAL_II_VECTORIZATION_WIDTH_IN_BITS >= 256 && defined(__AVX2__)
    else if constexpr (width == 4 && n <= 3)
      {
        if constexpr (n == 2)
          r.data = internal::values_to_batch(x[0].data, x[1].data, j);
        else
          r.data = internal::values_to_batch(x[0].data, x[1].data, x[2].data, j);
        return r;
      }
#endif
    else
      {
        for (unsigned int e = 0; e < width; ++e)
          r[e] = x[(j * width + e) % n][(j * width + e) / n];
        return r;
      }
  }

  /// out[l n + k] = x[k][l]: the n values of `width` cells stored cell after
  /// cell (deal.II's vectorized_transpose_and_store() for consecutive cells),
  /// on AVX-512 (and AVX2 for n <= 3) batch by batch from cell_major_batch().
  template <unsigned int n, std::size_t width>
  DEAL_II_ALWAYS_INLINE inline void
  store_cell_major(const dealii::VectorizedArray<double, width> (&x)[n], double *out)
  {
    if constexpr (n == 1)
      x[0].store(out);
#if DEAL_II_VECTORIZATION_WIDTH_IN_BITS >= 512 && defined(__AVX512F__)
    else if constexpr (width == 8)
      for (unsigned int j = 0; j < n; ++j)
        cell_major_batch(x, j).store(out + 8 * j);
#endif
#if DEAL_II_VECTORIZATION_WIDTH_IN_BITS >= 256 && defined(__AVX2__)
    else if constexpr (width == 4 && n <= 3)
      for (unsigned int j = 0; j < n; ++j)
        cell_major_batch(x, j).store(out + 4 * j);
#endif
    else
      {
        unsigned int offsets[width];
        for (unsigned int l = 0; l < width; ++l)
          offsets[l] = l * n;
        dealii::vectorized_transpose_and_store(false, n, x, offsets, out);
      }
  }

  /// f(j, cell_major_batch(x, j)) for j = 0 .. n - 1; elsewhere than AVX-512
  /// and AVX2 with n <= 3 through store_cell_major() into a local array
  /// (deal.II's shuffles beat a lane-by-lane assembly there).
  template <unsigned int n, std::size_t width, typename F>
  DEAL_II_ALWAYS_INLINE inline void
  for_cell_major_batches(const dealii::VectorizedArray<double, width> (&x)[n], const F &f)
  {
#if DEAL_II_VECTORIZATION_WIDTH_IN_BITS >= 512 && defined(__AVX512F__)
    if constexpr (n == 1 || width == 8)
#elif DEAL_II_VECTORIZATION_WIDTH_IN_BITS >= 256 && defined(__AVX2__)
    if constexpr (n == 1 || (width == 4 && n <= 3))
#else
    if constexpr (n == 1)
#endif
      for (unsigned int j = 0; j < n; ++j)
        f(j, cell_major_batch(x, j));
    else
      {
        double values[width * n];
        store_cell_major(x, values);
        for (unsigned int j = 0; j < n; ++j)
          {
            dealii::VectorizedArray<double, width> batch;
            batch.load(values + j * width);
            f(j, batch);
          }
      }
  }

  /// The inverse of cell_major_batch(): x[k][l] = in[l n + k], the n values
  /// of `width` cells stored cell after cell (deal.II's
  /// vectorized_load_and_transpose() for consecutive cells). With n = 2, 3,
  /// where deal.II gathers every value, n contiguous loads and lane permutes:
  /// masked on AVX-512, blends on AVX2 (from n = 4 on its shuffles are
  /// faster).
  template <unsigned int n, std::size_t width>
  DEAL_II_ALWAYS_INLINE inline void
  load_cell_major(const double *in, dealii::VectorizedArray<double, width> (&x)[n])
  {
    if constexpr (n == 1)
      x[0].load(in);
#if DEAL_II_VECTORIZATION_WIDTH_IN_BITS >= 512 && defined(__AVX512F__)
    else if constexpr (width == 8 && n < 4)
      {
        static constexpr internal::CellMajorTables<n> tables;
        __m512d                                       batch[n];
        for (unsigned int j = 0; j < n; ++j)
          batch[j] = _mm512_loadu_pd(in + 8 * j);
        for (unsigned int k = 0; k < n; ++k)
          x[k].data = internal::permute_lanes(tables.value[k], [&](const unsigned int j) { return batch[j]; });
      }
#endif
#if DEAL_II_VECTORIZATION_WIDTH_IN_BITS >= 256 && defined(__AVX2__)
    else if constexpr (width == 4 && n <= 3)
      {
        if constexpr (n == 2)
          internal::batches_to_values(_mm256_loadu_pd(in), _mm256_loadu_pd(in + 4), x[0].data,
                                      x[1].data);
        else
          internal::batches_to_values(_mm256_loadu_pd(in), _mm256_loadu_pd(in + 4),
                                      _mm256_loadu_pd(in + 8), x[0].data, x[1].data, x[2].data);
      }
#endif
    else
      {
        unsigned int offsets[width];
        for (unsigned int l = 0; l < width; ++l)
          offsets[l] = l * n;
        dealii::vectorized_load_and_transpose(n, in, offsets, x);
      }
  }
} // namespace granular_dg
