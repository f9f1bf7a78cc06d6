#pragma once

#include <deal.II/base/time_stepping.h>
#include <deal.II/base/vectorization.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <granular_dg/base/vectorized_math.h>

#include <functional>
#include <utility>
#include <vector>

namespace granular_dg::dg
{
  using VectorType = dealii::LinearAlgebra::distributed::Vector<double>;

  /**
   * One fused Runge-Kutta stage: dst = (alpha src + beta old) + gamma L(t, src),
   * or dst = src + gamma L(t, src) when old is null; dst may be src or old.
   * An operator with apply_stage(t, src, dst, StageUpdate) computes it in its
   * own pass over the cells, rounding as the vector operations do (see
   * rounded_product()): bit for bit what apply() followed by Vector::equ/sadd
   * and Vector::add gives.
   */
  template <typename Vector = VectorType>
  struct StageUpdate
  {
    const Vector *old   = nullptr;
    double        alpha = 1., beta = 0., gamma = 0.;
    /// a vector the stage may overwrite (not src, dst or old) to hold the
    /// rate when dst is src or old; null: the operator's own
    Vector *scratch = nullptr;
  };

  /// a * b rounded on its own: never contracted with a following sum into
  /// an FMA (deal.II's vector operations, compiled for baseline x86-64, round
  /// every product), so that a fused stage update adds up as they do.
  inline double
  rounded_product(const double a, const double b)
  {
    double p = a * b;
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
    asm("" : "+x"(p));
#else
    volatile double v = p;
    p                 = v;
#endif
    return p;
  }

  /// (alpha src + beta old) + gamma rate: the update of a StageUpdate with
  /// s.old for one value (src, old: the values at the same index).
  inline double
  stage_value(const double alpha, const double beta, const double gamma, const double src,
              const double old, const double rate)
  {
    return (rounded_product(alpha, src) + rounded_product(beta, old)) +
           rounded_product(gamma, rate);
  }

  /// src + gamma rate: the update of a StageUpdate without s.old.
  inline double
  stage_value(const double gamma, const double src, const double rate)
  {
    return src + rounded_product(gamma, rate);
  }

  /// rounded_product() of a SIMD batch: each lane's product rounded on its
  /// own, as the scalar one (the stage updates below then give the scalar
  /// updates' values lane by lane).
  template <typename Number, std::size_t width>
  inline dealii::VectorizedArray<Number, width>
  rounded_product(const dealii::VectorizedArray<Number, width> &a,
                  const dealii::VectorizedArray<Number, width> &b)
  {
    dealii::VectorizedArray<Number, width> p = a * b;
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
    asm("" : "+v"(p.data));
#else
    for (unsigned int l = 0; l < width; ++l)
      p[l] = rounded_product(a[l], b[l]);
#endif
    return p;
  }

  /// stage_value() of a SIMD batch of values.
  template <typename Number, std::size_t width>
  inline dealii::VectorizedArray<Number, width>
  stage_value(const dealii::VectorizedArray<Number, width> &alpha,
              const dealii::VectorizedArray<Number, width> &beta,
              const dealii::VectorizedArray<Number, width> &gamma,
              const dealii::VectorizedArray<Number, width> &src,
              const dealii::VectorizedArray<Number, width> &old,
              const dealii::VectorizedArray<Number, width> &rate)
  {
    return (rounded_product(alpha, src) + rounded_product(beta, old)) +
           rounded_product(gamma, rate);
  }

  /// stage_value() without old of a SIMD batch of values.
  template <typename Number, std::size_t width>
  inline dealii::VectorizedArray<Number, width>
  stage_value(const dealii::VectorizedArray<Number, width> &gamma,
              const dealii::VectorizedArray<Number, width> &src,
              const dealii::VectorizedArray<Number, width> &rate)
  {
    return src + rounded_product(gamma, rate);
  }

  /**
   * Where an operator's cell loop puts the rates of a fused stage: dst[i] =
   * stage_value(..., src[i], old[i], rate) for one value, cells(i, rate) for
   * a SIMD batch of cells from index i on, the same values lane by lane.
   * with_old: a StageUpdate with s.old.
   */
  template <bool with_old>
  struct StageWriter
  {
    const double *src, *old;
    double       *dst;
    double        alpha, beta, gamma;

