#pragma once

/**
 * The members of EdgeLines<Law>: a scene includes this file once and
 * instantiates them for its Law.
 */

#include <deal.II/base/polynomial.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/vectorization.h>

#include <granular_dg/base/vectorized_math.h>
#include <granular_dg/dg/limiter.templates.h>
#include <granular_dg/dg/modal_layout.h>
#include <granular_dg/network/edge_lines.h>

#include <algorithm>
#include <cmath>

namespace granular_dg::network
{
  namespace internal
  {
    /// whether T has ==
    template <typename T, typename = void>
    struct equality_comparable : std::false_type
    {};
    template <typename T>
    struct equality_comparable<T, std::void_t<decltype(std::declval<const T &>() == std::declval<const T &>())>>
      : std::true_type
    {};

    /// the state at Gauss point q of a cell with modes u (double or a batch)
    template <unsigned int nm, typename Number, typename Basis>
    DEAL_II_ALWAYS_INLINE inline Number
    point_state(const Number *u, const Basis &B)
    {
      Number s = 0.;
      for (unsigned int k = 0; k < nm; ++k)
        s += u[k] * B[k];
      return s;
    }
  } // namespace internal

  template <typename Law>
  EdgeLines<Law>::EdgeLines(const EdgeMethod &m, std::vector<Law> flux,
                            const std::vector<unsigned int> &n_cells, const std::vector<double> &sizes)
    : method(m)
    , cells(n_cells)
    , h(sizes)
    , end_kind(2 * n_cells.size(), EndKind::outflow)
    , outer(2 * n_cells.size(), 0.)
    , end_flux(2 * n_cells.size(), 0.)
    , modes(m.degree + 1)
  {
    AssertThrow(modes <= max_modes, ExcMessage("the network's edges support degrees 0-4"));
    // the table of distinct laws: an edge's law is looked for among the
    // first max_laws, beyond them only in the last (runs of equal laws)
    for (const Law &l : flux)
      {
        unsigned int i = distinct_laws.size();
        if constexpr (internal::equality_comparable<Law>::value)
          {
            const unsigned int from = i > max_laws ? i - 1 : 0;
            i = std::find(distinct_laws.begin() + from, distinct_laws.end(), l) - distinct_laws.begin();
          }
        if (i == distinct_laws.size())
          distinct_laws.push_back(l);
        law_of_edge.push_back(i);
      }
    first.assign(1, 0);
    for (const unsigned int n : cells)
      first.push_back(first.back() + n);
    for (const double size : h)
      inverse_h.push_back(1. / size);

    const QGauss<1> q(modes + 1);
    n_q = q.size();
    for (unsigned int i = 0; i < n_q; ++i)
      {
        points[i]  = q.point(i)[0];
        weights[i] = q.weight(i);
      }
    const auto L0 = dg::legendre_values(modes, 0.), L1 = dg::legendre_values(modes, 1.);
    for (unsigned int k = 0; k < modes; ++k)
      basis_functions.emplace_back(k);
    for (unsigned int k = 0; k < modes; ++k)
      {
        const Polynomials::Legendre &L = basis_functions[k];
        std::vector<double>         values(2);
        for (unsigned int i = 0; i < n_q; ++i)
          {
            L.value(points[i], values);
            basis[i][k]      = values[0];
            derivative[i][k] = values[1];
          }
        at_0[k] = L0[k];
        at_1[k] = L1[k];
      }
    indicator_threshold = method.indicator_threshold > 0 ? method.indicator_threshold :
                          method.indicator == dg::TroubleIndicator::kxrcf ?
                                                           1. :
                                                           dg::modal_energy_threshold(method.degree);
    if (method.blending_max > 0)
      {
        blend.reinit(modes, method.blending_max);
        raw_alpha.assign(first.back(), 0.);
        alpha.assign(first.back(), 0.);
      }
  }

  template <typename Law>
  double
  EdgeLines<Law>::trace(const double *u, const unsigned int e, const unsigned int side) const
  {
    return trace_at(u + index(e, side == 0 ? 0 : cells[e] - 1), side);
  }

