#pragma once

#include <deal.II/base/function.h>
#include <deal.II/base/polynomial.h>
#include <deal.II/base/quadrature_lib.h>

#include <granular_dg/base/evolution.h>
#include <granular_dg/base/run_parameters.h>
#include <granular_dg/dg/limiter.h>
#include <granular_dg/dg/parameters.h>
#include <granular_dg/dg/time_integrator.h>
#include <granular_dg/network/edge_lines.h>
#include <granular_dg/network/edge_partition.h>
#include <granular_dg/network/exact_solution.h>
#include <granular_dg/network/graph.h>
#include <granular_dg/network/junction.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace granular_dg::network
{
  /// The state of the network: the modes of the edges' cells (EdgeLines'
  /// layout: edge after edge) and the value of every vertex. Has what
  /// dg::SSPRK3 needs of a vector. On several MPI ranks a rank holds the
  /// modes of its own edges and keeps the values of the vertices they meet.
  struct NetworkState
  {
    std::vector<double> edges;
    std::vector<double> vertices;

    void reinit(const NetworkState &other);
    void
    swap(NetworkState &other)
    {
      edges.swap(other.edges);
      vertices.swap(other.vertices);
    }
  };

  enum class Integrator
  {
    automatic,     ///< forward_euler at degree 0 (the paper's scheme), else ssprk3
    forward_euler, ///< (4.1): one explicit Euler step
    ssprk3
  };

  /// What a snapshot writes besides solution-NNNN.vtu.
  enum class Profiles
  {
    per_edge, ///< profile-NNNN-edge-K.csv, one per edge
    one_file, ///< profile-NNNN.csv with an edge column
    none
  };

  /// The most points of one piece of a VTU file (about: a piece ends with
  /// the edge that fills it), above which the file is written in pieces of
  /// whole edges and equal size (VTK's UnstructuredGrid format allows many;
  /// ParaView reads them as one data set): deal.II's writer holds ~110 bytes
  /// per point of the piece it writes. (ParaView 5.11 opened the 10^6-edge
  /// city grid's 49 M points in 46 s as 12 pieces, 48 s as one, 180 s as
  /// 188 pieces of 2^18 points.)
  inline constexpr std::size_t vtu_piece_points = std::size_t(1) << 22;

  /// What the network adds to the method of every scene
  /// (dg::DiscretizationParameters): the mesh of the edges, the integrator
  /// and what a snapshot writes. (The numerical flux is the edges' Law's.)
  struct NetworkOptions
  {
    /// 2^l at grid level l: an edge of length L gets round(L * this) cells
    double        cells_per_unit_length = 256;
    Integrator    integrator            = Integrator::automatic;
    Profiles      profiles              = Profiles::per_edge;
    /// whether solution-NNNN.vtu are written
    bool          write_vtu = true;
    /// the pieces of a VTU file compressed at once, each by a thread of its
    /// own while the next is sampled (the scene: one per core of the rank,
    /// as many as its memory holds)
    unsigned int  vtu_writers = 1;
  };

  /// The cells of every edge of graph at cells per unit length (at least one).
  std::vector<unsigned int>
  edge_cells(const Graph &graph, double cells_per_unit_length);

  /// Adds to result[k] the moment int_a^b g(x) L_k((x - x0) / h) dx of g
  /// over [a, b] inside the cell [x0, x0 + h], k = 0 .. legendre.size() - 1:
  /// adaptive Gauss integration (rule quad) that bisects until two levels
  /// agree to round-off, so a jump inside a cell is located to machine
  /// precision (exact cell averages, (4.11)); smooth data need one level.
  void
  add_cell_moments(const Function<1> &g, const std::vector<Polynomials::Legendre> &legendre,
                   const QGauss<1> &quad, double x0, double h, double a, double b,
                   std::vector<double> &result, unsigned int depth = 0);

  /// Bytes of one snapshot of the network (the estimate of
  /// require_reasonable_snapshot_count()), without building it.
  double
  snapshot_bytes(unsigned long n_cells, const dg::DiscretizationParameters &method,
                 const NetworkOptions &options);

  /// Data of one edge: initial data u(x) and, for a Dirichlet far end, g(t)
  /// (evaluated at the far end point). initial_breakpoints: where the
  /// initial data jump (cell averages are integrated piecewise there).
  struct EdgeData
  {
    std::shared_ptr<Function<1>> initial;
    std::shared_ptr<Function<1>> far_end;
    std::vector<double>          initial_breakpoints;
  };

  /// Error norms over all edges and the vertex cell.
  struct NetworkErrors
  {
    double l1 = 0, l2 = 0, linf = 0;
    double l1_edges = 0, l1_vertex = 0;
    std::vector<double> l1_per_edge;
  };

  /// What NetworkProblem's members use that does not depend on the law
  /// (source/network/network.cc).
  namespace internal
  {
    /// Whether every entry of v is finite and, with `range`, their
    /// [min, max]: one SIMD pass
    struct Scan
    {
      bool   finite;
      double lo, hi;
    };
    template <bool range>
    Scan
    scan(const std::vector<double> &v);

    /// Adds to m and tv, edge after edge (EdgeLines' layout from u on, cells[e]
    /// cells of size h[e], stride values per cell), h[e] times the sum of the
    /// edge's cell means and their total variation along the edge. (One call
    /// for all edges: the sums of an edge are inlined, not a call each.)
    void
    add_edge_sums(const double *u, unsigned int stride, const std::vector<unsigned int> &cells,
                  const std::vector<double> &h, double &m, double &tv);
  } // namespace internal

  /**
   * The network as one discretisation and the Evolution the TimeLoop drives:
   * the cells of all edges of a rank in one line engine (EdgeLines), whose
   * vertex faces take the current vertex value as their Dirichlet state; the
   * Junction couples them. apply_stage() is a Runge-Kutta stage of the whole network
   * (edges and vertex), so dg::SSPRK3<NetworkState> and
   * dg::ForwardEuler<NetworkState> advance it.
   *
   * Law is the physics of an edge, one object per edge: copyable, with
   * value(u), derivative(u) = f'(u) and the numerical flux flux(u_l, u_r),
   * each a template in the number type (double and VectorizedArray<double>),
   * admissible_range() = {lo, hi}, the states it admits (infinite bounds
   * where unbounded), vertex_range(incoming), the vertex values for which
   * the flux at a vertex end of it is physical (both checked after every
   * stage), describe() for
   * messages and output headers, flux_name() for summary.json and a static
   * `name` (tests/network/custom_law.cc has a minimal one). It may have ==
   * (the line operator then keeps one copy of equal laws) and overload
   * with_fixed_law() (edge_lines.h) to hand the line operator a copy of
   * itself with its branches resolved at compile time. The members are
   * defined in network.templates.h and output.templates.h, which the scene
   * instantiates for its Law.
   *
   * On several MPI ranks each rank discretises its own edges (EdgePartition)
   * and updates the vertices they meet; the traces at vertices shared with
   * other ranks are exchanged once per stage. The solution is the same bit
   * for bit on any number of ranks. Sums over the network (mass, errors,
   * total variation) and the time step are reduced over the ranks; output
   * and checkpoints are gathered on rank 0 and do not depend on the number
   * of ranks.
   */
  template <typename Law>
  class NetworkProblem : public Evolution
  {
  public:
    /// The vertices' widths and initial values are the graph's; laws and
    /// data: one per edge.
    NetworkProblem(const Graph &graph, std::vector<Law> laws,
                   const dg::DiscretizationParameters &method, const NetworkOptions &options,
                   std::vector<EdgeData> data, const ExactSolution *exact = nullptr,
                   const std::string &scene = "network");
    ~NetworkProblem() override;

    // ------------------------------------------------------------ Evolution
    /// edges, vertex ends, cells and DoFs of all edges (+1: the vertex value)
    EvolutionInfo
    info() const override;
    /// Project the initial data (exact cell averages at degree 0), limit,
    /// and set every vertex: the given value, or the discrete stationary one
    /// for the initial edge traces.
    double
    initialize() override;
    /// every mode of every edge and the vertex value finite
    void
    check_initial_state(double t) override;
    /// The CFL step of the current state: cfl * min h / max |f'|, the
    /// vertex values included (condition (4.7) for cfl <= 1/2), and no
    /// longer than the monotonicity bound dt sum max|f'| <= dx_0 of the
    /// vertex cells narrower than that step covers (narrow_vertex_rate()).
    double
    time_step(double t) override;
    /// One step of the integrator (limiter after every stage); throws
    /// Inadmissible when a stage is not finite (or, at degree 0, leaves the
    /// range of the data).
    void
    advance(double t, double dt) override;
    /// the mass balance and the largest total variation so far
    void
    end_of_step(double t, double dt, unsigned long step) override;
    void
    store(Slot slot) override;
    void
    restore(Slot slot) override;
    /// solution-NNNN.vtu (the edges and vertices in the plane) and
    /// profile-NNNN-edge-K.csv
    SnapshotFiles
    write_snapshot(const std::string &directory, unsigned int index, double t) override;
    /// mass, mass balance, inflow, (first) vertex value, TV, largest
    /// Rankine-Hugoniot residual (and the errors against an exact solution)
    std::vector<std::string>
    timeseries_names() const override;
    std::string
    timeseries_comment() const override;
    std::vector<double>
    timeseries_values(double t) override;
    /// the modes of every edge, the vertex values, the far-end inflow and
    /// the running diagnostics
    void
    save(ByteWriter &w) override;
    void
    load(ByteReader &r) override;
    /// summary.json: mass balance, vertex and TV diagnostics, errors
    void
    finish(double t, RunResult &result, bool write_files) override;
    void
    set_phases(StepPhases *p) override
    {
      phases = p;
    }

    // ------------------------------------------------------------ the method
    /// One Runge-Kutta stage (dg::StageUpdate; dst may be src or s.old):
    /// the coupling and every edge's operator and update.
    void
    apply_stage(double t, const NetworkState &src, NetworkState &dst,
                const dg::StageUpdate<NetworkState> &s) const;

    /// of the whole network (all ranks)
    unsigned long n_dofs() const;
    unsigned long n_cells() const;
    unsigned int  n_stages() const;
    double        min_cell_size() const { return h_min; }
    const Graph  &graph() const { return net; }
    const Junction<Law> &junction(unsigned int v = 0) const { return junctions[v]; }
    const EdgePartition &partition() const { return *ranks; }
    /// u_0 of vertex v on a rank that owns one of its edges (every vertex on
    /// one rank); vertex_values() has all of them on every rank.
    double        vertex_value(unsigned int v = 0) const { return u.vertices[v]; }
    /// Collective: the value of every vertex, on every rank.
    std::vector<double> vertex_values() const;

    /// Collective (as all sums and norms below): total mass, the integrals
    /// over the edges + dx_0 u_0 of every vertex.
    double mass() const;
    /// int_0^t (inflow - outflow at the far ends) dt, as the integrator saw it.
    double boundary_inflow() const { return ranks->sum(inflow); }
    /// L1 norm of the cell averages and the vertices (the scale of the drift).
    double l1_norm() const;
    /// The traces of state's edges at the ends of this rank's vertices, in
    /// one pass (at a vertex shared with other ranks: those of the last
    /// exchange_traces()); traces_at(v): those of vertex v, in
    /// Junction::ends() order, until the next call.
    void fill_traces(const NetworkState &state) const;
    const double *
    traces_at(const unsigned int v) const
    {
      return end_traces.data() + vertex_ends.first[v];
    }
    /// Collective: share the traces of state at the vertices whose edges lie
    /// on several ranks (nothing to do on one rank).
    void exchange_traces(const NetworkState &state) const;
    /// sum_in F - sum_out F for the current state at the vertex where it is
    /// largest in magnitude (0 without vertices).
    double rh_residual() const;
    /// (4.4): TV of the cell averages along every edge plus the jumps
    /// between each vertex and its neighbouring cells.
    double total_variation() const;
    NetworkErrors errors(const ExactSolution &exact, double t) const;
    /// ||u - v||_L1 over edges and vertices (same mesh).
    double l1_distance(const NetworkProblem &other) const;
    const NetworkState &state() const { return u; }

    /// The mass balance of a run: R = (mass(t) - mass(0) - far-end inflow) /
    /// ||u(0)||_L1 after every step; its largest |R| (the drift) and its
    /// largest change in one step (the conservation error of a step).
    struct MassBalance
    {
      double mass0 = 0, scale = 1, last = 0, max_residual = 0, max_step = 0;
    };

    const MassBalance &
    mass_balance() const
    {
      return balance;
    }

    /// The solution at equally spaced points of every cell (both ends
    /// included): per edge the pairs (x, u), of this rank's edges (the
    /// others empty); gathered_sample() has all edges on rank 0.
    std::vector<std::vector<std::pair<double, double>>>
    sample(unsigned int points_per_cell) const;
    /// the pairs (x, u) of one edge of this rank
    std::vector<std::pair<double, double>>
    sample_edge(unsigned int k, unsigned int points_per_cell) const;
    std::vector<std::vector<std::pair<double, double>>>
    gathered_sample(unsigned int points_per_cell) const;

  private:
    /// the outer states of the edge ends at time: the values vertex_u0 of
    /// their vertices, the far-end data
    void   set_end_states(double time) const;
    /// The largest sum over the ends of max(|f'(u_0)|, |f'(trace)|) / dx_0
    /// of this rank's narrow vertices (0 without them): 1 / (the longest
    /// step for which their update (4.1b) is monotone).
    double narrow_vertex_rate() const;
    /// the local number of edge k in EdgeLines (this rank's edges)
    unsigned int local(const unsigned int k) const { return local_edge[k]; }
    /// the trace of edge k at x = 0 (at_end false) or x = L (at_end true)
    double trace(unsigned int edge, bool at_end, const NetworkState &s) const;
    /// The values the edges see at the vertices in a stage (or limiter pass)
    /// at s: vertex_u0 and the outer states of the edge ends.
    void set_vertex_states(const NetworkState &s, double time) const;
    /// After the edges' stage: the vertex rates (4.1b) from the fluxes the
    /// edges used at their vertex ends; records the stage's far-end inflow.
    const std::vector<double> &vertex_rates() const;
    /// the value the edges see at vertex v: u_0, or the balance of the
    /// traces (of the last fill_traces(s)) for a vertex without volume
    double vertex_state(unsigned int v, const NetworkState &s, double t) const;
    /// f(face, g) for every face (edge, side) of data_faces and its far-end
    /// data g at time
    template <typename F>
    void far_end_data(double time, const F &f) const;
    /// the point of a free end face (edge, side) on its edge
    double far_end_point(const std::pair<unsigned int, unsigned int> &face) const
    {
      return face.second == 0 ? 0. : net.edges[face.first].length;
    }
    /// inflow - outflow through the free ends of this rank's edges in the
    /// last stage (the fluxes the edges used)
    double far_end_inflow() const;
    /// the limiter and the checks after a stage (last: the step's last)
    void   post_stage(NetworkState &s, double stage_time, bool last);
    /// Inadmissible unless s is finite and admissible (and, at degree 0,
    /// in the range of the step); means: check every cell mean against its
    /// edge's admissible range too (the initial state and, at degrees >= 1,
    /// the state of a step); initial: s is the initial state.
    void   post_stage_checks(const NetworkState &s, double stage_time, bool means,
                             bool initial = false);
    /// this rank's part of post_stage_checks (principle: check the maximum
    /// principle against bounds)
    void   local_checks(const NetworkState &s, double stage_time, bool principle, bool means,
                        bool initial);
    /// Inadmissible unless every far-end datum, (where means) cell mean and
    /// vertex value of s lies in the range its laws admit
    /// (Law::admissible_range(), vertex_range()); after a stage (initial
    /// false) the upper bounds only.
    void   check_admissible_ranges(const NetworkState &s, double stage_time, bool means,
                                   bool initial) const;
    /// Degree 0: the range [min, max] of the cell averages, the vertex values
    /// and the free ends' Dirichlet data of the step from t to t + dt.
    std::pair<double, double> range_of_step(double t, double dt) const;
    /// Degree 0: Inadmissible unless every cell average of s lies in the
    /// step's range (widened by the stage's vertex values); [lo_s, hi_s]:
    /// the range of the cell averages of s.
    void check_maximum_principle(const NetworkState &s, double stage_time, double lo_s,
                                 double hi_s);
    /// where: an edge k >= 0 at x, or vertex -1 - k
    Inadmissible failure(double time, int edge, double x, double value,
                         const std::string &reason) const;
    double balance_residual() const;
    /// Collective: values[k] of every edge k on rank 0 (each rank fills
    /// those of its edges).
    void gather_edge_values(std::vector<std::vector<double>> &values) const;
    /// this rank's part of mass()
    double local_mass() const;
    /// this rank's mass and total variation in one pass
    std::array<double, 2> local_sums() const;
    /// Junction::balance at vertex v of the traces of the last fill_traces();
    /// in parallel a failure is held (NaN is returned) until the stage's
    /// collective check reports it on every rank.
    double balance_at(unsigned int v, double time) const;
    using Samples = std::vector<std::vector<std::pair<double, double>>>;
    /// sample points per cell of the VTU (at least 2) and of the profiles
    unsigned int vtu_points() const
    {
      return method.profile_points > 0 ? std::max(2u, method.profile_points) :
                                         std::max(2u, method.degree + 1);
    }
    unsigned int profile_points() const
    {
      return method.profile_points > 0 ? method.profile_points :
                                         std::max(2u, method.degree + 1);
    }
    /// rank 0: the profiles of a snapshot from the gathered samples
    void write_profiles(const std::string &directory, unsigned int index, double t,
                        const Samples &profile, const std::vector<double> &vertices) const;
    /// The VTU file `name` of this rank's edges and of the vertices it
    /// reports, sampled edge by edge as the file is written.
    void write_vtu(const std::string &directory, const std::string &name, unsigned int index,
                   double t, const std::vector<double> &vertices) const;
    /// What a checkpoint holds (the modes of every edge, the vertex values,
    /// the far-end inflow and the diagnostics), written and read alike.
    template <typename Archive>
    void
    state_io(Archive &ar, std::vector<double> &vertices, std::vector<std::vector<double>> &modes,
             double &total_inflow);

    Graph                       net;
    std::vector<Law>            laws;
    dg::DiscretizationParameters method;
    NetworkOptions              options;
    std::vector<EdgeData> data;
    const ExactSolution  *exact;
    std::string           scene;
    std::unique_ptr<EdgePartition>                   ranks;
    /// cells and cell size of every edge
    std::vector<unsigned int>                        edge_cells;
    std::vector<double>                              edge_h;
    /// the cells of this rank's edges; the local number of every edge (-1:
    /// on another rank)
    std::unique_ptr<EdgeLines<Law>>                  lines;
    std::vector<int>                                 local_edge;
    /// the traces (and, after a stage, the fluxes) of the ends of the
    /// vertices shared by several ranks, one per slot
    mutable std::vector<double>                      exchanged, exchanged_flux;
    /// a vertex balance that failed on this rank (parallel runs)
    mutable std::optional<std::string>               pending_error;
    /// fill_traces(): one per entry of vertex_ends
    mutable std::vector<double>                      end_traces;
    /// whether a vertex of this rank has no volume (balanced every stage)
    bool                                             without_volume = false;
    /// This rank's vertices whose cell the edges' CFL step does not cover
    /// (Vertex::narrower_than_step()); whether any rank has such a vertex,
    /// and one that is cut (collective decisions in time_step()).
    std::vector<unsigned int>                        narrow_vertices;
    bool                                             narrow_anywhere = false, narrow_cut = false;
    /// the end faces of this rank's edges (2 local edge + side) at each
    /// vertex, the (edge, side) of the free ends and of those among them
    /// with Dirichlet data
    std::vector<std::pair<unsigned int, unsigned int>> vertex_faces, free_faces, data_faces;
    /// the ends of each vertex (CSR: those of v are first[v] .. first[v +
    /// 1] - 1, in Junction::ends() order): the end face of a local edge
    /// whose trace and flux it takes (face = 2 e + side >= 0), or -1 - its
    /// slot in exchanged (a vertex shared with other ranks); at_end: the
    /// face at x = L (an incoming end)
    struct VertexEnds
    {
      std::vector<std::size_t>   first;
      std::vector<long>          face;
      std::vector<unsigned char> at_end;
    } vertex_ends;
    /// the ends of this rank's vertices on this rank's edges, in the order
    /// of vertex_ends (one flat pass for the total variation): the vertex
    /// and the array index of mode 0 of the end cell
    struct OwnedEnd
    {
      unsigned int vertex;
      std::size_t  cell;
    };
    std::vector<OwnedEnd> owned_ends;
    /// time_step(): the vertex value at each face of vertex_faces
    std::vector<double> face_values;
    std::vector<Junction<Law>>                       junctions;
    /// the value the edges see at each vertex in the current stage
    mutable std::vector<double>                      vertex_u0;
    /// the time of the far-end data in the edges' outer states
    mutable double                                   data_time = NAN;
    /// last_good: the spare of a step, which ends by swapping it with u;
    /// the state before the step while last_good_swapped
    NetworkState               u, last_good, benchmark_start;
    bool                       last_good_swapped = false;
    dg::SSPRK3<NetworkState>   rk3;
    /// inflow: this rank's far ends
    double                     t = 0., inflow = 0., h_min = 0.;
    MassBalance                balance;
    double                     tv0 = 0, u00 = 0, tv_max = 0;
    /// The admissible range of every vertex (the intersection of the
    /// vertex_range() of its ends, and the ends that bound it from below and
    /// above) and of the edges of this rank whose law bounds the state; each
    /// widened by 1e-12 of its larger finite bound (round-off).
    struct Bounded
    {
      std::array<double, 2>  range;
      std::array<EdgeEnd, 2> end;
    };
    std::vector<Bounded>                             vertex_range;
    /// r widened by 1e-12 of the larger finite bound of the law's
    /// admissible range a (round-off)
    static std::array<double, 2>
    widened(const std::array<double, 2> &r, const std::array<double, 2> &a)
    {
      double scale = 0;
      for (const double b : a)
        if (std::isfinite(b))
          scale = std::max(scale, std::abs(b));
      return {{r[0] - 1e-12 * scale, r[1] + 1e-12 * scale}};
    }
    static std::array<double, 2>
    widened(const std::array<double, 2> &r)
    {
      return widened(r, r);
    }
    std::vector<std::pair<unsigned int, std::array<double, 2>>> bounded_edges;
    /// the range of the current step (degree 0's maximum principle)
    std::pair<double, double>  bounds{-INFINITY, INFINITY};
    /// far-end inflow rate of each stage in the current step
    mutable std::vector<double> stage_inflow;
    /// the vertex rates of the current stage
    mutable std::vector<double> rates;
    StepPhases                 *phases = nullptr;
  };

  /// A single run with output (solution.pvd with the network drawn in the
  /// plane, profile-NNNN-edge-K.csv, timeseries.csv, summary.json).
  template <typename Law>
  RunResult
  run_network(const Graph &graph, std::vector<Law> laws, const std::vector<EdgeData> &data,
              const dg::DiscretizationParameters &method, const NetworkOptions &options,
              const ExactSolution *exact,
              const RunParameters &params, bool write_files,
              const std::string &scene = "network");

  /// The convergence study (run_convergence_study()) of Convergence/degrees x
  /// Convergence/cells (cells per unit length): L1 error over edges and
  /// vertex (and per edge), its EOC, steps, CPU time, in convergence.csv (and
  /// a Table-1-like table on stdout); the EOC of the two finest meshes per
  /// degree in convergence-rates.csv.
  template <typename Law>
  void
  run_network_convergence(const Graph &graph, const std::vector<Law> &laws,
                          const std::vector<EdgeData> &data,
                          const dg::DiscretizationParameters &method,
                          const NetworkOptions &options, const ExactSolution &exact,
                          const RunParameters &params);
} // namespace granular_dg::network
