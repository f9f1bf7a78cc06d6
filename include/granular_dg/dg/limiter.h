#pragma once

#include <deal.II/base/tensor.h>
#include <deal.II/base/vectorization.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <granular_dg/dg/active_cells.h>
#include <granular_dg/dg/boundary.h>
#include <granular_dg/dg/modal_layout.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

namespace granular_dg::dg
{
  using namespace dealii;

  /// What a boundary face tells the limiter (optional Physics::limiter_boundary()).
  template <int n_components>
  struct LimiterBoundary
  {
    Tensor<1, n_components>         difference; ///< ghost average - cell average
    std::array<bool, n_components>  known;      ///< false: use the other side's difference
  };

  /// Which cells the limiter examines: every cell (the TVB test alone), or
  /// the cells a smoothness indicator flags (Limiter/indicator), or those
  /// and their face neighbours (modal_energy_neighbours).
  enum class TroubleIndicator
  {
    everywhere,
    modal_energy,
    kxrcf,
    modal_energy_neighbours
  };

  /// The threshold of the modal-energy indicator for degree p (Hennemann,
  /// Winters & Gassner 2021, eq. (41); Trixi.jl's IndicatorHennemannGassner):
  /// T(p) = 0.5 10^(-1.8 (p + 1)^(1/4)).
  inline double
  modal_energy_threshold(const unsigned int degree)
  {
    return 0.5 * std::pow(10., -1.8 * std::pow(degree + 1., 0.25));
  }

  /// A cell whose indicator variable is below this fraction of the variable's
  /// largest cell mean holds round-off (ahead of a front), not a shock: the
  /// floor of the modal-energy indicator and of subcell blending.
  inline constexpr double indicator_floor_fraction = 1e-10;

  /// The factor by which modes q[0..n) whose sum of squares is total are
  /// scaled before squaring: 1 / their largest magnitude where total left
  /// [1e-280, 1e280] (it may have overflowed or lost digits to underflow)
  /// and the modes are finite and not all 0, else 1. A share of squares
  /// computed at that scale does not depend on the scale of q.
  inline double
  square_safe_scale(const double *q, const unsigned int n, const double total)
  {
    if (total > 1e-280 && total < 1e280)
      return 1.;
    double largest = 0;
    bool   finite  = true;
    for (unsigned int k = 0; k < n; ++k)
      {
        finite  = finite && std::isfinite(q[k]);
        largest = std::max(largest, std::abs(q[k]));
      }
    return finite && largest > 0 ? 1. / largest : 1.;
  }

  /// The modal-energy indicator's measure of one field of a cell (its modes
  /// q, n1 per direction, m = k_0 + n1 k_1): the share e_p / sum_k e_k of the
  /// highest degree p = n1 - 1 in the energy by degree (in 2D a mode's degree
  /// is the larger of its two), or -1 where the energy is not above floor^2
  /// (round-off ahead of a front is not a shock). Used by the limiter's
  /// modal_energy indicator and by subcell blending in 2D.
  /// (At square_safe_scale(): the share does not depend on the scale.)
  template <int dim, unsigned int n1>
  double
  highest_mode_energy_share(const double *q, const double floor)
  {
    constexpr unsigned int n_modes = dim == 1 ? n1 : n1 * n1;
    const auto share = [&](const double scale) {
      std::array<double, n1> level{};
      for (unsigned int m = 0; m < n_modes; ++m)
        level[std::max(m % n1, m / n1)] += (q[m] * scale) * (q[m] * scale);
      double total = 0;
      for (const double e : level)
        total += e;
      const double f = floor * scale;
      return std::pair(total > f * f ? level[n1 - 1] / total : -1., total);
    };
    const auto [result, total] = share(1.);
    const double scale         = square_safe_scale(q, n_modes, total);
    return scale == 1. ? result : share(scale).first;
  }

  /// What the limiter limits: nothing, the conserved variables, the
  /// characteristic fields, or variables the physics names (its
  /// limiting_variables(), called by the name the physics gives them).
  enum class LimiterType
  {
    none,
    componentwise,
    characteristic,
    physics_variables
  };

