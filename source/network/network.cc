/**
 * The parts of the network engine that do not depend on the physics of an
 * edge: the initial projection's moments, the cells per edge, the snapshot
 * size, and the scans NetworkProblem<Law> makes of its state.
 */

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/vectorization.h>

#include <granular_dg/base/vectorized_math.h>
#include <granular_dg/network/network.h>

#include <immintrin.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace granular_dg::network
{
  void
  NetworkState::reinit(const NetworkState &other)
  {
    edges.assign(other.edges.size(), 0.);
    vertices.assign(other.vertices.size(), 0.);
  }

  namespace
  {
    /// x[0] + ... + x[7], added pairwise
    double
    pairwise_sum(const double (&x)[8])
    {
      return ((x[0] + x[1]) + (x[2] + x[3])) + ((x[4] + x[5]) + (x[6] + x[7]));
    }

#if defined(__AVX__)
    /// pairwise_sum() of the lanes of lo (x[0..3]) and hi (x[4..7]), for two
    /// such pairs at once: the same additions, in registers
    __m128d
    pairwise_sums(const __m256d sum_lo, const __m256d sum_hi, const __m256d tv_lo, const __m256d tv_hi)
    {
      // hadd: (x0 + x1, x4 + x5, x2 + x3, x6 + x7); halves added: the two
      // quarters of pairwise_sum(), which the last hadd adds
      const __m256d s = _mm256_hadd_pd(sum_lo, sum_hi), t = _mm256_hadd_pd(tv_lo, tv_hi);
      return _mm_hadd_pd(_mm_add_pd(_mm256_castpd256_pd128(s), _mm256_extractf128_pd(s, 1)),
                         _mm_add_pd(_mm256_castpd256_pd128(t), _mm256_extractf128_pd(t, 1)));
    }

    /// edge_sums() below at stride 1 (degree 0), the partial sums in the
    /// lanes of two registers each (lanes 0-3 and 4-7): the same additions
    /// in the same order, so the same result to the bit. The blocks of 8
    /// whose cells and jumps all lie on the edge first, then the last with
    /// masked loads (the lanes past the edge keep their sums: blend).
    DEAL_II_ALWAYS_INLINE inline std::array<double, 2>
    contiguous_edge_sums(const double *mean, const unsigned int n)
    {
      const __m256d sign   = _mm256_set1_pd(-0.);
      __m256d       sum[2] = {_mm256_setzero_pd(), _mm256_setzero_pd()};
      __m256d       tv[2]  = {_mm256_setzero_pd(), _mm256_setzero_pd()};
      unsigned int  c      = 0;
      for (; c + 8 < n; c += 8)
        for (unsigned int h = 0; h < 2; ++h)
          {
            const __m256d x = _mm256_loadu_pd(mean + c + 4 * h), next = _mm256_loadu_pd(mean + c + 4 * h + 1);
            sum[h] = _mm256_add_pd(sum[h], x);
            tv[h]  = _mm256_add_pd(tv[h], _mm256_andnot_pd(sign, _mm256_sub_pd(next, x)));
          }
      // the first k of the 8 lanes, half h: lanes 4 h .. 4 h + 3
      static const long long ones[16] = {-1, -1, -1, -1, -1, -1, -1, -1};
      const auto             first    = [](const unsigned int k, const unsigned int h) {
        return _mm256_loadu_si256(
          reinterpret_cast<const __m256i *>(ones + 8 - std::min(k, 8u) + 4 * h));
      };
      for (unsigned int h = 0; c < n && h < 2; ++h)
        {
          // lane l: cell c + 4 h + l and the jump from it to the next
          const __m256i cells = first(n - c, h), jumps = first(n - c - 1, h);
          const __m256d x     = _mm256_maskload_pd(mean + c + 4 * h, cells);
          const __m256d next  = _mm256_maskload_pd(mean + c + 4 * h + 1, jumps);
          sum[h] = _mm256_blendv_pd(sum[h], _mm256_add_pd(sum[h], x), _mm256_castsi256_pd(cells));
          tv[h]  = _mm256_blendv_pd(tv[h],
                                   _mm256_add_pd(tv[h], _mm256_andnot_pd(sign, _mm256_sub_pd(next, x))),
                                   _mm256_castsi256_pd(jumps));
        }
      double result[2];
      _mm_storeu_pd(result, pairwise_sums(sum[0], sum[1], tv[0], tv[1]));
      return {{result[0], result[1]}};
    }
#endif

    /// The sum of the n cell means of an edge (at mean[c * stride]) and their
    /// total variation, each over 8 interleaved partial sums (cell c in sum
    /// c % 8: no long chain of dependent additions) added pairwise. Written
    /// in blocks of 8 so that the partial sums stay in registers.
    DEAL_II_ALWAYS_INLINE inline std::array<double, 2>
    edge_sums(const double *mean, const unsigned int stride, const unsigned int n)
    {
#if defined(__AVX__)
      if (stride == 1)
        return contiguous_edge_sums(mean, n);
#endif
      constexpr unsigned int L      = 8;
      double                 sum[L] = {}, tv[L] = {};
      const auto             add    = [&](const unsigned int c, const unsigned int l) {
        sum[l] += mean[c * stride];
        if (c + 1 < n)
          tv[l] += std::abs(mean[(c + 1) * stride] - mean[c * stride]);
      };
      unsigned int c = 0;
      for (; c + L <= n; c += L)
        for (unsigned int l = 0; l < L; ++l)
          add(c + l, l);
      for (unsigned int l = 0; l < L; ++l)
        if (c + l < n)
          add(c + l, l);
      return {{pairwise_sum(sum), pairwise_sum(tv)}};
    }
  } // namespace

  namespace internal
  {
    /// One SIMD pass over v: whether every entry is finite (x - x is 0 for a
    /// finite x and NaN otherwise, and a NaN stays in a sum), and with
    /// `range` [min, max] of the entries when they are (min and max are
    /// exact in any order)
    template <bool range>
    Scan
    scan(const std::vector<double> &v)
    {
      using VA       = VectorizedArray<double>;
      VA          lo = INFINITY, hi = -INFINITY, sum = 0.;
      std::size_t i  = 0;
      for (; i + VA::size() <= v.size(); i += VA::size())
        {
          VA x;
          x.load(v.data() + i);
          sum += x - x;
          if constexpr (range)
            {
              lo = std::min(lo, x);
              hi = std::max(hi, x);
            }
        }
      Scan result{granular_dg::all_finite(sum), INFINITY, -INFINITY};
      for (unsigned int l = 0; l < VA::size(); ++l)
        {
          result.lo = std::min(result.lo, lo[l]);
          result.hi = std::max(result.hi, hi[l]);
        }
      for (; i < v.size(); ++i)
        {
          result.finite = result.finite && std::isfinite(v[i]);
          result.lo     = std::min(result.lo, v[i]);
          result.hi     = std::max(result.hi, v[i]);
        }
      return result;
    }

    void
    add_edge_sums(const double *u, const unsigned int stride, const std::vector<unsigned int> &cells,
                  const std::vector<double> &h, double &m, double &tv)
    {
      for (unsigned int e = 0; e < cells.size(); ++e)
        {
          const auto [sum, variation] = edge_sums(u, stride, cells[e]);
          m += h[e] * sum;
          tv += variation;
          u += std::size_t(cells[e]) * stride;
        }
    }

    template Scan scan<false>(const std::vector<double> &);
    template Scan scan<true>(const std::vector<double> &);
  } // namespace internal

  void
  add_cell_moments(const Function<1> &g, const std::vector<Polynomials::Legendre> &legendre,
                   const QGauss<1> &quad, const double x0, const double h, const double a,
                   const double b, std::vector<double> &result, const unsigned int depth)
  {
    // (on the stack: a graph of 10^6 edges has 1.6 10^7 cells)
    using Moments = std::array<double, 8>;
    const unsigned int n_modes = legendre.size();
    AssertThrow(n_modes <= Moments().size(), ExcMessage("at most 8 Legendre moments"));
    auto moments = [&](const double lo, const double hi) {
      Moments m{};
      // the points in the cell's coordinate, from lo rather than from x:
      // (x - x0) / h would carry the rounding of x magnified by x / h, and
      // the two levels would then never agree in cells far from x = 0
      // (2.5 10^6 evaluations of g per cell instead of 15 at 20000 cells per
      // unit length, tests/network/cell_moments)
      const double xi_lo = (lo - x0) / h, xi_width = (hi - lo) / h;
      for (unsigned int q = 0; q < quad.size(); ++q)
        {
          const double x  = lo + (hi - lo) * quad.point(q)[0];
          const double w  = (hi - lo) * quad.weight(q);
          const double v  = g.value(Point<1>(x));
          const double xi = xi_lo + xi_width * quad.point(q)[0];
          for (unsigned int k = 0; k < n_modes; ++k)
            m[k] += w * v * legendre[k].value(xi);
        }
      return m;
    };
    const double mid   = 0.5 * (a + b);
    const auto   whole = moments(a, b);
    auto         halves = moments(a, mid);
    const auto   right  = moments(mid, b);
    double       diff = 0, size = 0;
    for (unsigned int k = 0; k < n_modes; ++k)
      {
        halves[k] += right[k];
        diff = std::max(diff, std::abs(halves[k] - whole[k]));
        size = std::max(size, std::abs(halves[k]));
      }
    if (diff <= 1e-15 * std::max(b - a, size) || depth >= 55)
      {
        for (unsigned int k = 0; k < n_modes; ++k)
          result[k] += halves[k];
        return;
      }
    add_cell_moments(g, legendre, quad, x0, h, a, mid, result, depth + 1);
    add_cell_moments(g, legendre, quad, x0, h, mid, b, result, depth + 1);
  }

  std::vector<unsigned int>
  edge_cells(const Graph &graph, const double cells_per_unit_length)
  {
    std::vector<unsigned int> n;
    for (const Edge &e : graph.edges)
      n.push_back(
        std::max(1u, static_cast<unsigned int>(std::lround(e.length * cells_per_unit_length))));
    return n;
  }

  double
  snapshot_bytes(const unsigned long n_cells, const dg::DiscretizationParameters &method,
                 const NetworkOptions &options)
  {
    const unsigned int points = method.profile_points > 0 ? method.profile_points :
                                                            std::max(2u, method.degree + 1);
    return n_cells * points * (options.write_vtu ? 60. : 0.) + n_cells * points * 40.;
  }

} // namespace granular_dg::network
