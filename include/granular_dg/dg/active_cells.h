#pragma once

#include <deal.II/lac/la_parallel_vector.h>

#include <granular_dg/base/checkpoint.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace granular_dg::dg
{
  /**
   * The cells of a line of cells (the 1D line engine) that a time step
   * computes, when cells that cannot change are left out (Time stepping/skip
   * tolerance; doc/engine.md, "Skipping quiet cells").
   *
   * A cell is quiet while none of its values has moved by more than
   * tolerance * scale_i (scale_i: the largest |value| of its component i seen
   * so far in any cell, so that a small component such as a decaying
   * velocity is measured against its own size, not against a larger one)
   * from where they were when it last moved more; a cell that moved more is
   * loud. A step computes the cells within `radius` cells of a cell that was
   * loud in the last step (radius: the reach of a whole step, its stages
   * times the reach of one stage, so that a change cannot arrive unseen), and
   * the cells that have not yet been quiet for `patience` steps. Measuring
   * the movement from a reference rather than per step keeps a slow drift
   * (below the tolerance per step, but adding up) from being taken for rest:
   * a cell is left out only if it moved less than the tolerance over the
   * last `patience` steps, while round-off cycles of a few ulps stay quiet.
   * Leaving cells out is sound only when a step repeats the last one: the
   * same time step and an operator that does not depend on time (the scene
   * says so); any other step computes all cells. A cell left out keeps its
   * values in every stage.
   *
   * At rest: the last step was a CFL step of the same size as the one before
   * it and left out every cell. Then a further step of that size would leave
   * out every cell again and change nothing (skip_step() counts it without
   * computing it); a step of another size may change the state (the
   * discrete rest state of a scheme with a stage operation such as the
   * friction projection depends on dt) and computes every cell.
   *
   * Cell c owns the vector entries [c n, (c + 1) n), n = n_components
   * n_modes, component i the n_modes entries from c n + i n_modes (the line
   * engine's numbering). Serial.
   */
  class ActiveCells
  {
  public:
    using VectorType = dealii::LinearAlgebra::distributed::Vector<double>;
    /// cells [first, end)
    using Range = std::pair<unsigned int, unsigned int>;

    /// steps a cell must stay quiet before it is left out
    static constexpr unsigned int patience = 1000;

    ActiveCells(const unsigned int n_cells, const unsigned int n_components,
                const unsigned int n_modes, const unsigned int radius, const bool periodic,
                const double tolerance)
      : n_cells(n_cells)
      , n_components(n_components)
      , n_modes(n_modes)
      , values_per_cell(n_components * n_modes)
      , radius(radius)
      , periodic(periodic)
      , tolerance(tolerance)
      , scale(n_components, 0.)
      , bound(n_components, 0.)
      , loud(n_cells, 1)
      , quiet_steps(n_cells, 0)
      , computed(n_cells, 1)
      , computed_before(n_cells, 1)
    {
      reset();
    }

    /// Forget what is known: the next step computes every cell and takes
    /// its values as the reference (a new, restored or loaded state).
    void
    reset()
    {
      known = false;
      ranges_now.assign(1, {0, n_cells});
      newly_left_out.clear();
      std::fill(computed.begin(), computed.end(), 1);
      std::fill(quiet_steps.begin(), quiet_steps.end(), 0);
    }

    /// Choose the cells of a step of size dt (cfl_step: the CFL step, not
    /// one shortened to land on an output time) from state u.
    void
    begin_step(const double dt, const bool cfl_step, const VectorType &u)
    {
      if (!known)
        {
          reference.assign(u.begin(), u.begin() + u.locally_owned_size());
          std::fill(loud.begin(), loud.end(), 1);
        }
      computed_before.swap(computed);
      if (known && dt == last_dt)
        choose_cells();
      else
        std::fill(computed.begin(), computed.end(), 1);
      last_dt       = dt;
      last_cfl_step = cfl_step;
      make_ranges();
      for (const auto &[first, end] : ranges_now)
        n_computed += end - first;
      n_updates += n_cells;
    }

    /// After the step: which computed cells moved, and for how long the
    /// others have been quiet.
    void
    end_step(const VectorType &u)
    {
      const double *x = u.begin();
      for (const auto &[first, end] : ranges_now)
        for (unsigned int c = first; c < end; ++c)
          for (unsigned int i = 0; i < n_components; ++i)
            {
              const double *xi = x + c * values_per_cell + i * n_modes;
              for (unsigned int k = 0; k < n_modes; ++k)
                scale[i] = std::max(scale[i], std::abs(xi[k]));
            }
      for (unsigned int i = 0; i < n_components; ++i)
        bound[i] = tolerance * scale[i];
      for (unsigned int c = 0; c < n_cells; ++c)
        {
          bool q = true;
          if (computed[c])
            for (unsigned int i = 0; i < n_components; ++i)
              {
                const std::size_t j = std::size_t(c) * values_per_cell + i * n_modes;
                for (unsigned int k = 0; k < n_modes; ++k)
                  q &= std::abs(x[j + k] - reference[j + k]) <= bound[i];
              }
          loud[c] = !q;
          if (q)
            quiet_steps[c] = std::min(quiet_steps[c] + 1, patience);
          else
            {
              quiet_steps[c] = 0;
              std::copy(x + c * values_per_cell, x + (c + 1) * values_per_cell,
                        reference.begin() + c * values_per_cell);
            }
        }
      known = true;
    }

    /// What the next steps depend on, for a checkpoint: a run resumed from it
    /// leaves out the same cells as the uninterrupted run.
    void
    save(ByteWriter &w) const
    {
      w.io(known);
      w.io(last_cfl_step);
      w.io(last_dt);
      w.io(scale);
      w.io(n_computed);
      w.io(n_updates);
      w.io(loud);
      w.io(quiet_steps);
      w.io(reference);
    }

    /// Continue from save(); the first step then sets the values of every
    /// cell it leaves out in the stage vectors, as after a step that
    /// computed all cells.
    void
    load(ByteReader &r)
    {
      r.io(known);
      r.io(last_cfl_step);
      r.io(last_dt);
      r.io(scale);
      r.io(n_computed);
      r.io(n_updates);
      r.io(loud);
      r.io(quiet_steps);
      r.io(reference);
      AssertThrow(loud.size() == n_cells && quiet_steps.size() == n_cells &&
                    scale.size() == n_components &&
                    reference.size() == std::size_t(n_cells) * values_per_cell,
                  dealii::ExcMessage("checkpoint of the skipped cells does not fit the mesh"));
      std::fill(computed.begin(), computed.end(), 1);
      ranges_now.assign(1, {0, n_cells});
      newly_left_out.clear();
    }

    /// The cells of the current step (all of them when it computes all).
    const std::vector<Range> &
    ranges() const
    {
      return ranges_now;
    }

    /// Cells the current step leaves out that the last step computed: their
    /// values in a stage's destination vector must be set to their state.
    const std::vector<Range> &
    newly_left_out_ranges() const
    {
      return newly_left_out;
    }

    bool
    computes(const unsigned int cell) const
    {
      return computed[cell];
    }

    /// After a CFL step that left out every cell (it had the size of the
    /// step before it, or it would have computed all): a step of that size
    /// from this state leaves out every cell again.
    bool
    at_rest() const
    {
      return known && last_cfl_step && ranges_now.empty();
    }

    /// Count a step of size dt that needs no computation: at rest, and dt is
    /// the size of the last step (a step that would leave out every cell and
    /// keep every value; what is known stays as it is). Returns false, and
    /// counts nothing, for any other step: that one must be computed.
    bool
    skip_step(const double dt)
    {
      if (!at_rest() || dt != last_dt)
        return false;
      n_updates += n_cells;
      return true;
    }

    /// Cell updates left out over all steps so far, of all cell updates (a
    /// step skip_step() counted left out every cell).
    double
    skipped_fraction() const
    {
      return n_updates > 0 ? 1. - n_computed / n_updates : 0.;
    }

  private:
    /// computed: the cells within radius of a loud cell, and those not yet
    /// quiet for patience steps
    void
    choose_cells()
    {
      const int n = n_cells, r = radius;
      for (int c = 0; c < n; ++c)
        computed[c] = quiet_steps[c] < patience;
      for (int c = 0; c < n; ++c)
        if (loud[c])
          for (int d = -r; d <= r; ++d)
            {
              int k = c + d;
              if (periodic)
                k = ((k % n) + n) % n;
              if (k >= 0 && k < n)
                computed[k] = 1;
            }
    }

    void
    make_ranges()
    {
      ranges_now.clear();
      newly_left_out.clear();
      for (unsigned int c = 0; c < n_cells; ++c)
        {
          if (computed[c] && (c == 0 || !computed[c - 1]))
            ranges_now.push_back({c, c + 1});
          else if (computed[c])
            ++ranges_now.back().second;
          const bool newly = !computed[c] && computed_before[c];
          if (newly && (newly_left_out.empty() || newly_left_out.back().second != c))
            newly_left_out.push_back({c, c + 1});
          else if (newly)
            ++newly_left_out.back().second;
        }
    }

    const unsigned int         n_cells, n_components, n_modes, values_per_cell, radius;
    const bool                 periodic;
    const double               tolerance;
    /// per component: the largest |value| seen so far, and tolerance times it
    std::vector<double>        scale, bound;
    std::vector<unsigned char> loud;
    std::vector<unsigned int>  quiet_steps;
    std::vector<unsigned char> computed, computed_before;
    /// per cell, its values when it was last loud
    std::vector<double>        reference;
    std::vector<Range>         ranges_now, newly_left_out;
    bool                       known = false, last_cfl_step = false;
    double                     last_dt = 0;
    double                     n_computed = 0, n_updates = 0;
  };

  /// f(first, end) for the ranges of cells a step computes: all n_cells
  /// without active cells.
  template <typename F>
  void
  for_active_ranges(const ActiveCells *active, const unsigned int n_cells, const F &f)
  {
    if (!active)
      f(0u, n_cells);
    else
      for (const auto &[first, end] : active->ranges())
        f(first, end);
  }
} // namespace granular_dg::dg