  /**
   * TVB minmod limiter on the Legendre modes of FE_DGQLegendre (Cockburn &
   * Shu). Per direction d, the cell's 1D expansion through the cell centre
   * gives the jumps to its face values, u(face+) - ubar and ubar - u(face-);
   * if minmod_TVB of either against the neighbour differences of averages
   * changes it, the cell is troubled: its modes other than the average are
   * replaced by the limited linear slope per direction. Cell averages (and so
   * conservation) are never touched. In characteristic mode the jumps are
   * transformed with the left eigenvectors of the flux Jacobian in direction
   * d at the cell average (with the cell's coefficients), limited field by
   * field, and transformed back.
   *
   * In physics_variables mode the limiter works on variables W(U, a) that
   * the physics names (Physics::limiting_variables(U, a) and its Jacobian
   * limiting_jacobian(U, a)), e.g. variables that are continuous across
   * material interfaces where the conserved ones jump. The neighbour differences are
   * W(avg_nb, a_nb) - W(avg, a) (each cell with its own material), the slopes
   * are mapped with the Jacobian at the cell average, and the limited slopes
   * mapped back.
   *
   * At a boundary face the neighbour average is the exterior state the
   * physics builds from the cell average (boundary_state() with the data at
   * the face centre, e.g. the mirror state of a symmetry line); at an outflow
   * boundary, whose exterior state is the interior one, the missing
   * difference is replaced by the one on the other side instead, so that the
   * boundary cell keeps its slope.
   *
   * A physics may refine this with an optional member
   *   std::optional<LimiterBoundary<n_components>>
   *   limiter_boundary(kind, avg, face_value, n, g, a,
   *                    const Tensor<2, n_components> *L) const;
   * (face_value the cell's trace at the face, n the outward normal of the
   * face, L the left eigenvectors the limiter works with, nullptr in
   * componentwise mode): the difference ghost - avg
   * across the face in the limiter's variables and, per field, whether the
   * boundary determines it (a field it does not determine uses the
   * difference on the other side, as at an outflow boundary). std::nullopt
   * keeps the default for that face.
   *
   * With the modal_energy indicator (set_indicator()) only the cells whose
   * indicator variable (the component Physics::indicator_component) is not
   * smooth go through the TVB test: with e_k the energy of the Legendre
   * modes of degree k (in 2D: of largest directional degree k) of that
   * component, the cell is flagged when the top modes' share
   * E = e_p / sum_k e_k exceeds the threshold (the modal decay of Persson &
   * Peraire 2006; by default the threshold T(p) of Hennemann et al. 2021).
   * A smooth function's modes decay fast and E stays small; a jump inside
   * the cell puts a share of O(1/p) of the energy into the top modes. Cells
   * whose indicator variable is below 1e-10 of its largest cell mean (the
   * round-off ahead of a front) are not flagged. The
   * mean counts in the sum: a sine crossing zero is not flagged for its
   * small mean (Trixi's second ratio, e_{p-1} / sum_{k<p} e_k, would be,
   * for variables that change sign).
   *
   * The mean also makes E depend on the level of the variable: a cell is
   * flagged when its top mode exceeds sqrt(T) of its own level, so of the
   * cells of a shock from 0 up to a level a only the one at its foot (mean
   * near 0) is, and the cells above it (means near a) may overshoot. With
   * modal_energy_neighbours the limiter examines the cells modal_energy
   * flags and their face neighbours (as subcell blending spreads its factor
   * to the neighbours). The flags of all cells, ghost neighbours included,
   * are computed from the unlimited state first.
   *
   * With the kxrcf indicator (Krivodonova, Xin, Remacle, Chevaugeon &
   * Flaherty 2004) a cell is flagged when the jumps of its indicator
   * variable across its faces are large for a smooth solution:
   *   I = sum_f |[q]_f| |f| / (h^((p+1)/2) |dK| max(|q|_K, floor)) > T,
   * [q]_f the jump of the face mean of q between the cell and its
   * neighbour, h half the cell's diagonal, |q|_K the largest of |mean| and
   * |face means|, T = 1 by default. KXRCF sum over the inflow faces, where
   * the jump of a smooth solution is O(h^(p+1)) against O(1) at a shock; the
   * systems here carry waves both ways, so every face is an inflow face of
   * some family and all faces are summed. The jumps are those of the
   * indicator component of the physics' limiting variables if it has them
   * (the stress of the layered strip, continuous across material interfaces
   * where the strain jumps), else of the indicator variable. The flags are
   * computed from the unlimited state before any cell is limited.
   */
  template <int dim, typename Physics>
  class ModalLimiter
  {
  public:
    static constexpr unsigned int n_components = Physics::n_components;
    using VectorType = LinearAlgebra::distributed::Vector<double>;

    ModalLimiter(const Physics &physics, LimiterType type, double tvb_M,
                 BoundaryMap<dim> boundary = {});