  template <typename Law>
  double
  EdgeLines<Law>::value(const double *u, const unsigned int e, const unsigned int c,
                        const double xi) const
  {
    const double *x   = u + index(e, c);
    double        sum = 0;
    for (unsigned int k = 0; k < modes; ++k)
      sum += x[k] * basis_functions[k].value(xi);
    return sum;
  }

  template <typename Law>
  double
  EdgeLines<Law>::outer_of(const unsigned int e, const unsigned int side, const double inner) const
  {
    return end_kind[2 * e + side] == EndKind::outflow ? inner : outer[2 * e + side];
  }

  // ---------------------------------------------------------------- the rate

  template <typename Law>
  void
  EdgeLines<Law>::stage(const double *src, double *dst, const double *old, const double a,
                        const double b, const double gamma) const
  {
    dg::with_n_modes(modes, [&](auto nm) {
      constexpr unsigned int n = decltype(nm)::value;
      // the branch on old outside the cell loops
      if (old)
        for (unsigned int e = 0; e < n_edges(); ++e)
          with_fixed_law(edge_law(e), [&](const auto &law) {
            rate_edge<n>(src, e, law, dg::StageWriter<true>{src, old, dst, a, b, gamma});
          });
      else
        for (unsigned int e = 0; e < n_edges(); ++e)
          with_fixed_law(edge_law(e), [&](const auto &law) {
            rate_edge<n>(src, e, law, dg::StageWriter<false>{src, old, dst, a, b, gamma});
          });
    });
  }

  /// dg::LineOperator::apply_range() on the cells of edge e: out(i, r) for
  /// every array index i of the edge and its rate r (out.cells() for the
  /// values of a SIMD batch), a cell's entries after all reads of it and of
  /// its left neighbour (out may overwrite src).
  template <typename Law>
  template <unsigned int nm, typename Number, typename FixedLaw>
  DEAL_II_ALWAYS_INLINE inline void
  EdgeLines<Law>::add_volume_term(const Number *u, const FixedLaw &law, Number (&res)[nm]) const
  {
    // (degree 0: L_0' = 0, the volume term is 0)
    for (unsigned int q = 0; nm > 1 && q < nm + 1; ++q)
      {
        const auto  &D  = derivative[q];
        const Number wf = weights[q] * law.value(internal::point_state<nm>(u, basis[q]));
        for (unsigned int k = 0; k < nm; ++k)
          res[k] += wf * D[k];
      }
  }

