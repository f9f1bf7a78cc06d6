#pragma once

#include <deal.II/base/function.h>
#include <deal.II/base/polynomial.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/tria.h>

#include <granular_dg/base/simulation.h>
#include <granular_dg/dg/limiter.h>
#include <granular_dg/dg/line_operator.h>
#include <granular_dg/dg/time_integrator.h>
#include <granular_dg/equations/network_scalar/system.h>
#include <granular_dg/network/exact_solution.h>
#include <granular_dg/network/graph.h>
#include <granular_dg/network/junction.h>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace granular_dg::network
{
  /// The DG operator of one edge: the lean 1D line operator (an edge is a
  /// serial line of cells). The network talks to it only through reinit,
  /// initialize_vector, apply, apply_stage, max_speed_over_h and integrals.
  using EdgeOperator = dg::LineOperator<System>;
  using EdgeLimiter  = dg::ModalLimiter<1, System>;

  /// The state of the network: one DG vector per edge and the vertex value.
  /// Has what dg::SSPRK3 needs of a vector; the vertex value is combined as
  /// deal.II combines the edge vectors (every product rounded on its own).
  struct NetworkState
  {
    std::vector<dg::VectorType> edges;
    double                      vertex = 0.;

    void reinit(const NetworkState &other);
    void equ(double a, const NetworkState &x);
    void add(double a, const NetworkState &x);
    void sadd(double s, double a, const NetworkState &x);
  };

  enum class Integrator
  {
    automatic,     ///< forward_euler at degree 0 (the paper's scheme), else ssprk3
    forward_euler, ///< (4.1): one explicit Euler step
    ssprk3
  };

  /// The numerical method on the network.
  struct Discretisation
  {
    unsigned int      degree = 0;
    dg::NumericalFlux flux   = dg::NumericalFlux::upwind;
    double            cfl    = 0.5;
    dg::LimiterType   limiter = dg::LimiterType::none;
    double            tvb_M   = 0.;
    /// 2^l at grid level l: an edge of length L gets round(L * this) cells
    double            cells_per_unit_length = 256;
    /// dx_0 = factor * sum over the vertex ends of h_k / 2 (1: the paper's
    /// N dx / 2; 0: a vertex without volume)
    double            vertex_width_factor = 1.;
    Integrator        integrator          = Integrator::automatic;
  };

  /// Data of one edge: initial data u(x) and, for a Dirichlet far end, g(t)
  /// (evaluated at the far end point). initial_breakpoints: where the
  /// initial data jump (cell averages are integrated piecewise there).
  struct EdgeData
  {
    std::shared_ptr<Function<1>> initial;
    std::shared_ptr<Function<1>> far_end;
    std::vector<double>          initial_breakpoints;
  };

  /// Where and why a stage produced an inadmissible state.
  struct StateFailure
  {
    double      time;
    int         edge; ///< -1: the vertex
    double      x;
    double      u;
    std::string reason;
  };

  /// Error norms over all edges and the vertex cell.
  struct NetworkErrors
  {
    double l1 = 0, l2 = 0, linf = 0;
    double l1_edges = 0, l1_vertex = 0;
    std::vector<double> l1_per_edge;
  };

  /**
   * The network as one discretisation: per edge a Triangulation<1>, a
   * DoFHandler with FE_DGQLegendre, an EdgeOperator (whose vertex face is a
   * Dirichlet boundary with the current vertex value) and a limiter; the
   * Junction couples them. apply() is the semi-discrete right-hand side of
   * the whole network, so dg::SSPRK3<NetworkState> advances it.
   */
  class NetworkProblem
  {
  public:
    NetworkProblem(const Graph &graph, const Discretisation &discretisation,
                   std::vector<EdgeData> data);
    ~NetworkProblem();

    /// Project the initial data (exact cell averages at degree 0), limit,
    /// and set the vertex: the given value, or the discrete stationary one
    /// for the initial edge traces (nullopt).
    void
    initialize(std::optional<double> vertex_value);

    /// The CFL step of the current state: cfl * min h / max |f'|, the
    /// vertex value included (condition (4.7) for cfl <= 1/2).
    double
    time_step() const;

    /// One step of the integrator (limiter after every stage); throws
    /// StateFailure when a stage is not finite.
    void
    step(double dt);

    /// The semi-discrete right-hand side: dst = R(t, src).
    void
    apply(double t, const NetworkState &src, NetworkState &dst) const;

    /// One Runge-Kutta stage (dg::StageUpdate; dst may be src or s.old):
    /// apply() and the vector operations in one pass over every edge.
    void
    apply_stage(double t, const NetworkState &src, NetworkState &dst,
                const dg::StageUpdate<NetworkState> &s) const;

    /// Charge the phases of the following steps to this (benchmark mode;
    /// nullptr: no timing).
    void set_phases(StepPhases *p) { phases = p; }

    double time() const { return t; }
    unsigned long n_steps() const { return steps; }
    double last_time_step() const { return dt_last; }
    unsigned long n_dofs() const;
    unsigned long n_cells() const;
    unsigned int  n_stages() const;
    double        min_cell_size() const { return h_min; }
    const Graph  &graph() const { return net; }
    const Junction &junction() const { return *vertex; }
    const Discretisation &discretisation() const { return disc; }
    const NetworkState &state() const { return u; }
    NetworkState       &state() { return u; }

    /// Total mass: integrals over the edges + dx_0 u_0.
    double mass() const;
    /// int_0^t (inflow - outflow at the far ends) dt, as the integrator saw it.
    double boundary_inflow() const { return inflow; }
    /// L1 norm of the cell averages and the vertex (the scale of the drift).
    double l1_norm() const;
    double vertex_value() const { return u.vertex; }
    /// Traces of the edges at the vertex ends (Junction::ends() order).
    std::vector<double> vertex_traces(const NetworkState &state) const;
    /// sum_in F - sum_out F at the vertex for the current state.
    double rh_residual() const;
    /// (4.4): TV of the cell averages along every edge plus the jumps
    /// between the vertex and its neighbouring cells.
    double total_variation() const;
    NetworkErrors errors(const ExactSolution &exact) const;
    /// ||u - v||_L1 over edges and vertex (same mesh).
    double l1_distance(const NetworkProblem &other) const;
    /// max |u - v| over the Legendre modes and the vertex.
    double max_mode_difference(const NetworkProblem &other) const;

    /// The state of a checkpoint (time, steps, last time step, far-end
    /// inflow, the modes of every edge and the vertex value), written and
    /// read by the same calls (ByteWriter/ByteReader).
    template <typename Archive>
    void
    checkpoint_io(Archive &ar)
    {
      ar.io(t);
      ar.io(inflow);
      ar.io(dt_last);
      ar.io(steps);
      ar.io(u.vertex);
      for (auto &e : u.edges)
        {
          std::vector<double> modes(e.begin(), e.end());
          ar.io(modes);
          if (modes.size() != e.size())
            throw RunError("the checkpoint's network has other edge sizes");
          std::copy(modes.begin(), modes.end(), e.begin());
        }
    }

    /// The solution at equally spaced points of every cell (both ends
    /// included): per edge the pairs (x, u).
    std::vector<std::vector<std::pair<double, double>>>
    sample(unsigned int points_per_cell) const;

  private:
    struct EdgeDiscretisation;

    double evaluate(unsigned int edge, unsigned int cell, double xi, const NetworkState &s) const;
    /// evaluate() at xi = 0 (at_end false) or xi = 1 (at_end true)
    double end_value(unsigned int edge, unsigned int cell, bool at_end, const NetworkState &s) const;
    /// the vertex rate and the far-end inflow of the stage at src (the
    /// coupling part of apply(); sets the vertex value the edges see)
    double couple(double t, const NetworkState &src) const;
    double far_end_inflow(double time, const NetworkState &s) const;
    void   post_stage(NetworkState &s, double stage_time);
    /// Degree 0: the range [min, max] of the cell averages, the vertex value
    /// and the far-end Dirichlet data of the step from t to t + dt.
    std::pair<double, double> range_of_step(double dt) const;
    /// Degree 0: a StateFailure unless every cell average of s lies in the
    /// step's range (widened by the stage's vertex value).
    void check_maximum_principle(const NetworkState &s, double stage_time);

    Graph                 net;
    Discretisation        disc;
    std::vector<EdgeData> data;
    std::vector<std::unique_ptr<EdgeDiscretisation>> edge;
    std::unique_ptr<Junction>                        vertex;
    class VertexData;
    std::shared_ptr<VertexData> vertex_data;
    NetworkState               u;
    dg::SSPRK3<NetworkState>   rk3;
    std::vector<Polynomials::Legendre> legendre;
    double                     t = 0., inflow = 0., h_min = 0., dt_last = 0.;
    /// the range of the current step (degree 0's maximum principle)
    std::pair<double, double>  bounds{-INFINITY, INFINITY};
    unsigned long              steps = 0;
    /// far-end inflow rate of each apply() call in the current step
    mutable std::vector<double> stage_inflow;
    StepPhases                 *phases = nullptr;
  };

  /// A single run with output (solution.pvd with the network drawn in the
  /// plane, profile-NNNN-edge-K.csv, timeseries.csv, summary.json).
  RunResult
  run_network(const Graph &graph, const std::vector<EdgeData> &data,
              const Discretisation &discretisation, std::optional<double> vertex_value,
              const ExactSolution *exact, const CommonParameters &params, bool write_files,
              const std::string &scene = "network");

  /// The study of Convergence/degrees x Convergence/cells (cells per unit
  /// length): L1 error over edges and vertex (and per edge), EOC, steps, CPU
  /// time, in convergence.csv (and a Table-1-like table on stdout); the EOC
  /// of the two finest meshes per degree in convergence-rates.csv. cfl[i] is
  /// the CFL number of degree i of the list.
  void
  run_network_convergence(const Graph &graph, const std::vector<EdgeData> &data,
                          const Discretisation &discretisation,
                          std::optional<double> vertex_value, const ExactSolution &exact,
                          const CommonParameters &params, const std::vector<double> &cfl);
} // namespace granular_dg::network