    /// Index tables for the vectors of the run (their partitioner).
    void
    reinit(const DoFHandler<dim> &dof_handler, const VectorType &vector);

    /// Index tables by global DoF index: for serial runs, where local and
    /// global indices coincide.
    void
    reinit(const DoFHandler<dim> &dof_handler);

    /// Limit in place at time t (for boundary data); returns the number of
    /// troubled (modified) cells on this rank. With active cells, only the
    /// cells of their current step (the others keep their flags).
    unsigned int
    apply(VectorType &solution, double t = 0., const ActiveCells *active = nullptr) const;

    /// Examine only the cells the indicator flags (threshold 0: the
    /// automatic modal_energy_threshold() of the degree, 1 for kxrcf), and
    /// their neighbours with modal_energy_neighbours.
    void
    set_indicator(TroubleIndicator indicator, double threshold = 0.);

    /// Cells the limiter examined in the last apply(): those the indicator
    /// flagged (and their neighbours with modal_energy_neighbours; all
    /// cells with TroubleIndicator::everywhere), on this rank.
    unsigned int
    n_flagged() const
    {
      return flagged;
    }

    /// Troubled flags of the last apply(), one per locally owned active cell
    /// in the order of dof_handler.active_cell_iterators().
    const std::vector<unsigned char> &
    troubled_cells() const
    {
      return troubled;
    }
    /// Set the flags (from a checkpoint: with skipped cells, the flags of
    /// cells a step leaves out are kept from when they were computed).
    void
    set_troubled_cells(const std::vector<unsigned char> &flags) const
    {
      troubled = flags;
    }

    /// Run the 1D TVB test in SIMD batches where it can (the default), or
    /// cell by cell (to compare the two in tests).
    void
    set_simd_batches(const bool on)
    {
      simd_batches = on;
    }

    LimiterType
    get_type() const
    {
      return type;
    }

    const ModalLayout<dim> &
    layout() const
    {
      return cells;
    }

    /// bytes of the cell and face tables, the ghosted copy and the flags
    std::size_t
    memory_consumption() const
    {
      return cells.memory_consumption() + coefficients.capacity() * sizeof(coefficients[0]) +
             faces.capacity() * sizeof(Face) + base.capacity() * sizeof(std::size_t) +
             troubled.capacity() + examined.capacity() + modal_flags.capacity() +
             limiting_values.capacity() * sizeof(State);
    }

  private:
    using State = Tensor<1, n_components>;

    /// What limits a cell across one of its faces: the neighbour, or at a
    /// boundary the condition there (if the map has one) and the face centre.
    struct Face
    {
      int                     neighbor = -1;
      bool                    has_condition = false;
      BoundaryCondition<dim>  condition;
      Point<dim>              center;
    };

    /// The tables of apply(): faces, the first vector entry of every cell.
    void
    build_tables();

    using Coefficients = std::array<double, Physics::n_coefficients>;

    /// What limits a cell in one direction, in the variables the limiter
    /// works on: the jumps of the cell's expansion to its two faces, its
    /// slope, the neighbour differences (dp: ahead, dm: behind), the maps
    /// back to the conserved variables and M h^2 (Number: double, or a SIMD
    /// batch of cells in the 1D limiter).
    template <typename Number>
    struct DirectionOf
    {
      Tensor<1, n_components, Number> jump_p, jump_m, slope, dp, dm;
      Tensor<2, n_components, Number> R, J;
      double                          Mh2 = 0;
    };
    using Direction = DirectionOf<double>;

    using VA = VectorizedArray<double>;
    /// cells per SIMD batch of the 1D limiter (limit_batch())
    static constexpr unsigned int batch_width = VA::size();

    /// The jumps to the faces and the slope of the modes x (direction
    /// stride apart, components n_modes apart) into r.
    template <unsigned int n1, typename Number>
    inline DEAL_II_ALWAYS_INLINE void
    modal_jumps(const Number *x, unsigned int stride, DirectionOf<Number> &r) const;

    /// The jumps, the slope and the differences dp, dm of r into the
    /// variables the limiter works on, at the cell average avg with
    /// coefficients a in direction d (characteristic: L the left
    /// eigenvectors, r.R the right ones; physics_variables: r.J).
    template <typename Number>
    inline DEAL_II_ALWAYS_INLINE void
    to_limiter_variables(const Tensor<1, n_components, Number>        &avg,
                         const std::array<Number, Physics::n_coefficients> &a, int d,
                         DirectionOf<Number> &r, Tensor<1, n_components, Number> &dp,
                         Tensor<1, n_components, Number> &dm,
                         Tensor<2, n_components, Number> &L) const;