  template <typename Law>
  template <unsigned int nm, typename FixedLaw, typename Out>
  void
  EdgeLines<Law>::rate_edge(const double *src, const unsigned int e, const FixedLaw &law,
                            const Out &out) const
  {
    const unsigned int n        = cells[e];
    const bool         blending = blend.enabled();
    if (blending)
      raw_blending_factors<nm>(src, e);
    const auto traces = [&](const unsigned int c, double &s0, double &s1) {
      const double *x = src + index(e, c);
      s0 = s1 = 0;
      for (unsigned int k = 0; k < nm; ++k)
        {
          s0 += x[k] * at_0[k];
          s1 += x[k] * at_1[k];
        }
    };
    double U0, U1;
    traces(0, U0, U1);
    // the flux through the left face of cell c, kept from one cell to the next
    // (the edge's start: a scalar flux; in the first batch's lane 0 it would
    // round differently with the traffic flux, 1e-12 on the city grid)
    double       F_left = law.flux(outer_of(e, 0, U0), U0);
    end_flux[2 * e]     = F_left;
    unsigned int c      = 0;
    if (W > 1 && !blending)
      {
        // SIMD batches, the last one ending the edge where it fits (its last
        // lane takes the flux through the edge's end): every edge alike,
        // whichever rank it lies on and wherever in the rank's array
        const bool last = e + 1 == n_edges();
        for (; c + W <= n; c += W)
          rate_batch<nm>(src, e, c,
                         last && c + W == n ? last_cells(src, e, c) : src + index(e, c + 1),
                         law, F_left, out);
        if (c == n)
          {
            end_flux[2 * e + 1] = F_left;
            return;
          }
        if (c != 0)
          traces(c, U0, U1);
      }
    const double inv_h = inverse_h[e];
    for (; c < n; ++c)
      {
        const double *u       = src + index(e, c);
        double        res[nm] = {};
        add_volume_term<nm>(u, law, res);
        double F_right, V0 = 0, V1 = 0;
        if (c + 1 < n)
          {
            traces(c + 1, V0, V1);
            F_right = law.flux(U1, V0);
          }
        else
          F_right = law.flux(U1, outer_of(e, 1, U1));

        const double blended = blending ? blending_factor(e, c) : 0.;
        if (blending && blended > 0)
          {
            double fv[nm];
            subcell_rate<nm>(u, e, law, F_left, F_right, fv);
            for (unsigned int k = 0; k < nm; ++k)
              out(index(e, c) + k,
                  (1. - blended) * ((res[k] - F_right * at_1[k] + F_left * at_0[k]) * inv_h) +
                    blended * fv[k]);
          }
        else
          for (unsigned int k = 0; k < nm; ++k)
            out(index(e, c) + k, (res[k] - F_right * at_1[k] + F_left * at_0[k]) * inv_h);
        F_left = F_right;
        U0     = V0;
        U1     = V1;
      }
    end_flux[2 * e + 1] = F_left;
  }

  /// The cells c + 1 .. c + W - 1 of the rank's last edge e and a cell of
  /// zeros after them (the cells rate_batch() reads as `next`).
  template <typename Law>
  const double *
  EdgeLines<Law>::last_cells(const double *src, const unsigned int e, const unsigned int c) const
  {
    after_last.assign(W * modes, 0.);
    std::copy(src + index(e, c + 1), src + index(e, c + W), after_last.begin());
    return after_last.data();
  }

  /// The cells [c, c + W) of edge e as one SIMD batch: dg::LineOperator::
  /// apply_batch(). F_left: the flux through the batch's left face on entry,
  /// through its right face on return. next: the cells c + 1 .. c + W; when
  /// the batch ends the edge, the last of them is the next edge's first cell
  /// (after the rank's last edge a cell of zeros, last_cells()), and the face
  /// to it takes the flux through the edge's end instead (the outer state in
  /// the last lane). Inlined into
  /// rate_edge(): as a call it costs the operator about 10 % at degrees 0 and 2.
  template <typename Law>
  template <unsigned int nm, typename FixedLaw, typename Out>
  DEAL_II_ALWAYS_INLINE inline void
  EdgeLines<Law>::rate_batch(const double *src, const unsigned int e, const unsigned int c,
                             const double *next, const FixedLaw &law, double &F_left,
                             const Out &out) const
  {
    VA u[nm], v[nm];
    load_cell_major<nm>(src + index(e, c), u);
    load_cell_major<nm>(next, v);
    VA res[nm] = {};
    add_volume_term<nm>(u, law, res);
    // the faces c + l | c + l + 1: right traces of u, left traces of v
    VA U1 = 0., V0 = 0.;
    for (unsigned int k = 0; k < nm; ++k)
      {
        U1 += u[k] * at_1[k];
        V0 += v[k] * at_0[k];
      }
    // the edge's end: the outer state in the last lane, one vector flux
    if (c + W == cells[e])
      V0[W - 1] = outer_of(e, 1, U1[W - 1]);
    const VA F_right = law.flux(U1, V0);
    const VA F_left_va = shift_lanes<true>(F_right, F_left);
    F_left             = F_right[W - 1];

    const VA inv_h = inverse_h[e];
    VA       rate[nm];
    for (unsigned int k = 0; k < nm; ++k)
      rate[k] = (res[k] - F_right * at_1[k] + F_left_va * at_0[k]) * inv_h;
    out.template cells<nm>(index(e, c), rate);
  }

