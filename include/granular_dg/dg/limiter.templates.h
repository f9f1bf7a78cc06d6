#pragma once

#include <granular_dg/dg/limiter.h>

#include <granular_dg/base/errors.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <type_traits>
#include <utility>

namespace granular_dg::dg
{
  namespace internal
  {
    inline double
    minmod(const double a, const double b, const double c)
    {
      if (a > 0 && b > 0 && c > 0)
        return std::min(a, std::min(b, c));
      if (a < 0 && b < 0 && c < 0)
        return std::max(a, std::max(b, c));
      return 0.;
    }

    /// TVB-modified minmod: a is returned unchanged when |a| <= M h^2.
    inline double
    minmod_tvb(const double a, const double b, const double c, const double Mh2)
    {
      if (std::abs(a) <= Mh2)
        return a;
      return minmod(a, b, c);
    }

    /// Whether the TVB test keeps the jump a against the differences b, c.
    inline bool
    tvb_keeps(const double a, const double b, const double c, const double Mh2)
    {
      return minmod_tvb(a, b, c, Mh2) == a;
    }

    /// tvb_keeps() in every lane of a SIMD batch: 1 where it keeps a, 0
    /// where not. minmod_tvb(a, b, c) == a holds exactly when |a| <= M h^2,
    /// a == 0, 0 < a <= b, c or 0 > a >= b, c (NaN anywhere: only through
    /// |a| <= M h^2); every comparison is ordered, as the scalar ones.
    template <typename Number>
    DEAL_II_ALWAYS_INLINE inline Number
    tvb_keeps_lanes(const Number &a, const Number &b, const Number &c, const Number &Mh2)
    {
      using S            = SIMDComparison;
      const Number one   = 1., zero = 0.;
      const Number up    = compare_and_apply_mask<S::greater_than_or_equal>(
        b, a, compare_and_apply_mask<S::greater_than_or_equal>(c, a, one, zero), zero);
      const Number down  = compare_and_apply_mask<S::less_than_or_equal>(
        b, a, compare_and_apply_mask<S::less_than_or_equal>(c, a, one, zero), zero);
      Number       keeps = compare_and_apply_mask<S::greater_than>(a, zero, up, zero);
      keeps = compare_and_apply_mask<S::less_than>(a, zero, down, keeps);
      keeps = compare_and_apply_mask<S::equal>(a, zero, one, keeps);
      return compare_and_apply_mask<S::less_than_or_equal>(std::abs(a), Mh2, one, keeps);
    }

    /// Whether the Physics has the optional limiter_boundary() (limiter.h).
    template <typename Physics, int dim, typename = void>
    struct has_limiter_boundary : std::false_type
    {};
    template <typename Physics, int dim>
    struct has_limiter_boundary<
      Physics, dim,
      std::void_t<decltype(std::declval<const Physics &>().limiter_boundary(
        BoundaryKind::outflow, Tensor<1, Physics::n_components>(),
        Tensor<1, Physics::n_components>(), Tensor<1, dim>(), Tensor<1, Physics::n_components>(),
        std::declval<const typename Physics::template Coefficients<double> &>(),
        static_cast<const Tensor<2, Physics::n_components> *>(nullptr)))>> : std::true_type
    {};

    /// Whether the Physics names limiting variables (physics_variables mode).
    template <typename Physics, typename = void>
    struct has_limiting_variables : std::false_type
    {};
    template <typename Physics>
    struct has_limiting_variables<
      Physics,
      std::void_t<decltype(std::declval<const Physics &>().limiting_jacobian(
        Tensor<1, Physics::n_components>(),
        std::declval<const typename Physics::template Coefficients<double> &>()))>>
      : std::true_type
    {};

    /// Whether the Physics' eigenvectors() and limiting_jacobian() are
    /// templates that take SIMD batches (the limiter's 1D batches).
    template <typename Physics, typename = void>
    struct has_batched_eigenvectors : std::false_type
    {};
    template <typename Physics>
    struct has_batched_eigenvectors<
      Physics, std::void_t<decltype(&Physics::template eigenvectors<VectorizedArray<double>>)>>
      : std::true_type
    {};
    template <typename Physics, typename = void>
    struct has_batched_limiting_jacobian : std::false_type
    {};
    template <typename Physics>
    struct has_batched_limiting_jacobian<
      Physics,
      std::void_t<decltype(&Physics::template limiting_jacobian<VectorizedArray<double>>)>>
      : std::true_type
    {};
  } // namespace internal

