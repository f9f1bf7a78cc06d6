#pragma once

#include <deal.II/lac/la_parallel_vector.h>

#include <functional>

namespace granular_dg::dg
{
  using VectorType = dealii::LinearAlgebra::distributed::Vector<double>;

  /**
   * Third-order strong-stability-preserving Runge-Kutta method in Shu-Osher
   * form:
   *   u1 = u + dt L(t, u)
   *   u2 = 3/4 u + 1/4 (u1 + dt L(t + dt, u1))
   *   u  = 1/3 u + 2/3 (u2 + dt L(t + dt/2, u2))
   * After every stage the post-stage hook (limiter, projections, admissibility
   * check) gets the new stage value, its time and the effective weight of the
   * explicit update in it: dt, dt/4 and 2 dt/3 — a stiff term treated
   * implicitly in the hook must carry exactly this weight to be consistent.
   *
   * Vector needs reinit(const Vector &), equ(a, x), add(a, x) and
   * sadd(s, a, x) (deal.II's vectors have them; so can a network state).
   */
  template <typename Vector = VectorType>
  class SSPRK3
  {
  public:
    using PostStageHook = std::function<void(Vector &u, double stage_time, double weight)>;

    template <typename Operator>
    void
    step(const Operator      &op,
         Vector              &u,
         const double         t,
         const double         dt,
         const PostStageHook &post_stage)
    {
      if (!initialized)
        {
          k.reinit(u);
          u1.reinit(u);
          initialized = true;
        }
      op.apply(t, u, k);
      u1.equ(1., u);
      u1.add(dt, k);
      post_stage(u1, t + dt, dt);

      op.apply(t + dt, u1, k);
      u1.sadd(0.25, 0.75, u);
      u1.add(0.25 * dt, k);
      post_stage(u1, t + 0.5 * dt, 0.25 * dt);

      op.apply(t + 0.5 * dt, u1, k);
      u.sadd(1. / 3., 2. / 3., u1);
      u.add(2. / 3. * dt, k);
      post_stage(u, t + dt, 2. / 3. * dt);
    }

    static constexpr unsigned int n_stages = 3;

  private:
    bool   initialized = false;
    Vector k, u1;
  };
} // namespace granular_dg::dg