  /// dg::LineOperator::subcell_rate(): the first-order finite-volume rate
  /// of the p + 1 subcells of a cell of edge e (modes u) as Legendre modes.
  template <typename Law>
  template <unsigned int nm, typename FixedLaw>
  void
  EdgeLines<Law>::subcell_rate(const double *u, const unsigned int e, const FixedLaw &law,
                               const double F_left, const double F_right, double (&fv)[nm]) const
  {
    double mean[nm];
    for (unsigned int j = 0; j < nm; ++j)
      {
        double s = 0;
        for (unsigned int k = 0; k < nm; ++k)
          s += u[k] * blend.to_subcells[j][k];
        mean[j] = s;
      }
    double       rate[nm];
    double       F_minus = F_left;
    const double scale   = nm / h[e];
    for (unsigned int j = 0; j < nm; ++j)
      {
        const double F_plus = j + 1 < nm ? law.flux(mean[j], mean[j + 1]) : F_right;
        rate[j]             = -(F_plus - F_minus) * scale;
        F_minus             = F_plus;
      }
    for (unsigned int k = 0; k < nm; ++k)
      {
        double s = 0;
        for (unsigned int j = 0; j < nm; ++j)
          s += blend.from_subcells[k][j] * rate[j];
        fv[k] = s;
      }
  }

  /// The blending factors before smoothing of the cells of edge e; the
  /// floor is a fraction of the edge's largest cell mean.
  template <typename Law>
  template <unsigned int nm>
  void
  EdgeLines<Law>::raw_blending_factors(const double *src, const unsigned int e) const
  {
    double scale = 0;
    for (unsigned int c = 0; c < cells[e]; ++c)
      scale = std::max(scale, std::abs(src[index(e, c)]));
    const double floor = dg::indicator_floor_fraction * scale;
    for (unsigned int c = 0; c < cells[e]; ++c)
      raw_alpha[first[e] + c] = blend.raw_factor<nm>(src + index(e, c), floor * floor);
  }

  /// max(alpha_c, alpha_N / 2) over the neighbours N on the edge (kept for
  /// the output)
  template <typename Law>
  double
  EdgeLines<Law>::blending_factor(const unsigned int e, const unsigned int c) const
  {
    const double *raw = raw_alpha.data() + first[e];
    double        a   = raw[c];
    if (c > 0)
      a = std::max(a, 0.5 * raw[c - 1]);
    if (c + 1 < cells[e])
      a = std::max(a, 0.5 * raw[c + 1]);
    alpha[first[e] + c] = a;
    return a;
  }

  template <typename Law>
  unsigned int
  EdgeLines<Law>::n_blended_cells() const
  {
    return std::count_if(alpha.begin(), alpha.end(), [](const double a) { return a > 0; });
  }

  // ---------------------------------------------------------------- the CFL scan

  template <typename Law>
  double
  EdgeLines<Law>::max_speed_over_h(const double *u, const double *vertex_values) const
  {
    return dg::with_n_modes(modes, [&](auto nm) {
      // (the largest over the lanes once at the end: max is exact in any order)
      VA     lanes  = 0.;
      double result = 0;
      for (unsigned int e = 0; e < n_edges();)
        {
          // a run of edges of one cell size and one law (the city grid's
          // streets between two avenues): one pass over their cells, their
          // largest speeds in registers, divided once (a division by h > 0
          // is monotone: the same maximum to the bit as dividing each)
          unsigned int end = e + 1;
          while (end < n_edges() && h[end] == h[e] && law_of_edge[end] == law_of_edge[e])
            ++end;
          VA     run_lanes = 0.;
          double run_rest  = 0.;
          max_speed_run<decltype(nm)::value>(u, vertex_values, e, end, run_lanes, run_rest);
          lanes  = std::max(lanes, run_lanes / VA(h[e]));
          result = std::max(result, run_rest / h[e]);
          e      = end;
        }
      for (unsigned int l = 0; l < W; ++l)
        result = std::max(result, lanes[l]);
      return result;
    });
  }