  template <int dim, typename Physics>
  ModalLimiter<dim, Physics>::ModalLimiter(const Physics &physics, const LimiterType type,
                                           const double tvb_M, BoundaryMap<dim> boundary)
    : physics(physics)
    , type(type)
    , M(tvb_M)
    , boundary(std::move(boundary))
  {
    require(type != LimiterType::physics_variables ||
              internal::has_limiting_variables<Physics>::value,
            "Limiter/scheme", "physics_variables",
            std::string("none, componentwise or characteristic: ") + Physics::name +
              " names no limiting variables");
    batchable = dim == 1 && batch_width > 1 &&
                (type == LimiterType::componentwise ||
                 (type == LimiterType::characteristic &&
                  internal::has_batched_eigenvectors<Physics>::value) ||
                 (type == LimiterType::physics_variables &&
                  internal::has_batched_limiting_jacobian<Physics>::value));
  }

  template <int dim, typename Physics>
  void
  ModalLimiter<dim, Physics>::reinit(const DoFHandler<dim> &dof_handler,
                                     const VectorType      &vector)
  {
    reinit(dof_handler);
    cells.localize(dof_handler, vector.get_mpi_communicator());
    build_tables();
  }

  template <int dim, typename Physics>
  void
  ModalLimiter<dim, Physics>::reinit(const DoFHandler<dim> &dof_handler)
  {
    cells.reinit(dof_handler);
    troubled.assign(cells.n_owned(), 0);
    // a limiter that never limits keeps no tables: apply() returns at once
    // (8 bytes per DoF of the 2D strip at P2, doc/program.md)
    if (type == LimiterType::none)
      return;
    // owned cells and the ghost neighbours (physics_variables needs theirs)
    coefficients.resize(cells.n_cells());
    for (unsigned int i = 0; i < cells.n_cells(); ++i)
      coefficients[i] = physics.coefficients(cells.cell(i)->material_id());
    build_tables();
  }

  template <int dim, typename Physics>
  void
  ModalLimiter<dim, Physics>::build_tables()
  {
    if (type == LimiterType::none)
      return;
    const unsigned int n_modes = cells.n_modes();
    base.resize(cells.n_cells());
    for (unsigned int i = 0; i < cells.n_cells(); ++i)
      {
        base[i] = cells.index(i, 0, 0);
        for (unsigned int c = 0; c < n_components; ++c)
          for (unsigned int m = 0; m < n_modes; ++m)
            AssertThrow(cells.index(i, c, m) == base[i] + c * n_modes + m,
                        ExcMessage("ModalLimiter expects the modes of a cell component by "
                                   "component (FESystem of FE_DGQLegendre)"));
      }
    at_0.resize(cells.degree() + 1);
    at_1.resize(cells.degree() + 1);
    for (unsigned int k = 0; k <= cells.degree(); ++k)
      {
        at_0[k] = cells.value_at_0(k);
        at_1[k] = cells.value_at_1(k);
      }
    faces.assign(cells.n_owned() * 2 * dim, Face());
    for (unsigned int i = 0; i < cells.n_owned(); ++i)
      for (unsigned int f = 0; f < 2 * dim; ++f)
        {
          Face &face    = faces[i * 2 * dim + f];
          face.neighbor = cells.neighbor(i, f);
          if (face.neighbor >= 0)
            continue;
          const auto bc = boundary.find(cells.boundary_id(i, f));
          if (bc == boundary.end())
            continue;
          face.has_condition = true;
          face.condition     = bc->second;
          face.center        = cells.cell(i)->face(f)->center();
        }
    interior.assign(cells.n_owned(), 0);
    for (unsigned int i = 0; i < cells.n_owned(); ++i)
      interior[i] = dim == 1 && faces[2 * i].neighbor >= 0 && faces[2 * i + 1].neighbor >= 0;
  }

  template <int dim, typename Physics>
  unsigned int
  ModalLimiter<dim, Physics>::apply(VectorType &u, const double t,
                                    const ActiveCells *active) const
  {
    const unsigned int n_modes_1d = cells.degree() + 1;
    if (type == LimiterType::none || n_modes_1d == 1)
      return 0;
    return with_n_modes(n_modes_1d, [&](auto n1) -> unsigned int {
      if constexpr (decltype(n1)::value == 1)
        return 0; // (returned above: a constant has no slope to limit)
      else
        return apply_impl<decltype(n1)::value>(u, t, active);
    });
  }

