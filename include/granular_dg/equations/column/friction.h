#pragma once

#include <deal.II/base/polynomial.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <granular_dg/dg/modal_layout.h>
#include <granular_dg/dg/scene_data.h>
#include <granular_dg/equations/column/system.h>

#include <cmath>
#include <optional>
#include <vector>

namespace granular_dg::column
{
  /**
   * The implicit friction step of Coffey & Gremaud (section 3, steps 1-4), applied per
   * cell after the explicit part of every Runge-Kutta stage. With the
   * orthonormal Legendre modes v_l of the velocity and
   *   R_l = int_0^1 sigma(u_h(xi)) L_l(xi) dxi  (R_0 >= 0),
   * the stage reads v_l = v*_l - w s R_l with s in sgn(v_0) and w the stage's
   * effective time step (SSP-RK3 in Shu-Osher form: dt, dt/4, 2dt/3; the
   * paper's printed weights dt, dt/2, dt do not match its explicit part, and a
   * stuck state would not stay stuck). The strain is already updated (step 1).
   * Assume the cell stops (step 2): s = v*_0 / (w R_0). If |s| <= 1 the
   * friction holds it: v = 0 in the whole cell. Otherwise s = sgn(v*_0) and
   * v_l = v*_l - w s R_l, which keeps the sign of v_0 (step 3). Cells without
   * load (R_0 = 0) feel no friction. The limiter comes after (step 4).
   */
  class FrictionProjection
  {
  public:
    enum class CellState : unsigned char
    {
      unloaded, ///< R_0 = 0: no friction
      stuck,    ///< held at rest, |s| <= 1
      sliding   ///< |s| = 1
    };

    FrictionProjection(const System &system, const dg::ModalLayout<1> &layout)
      : system(system)
      , layout(layout)
      , n_modes(layout.n_modes())
      , multiplier(layout.n_owned(), 0.)
      , state(layout.n_owned(), CellState::unloaded)
    {
      AssertThrow(n_modes <= max_modes, ExcMessage("degrees 0-4"));
      // the operator's quadrature (p + 2 Gauss points)
      const QGauss<1> q(n_modes + 1);
      weights = q.get_weights();
      basis.assign(q.size() * max_modes, 0.);
      for (unsigned int i = 0; i < q.size(); ++i)
        {
          const auto L = dg::legendre_values(n_modes, q.point(i)[0]);
          for (unsigned int k = 0; k < n_modes; ++k)
            basis[i * max_modes + k] = L[k];
        }
      for (unsigned int c = 0; c < layout.n_owned(); ++c)
        for (unsigned int k = 0; k < n_modes; ++k)
          {
            AssertThrow(layout.index(c, 0, k) == layout.index(c, 0, 0) + k * mode_stride() &&
                          layout.index(c, 1, k) == layout.index(c, 1, 0) + k * mode_stride(),
                        ExcMessage("FrictionProjection expects affine mode indices"));
          }
    }

    /// R_l of a cell from its strain modes u[k * stride] (Number: double,
    /// or a SIMD batch of cells).
    template <unsigned int nm, typename Number>
    void
    load_modes(const Number *u, const std::size_t stride, Number *R) const
    {
      for (unsigned int k = 0; k < nm; ++k)
        R[k] = 0.;
      // the operator's nm + 1 Gauss points
      for (unsigned int i = 0; i < nm + 1; ++i)
        {
          const double *phi = &basis[i * max_modes];
          Number        ui  = 0.;
          for (unsigned int k = 0; k < nm; ++k)
            ui += u[k * stride] * phi[k];
          const Number ws = weights[i] * system.stress(ui);
          for (unsigned int k = 0; k < nm; ++k)
            R[k] += ws * phi[k];
        }
    }

    /// Apply the step with weight w to the stage vector U (owned cells; with
    /// active cells those of the current step).
    void
    apply(LinearAlgebra::distributed::Vector<double> &U, const double w,
          const dg::ActiveCells *active = nullptr)
    {
      dg::with_n_modes(n_modes, [&](auto nm) {
        const auto range = [&](const unsigned int first, const unsigned int end) {
          apply_impl<decltype(nm)::value>(U, w, first, end);
        };
        dg::for_active_ranges(active, layout.n_owned(), range);
      });
    }

    /// Keep the cells the friction holds at rest: a limiter that mixes
    /// components (characteristic limiting) must not set them in motion.
    void
    keep_stuck_at_rest(LinearAlgebra::distributed::Vector<double> &U,
                       const dg::ActiveCells *active = nullptr) const
    {
      const auto range = [&](const unsigned int first, const unsigned int end) {
        for (unsigned int c = first; c < end; ++c)
          if (state[c] == CellState::stuck)
            for (unsigned int k = 0; k < n_modes; ++k)
              U.local_element(layout.index(c, 1, k)) = 0.;
      };
      dg::for_active_ranges(active, layout.n_owned(), range);
    }

    /// sgn(v) of the last step per owned cell (the friction multiplier)
    const std::vector<double> &
    multipliers() const
    {
      return multiplier;
    }

    const std::vector<CellState> &
    states() const
    {
      return state;
    }