    void
    operator()(const std::size_t i, const double rate) const
    {
      if constexpr (with_old)
        dst[i] = stage_value(alpha, beta, gamma, src[i], old[i], rate);
      else
        dst[i] = stage_value(gamma, src[i], rate);
    }

    /// The rates of W cells (W the SIMD width) of n values each from index
    /// i on, cell after cell: rate[k][l] is value k of cell l.
    template <unsigned int n>
    void
    cells(const std::size_t i, const dealii::VectorizedArray<double> (&rate)[n]) const
    {
      using VA = dealii::VectorizedArray<double>;
      const VA a = alpha, b = beta, g = gamma;
      for_cell_major_batches(rate, [&](const unsigned int j, const VA &r) {
        const std::size_t at = i + j * VA::size();
        VA                u;
        u.load(src + at);
        if constexpr (with_old)
          {
            VA o;
            o.load(old + at);
            stage_value(a, b, g, u, o, r).store(dst + at);
          }
        else
          stage_value(g, u, r).store(dst + at);
      });
    }
  };

  /// The update of StageUpdate for one value (src, old: the values at the
  /// same index; old unused without s.old).
  template <typename Vector>
  inline double
  stage_value(const StageUpdate<Vector> &s, const double src, const double old, const double rate)
  {
    return s.old ? stage_value(s.alpha, s.beta, s.gamma, src, old, rate) :
                   stage_value(s.gamma, src, rate);
  }

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
   * Vector needs reinit(const Vector &) (deal.II's vectors have it; so can
   * a network state); the operator's apply_stage() (StageUpdate) does the
   * operator and the vector updates of a stage, with the results of apply()
   * followed by Vector::sadd and Vector::add.
   */
  template <typename Vector = VectorType>
  class SSPRK3
  {
  public:
    using PostStageHook = std::function<void(Vector &u, double stage_time, double weight)>;

    /// One step: op.apply_stage(t, src, dst, StageUpdate) does a stage.
    /// With a spare vector (of u's layout, its values free to overwrite) the
    /// new state goes to *spare and u keeps the old one (the caller swaps):
    /// the spare holds the rate of the in-place second stage and the last
    /// stage needs none, so the operator keeps no rate vector of its own.
    template <typename Operator>
    void
    step(const Operator      &op,
         Vector              &u,
         const double         t,
         const double         dt,
         const PostStageHook &post_stage,
         Vector              *spare = nullptr)
    {
      if (!initialized)
        {
          u1.reinit(u);
          initialized = true;
        }
      op.apply_stage(t, u, u1, StageUpdate<Vector>{nullptr, 1., 0., dt});
      post_stage(u1, t + dt, dt);
      // u1 = 1/4 u1 + 3/4 u + dt/4 L(u1), in place
      op.apply_stage(t + dt, u1, u1, StageUpdate<Vector>{&u, 0.25, 0.75, 0.25 * dt, spare});
      post_stage(u1, t + 0.5 * dt, 0.25 * dt);
      // u_new = 2/3 u1 + 1/3 u + 2/3 dt L(u1)
      Vector &out = spare ? *spare : u;
      op.apply_stage(t + 0.5 * dt, u1, out,
                     StageUpdate<Vector>{&u, 2. / 3., 1. / 3., 2. / 3. * dt});
      post_stage(out, t + dt, 2. / 3. * dt);
    }

    static constexpr unsigned int n_stages = 3;

    /// bytes of the stage vector (0 before the first step)
    std::size_t
    memory_consumption() const
    {
      return initialized ? u1.memory_consumption() : 0;
    }

  private:
    bool   initialized = false;
    Vector u1;
  };

  /// The explicit Runge-Kutta schemes of Time stepping/scheme.
  enum class TimeScheme
  {
    ssp_rk3,  ///< SSPRK3 below (Shu-Osher), the default
    lsrk_3_3, ///< deal.II's low-storage RK, 3 stages, order 3
    lsrk_5_4, ///< 5 stages, order 4 (Kennedy, Carpenter, Lewis 2000; step-67)
    lsrk_7_4, ///< 7 stages, order 4 (Tselios, Simos 2007)
    lsrk_9_5  ///< 9 stages, order 5 (Kennedy, Carpenter, Lewis 2000)
  };