  template <int dim, typename Physics>
  typename ModalLimiter<dim, Physics>::State
  ModalLimiter<dim, Physics>::average(const unsigned int cell) const
  {
    State avg;
    for (unsigned int c = 0; c < n_components; ++c)
      avg[c] = averages[base[cell] + c * cells.n_modes()];
    return avg;
  }

  template <int dim, typename Physics>
  typename ModalLimiter<dim, Physics>::State
  ModalLimiter<dim, Physics>::boundary_data(const Face &face) const
  {
    State g;
    if (face.condition.data)
      for (unsigned int c = 0; c < n_components; ++c)
        g[c] = face.condition.data->value(face.center, c);
    return g;
  }

  template <int dim, typename Physics>
  bool
  ModalLimiter<dim, Physics>::neighbor_average(const Face &face, const unsigned int f,
                                               const State &avg, const Coefficients &a,
                                               State &result, const Coefficients *&a_nb) const
  {
    a_nb = &a;
    if (face.neighbor >= 0)
      {
        result = average(face.neighbor);
        a_nb   = &coefficients[face.neighbor];
        return true;
      }
    if (!face.has_condition || face.condition.kind == BoundaryKind::outflow)
      return false;
    Tensor<1, dim> n;
    n[f / 2] = (f % 2 == 0) ? -1. : 1.;
    result   = physics.boundary_state(face.condition.kind, avg, n, boundary_data(face), a);
    return true;
  }

  template <int dim, typename Physics>
  template <unsigned int n1>
  typename ModalLimiter<dim, Physics>::Direction
  ModalLimiter<dim, Physics>::analyse(const unsigned int i, const int d, const double *x,
                                      const State &avg) const
  {
    constexpr unsigned int nc      = n_components;
    const unsigned int     stride  = d == 0 ? 1 : n1;
    const auto            &a       = coefficients[i];
    const Face            *face    = &faces[i * 2 * dim];
    Direction              r;
    State                  avg_m, avg_p;
    const Coefficients    *a_m, *a_p;
    const bool has_m = neighbor_average(face[2 * d], 2 * d, avg, a, avg_m, a_m);
    const bool has_p = neighbor_average(face[2 * d + 1], 2 * d + 1, avg, a, avg_p, a_p);
    modal_jumps<n1>(x, stride, r);
    State dp = has_p ? avg_p - avg : State(), dm = has_m ? avg - avg_m : State();
    // the traces at the two faces (for limiter_boundary())
    const State face_value[2] = {avg - r.jump_m, avg + r.jump_p};
    if constexpr (internal::has_limiting_variables<Physics>::value)
      if (type == LimiterType::physics_variables)
        {
          const State &W = limiting_values[i];
          if (has_p)
            dp = (face[2 * d + 1].neighbor >= 0 ? limiting_values[face[2 * d + 1].neighbor] :
                                                  physics.limiting_variables(avg_p, *a_p)) -
                 W;
          if (has_m)
            dm = W - (face[2 * d].neighbor >= 0 ? limiting_values[face[2 * d].neighbor] :
                                                  physics.limiting_variables(avg_m, *a_m));
        }
    Tensor<2, nc> L;
    to_limiter_variables(avg, a, d, r, dp, dm, L);
    // per field: whether the difference across the face is known
    std::array<bool, nc> known_p, known_m;
    known_p.fill(has_p);
    known_m.fill(has_m);
    if constexpr (internal::has_limiter_boundary<Physics, dim>::value)
      for (const unsigned int f : {2 * d, 2 * d + 1})
        {
          if (face[f].neighbor >= 0 || !face[f].has_condition)
            continue;
          Tensor<1, dim> n;
          n[d]         = (f % 2 == 0) ? -1. : 1.;
          const auto o = physics.limiter_boundary(face[f].condition.kind, avg,
                                                  face_value[f % 2], n, boundary_data(face[f]),
                                                  a, type == LimiterType::characteristic ? &L :
                                                                                           nullptr);
          if (!o)
            continue;
          (f % 2 == 0 ? dm : dp)           = (f % 2 == 0 ? -1. : 1.) * o->difference;
          (f % 2 == 0 ? known_m : known_p) = o->known;
        }
    const double h = cells.extent(i, d);
    r.Mh2          = M * h * h;
    for (unsigned int c = 0; c < nc; ++c)
      {
        // at an outflow boundary the missing difference does not limit
        r.dp[c] = known_p[c] ? dp[c] : dm[c];
        r.dm[c] = known_m[c] ? dm[c] : dp[c];
      }
    return r;
  }