    /// The multipliers and states, for a checkpoint (a run that skips quiet
    /// cells keeps those of the cells it leaves out).
    template <typename Archive>
    void
    state_io(Archive &ar)
    {
      ar.io(multiplier);
      ar.io(state);
    }

  private:
    static constexpr unsigned int max_modes = 5;

    std::size_t
    mode_stride() const
    {
      return n_modes > 1 ? layout.index(0, 0, 1) - layout.index(0, 0, 0) : 1;
    }

    /// The cells [first, end): R_l in SIMD batches of W cells (the
    /// stress at the Gauss points is most of the work), then cell by cell
    /// the projection itself.
    template <unsigned int nm>
    void
    apply_impl(LinearAlgebra::distributed::Vector<double> &U, const double w,
               const unsigned int first, const unsigned int end)
    {
      using VA                   = VectorizedArray<double>;
      constexpr unsigned int W   = VA::size();
      const std::size_t stride   = mode_stride();
      double           *data     = U.begin();
      unsigned int      c        = first;
      if constexpr (W > 1)
        for (; c + W <= end; c += W)
          {
            unsigned int offsets[W];
            for (unsigned int l = 0; l < W; ++l)
              offsets[l] = layout.index(c + l, 0, 0);
            VA u[nm], R[nm];
            for (unsigned int k = 0; k < nm; ++k)
              u[k].gather(data + k * stride, offsets);
            load_modes<nm>(u, 1, R);
            double R_lanes[nm][W];
            for (unsigned int k = 0; k < nm; ++k)
              R[k].store(R_lanes[k]);
            for (unsigned int l = 0; l < W; ++l)
              {
                double R_cell[nm];
                for (unsigned int k = 0; k < nm; ++k)
                  R_cell[k] = R_lanes[k][l];
                project<nm>(c + l, data + layout.index(c + l, 1, 0), stride, w, R_cell);
              }
          }
      for (; c < end; ++c)
        {
          double R[nm];
          load_modes<nm>(data + layout.index(c, 0, 0), stride, R);
          project<nm>(c, data + layout.index(c, 1, 0), stride, w, R);
        }
    }

    /// The projection of cell c with velocity modes v[k * stride] and R_l.
    template <unsigned int nm>
    void
    project(const unsigned int c, double *v, const std::size_t stride, const double w,
            const double *R)
    {
      if (!(R[0] > 0.))
        {
          state[c]      = CellState::unloaded;
          multiplier[c] = v[0] > 0 ? 1. : (v[0] < 0 ? -1. : 0.);
          return;
        }
      const double s = v[0] / (w * R[0]);
      if (std::abs(s) <= 1.)
        {
          state[c]      = CellState::stuck;
          multiplier[c] = s;
          for (unsigned int k = 0; k < nm; ++k)
            v[k * stride] = 0.;
        }
      else
        {
          const double sgn = s > 0 ? 1. : -1.;
          state[c]         = CellState::sliding;
          multiplier[c]    = sgn;
          for (unsigned int k = 0; k < nm; ++k)
            v[k * stride] -= w * sgn * R[k];
        }
    }

    const System              system;
    const dg::ModalLayout<1> &layout;
    const unsigned int        n_modes;
    std::vector<double>       weights, basis;
    std::vector<double>       multiplier;
    std::vector<CellState>    state;
  };

  /**
   * The friction projection as the stage operation of the column's runs
   * (with Physics/friction = projection; otherwise it does nothing): after the
   * explicit part of every stage, with the stage's effective time step (or,
   * for comparison, the paper's printed weights dt, dt/2, dt), and after the
   * limiter v = 0 again in the cells the friction holds.
   */
  class FrictionHooks : public dg::SceneHooks<1>
  {
  public:
    FrictionHooks(const System &system, const bool printed_weights)
      : system(system)
      , printed_weights(printed_weights)
    {}

    void
    initialize(const DoFHandler<1> &, const Mapping<1> &,
               const dg::ModalLayout<1> &layout) override
    {
      projection.emplace(system, layout);
    }

    void
    post_stage(dg::VectorType &U, double, const double weight) override
    {
      if (!implicit())
        return;
      const double printed[3] = {1., 2., 1.5};
      const double w          = printed_weights ? weight * printed[stage % 3] : weight;
      ++stage;
      projection->apply(U, w, active_cells());
    }

    void
    post_limiter(dg::VectorType &U, double) override
    {
      if (implicit())
        projection->keep_stuck_at_rest(U, active_cells());
    }

    /// the projection acts on each cell alone
    bool
    honours_active_cells() const override
    {
      return true;
    }

    std::string
    stage_operation() const override
    {
      return implicit() ? "the friction projection of every stage" : "";
    }

    void
    save(ByteWriter &w) override
    {
      w.io(stage);
      projection->state_io(w);
    }

    void
    load(ByteReader &r) override
    {
      r.io(stage);
      projection->state_io(r);
    }

    /// whether the friction is the implicit projection
    bool
    implicit() const
    {
      return system.parameters().friction == FrictionTreatment::projection;
    }

    const FrictionProjection &
    state() const
    {
      return *projection;
    }

  private:
    const System                      system;
    const bool                        printed_weights;
    std::optional<FrictionProjection> projection;
    unsigned long                     stage = 0;
  };
} // namespace granular_dg::column