  /// dg::LineOperator::max_speed_impl() on the edges [e0, e1), which share
  /// their law: the largest speed of their cells, which lie one after the
  /// other (SIMD batches into lanes, a batch may span two edges; the rest
  /// into rest), and of the vertex values at their vertex ends (into rest);
  /// the caller divides by h (division by h > 0 is monotone: the same
  /// maximum as dividing every speed). With the law fixed at compile time
  /// (with_fixed_law()): no branch on it at every point. Inlined: as a call
  /// its maxima go through memory.
  template <typename Law>
  template <unsigned int nm>
  DEAL_II_ALWAYS_INLINE inline void
  EdgeLines<Law>::max_speed_run(const double *src, const double *vertex_values,
                                const unsigned int e0, const unsigned int e1, VA &lanes,
                                double &rest) const
  {
    with_fixed_law(edge_law(e0), [&](const auto &f) {
      const auto cell_speed = [&](const auto *u) {
        using Number    = std::remove_cv_t<std::remove_pointer_t<decltype(u)>>;
        // (degree 0: every point has the cell's value)
        Number cell_max = 0.;
        for (unsigned int q = 0; q < (nm > 1 ? nm + 1 : 1); ++q)
          cell_max = std::max(cell_max, std::max(std::abs(f.derivative(
                                                   internal::point_state<nm>(u, basis[q]))),
                                                 Number(0.)));
        return cell_max;
      };
      std::size_t c = first[e0];
      for (; c + W <= first[e1]; c += W)
        {
          VA u[nm];
          load_cell_major<nm>(src + c * nm, u);
          lanes = std::max(lanes, cell_speed(u));
        }
      for (; c < first[e1]; ++c)
        rest = std::max(rest, cell_speed(src + c * nm));
      for (unsigned int e = e0; e < e1; ++e)
        for (const unsigned int side : {0u, 1u})
          if (end_kind[2 * e + side] == EndKind::vertex)
            rest = std::max(rest, std::abs(f.derivative(vertex_values[2 * e + side])));
    });
  }

  // ---------------------------------------------------------------- the limiter

  template <typename Law>
  unsigned int
  EdgeLines<Law>::limit(double *u) const
  {
    if (!limits())
      return 0;
    return dg::with_n_modes(modes, [&](auto nm) -> unsigned int {
      if constexpr (decltype(nm)::value == 1)
        return 0;
      else
        {
          unsigned int troubled = 0;
          for (unsigned int e = 0; e < n_edges(); ++e)
            troubled += limit_edge<decltype(nm)::value>(u, e);
          return troubled;
        }
    });
  }

  /// dg::ModalLimiter::apply() on edge e as a line of its own: the
  /// indicator's floor from the edge's largest mean, the flags of the
  /// indicators that look at neighbours from the unlimited state
  template <typename Law>
  template <unsigned int nm>
  unsigned int
  EdgeLines<Law>::limit_edge(double *u, const unsigned int e) const
  {
    using dg::TroubleIndicator;
    const unsigned int n     = cells[e];
    double             floor = 0;
    if (method.indicator != TroubleIndicator::everywhere)
      {
        double scale = 0;
        for (unsigned int c = 0; c < n; ++c)
          scale = std::max(scale, std::abs(u[index(e, c)]));
        floor = dg::indicator_floor_fraction * scale;
      }
    if (method.indicator == TroubleIndicator::kxrcf)
      {
        examined.resize(n);
        for (unsigned int c = 0; c < n; ++c)
          examined[c] = kxrcf_indicated<nm>(u, e, c, floor);
      }
    if (method.indicator == TroubleIndicator::modal_energy_neighbours)
      {
        flags.resize(n);
        for (unsigned int c = 0; c < n; ++c)
          flags[c] = dg::highest_mode_energy_share<1, nm>(u + index(e, c), floor) >
                     indicator_threshold;
        examined.resize(n);
        for (unsigned int c = 0; c < n; ++c)
          examined[c] = flags[c] || (c > 0 && flags[c - 1]) || (c + 1 < n && flags[c + 1]);
      }
    unsigned int troubled = 0, c = 0;
    if (W > 1 && nm > 1 && method.indicator == TroubleIndicator::everywhere)
      for (; c + W <= n; c += W)
        troubled += limit_batch<nm>(u, e, c);
    for (; c < n; ++c)
      troubled += limit_cell<nm>(u, e, c, floor);
    return troubled;
  }