    /// Whether the TVB test leaves the jumps of direction r unchanged in
    /// every field (limit_batch() runs the same test lane by lane).
    static bool
    passes_tvb(const Direction &r);

    /// The troubled cell with modes x: its modes other than the average
    /// replaced by the limited slopes of dir (per direction).
    template <unsigned int n1>
    void
    replace_modes(const std::array<Direction, dim> &dir, double *x) const;

    /// Lane l of a batch's direction.
    static void
    extract_lane(const DirectionOf<VA> &r, unsigned int l, Direction &lane);

    /// 1D, every cell examined: whether the owned cells i .. i + W - 1 can
    /// go through limit_batch() together.
    bool
    batch_fits(unsigned int i, unsigned int end) const;

    /// limit_cell() of the owned interior cells i .. i + W - 1 of a 1D mesh
    /// in one SIMD batch: the directions of all lanes at once, then the TVB
    /// test and the new modes of each troubled lane.
    template <unsigned int n1>
    void
    limit_batch(unsigned int i, double *u_data) const;

    /// apply() with n1 = degree + 1 modes per direction
    template <unsigned int n1>
    unsigned int
    apply_impl(VectorType &u, double t, const ActiveCells *active) const;

    /// Whether the modal-energy indicator flags the cell with modes x.
    template <unsigned int n1>
    bool
    indicated(const double *x) const;

    /// Whether the KXRCF indicator flags owned cell i (from the unlimited
    /// modes of the cell and its neighbours).
    template <unsigned int n1>
    bool
    kxrcf_indicated(unsigned int i) const;

    /// The variable whose jumps KXRCF measures, of state U in cell: the
    /// indicator component of the physics' limiting variables if it has
    /// them (continuous across material interfaces), else of U.
    double
    jump_variable(const State &U, unsigned int cell) const;

    /// Limit the modes x of owned cell i; true if it was troubled.
    template <unsigned int n1>
    bool
    limit_cell(unsigned int i, double *x) const;

    /// The limiter's view of owned cell i (modes x, average avg) in
    /// direction d.
    template <unsigned int n1>
    Direction
    analyse(unsigned int i, int d, const double *x, const State &avg) const;

    /// The average of cell (owned or ghost) of the current apply()
    State
    average(unsigned int cell) const;

    /// The boundary data of a face, at its centre.
    State
    boundary_data(const Face &face) const;

    /// The neighbour average across face f of a cell with average avg and
    /// coefficients a (and the neighbour's coefficients); false at an
    /// outflow boundary (no neighbour to limit against).
    bool
    neighbor_average(const Face &face, unsigned int f, const State &avg, const Coefficients &a,
                     State &result, const Coefficients *&a_nb) const;

    const Physics    physics;
    LimiterType      type;
    double           M;
    BoundaryMap<dim> boundary;
    ModalLayout<dim> cells;
    std::vector<std::array<double, Physics::n_coefficients>> coefficients;
    /// per owned cell and face (2 dim per cell)
    std::vector<Face>        faces;
    /// index(cell, 0, 0) of every cell (owned and ghost neighbours): the
    /// modes of a cell are base + component * n_modes() + mode
    std::vector<std::size_t> base;

    /// L_k(0) and L_k(1)
    std::vector<double> at_0, at_1;
    /// 1D, per owned cell: both neighbours are cells (limit_batch())
    std::vector<unsigned char> interior;
    /// whether the physics has the SIMD versions limit_batch() needs
    bool batchable    = false;
    bool simd_batches = true;

    TroubleIndicator indicator           = TroubleIndicator::everywhere;
    double           indicator_threshold = 0.;
    /// cells whose indicator variable is below this size are not flagged
    mutable double   indicator_floor = 0.;

    mutable std::vector<unsigned char> troubled;
    /// kxrcf and modal_energy_neighbours: whether the current apply()
    /// examines owned cell i, decided before any cell is limited
    mutable std::vector<unsigned char> examined;
    /// modal_energy_neighbours: the modal_energy flag of every cell (owned
    /// and ghost) in the current apply()
    mutable std::vector<unsigned char> modal_flags;
    mutable unsigned int               flagged = 0;
    /// the (ghosted) solution of the current apply(), for the averages
    mutable const double *averages = nullptr;
    /// physics_variables: W(average) of every cell of the current apply()
    mutable std::vector<State> limiting_values;
  };
} // namespace granular_dg::dg
