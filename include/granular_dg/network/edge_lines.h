#pragma once

#include <deal.II/base/polynomial.h>
#include <deal.II/base/vectorization.h>

#include <granular_dg/dg/limiter.h>
#include <granular_dg/dg/subcell_blending.h>
#include <granular_dg/dg/time_integrator.h>

#include <array>
#include <cstddef>
#include <type_traits>
#include <vector>

namespace granular_dg::network
{
  /// body(law). A Law may overload it (found by argument-dependent lookup)
  /// to call body with an equivalent law whose branches are resolved at
  /// compile time (system.h: EdgeLaw); EdgeLines' operator calls it per edge.
  template <typename Law, typename Body>
  DEAL_II_ALWAYS_INLINE inline void
  with_fixed_law(const Law &law, Body &&body)
  {
    body(law);
  }

  /// Where the outer state of an edge end comes from.
  enum class EndKind : unsigned char
  {
    vertex,    ///< the vertex value u_0 (Dirichlet)
    dirichlet, ///< far-end data g(t) (Dirichlet)
    outflow    ///< the inner trace (zero gradient)
  };

  /// The method on the edges, as EdgeLines needs it.
  struct EdgeMethod
  {
    unsigned int         degree    = 0;
    dg::LimiterType      limiter   = dg::LimiterType::none;
    double               tvb_M     = 0.;
    dg::TroubleIndicator indicator = dg::TroubleIndicator::everywhere;
    /// 0: the indicator's automatic threshold
    double               indicator_threshold = 0.;
    /// the largest subcell blending factor (0: off)
    double               blending_max = 0.;
  };

  /**
   * The DG method on all edges of one rank as one line engine: the modal
   * coefficients of every cell of every edge lie in one array, edge after
   * edge, cell after cell from x = 0 to x = L, mode after mode (the layout of
   * dg::LineOperator on one line). An edge is two numbers of geometry (its
   * cell count and cell size) and its Law; there is no mesh object.
   *
   * The discretisation is dg::LineOperator's (p + 2 Gauss points, the
   * physics' numerical flux at faces, a fused Runge-Kutta stage update),
   * dg::ModalLimiter's TVB limiter with its trouble indicators and
   * dg::SubcellBlending, per edge as one such line: the same operations in
   * the same order, so each edge's values are those of a line engine on that
   * edge alone (to round-off where the compiler contracts differently). Cells
   * go through the stage, the CFL scan and the limiter in SIMD batches of W
   * (the native width); a batch may end an edge, its last lane then taking
   * the flux through the edge's end. The two end faces of an edge take their
   * outer state from outer_state(): the vertex value, far-end data or
   * (outflow) the inner trace.
   *
   * Law: the physics of an edge (NetworkProblem).
   */
  template <typename Law>
  class EdgeLines
  {
  public:
    /// flux[e], n_cells[e], h[e]: of the local edges e = 0, 1, ...
    EdgeLines(const EdgeMethod &method, std::vector<Law> flux,
              const std::vector<unsigned int> &n_cells, const std::vector<double> &h);

    unsigned int n_edges() const { return cells.size(); }
    unsigned int n_modes() const { return modes; }
    /// values of all edges (cells times modes)
    std::size_t  size() const { return first.back() * modes; }
    unsigned int n_cells(const unsigned int e) const { return cells[e]; }
    /// n_cells() and the cell size of every edge
    const std::vector<unsigned int> &cell_counts() const { return cells; }
    const std::vector<double>       &cell_sizes() const { return h; }
    /// the array index of mode 0 of cell c of edge e
    std::size_t
    index(const unsigned int e, const unsigned int c) const
    {
      return (first[e] + c) * modes;
    }

    /// The kind of the end (side 0: x = 0, side 1: x = L) of edge e, and the
    /// outer state at it (for vertex and dirichlet ends, set before every
    /// stage and every limiter pass).
    EndKind &kind(const unsigned int e, const unsigned int side) { return end_kind[2 * e + side]; }
    double  &outer_state(const unsigned int e, const unsigned int side) { return outer[2 * e + side]; }

    /// The flux through the end side of edge e (in the edge's direction)
    /// in the last stage(): the flux the edge's update used, which the
    /// vertex and the far-end balance take as theirs (so edges and vertices
    /// conserve mass to the bit). face = 2 e + side.
    double boundary_flux(const std::size_t face) const { return end_flux[face]; }
    /// the trace of edge e at x = 0 (side 0) or x = L (side 1)
    double trace(const double *u, unsigned int e, unsigned int side) const;
    /// the trace of the cell with modes x at xi = 0 (side 0) or 1 (side 1)
    double
    trace_at(const double *x, const unsigned int side) const
    {
      const double *value = side == 0 ? at_0.data() : at_1.data();
      double        sum   = 0;
      for (unsigned int k = 0; k < modes; ++k)
        sum += x[k] * value[k];
      return sum;
    }
    /// the solution on edge e at x = (c + xi) h
    double value(const double *u, unsigned int e, unsigned int c, double xi) const;
    /// the Legendre polynomials L_0 .. L_p on [0, 1] (FE_DGQLegendre's)
    const std::vector<Polynomials::Legendre> &legendre() const { return basis_functions; }