  /// limit_cell() on the cells c .. c + W - 1 of edge e as one SIMD batch
  /// (every cell examined): the TVB test by dg::internal::tvb_keeps_lanes(),
  /// which decides as tvb_keeps() does, and the TVB minmod slope lane by
  /// lane; the troubled cells.
  template <typename Law>
  template <unsigned int nm>
  unsigned int
  EdgeLines<Law>::limit_batch(double *u, const unsigned int e, const unsigned int c) const
  {
    VA x[nm];
    load_cell_major<nm>(u + index(e, c), x);
    // the neighbours' means: the batch's own, shifted by one lane, and at
    // the batch's ends the next cells or the outer states beyond the edge
    const VA avg_m = shift_lanes<true>(x[0], c > 0 ? u[index(e, c - 1)] : outer[2 * e]);
    const VA avg_p =
      shift_lanes<false>(x[0], c + W < cells[e] ? u[index(e, c + W)] : outer[2 * e + 1]);
    VA dp = avg_p - x[0], dm = x[0] - avg_m;
    // at an outflow end the missing difference does not limit
    if (c == 0 && end_kind[2 * e] == EndKind::outflow)
      dm[0] = dp[0];
    if (c + W == cells[e] && end_kind[2 * e + 1] == EndKind::outflow)
      dp[W - 1] = dm[W - 1];
    VA jump_p = 0., jump_m = 0.;
    for (unsigned int k = 1; k < nm; ++k)
      {
        jump_p += x[k] * at_1[k];
        jump_m -= x[k] * at_0[k];
      }
    const VA Mh2   = method.tvb_M * h[e] * h[e];
    const VA keeps = dg::internal::tvb_keeps_lanes(jump_p, dp, dm, Mh2) *
                     dg::internal::tvb_keeps_lanes(jump_m, dp, dm, Mh2);
    unsigned int troubled = 0;
    for (unsigned int l = 0; l < W; ++l)
      troubled += keeps[l] == 0.;
    if (troubled == 0)
      return 0;
    // minmod_tvb(slope, dp, dm, Mh2): the slope where |slope| <= M h^2, else
    // the smallest of the three when they share a sign, else 0
    using S          = SIMDComparison;
    const VA zero    = 0., slope = x[1] * at_1[1];
    const VA all_pos = compare_and_apply_mask<S::greater_than>(
      slope, zero,
      compare_and_apply_mask<S::greater_than>(
        dp, zero, compare_and_apply_mask<S::greater_than>(dm, zero, VA(1.), zero), zero),
      zero);
    const VA all_neg = compare_and_apply_mask<S::less_than>(
      slope, zero,
      compare_and_apply_mask<S::less_than>(
        dp, zero, compare_and_apply_mask<S::less_than>(dm, zero, VA(1.), zero), zero),
      zero);
    VA s = compare_and_apply_mask<S::equal>(all_pos, VA(1.), std::min(slope, std::min(dp, dm)),
                                            zero);
    s    = compare_and_apply_mask<S::equal>(all_neg, VA(1.), std::max(slope, std::max(dp, dm)), s);
    s    = compare_and_apply_mask<S::less_than_or_equal>(std::abs(slope), Mh2, slope, s);
    // troubled lanes: the limited slope, no higher modes
    const VA limited = s / at_1[1];
    x[1]             = compare_and_apply_mask<S::equal>(keeps, zero, limited, x[1]);
    for (unsigned int k = 2; k < nm; ++k)
      x[k] = compare_and_apply_mask<S::equal>(keeps, zero, zero, x[k]);
    store_cell_major<nm>(x, u + index(e, c));
    return troubled;
  }