  template <int dim, typename Physics>
  template <unsigned int n1, typename Number>
  void
  ModalLimiter<dim, Physics>::modal_jumps(const Number *x, const unsigned int stride,
                                          DirectionOf<Number> &r) const
  {
    constexpr unsigned int n_modes = dim == 1 ? n1 : n1 * n1;
    for (unsigned int c = 0; c < n_components; ++c)
      {
        const Number *xc = x + c * n_modes;
        for (unsigned int k = 1; k < n1; ++k)
          {
            const Number mode = xc[k * stride];
            r.jump_p[c] += mode * at_1[k];
            r.jump_m[c] -= mode * at_0[k];
          }
        r.slope[c] = xc[stride] * at_1[1];
      }
  }

  template <int dim, typename Physics>
  template <typename Number>
  void
  ModalLimiter<dim, Physics>::to_limiter_variables(
    const Tensor<1, n_components, Number> &avg, const std::array<Number, Physics::n_coefficients> &a,
    const int d, DirectionOf<Number> &r, Tensor<1, n_components, Number> &dp,
    Tensor<1, n_components, Number> &dm, Tensor<2, n_components, Number> &L) const
  {
    // (a SIMD batch only where the physics takes one: limit_batch())
    constexpr bool scalar = std::is_same_v<Number, double>;
    if constexpr (internal::has_limiting_variables<Physics>::value &&
                  (scalar || internal::has_batched_limiting_jacobian<Physics>::value))
      if (type == LimiterType::physics_variables)
        {
          r.J      = physics.limiting_jacobian(avg, a);
          r.jump_p = r.J * r.jump_p;
          r.jump_m = r.J * r.jump_m;
          r.slope  = r.J * r.slope;
        }
    if constexpr (scalar || internal::has_batched_eigenvectors<Physics>::value)
      if (type == LimiterType::characteristic)
      {
        Tensor<1, dim, Number> n;
        n[d] = 1.;
        physics.eigenvectors(avg, n, a, L, r.R);
        r.jump_p = L * r.jump_p;
        r.jump_m = L * r.jump_m;
        r.slope  = L * r.slope;
        dp       = L * dp;
        dm       = L * dm;
      }
  }

  template <int dim, typename Physics>
  bool
  ModalLimiter<dim, Physics>::passes_tvb(const Direction &r)
  {
    for (unsigned int c = 0; c < n_components; ++c)
      if (!internal::tvb_keeps(r.jump_p[c], r.dp[c], r.dm[c], r.Mh2) ||
          !internal::tvb_keeps(r.jump_m[c], r.dp[c], r.dm[c], r.Mh2))
        return false;
    return true;
  }

  template <int dim, typename Physics>
  void
  ModalLimiter<dim, Physics>::extract_lane(const DirectionOf<VA> &r, const unsigned int l,
                                           Direction &lane)
  {
    for (unsigned int c = 0; c < n_components; ++c)
      {
        lane.jump_p[c] = r.jump_p[c][l];
        lane.jump_m[c] = r.jump_m[c][l];
        lane.slope[c]  = r.slope[c][l];
        lane.dp[c]     = r.dp[c][l];
        lane.dm[c]     = r.dm[c][l];
        for (unsigned int e = 0; e < n_components; ++e)
          {
            lane.R[c][e] = r.R[c][e][l];
            lane.J[c][e] = r.J[c][e][l];
          }
      }
  }

  template <int dim, typename Physics>
  bool
  ModalLimiter<dim, Physics>::batch_fits(const unsigned int i, const unsigned int end) const
  {
    if (i + batch_width > end)
      return false;
    for (unsigned int l = 0; l < batch_width; ++l)
      if (!interior[i + l])
        return false;
    return true;
  }

