#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <granular_dg/dg/active_cells.h>
#include <granular_dg/dg/time_integrator.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

namespace granular_dg::dg
{
  using namespace dealii;
  using VectorType = LinearAlgebra::distributed::Vector<double>;

  /// Where and why a state left the admissible set (a point of an operator's
  /// quadrature).
  struct AdmissibilityReport
  {
    bool                ok = true;
    Point<3>            position; ///< first inadmissible quadrature point
    std::vector<double> state;
    std::string         reason;
  };

  /// Collective: every rank gets the report of the lowest rank whose
  /// report is not ok (rank 0 prints it), or its own when all are ok.
  AdmissibilityReport
  first_failure(AdmissibilityReport report, MPI_Comm comm);

  /// The operator behind a run: MatrixFree's DGOperator (any dim, MPI), or
  /// the lean LineOperator (1D, serial); automatic takes the line engine in
  /// serial 1D.
  enum class Engine
  {
    automatic,
    matrix_free,
    line
  };

  /**
   * What the solver needs of a DG operator, whichever engine computes it:
   * the right-hand side M^{-1} R(t, u), a fused Runge-Kutta stage, the
   * largest wave speed over the cell size (the CFL step) and the scan of the
   * admissible set. Both engines discretise alike (modal FE_DGQLegendre,
   * p + 2 Gauss points, the Physics' numerical flux and boundary states);
   * projection, integrals and errors are shared (CellQuadrature).
   */
  template <int dim>
  class Operator
  {
  public:
    virtual ~Operator() = default;

    virtual void
    reinit(const Mapping<dim> &mapping, const DoFHandler<dim> &dof_handler) = 0;

    virtual void
    initialize_vector(VectorType &vector) const = 0;

    /// dst = M^{-1} R(t, src)
    virtual void
    apply(double time, const VectorType &src, VectorType &dst) const = 0;

    /// One Runge-Kutta stage (StageUpdate; dst may be src or s.old):
    /// bit for bit apply() followed by deal.II's vector operations. This
    /// default does exactly that, with the rate in dst itself when dst is
    /// neither src nor s.old, else in s.scratch or a vector of its own; an
    /// engine may fuse it into its cell loop.
    virtual void
    apply_stage(const double time, const VectorType &src, VectorType &dst,
                const StageUpdate<> &s) const
    {
      VectorType &k = rate_vector(src, dst, s);
      apply(time, src, k);
      update_stage(src, dst, k, s, 0, src.locally_owned_size());
    }

    /// max over the quadrature points of max(lambda(U), min_speed) *
    /// sum_d |row_d(J^{-1})| (collective): the stable step is CFL / this.
    virtual double
    max_speed_over_h(const VectorType &solution, double min_speed) const = 0;

    /// The first inadmissible quadrature point (Physics::is_admissible /
    /// admissibility_violation), collective (first_failure()).
    virtual AdmissibilityReport
    check_admissibility(const VectorType &solution) const = 0;

    /// "matrix_free" or "line"
    virtual std::string
    engine_name() const = 0;

    /// Bytes this operator holds on this rank: the engine's data
    /// (MatrixFree's memory_consumption(), or the line engine's tables) and
    /// the scratch vector of apply_stage().
    std::size_t
    memory_consumption() const
    {
      return engine_memory() + rate.memory_consumption();
    }

    /// the engine's part of memory_consumption()
    virtual std::size_t
    engine_memory() const = 0;

    /// Compute only the cells of active's current step from now on (null:
    /// all cells again): apply, apply_stage and the admissibility scan work
    /// on those; apply_stage sets a destination's values of the cells just
    /// left out to the source's; the wave-speed scan refreshes the cells of
    /// the last step. False if the engine cannot (then nothing changes).
    virtual bool
    restrict_to(const ActiveCells * /*active*/)
    {
      return false;
    }

    /// How the batches found at rest by find_cells_at_rest() are used: not
    /// at all, by the wave-speed scan only, or by a whole step (apply,
    /// apply_stage and the admissibility scan leave out the batches out of
    /// reach, and the step is counted in cell_updates_left_out()).
    enum class RestUse
    {
      off,
      wave_speed_scan,
      step
    };

    /// Leave out the cells at rest and out of reach of the loud ones
    /// (CellsAtRest: tolerance, reach in face neighbours). False if the
    /// engine cannot (then nothing changes).
    virtual bool
    skip_cells_at_rest(const double /*tolerance*/, const unsigned int /*reach*/)
    {
      return false;
    }

    /// Find the cells of u at rest and the batches a step from u computes.
    virtual void
    find_cells_at_rest(const VectorType & /*u*/)
    {}

    virtual void
    use_cells_at_rest(const RestUse /*use*/) const
    {}

    /// Cell updates left out and all cell updates of the steps so far, summed
    /// over ranks (collective; zeros when nothing is left out).
    virtual std::pair<double, double>
    cell_updates_left_out() const
    {
      return {0., 0.};
    }

    /// Continue the counts of cell_updates_left_out() from a checkpoint
    /// (the sums over the ranks; collective).
    virtual void
    set_cell_updates_left_out(const std::pair<double, double> & /*counts*/)
    {}

    /// Blend the DG rate with a first-order finite-volume rate on p + 1
    /// subcells, by a factor of at most alpha_max from the modal-energy
    /// indicator (SubcellBlending; Limiter/subcell blending). False if the
    /// engine cannot (then nothing changes).
    virtual bool
    set_subcell_blending(const double /*alpha_max*/)
    {
      return false;
    }

    /// The blending factor of every owned cell in the last apply() (empty:
    /// no blending).
    virtual const std::vector<double> &
    blending_factors() const
    {
      static const std::vector<double> none;
      return none;
    }

    /// The number of owned cells with a blending factor > 0 in the last
    /// apply() (the timeseries' blended_cells).
    unsigned int
    n_blended_cells() const
    {
      const auto &alpha = blending_factors();
      return std::count_if(alpha.begin(), alpha.end(), [](const double a) { return a > 0; });
    }

  protected:
    /// Where apply_stage() puts the rate: dst itself when dst is neither src
    /// nor s.old, else s.scratch or a vector of the operator's own.
    VectorType &
    rate_vector(const VectorType &src, VectorType &dst, const StageUpdate<> &s) const
    {
      if (&dst != &src && &dst != s.old)
        return dst;
      if (s.scratch == nullptr && rate.size() != src.size())
        rate.reinit(src);
      return s.scratch ? *s.scratch : rate;
    }

    /// The stage's vector operation on the locally owned entries [begin, end):
    /// dst = (alpha src + beta old) + gamma k, or src + gamma k.
    static void
    update_stage(const VectorType &src, VectorType &dst, const VectorType &k,
                 const StageUpdate<> &s, const unsigned int begin, const unsigned int end)
    {
      const double *u = src.begin(), *r = k.begin();
      double       *out = dst.begin();
      if (s.old)
        for (unsigned int i = begin; i < end; ++i)
          out[i] = stage_value(s.alpha, s.beta, s.gamma, u[i], s.old->begin()[i], r[i]);
      else
        for (unsigned int i = begin; i < end; ++i)
          out[i] = stage_value(s.gamma, u[i], r[i]);
    }

  private:
    mutable VectorType rate;
  };
} // namespace granular_dg::dg