    /// One Runge-Kutta stage (dg::StageUpdate: dst = (alpha src + beta old)
    /// + gamma M^{-1} R(src), or src + gamma M^{-1} R(src) without old; dst
    /// may be src or old).
    void stage(const double *src, double *dst, const double *old, double alpha, double beta,
               double gamma) const;
    /// max over the cells and Gauss points of |f'(u)| / h, and over the
    /// vertex ends (kind() == vertex) of |f'(vertex_values[2 e + side])| / h
    double max_speed_over_h(const double *u, const double *vertex_values) const;
    /// whether limit() changes anything (a limiter, degree > 0)
    bool limits() const { return method.limiter != dg::LimiterType::none && modes > 1; }
    /// The TVB limiter in place (the outer states are those at the time of
    /// u); the number of troubled cells.
    unsigned int limit(double *u) const;
    /// cells whose last stage blended in finite volumes
    unsigned int n_blended_cells() const;


  private:
    using VA = VectorizedArray<double>;
    /// cells per SIMD batch (the native width)
    static constexpr unsigned int W = VA::size();

    /// res += the volume term of a cell's rate, sum_q w_q f(u(x_q)) L_k'(x_q):
    /// of one cell (Number = double) or of a SIMD batch of cells (VA); inlined
    /// into the kernels (a call costs the degree-2 operator 15 %)
    template <unsigned int nm, typename Number, typename FixedLaw>
    void add_volume_term(const Number *u, const FixedLaw &law, Number (&res)[nm]) const;
    /// the rate of edge e with its law (with_fixed_law(): edge_law(e) or a copy
    /// fixed at compile time)
    template <unsigned int nm, typename FixedLaw, typename Out>
    void rate_edge(const double *src, unsigned int e, const FixedLaw &law, const Out &out) const;
    template <unsigned int nm, typename FixedLaw, typename Out>
    void rate_batch(const double *src, unsigned int e, unsigned int c, const double *next,
                    const FixedLaw &law, double &F_left, const Out &out) const;
    const double *last_cells(const double *src, unsigned int e, unsigned int c) const;
    template <unsigned int nm, typename FixedLaw>
    void subcell_rate(const double *u, unsigned int e, const FixedLaw &law, double F_left,
                      double F_right, double (&fv)[nm]) const;
    template <unsigned int nm>
    void raw_blending_factors(const double *src, unsigned int e) const;
    double blending_factor(unsigned int e, unsigned int c) const;
    /// the largest speed |f'| of the edges [e0, e1) of one law: of SIMD
    /// batches of their cells (lanes) and of their other cells and vertex
    /// ends (rest), not yet divided by h
    template <unsigned int nm>
    void max_speed_run(const double *u, const double *vertex_values, unsigned int e0,
                       unsigned int e1, VectorizedArray<double> &lanes, double &rest) const;
    template <unsigned int nm>
    unsigned int limit_edge(double *u, unsigned int e) const;
    template <unsigned int nm>
    unsigned int limit_batch(double *u, unsigned int e, unsigned int c) const;
    template <unsigned int nm>
    bool limit_cell(double *u, unsigned int e, unsigned int c, double floor) const;
    template <unsigned int nm>
    bool kxrcf_indicated(const double *u, unsigned int e, unsigned int c, double floor) const;
    /// the outer state at end side of edge e whose inner trace is inner
    double outer_of(unsigned int e, unsigned int side, double inner) const;

    EdgeMethod                method;
    /// the distinct laws (as far as Law has ==) and the one of each edge: a
    /// table that stays in the cache and an index per edge, not a copy per
    /// edge (on the city grid one law for 10224 edges)
    static constexpr unsigned int max_laws = 16;
    std::vector<Law>              distinct_laws;
    std::vector<unsigned int>     law_of_edge;
    const Law &edge_law(const unsigned int e) const { return distinct_laws[law_of_edge[e]]; }
    std::vector<unsigned int> cells;
    /// first[e]: the cells before edge e (first[n_edges]: all)
    std::vector<std::size_t>  first;
    std::vector<double>       h, inverse_h;
    std::vector<EndKind>      end_kind;
    std::vector<double>       outer;
    /// boundary_flux(): 2 per edge, written by stage()
    mutable std::vector<double> end_flux;
    unsigned int              modes = 1, n_q = 1;
    static constexpr unsigned int max_modes = 5, max_points = max_modes + 1;
    /// Gauss points and weights on [0, 1]; basis[q][k] = L_k(x_q), derivative[q][k] = L_k'(x_q)
    std::array<double, max_points> weights{}, points{};
    std::array<std::array<double, max_modes>, max_points> basis{}, derivative{};
    std::array<double, max_modes>  at_0{}, at_1{};
    std::vector<Polynomials::Legendre> basis_functions;
    double                         indicator_threshold = 0.;
    dg::SubcellBlending            blend;
    /// blending factors of the last stage, before and after smoothing
    mutable std::vector<double>    raw_alpha, alpha;
    /// the limiter's per-cell flags of one edge (indicators that look at
    /// the neighbours)
    mutable std::vector<unsigned char> flags, examined;
    /// the rank's last W - 1 cells and a cell of zeros (last_cells())
    mutable std::vector<double>    after_last;
  };
} // namespace granular_dg::network