  template <int dim, typename Physics>
  template <unsigned int n1>
  void
  ModalLimiter<dim, Physics>::limit_batch(const unsigned int i, double *u_data) const
  {
    constexpr unsigned int nc = n_components, W = batch_width;
    if constexpr (dim == 1 && W > 1)
      {
        // lane l: cell i + l; its modes (mode 0: the average), the averages
        // and limiting values of its neighbours, its coefficients
        unsigned int offsets[W], offsets_m[W], offsets_p[W], values[W], values_m[W],
          values_p[W], coefficient_offsets[W];
        double Mh2[W];
        for (unsigned int l = 0; l < W; ++l)
          {
            const unsigned int cell = i + l, m = faces[2 * cell].neighbor,
                               p = faces[2 * cell + 1].neighbor;
            offsets[l]             = base[cell];
            offsets_m[l]           = base[m];
            offsets_p[l]           = base[p];
            values[l]              = cell * nc;
            values_m[l]            = m * nc;
            values_p[l]            = p * nc;
            coefficient_offsets[l] = l * Physics::n_coefficients;
            const double h         = cells.extent(cell, 0);
            Mh2[l]                 = M * h * h;
          }
        VA x[nc * n1];
        vectorized_load_and_transpose(nc * n1, u_data, offsets, x);
        Tensor<1, nc, VA> avg, avg_m, avg_p;
        for (unsigned int c = 0; c < nc; ++c)
          {
            avg[c] = x[c * n1];
            avg_m[c].gather(averages + c * n1, offsets_m);
            avg_p[c].gather(averages + c * n1, offsets_p);
          }
        std::array<VA, Physics::n_coefficients> a;
        if constexpr (Physics::n_coefficients > 0)
          vectorized_load_and_transpose(Physics::n_coefficients, coefficients[i].data(),
                                        coefficient_offsets, a.data());
        DirectionOf<VA> r;
        modal_jumps<n1>(x, 1, r);
        Tensor<1, nc, VA> dp = avg_p - avg, dm = avg - avg_m;
        if constexpr (internal::has_limiting_variables<Physics>::value)
          if (type == LimiterType::physics_variables)
            for (unsigned int c = 0; c < nc; ++c)
              {
                const double *W0 = &limiting_values[0][c];
                VA            Wc, Wm, Wp;
                Wc.gather(W0, values);
                Wm.gather(W0, values_m);
                Wp.gather(W0, values_p);
                dp[c] = Wp - Wc;
                dm[c] = Wc - Wm;
              }
        Tensor<2, nc, VA> L;
        to_limiter_variables(avg, a, 0, r, dp, dm, L);
        // the TVB test of limit_cell() in all lanes at once
        VA Mh2_lanes, keeps = 1.;
        Mh2_lanes.load(Mh2);
        for (unsigned int c = 0; c < nc; ++c)
          keeps *= internal::tvb_keeps_lanes(r.jump_p[c], dp[c], dm[c], Mh2_lanes) *
                   internal::tvb_keeps_lanes(r.jump_m[c], dp[c], dm[c], Mh2_lanes);
        bool passes[W];
        for (unsigned int l = 0; l < W; ++l)
          passes[l] = keeps[l] != 0.;
        // a troubled lane is limited with what the batch computed for it
        r.dp = dp;
        r.dm = dm;
        for (unsigned int l = 0; l < W; ++l)
          {
            const unsigned int cell = i + l;
            ++flagged;
            troubled[cell] = !passes[l];
            if (passes[l])
              continue;
            std::array<Direction, dim> dir;
            extract_lane(r, l, dir[0]);
            dir[0].Mh2 = Mh2[l];
            replace_modes<n1>(dir, u_data + base[cell]);
          }
      }
    else
      {
        (void)i;
        (void)u_data;
        Assert(false, ExcInternalError());
      }
  }

  template <int dim, typename Physics>
  void
  ModalLimiter<dim, Physics>::set_indicator(const TroubleIndicator ind, const double threshold)
  {
    static_assert(Physics::indicator_component < Physics::n_components);
    indicator           = ind;
    indicator_threshold = threshold > 0                        ? threshold :
                          ind == TroubleIndicator::kxrcf ? 1. :
                                                             modal_energy_threshold(cells.degree());
  }