  /**
   * deal.II's low-storage explicit Runge-Kutta schemes
   * (TimeStepping::LowStorageRungeKutta, their coefficients a, b, c) in the
   * two-register form of step-67: with r = u at the first stage,
   *   k = L(t + c_i dt, r);  r = u + a_i dt k  (i < s);  u = u + b_i dt k,
   * both updates in one pass over the vector. The stage values r (and u at
   * the end) go to the post-stage hook; the scheme is not a convex
   * combination of Euler steps, so the hook may check a stage but must not
   * change it: Solver refuses limiters and stage operations with these
   * schemes (doc/program.md, "Time stepping").
   */
  class LowStorageRK
  {
  public:
    using PostStageHook = std::function<void(VectorType &u, double stage_time, double weight)>;

    explicit LowStorageRK(const TimeScheme scheme)
    {
      using namespace dealii::TimeStepping;
      const runge_kutta_method method =
        scheme == TimeScheme::lsrk_3_3 ? LOW_STORAGE_RK_STAGE3_ORDER3 :
        scheme == TimeScheme::lsrk_5_4 ? LOW_STORAGE_RK_STAGE5_ORDER4 :
        scheme == TimeScheme::lsrk_7_4 ? LOW_STORAGE_RK_STAGE7_ORDER4 :
                                         LOW_STORAGE_RK_STAGE9_ORDER5;
      Assert(scheme != TimeScheme::ssp_rk3, dealii::ExcInternalError());
      LowStorageRungeKutta<VectorType>(method).get_coefficients(a, b, c);
    }

    unsigned int
    n_stages() const
    {
      return b.size();
    }

    /// One step: op.apply(t, src, dst) evaluates L.
    template <typename Operator>
    void
    step(const Operator &op, VectorType &u, const double t, const double dt,
         const PostStageHook &post_stage)
    {
      if (r.size() != u.size())
        {
          r.reinit(u);
          k.reinit(u);
        }
      for (unsigned int i = 0; i < n_stages(); ++i)
        {
          op.apply(t + c[i] * dt, i == 0 ? u : r, k);
          const bool   last = i + 1 == n_stages();
          const double ai = last ? 0. : a[i] * dt, bi = b[i] * dt;
          double      *pu = u.begin(), *pr = r.begin();
          const double *pk = k.begin();
          const unsigned int n = u.locally_owned_size();
          if (!last)
            for (unsigned int j = 0; j < n; ++j)
              {
                pr[j] = pu[j] + ai * pk[j];
                pu[j] += bi * pk[j];
              }
          else
            for (unsigned int j = 0; j < n; ++j)
              pu[j] += bi * pk[j];
          if (last)
            post_stage(u, t + dt, bi);
          else
            post_stage(r, t + c[i + 1] * dt, ai);
        }
    }

    /// bytes of the two stage registers
    std::size_t
    memory_consumption() const
    {
      return r.memory_consumption() + k.memory_consumption();
    }

  private:
    std::vector<double> a, b, c;
    VectorType          r, k;
  };

  /// The forward Euler step u = u + dt L(t, u) (one stage, in place), with
  /// the post-stage hook after it. With a spare vector (as SSPRK3's) the new
  /// state goes to *spare and u keeps the old one (the caller swaps).
  template <typename Vector = VectorType>
  class ForwardEuler
  {
  public:
    using PostStageHook = std::function<void(Vector &u, double stage_time, double weight)>;

    template <typename Operator>
    void
    step(const Operator &op, Vector &u, const double t, const double dt,
         const PostStageHook &post_stage, Vector *spare = nullptr)
    {
      Vector &out = spare ? *spare : u;
      op.apply_stage(t, u, out, StageUpdate<Vector>{nullptr, 1., 0., dt});
      post_stage(out, t + dt, dt);
    }

    static constexpr unsigned int n_stages = 1;
  };
} // namespace granular_dg::dg