  /// dg::ModalLimiter::limit_cell() of a scalar law (the characteristic
  /// field is u itself): the TVB test of the jumps to the faces against the
  /// differences of the means, the slope replaced by the TVB minmod one
  template <typename Law>
  template <unsigned int nm>
  bool
  EdgeLines<Law>::limit_cell(double *u, const unsigned int e, const unsigned int c,
                             const double floor) const
  {
    using dg::TroubleIndicator;
    double *x = u + index(e, c);
    if ((method.indicator == TroubleIndicator::modal_energy &&
         !(dg::highest_mode_energy_share<1, nm>(x, floor) > indicator_threshold)) ||
        ((method.indicator == TroubleIndicator::kxrcf ||
          method.indicator == TroubleIndicator::modal_energy_neighbours) &&
         !examined[c]))
      return false;
    const double avg = x[0];
    // the neighbours' means; at an end the outer state (outflow: unknown)
    const auto neighbour = [&](const unsigned int side, double &mean) {
      const bool inside = side == 0 ? c > 0 : c + 1 < cells[e];
      if (inside)
        mean = u[index(e, side == 0 ? c - 1 : c + 1)];
      else if (end_kind[2 * e + side] != EndKind::outflow)
        mean = outer[2 * e + side];
      return inside || end_kind[2 * e + side] != EndKind::outflow;
    };
    double     avg_m = 0, avg_p = 0;
    const bool has_m = neighbour(0, avg_m), has_p = neighbour(1, avg_p);
    double     jump_p = 0, jump_m = 0;
    for (unsigned int k = 1; k < nm; ++k)
      {
        jump_p += x[k] * at_1[k];
        jump_m -= x[k] * at_0[k];
      }
    const double slope = x[1] * at_1[1];
    const double dp = has_p ? avg_p - avg : 0., dm = has_m ? avg - avg_m : 0.;
    // at an outflow end the missing difference does not limit
    const double d_p = has_p ? dp : dm, d_m = has_m ? dm : dp;
    const double Mh2 = method.tvb_M * h[e] * h[e];
    if (dg::internal::tvb_keeps(jump_p, d_p, d_m, Mh2) &&
        dg::internal::tvb_keeps(jump_m, d_p, d_m, Mh2))
      return false;
    x[1] = dg::internal::minmod_tvb(slope, d_p, d_m, Mh2) / at_1[1];
    for (unsigned int k = 2; k < nm; ++k)
      x[k] = 0.;
    return true;
  }

  /// dg::ModalLimiter::kxrcf_indicated() in 1D: the jumps of u at the
  /// cell's inner faces against h^{(p+1)/2} and the cell's size of u
  template <typename Law>
  template <unsigned int nm>
  bool
  EdgeLines<Law>::kxrcf_indicated(const double *u, const unsigned int e, const unsigned int c,
                                  const double floor) const
  {
    const auto face_value = [&](const unsigned int cell, const unsigned int f) {
      double U = 0;
      for (unsigned int k = 0; k < nm; ++k)
        U += u[index(e, cell) + k] * (f == 0 ? at_0[k] : at_1[k]);
      return U;
    };
    double size = std::abs(u[index(e, c)]), jumps = 0, boundary = 0;
    for (unsigned int f = 0; f < 2; ++f)
      {
        const double own = face_value(c, f);
        size             = std::max(size, std::abs(own));
        const bool inside = f == 0 ? c > 0 : c + 1 < cells[e];
        if (!inside)
          continue;
        jumps += std::abs(own - face_value(f == 0 ? c - 1 : c + 1, f ^ 1u)) * 1.;
        boundary += 1.;
      }
    if (!(size > floor) || boundary == 0)
      return false;
    const double half_h = 0.5 * std::sqrt(h[e] * h[e]);
    return jumps / (std::pow(half_h, 0.5 * nm) * boundary * size) > indicator_threshold;
  }
} // namespace granular_dg::network