  template <int dim, typename Physics>
  template <unsigned int n1>
  bool
  ModalLimiter<dim, Physics>::indicated(const double *x) const
  {
    constexpr unsigned int n_modes = dim == 1 ? n1 : n1 * n1;
    // below the floor the share is -1: not flagged (the threshold is > 0)
    return highest_mode_energy_share<dim, n1>(x + Physics::indicator_component * n_modes,
                                              indicator_floor) > indicator_threshold;
  }

  template <int dim, typename Physics>
  double
  ModalLimiter<dim, Physics>::jump_variable(const State &U, const unsigned int cell) const
  {
    if constexpr (internal::has_limiting_variables<Physics>::value)
      return physics.limiting_variables(U, coefficients[cell])[Physics::indicator_component];
    else
      return U[Physics::indicator_component];
  }

  template <int dim, typename Physics>
  template <unsigned int n1>
  bool
  ModalLimiter<dim, Physics>::kxrcf_indicated(const unsigned int i) const
  {
    constexpr unsigned int n_modes = dim == 1 ? n1 : n1 * n1;
    constexpr unsigned int p       = n1 - 1;
    // the face mean of the jump variable on face f of cell c (f = 2d:
    // coordinate d at 0, 2d + 1: at 1): only the modes constant across the
    // face contribute
    const auto face_value = [&](const unsigned int c, const unsigned int f) {
      const unsigned int d = f / 2, stride = d == 0 ? 1 : n1;
      State              U;
      for (unsigned int comp = 0; comp < n_components; ++comp)
        for (unsigned int k = 0; k < n1; ++k)
          U[comp] += averages[base[c] + comp * n_modes + k * stride] * (f % 2 == 0 ? at_0[k] : at_1[k]);
      return jump_variable(U, c);
    };
    double size = std::abs(jump_variable(average(i), i)), jumps = 0, boundary = 0, h2 = 0;
    for (unsigned int d = 0; d < dim; ++d)
      h2 += cells.extent(i, d) * cells.extent(i, d);
    for (unsigned int f = 0; f < 2 * dim; ++f)
      {
        const double own = face_value(i, f);
        size             = std::max(size, std::abs(own));
        const Face &face = faces[i * 2 * dim + f];
        if (face.neighbor < 0)
          continue;
        // the face's measure: the product of the extents across it
        double measure = 1;
        for (unsigned int e = 0; e < dim; ++e)
          if (e != f / 2)
            measure *= cells.extent(i, e);
        jumps += std::abs(own - face_value(face.neighbor, f ^ 1u)) * measure;
        boundary += measure;
      }
    if (!(size > indicator_floor) || boundary == 0)
      return false;
    const double h = 0.5 * std::sqrt(h2);
    return jumps / (std::pow(h, 0.5 * (p + 1)) * boundary * size) > indicator_threshold;
  }

  template <int dim, typename Physics>
  template <unsigned int n1>
  bool
  ModalLimiter<dim, Physics>::limit_cell(const unsigned int i, double *x) const
  {
    if ((indicator == TroubleIndicator::modal_energy && !indicated<n1>(x)) ||
        ((indicator == TroubleIndicator::kxrcf ||
          indicator == TroubleIndicator::modal_energy_neighbours) &&
         !examined[i]))
      return false;
    ++flagged;
    const State avg = average(i);
    // per direction: jumps to the faces and the slope, in the variables the
    // limiter works on (components or characteristic fields), and the
    // neighbour differences; the limited slopes only for a troubled cell
    std::array<Direction, dim> dir;
    bool                       is_troubled = false;
    for (int d = 0; d < dim; ++d)
      {
        dir[d] = analyse<n1>(i, d, x, avg);
        if (!passes_tvb(dir[d]))
          is_troubled = true;
      }
    if (!is_troubled)
      return false;
    replace_modes<n1>(dir, x);
    return true;
  }

  template <int dim, typename Physics>
  template <unsigned int n1>
  void
  ModalLimiter<dim, Physics>::replace_modes(const std::array<Direction, dim> &dir,
                                            double *x) const
  {
    constexpr unsigned int nc      = n_components;
    constexpr unsigned int n_modes = dim == 1 ? n1 : n1 * n1;
    for (int d = 0; d < dim; ++d)
      {
        const Direction &r = dir[d];
        State            s;
        for (unsigned int c = 0; c < nc; ++c)
          s[c] = internal::minmod_tvb(r.slope[c], r.dp[c], r.dm[c], r.Mh2);
        if (type == LimiterType::characteristic)
          s = r.R * s;
        else if (type == LimiterType::physics_variables)
          s = invert(r.J) * s;
        const unsigned int stride = d == 0 ? 1 : n1;
        for (unsigned int c = 0; c < nc; ++c)
          x[c * n_modes + stride] = s[c] / at_1[1];
      }
    // a troubled cell keeps its average and linear modes only
    for (unsigned int c = 0; c < nc; ++c)
      for (unsigned int m = 1; m < n_modes; ++m)
        if (!(m == 1 || (dim == 2 && m == n1)))
          x[c * n_modes + m] = 0.;
  }

