#pragma once

#include <granular_dg/dg/limiter.h>

#include <granular_dg/base/errors.h>

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

    /// Whether the Physics has the optional limiter_boundary() (limiter.h).
    template <typename Physics, int dim, typename = void>
    struct has_limiter_boundary : std::false_type
    {};
    template <typename Physics, int dim>
    struct has_limiter_boundary<
      Physics, dim,
      std::void_t<decltype(std::declval<const Physics &>().limiter_boundary(
        BoundaryKind::custom, Tensor<1, Physics::n_components>(),
        Tensor<1, Physics::n_components>(), Tensor<1, dim>(), Tensor<1, Physics::n_components>(),
        std::declval<const typename Physics::template Coefficients<double> &>(),
        static_cast<const Tensor<2, Physics::n_components> *>(nullptr)))>> : std::true_type
    {};
  } // namespace internal

  namespace internal
  {
    /// Whether the Physics names limiting variables (flux_variables mode).
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
  } // namespace internal

  template <int dim, typename Physics>
  ModalLimiter<dim, Physics>::ModalLimiter(const Physics &physics, const LimiterType type,
                                           const double tvb_M, BoundaryMap<dim> boundary)
    : physics(physics)
    , type(type)
    , M(tvb_M)
    , boundary(std::move(boundary))
  {
    require(type != LimiterType::flux_variables ||
              internal::has_limiting_variables<Physics>::value,
            "Limiter/scheme", "flux_variables",
            std::string("none, componentwise or characteristic: ") + Physics::name +
              " names no flux variables");
  }

  template <int dim, typename Physics>
  void
  ModalLimiter<dim, Physics>::reinit(const DoFHandler<dim> &dof_handler,
                                     const VectorType      &vector)
  {
    reinit(dof_handler);
    cells.localize(dof_handler, vector.get_mpi_communicator());
  }

  template <int dim, typename Physics>
  void
  ModalLimiter<dim, Physics>::reinit(const DoFHandler<dim> &dof_handler)
  {
    cells.reinit(dof_handler);
    troubled.assign(cells.n_owned(), 0);
    // owned cells and the ghost neighbours (flux_variables needs theirs)
    coefficients.resize(cells.n_cells());
    for (unsigned int i = 0; i < cells.n_cells(); ++i)
      coefficients[i] = physics.coefficients(cells.cell(i)->material_id());
  }

  template <int dim, typename Physics>
  unsigned int
  ModalLimiter<dim, Physics>::apply(VectorType &u, const double t) const
  {
    const unsigned int n_modes_1d = cells.degree() + 1;
    if (type == LimiterType::none || n_modes_1d == 1)
      return 0;

    // neighbours (also ghost cells) are read from g, owned cells written in u
    const VectorType &g     = cells.with_ghosts(u);
    auto              value = [&](const unsigned int cell, const unsigned int c,
                     const unsigned int mode) -> double & {
      return u.local_element(cells.index(cell, c, mode));
    };
    using State = Tensor<1, n_components>;
    auto average = [&](const unsigned int cell) {
      State avg;
      for (unsigned int c = 0; c < n_components; ++c)
        avg[c] = g.local_element(cells.index(cell, c, 0));
      return avg;
    };
    for (auto &b : boundary)
      if (b.second.data)
        b.second.data->set_time(t);

    unsigned int n_troubled = 0;
    for (unsigned int i = 0; i < cells.n_owned(); ++i)
      {
        const State avg = average(i);
        const auto &a   = coefficients[i];

        // the neighbour average across face f (and the neighbour's
        // coefficients); false at an outflow boundary
        const std::array<double, Physics::n_coefficients> *a_nb = &a;
        auto neighbor_average = [&](const unsigned int f, State &result) {
          const int nb = cells.neighbor(i, f);
          a_nb         = &a;
          if (nb >= 0)
            {
              result = average(nb);
              a_nb   = &coefficients[nb];
              return true;
            }
          const auto bc = boundary.find(cells.boundary_id(i, f));
          if (bc == boundary.end() || bc->second.kind == BoundaryKind::outflow)
            return false;
          Tensor<1, dim> n;
          n[f / 2] = (f % 2 == 0) ? -1. : 1.;
          State g;
          if (bc->second.data)
            {
              const Point<dim> x = cells.cell(i)->face(f)->center();
              for (unsigned int c = 0; c < n_components; ++c)
                g[c] = bc->second.data->value(x, c);
            }
          result = physics.boundary_state(bc->second.kind, avg, n, g, a);
          return true;
        };

        // per direction: jumps to the faces and limited slopes, in the
        // variables the limiter works on (components or characteristic fields)
        std::array<State, dim>                   new_slope;
        bool                                     is_troubled = false;
        std::array<Tensor<2, n_components>, dim> R;
        for (int d = 0; d < dim; ++d)
          {
            const unsigned int stride = cells.stride(d);
            State              avg_m, avg_p, jump_p, jump_m, slope;
            const bool         has_m = neighbor_average(2 * d, avg_m);
            const auto        *a_m   = a_nb;
            const bool         has_p = neighbor_average(2 * d + 1, avg_p);
            const auto        *a_p   = a_nb;
            for (unsigned int c = 0; c < n_components; ++c)
              {
                for (unsigned int k = 1; k < n_modes_1d; ++k)
                  {
                    const double mode = value(i, c, k * stride);
                    jump_p[c] += mode * cells.value_at_1(k);
                    jump_m[c] -= mode * cells.value_at_0(k);
                  }
                slope[c] = value(i, c, stride) * cells.value_at_1(1);
              }
            State dp = has_p ? avg_p - avg : State(), dm = has_m ? avg - avg_m : State();
            // the traces at the two faces (for limiter_boundary())
            const State face_value[2] = {avg - jump_m, avg + jump_p};
            Tensor<2, n_components> L;
            if constexpr (internal::has_limiting_variables<Physics>::value)
              if (type == LimiterType::flux_variables)
                {
                  const State W = physics.limiting_variables(avg, a);
                  const auto  J = physics.limiting_jacobian(avg, a);
                  R[d]          = invert(J);
                  if (has_p)
                    dp = physics.limiting_variables(avg_p, *a_p) - W;
                  if (has_m)
                    dm = W - physics.limiting_variables(avg_m, *a_m);
                  jump_p = J * jump_p;
                  jump_m = J * jump_m;
                  slope  = J * slope;
                }
            if (type == LimiterType::characteristic)
              {
                Tensor<1, dim> n;
                n[d] = 1.;
                physics.eigenvectors(avg, n, a, L, R[d]);
                jump_p = L * jump_p;
                jump_m = L * jump_m;
                slope  = L * slope;
                dp     = L * dp;
                dm     = L * dm;
              }
            // per field: whether the difference across the face is known
            std::array<bool, n_components> known_p, known_m;
            known_p.fill(has_p);
            known_m.fill(has_m);
            if constexpr (internal::has_limiter_boundary<Physics, dim>::value)
              for (const unsigned int f : {2 * d, 2 * d + 1})
                {
                  const auto bc = boundary.find(cells.boundary_id(i, f));
                  if (cells.neighbor(i, f) >= 0 || bc == boundary.end())
                    continue;
                  Tensor<1, dim> n;
                  n[d] = (f % 2 == 0) ? -1. : 1.;
                  State g;
                  if (bc->second.data)
                    {
                      const Point<dim> x = cells.cell(i)->face(f)->center();
                      for (unsigned int c = 0; c < n_components; ++c)
                        g[c] = bc->second.data->value(x, c);
                    }
                  const auto o = physics.limiter_boundary(
                    bc->second.kind, avg, face_value[f % 2], n, g, a,
                    type == LimiterType::characteristic ? &L : nullptr);
                  if (!o)
                    continue;
                  (f % 2 == 0 ? dm : dp) = (f % 2 == 0 ? -1. : 1.) * o->difference;
                  (f % 2 == 0 ? known_m : known_p) = o->known;
                }
            const double h   = cells.extent(i, d);
            const double Mh2 = M * h * h;
            for (unsigned int c = 0; c < n_components; ++c)
              {
                // at an outflow boundary the missing difference does not limit
                const double dpc = known_p[c] ? dp[c] : dm[c];
                const double dmc = known_m[c] ? dm[c] : dp[c];
                if (internal::minmod_tvb(jump_p[c], dpc, dmc, Mh2) != jump_p[c] ||
                    internal::minmod_tvb(jump_m[c], dpc, dmc, Mh2) != jump_m[c])
                  is_troubled = true;
                new_slope[d][c] = internal::minmod_tvb(slope[c], dpc, dmc, Mh2);
              }
          }
        troubled[i] = is_troubled;
        if (!is_troubled)
          continue;
        ++n_troubled;
        for (int d = 0; d < dim; ++d)
          {
            State s = new_slope[d];
            if (type == LimiterType::characteristic || type == LimiterType::flux_variables)
              s = R[d] * s;
            for (unsigned int c = 0; c < n_components; ++c)
              value(i, c, cells.stride(d)) = s[c] / cells.value_at_1(1);
          }
        for (unsigned int c = 0; c < n_components; ++c)
          for (unsigned int m = 1; m < cells.n_modes(); ++m)
            {
              bool linear = false;
              for (int d = 0; d < dim; ++d)
                linear |= (m == cells.stride(d));
              if (!linear)
                value(i, c, m) = 0.;
            }
      }
    return n_troubled;
  }
} // namespace granular_dg::dg