  template <int dim, typename Physics>
  template <unsigned int n1>
  unsigned int
  ModalLimiter<dim, Physics>::apply_impl(VectorType &u, const double t,
                                         const ActiveCells *active) const
  {
    // averages (also of ghost cells) are read from the ghosted vector, the
    // modes of owned cells read and written in u
    averages = cells.with_ghosts(u).begin();
    for (auto &b : boundary)
      if (b.second.data)
        b.second.data->set_time(t);
    if constexpr (internal::has_limiting_variables<Physics>::value)
      if (type == LimiterType::physics_variables)
        {
          limiting_values.resize(cells.n_cells());
          for (unsigned int i = 0; i < cells.n_cells(); ++i)
            limiting_values[i] = physics.limiting_variables(average(i), coefficients[i]);
        }
    double *u_data = u.begin();
    flagged        = 0;
    if (indicator != TroubleIndicator::everywhere)
      {
        // the scale of the indicator variable: its largest cell mean
        double scale = 0;
        for (unsigned int i = 0; i < cells.n_owned(); ++i)
          scale = std::max(scale, std::abs(indicator == TroubleIndicator::kxrcf ?
                                             jump_variable(average(i), i) :
                                             average(i)[Physics::indicator_component]));
        indicator_floor =
          indicator_floor_fraction * Utilities::MPI::max(scale, u.get_mpi_communicator());
      }
    if (indicator == TroubleIndicator::kxrcf)
      {
        // all flags from the unlimited state: limiting a cell changes the
        // traces its neighbours see
        examined.resize(cells.n_owned());
        for_active_ranges(active, cells.n_owned(), [&](const unsigned int first, const unsigned int end) {
          for (unsigned int i = first; i < end; ++i)
            examined[i] = kxrcf_indicated<n1>(i);
        });
      }
    if (indicator == TroubleIndicator::modal_energy_neighbours)
      {
        // the flags of all cells (ghost neighbours too) from the unlimited
        // state, then a cell is examined if it or a face neighbour is flagged
        modal_flags.resize(cells.n_cells());
        for (unsigned int c = 0; c < cells.n_cells(); ++c)
          modal_flags[c] = indicated<n1>(averages + base[c]);
        examined.resize(cells.n_owned());
        for_active_ranges(active, cells.n_owned(), [&](const unsigned int first, const unsigned int end) {
          for (unsigned int i = first; i < end; ++i)
            {
              examined[i] = modal_flags[i];
              for (unsigned int f = 0; f < 2 * dim; ++f)
                {
                  const int neighbor = faces[i * 2 * dim + f].neighbor;
                  if (neighbor >= 0 && modal_flags[neighbor])
                    examined[i] = 1;
                }
            }
        });
      }
    // in 1D with every cell examined, the TVB test runs on SIMD batches of
    // interior cells; a cell it finds troubled is limited by limit_cell()
    const bool batches = batchable && simd_batches && indicator == TroubleIndicator::everywhere;
    const auto limit_range = [&](const unsigned int first, const unsigned int end) {
      unsigned int i = first;
      if (batches)
        {
          while (i + batch_width <= end)
            if (batch_fits(i, end))
              {
                limit_batch<n1>(i, u_data);
                i += batch_width;
              }
            else
              {
                troubled[i] = limit_cell<n1>(i, u_data + base[i]);
                ++i;
              }
        }
      for (; i < end; ++i)
        troubled[i] = limit_cell<n1>(i, u_data + base[i]);
    };
    for_active_ranges(active, cells.n_owned(), limit_range);
    unsigned int n_troubled = 0;
    for (const unsigned char flag : troubled)
      n_troubled += flag;
    return n_troubled;
  }
} // namespace granular_dg::dg
