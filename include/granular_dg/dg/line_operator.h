#pragma once

#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/polynomial.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/vectorization.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/la_parallel_vector.h>

#include <granular_dg/base/errors.h>
#include <granular_dg/base/vectorized_math.h>
#include <granular_dg/dg/boundary.h>
#include <granular_dg/dg/modal_layout.h>
#include <granular_dg/dg/operator.h>
#include <granular_dg/dg/subcell_blending.h>
#include <granular_dg/dg/time_integrator.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <type_traits>
#include <vector>

namespace granular_dg::dg
{
  using namespace dealii;

  namespace internal
  {
    /// What Physics::source() takes as position: Point<1>, or what the
    /// optional Physics::source_position(x) makes of it (doc/engine.md).
    template <typename Physics, typename = void>
    struct SourcePosition
    {
      using type = Point<1>;
      static type
      of(const Physics &, const Point<1> &x)
      {
        return x;
      }
    };
    template <typename Physics>
    struct SourcePosition<
      Physics,
      std::void_t<decltype(std::declval<const Physics &>().source_position(Point<1>()))>>
    {
      using type = decltype(std::declval<const Physics &>().source_position(Point<1>()));
      static type
      of(const Physics &physics, const Point<1> &x)
      {
        return physics.source_position(x);
      }
    };
  } // namespace internal

  /**
   * The lean 1D DG operator: the same discretisation as DGOperator<1> (modal
   * FE_DGQLegendre, p + 2 Gauss points, the same numerical fluxes, boundary
   * states and inverse mass matrix, the same vector and DoF numbering), written
   * as plain loops over a line of cells instead of MatrixFree's cell and face
   * batches. In 1D the per-cell and per-face overhead of a generic engine
   * dominates (a cell has only (p+1) n_components unknowns), and here a cell
   * costs a few hundred flops and no indirection. Serial only (1D runs are).
   *
   * The kernels are compiled for each degree 0-4 (the number of modes is a
   * template parameter, so the compiler unrolls the mode and point loops).
   * apply_stage() does a Runge-Kutta stage (dg::StageUpdate) in the same pass
   * over the cells, with the rounding of the vector operations it replaces.
   */
  template <typename Physics>
  class LineOperator : public Operator<1>
  {
  public:
    static constexpr unsigned int n_components   = Physics::n_components;
    static constexpr unsigned int n_coefficients = Physics::n_coefficients;
    template <typename T>
    using State = Tensor<1, n_components, T>;
    template <typename T>
    using Coefficients = std::array<T, n_coefficients>;

    LineOperator(const Physics &physics, BoundaryMap<1> bc)
      : phys(physics)
      , boundary(std::move(bc))
    {}

    std::string
    engine_name() const override
    {
      return "line";
    }

    std::size_t
    engine_memory() const override
    {
      const auto n = [](const auto &v) { return v.capacity() * sizeof(v[0]); };
      return layout.memory_consumption() + n(h) + n(x_left) + n(coefficients) + n(cell_speed) +
             n(source_points) + n(raw_alpha) + n(alpha) + n(subcell_points);
    }

    void
    reinit(const Mapping<1> &, const DoFHandler<1> &dof_handler) override
    {
      // the line engine works on a serial mesh: one rank's whole line (the
      // network's edges are such meshes on every rank)
      require(dynamic_cast<const parallel::TriangulationBase<1> *>(
                &dof_handler.get_triangulation()) == nullptr,
              "Discretization/engine", "line",
              "auto or matrix_free on a mesh spread over MPI ranks (the line engine "
              "needs the whole line on one rank)");
      layout.reinit(dof_handler);
      n_cells = layout.n_owned();
      n_modes = layout.n_modes();
      AssertThrow(n_modes <= max_modes, ExcMessage("the line engine supports degrees 0-4"));
      n_dofs        = dof_handler.n_dofs();

      // the vector index of (cell, component, mode) is c (p+1) n + i (p+1) + k
      // (FESystem numbers the interior DoFs component by component), and the
      // cells are ordered left to right, so that the kernels can stream
      for (unsigned int c = 0; c < n_cells; ++c)
        {
          for (unsigned int i = 0; i < n_components; ++i)
            for (unsigned int k = 0; k < n_modes; ++k)
              AssertThrow(layout.index(c, i, k) == index(c, i, k),
                          ExcMessage("the line engine needs the cell-wise DoF numbering "
                                     "of a freshly distributed 1D DoFHandler"));
          AssertThrow(c == 0 || layout.neighbor(c, 0) == int(c) - 1,
                      ExcMessage("the line engine needs the cells ordered left to right"));
        }
      periodic = layout.neighbor(0, 0) == int(n_cells) - 1;

      h.resize(n_cells);
      inverse_h.resize(n_cells);
      x_left.resize(n_cells);
      coefficients.resize(n_cells);
      for (unsigned int c = 0; c < n_cells; ++c)
        {
          h[c]            = layout.extent(c, 0);
          inverse_h[c]    = 1. / h[c];
          x_left[c]       = layout.cell(c)->vertex(0)[0];
          coefficients[c] = phys.coefficients(layout.cell(c)->material_id());
        }
      if (!periodic)
        {
          left_bc  = find_bc(layout.boundary_id(0, 0));
          right_bc = find_bc(layout.boundary_id(n_cells - 1, 1));
        }

      const QGauss<1> q(n_modes + 1);
      n_q = q.size();
      for (unsigned int i = 0; i < n_q; ++i)
        {
          points[i]  = q.point(i)[0];
          weights[i] = q.weight(i);
        }
      for (unsigned int k = 0; k < n_modes; ++k)
        {
          const Polynomials::Legendre L(k);
          std::vector<double>         values(2);
          for (unsigned int i = 0; i < n_q; ++i)
            {
              L.value(points[i], values);
              basis[i][k]      = values[0];
              derivative[i][k] = values[1];
            }
          at_0[k] = layout.value_at_0(k);
          at_1[k] = layout.value_at_1(k);
        }
      if constexpr (Physics::has_source_term)
        {
          source_points.clear();
          for (unsigned int c = 0; c < n_cells; ++c)
            for (unsigned int q = 0; q < n_q; ++q)
              source_points.push_back(internal::SourcePosition<Physics>::of(
                phys, Point<1>(x_left[c] + h[c] * points[q])));
        }
      setup_blending();
    }

    bool
    set_subcell_blending(const double alpha_max) override
    {
      blend.alpha_max = alpha_max;
      setup_blending();
      return true;
    }

    const std::vector<double> &
    blending_factors() const override
    {
      return alpha;
    }

    void
    initialize_vector(VectorType &v) const override
    {
      v.reinit(n_dofs);
    }

    /// dst = M^{-1} R(t, src)
    void
    apply(const double t, const VectorType &src, VectorType &dst) const override
    {
      dispatch([&](auto nm) {
        apply_impl<decltype(nm)::value>(t, src.begin(), RateWriter{dst.begin()});
      });
    }

    /// One Runge-Kutta stage in one pass (dg::StageUpdate; dst may be src or
    /// s.old): the same values as apply() and the vector operations.
    void
    apply_stage(const double t, const VectorType &src, VectorType &dst,
                const StageUpdate<> &s) const override
    {
      const double *u   = src.begin();
      double       *out = dst.begin();
      // cells this step leaves out keep their state in every stage
      if (active && out != u)
        for (const auto &[first, end] : active->newly_left_out_ranges())
          std::copy(u + first * n_components * n_modes, u + end * n_components * n_modes,
                    out + first * n_components * n_modes);
      dispatch([&](auto nm) {
        constexpr unsigned int n = decltype(nm)::value;
        // the branch on s.old outside the cell loop
        if (s.old)
          apply_impl<n>(t, u, StageWriter<true>{u, s.old->begin(), out, s.alpha, s.beta, s.gamma});
        else
          apply_impl<n>(t, u, StageWriter<false>{u, nullptr, out, s.alpha, s.beta, s.gamma});
      });
    }

    double
    max_speed_over_h(const VectorType &u, const double min_speed) const override
    {
      return dispatch([&](auto nm) { return max_speed_impl<decltype(nm)::value>(u.begin(), min_speed); });
    }

    AdmissibilityReport
    check_admissibility(const VectorType &u) const override
    {
      AdmissibilityReport report;
      // the fast scan (mode loops unrolled); the report from the first failure
      const unsigned int first_bad =
        dispatch([&](auto nm) { return first_inadmissible<decltype(nm)::value>(u.begin()); });
      for (unsigned int c = first_bad; c < n_cells; ++c)
        for (unsigned int q = 0; q < n_q && (!active || active->computes(c)); ++q)
          {
            const auto U = state_at(u, c, q);
            if (!admissible(phys, U, coefficients[c]))
              {
                report.ok          = false;
                report.reason      = phys.admissibility_violation(U, coefficients[c]);
                report.position[0] = x_left[c] + h[c] * points[q];
                report.state.assign(U.begin_raw(), U.end_raw());
                return report;
              }
          }
      return report;
    }

    bool
    restrict_to(const ActiveCells *cells) override
    {
      active = cells;
      cell_speed.clear();
      return true;
    }

    const Physics &
    physics() const
    {
      return phys;
    }

    /// Whether apply() may run cells in SIMD batches (true; false: cell by
    /// cell, the kernel of the scalar build, for tests/unit/line_batches).
    void
    set_simd_batches(const bool on)
    {
      simd_batches = on;
    }

  private:
    static constexpr unsigned int max_modes = 5;
    using VA                                = VectorizedArray<double>;

    /// apply_impl()'s writer of plain rates (apply()): dst[i] = rate
    struct RateWriter
    {
      double *dst;
      void
      operator()(const std::size_t i, const double rate) const
      {
        dst[i] = rate;
      }
      template <unsigned int n>
      void
      cells(const std::size_t i, const VA (&rate)[n]) const
      {
        store_cell_major(rate, dst + i);
      }
    };
    /// cells per SIMD batch of apply_range() (the native width of the SIMD
    /// build, 1 without it)
    static constexpr unsigned int batch_width = VA::size();
    /// Whether apply_range() runs the interior cells in SIMD batches: with
    /// more than one lane, and when source() takes the position as a point
    /// (a physics' own source_position() type has no batched form here).
    static constexpr bool batched =
      batch_width > 1 &&
      std::is_same_v<typename internal::SourcePosition<Physics>::type, Point<1>>;

    /// f(std::integral_constant<unsigned int, n_modes>()): the mode loops of
    /// the per-point kernels unrolled for the degree at hand
    template <typename F>
    decltype(auto)
    dispatch(const F &f) const
    {
      return with_n_modes(n_modes, f);
    }

    /// The modes of the cells c .. c + W - 1 (lane l: cell c + l) and
    /// their coefficients, for the SIMD batches.
    template <unsigned int nm>
    DEAL_II_ALWAYS_INLINE void
    load_batch(const double *src, const unsigned int c, VA (&u)[n_components * nm],
               Coefficients<VA> &a) const
    {
      constexpr unsigned int dpc = n_components * nm;
      load_cell_major(src + c * dpc, u);
      if constexpr (n_coefficients > 0)
        {
          unsigned int coefficient_offsets[batch_width];
          for (unsigned int l = 0; l < batch_width; ++l)
            coefficient_offsets[l] = l * n_coefficients;
          vectorized_load_and_transpose(n_coefficients, coefficients[c].data(),
                                        coefficient_offsets, a.data());
        }
    }

    /// The state at point q of the cells with modes u (double or a batch).
    template <unsigned int nm, typename Number>
    DEAL_II_ALWAYS_INLINE State<Number>
    point_state(const Number *u, const unsigned int q) const
    {
      State<Number> U;
      for (unsigned int i = 0; i < n_components; ++i)
        {
          Number s = 0.;
          for (unsigned int k = 0; k < nm; ++k)
            s += u[i * nm + k] * basis[q][k];
          U[i] = s;
        }
      return U;
    }

    /// The cells [first, end): SIMD batches through batch(c) (W cells from
    /// c) if batches, the rest cell by cell through single(c).
    template <bool batches, typename Batch, typename Single>
    void
    for_cells(const unsigned int first, const unsigned int end, const Batch &batch,
              const Single &single) const
    {
      unsigned int c = first;
      if constexpr (batches && batch_width > 1)
        for (; simd_batches && c + batch_width <= end; c += batch_width)
          batch(c);
      for (; c < end; ++c)
        single(c);
    }

    /// (in SIMD batches where apply() runs them: the hopper's wave speed
    /// rounds differently in its SIMD form, which moved its march by 7e-11)
    template <unsigned int nm>
    double
    max_speed_impl(const double *src, const double min_speed) const
    {
      // the largest speed of a cell, divided once by h: the same maximum
      // (division by h > 0 is monotone)
      const auto cell_value = [&](const auto *u, const auto &a, const auto &h_c) {
        using Number  = std::remove_cv_t<std::remove_reference_t<decltype(h_c)>>;
        Number cell_max = 0.;
        for (unsigned int q = 0; q < nm + 1; ++q)
          cell_max = std::max(cell_max, std::max(phys.max_wave_speed(point_state<nm>(u, q), a),
                                                 Number(min_speed)));
        return cell_max / h_c;
      };
      const auto single = [&](const unsigned int c) {
        return cell_value(src + c * n_components * nm, coefficients[c], h[c]);
      };
      const auto batch = [&](const unsigned int c) {
        VA               u[n_components * nm], h_c;
        Coefficients<VA> a;
        load_batch<nm>(src, c, u, a);
        h_c.load(&h[c]);
        return cell_value(u, a, h_c);
      };
      if (!active)
        {
          double result = 0;
          for_cells<batched>(
            0, n_cells,
            [&](const unsigned int c) {
              const VA speed = batch(c);
              for (unsigned int l = 0; l < batch_width; ++l)
                result = std::max(result, speed[l]);
            },
            [&](const unsigned int c) { result = std::max(result, single(c)); });
          return result;
        }
      // with active cells: refresh the cells the last step computed
      const auto refresh = [&](const unsigned int first, const unsigned int end) {
        for_cells<batched>(
          first, end, [&](const unsigned int c) { batch(c).store(&cell_speed[c]); },
          [&](const unsigned int c) { cell_speed[c] = single(c); });
      };
      if (cell_speed.size() != n_cells || min_speed != cell_speed_floor)
        {
          cell_speed.assign(n_cells, 0.);
          cell_speed_floor = min_speed;
          refresh(0, n_cells);
        }
      else
        for (const auto &[first, end] : active->ranges())
          refresh(first, end);
      return *std::max_element(cell_speed.begin(), cell_speed.end());
    }

    /// the first cell with an inadmissible point value (n_cells: none)
    template <unsigned int nm>
    unsigned int
    first_inadmissible(const double *src) const
    {
      // batches where the physics' is_admissible() takes them
      constexpr bool batches =
        internal::has_is_admissible<Physics, State<VA>, Coefficients<VA>>::value;
      unsigned int first_bad = n_cells;
      const auto   single    = [&](const unsigned int c) {
        if (first_bad == n_cells &&
            !points_admissible<nm>(src + c * n_components * nm, coefficients[c]))
          first_bad = c;
      };
      const auto batch = [&](const unsigned int c) {
        if constexpr (batches)
          {
            VA               u[n_components * nm];
            Coefficients<VA> a;
            load_batch<nm>(src, c, u, a);
            if (first_bad == n_cells && !points_admissible<nm>(u, a))
              for (unsigned int l = 0; l < batch_width; ++l)
                single(c + l);
          }
      };
      for_active_ranges(active, n_cells, [&](const unsigned int first, const unsigned int end) {
        for_cells<batches>(first, end, batch, single);
      });
      return first_bad;
    }

    /// Whether the states at all points of the cell with modes u (or of
    /// the batch) are admissible, without a branch per point.
    template <unsigned int nm, typename Number>
    bool
    points_admissible(const Number *u, const Coefficients<Number> &a) const
    {
      bool ok = true;
      for (unsigned int q = 0; q < nm + 1; ++q)
        ok &= admissible(phys, point_state<nm>(u, q), a);
      return ok;
    }

    std::size_t
    index(const unsigned int c, const unsigned int i, const unsigned int k) const
    {
      return (std::size_t(c) * n_components + i) * n_modes + k;
    }

    State<double>
    state_at(const LinearAlgebra::distributed::Vector<double> &u, const unsigned int c,
             const unsigned int q) const
    {
      State<double> U;
      for (unsigned int i = 0; i < n_components; ++i)
        for (unsigned int k = 0; k < n_modes; ++k)
          U[i] += u.local_element(index(c, i, k)) * basis[q][k];
      return U;
    }

    const BoundaryCondition<1> *
    find_bc(const types::boundary_id id) const
    {
      const auto it = boundary.find(id);
      AssertThrow(it != boundary.end(),
                  ExcMessage("no boundary condition for boundary id " + std::to_string(id)));
      return &it->second;
    }

    /// F*.n at a boundary face with interior trace U_m and outward normal n
    State<double>
    boundary_flux(const BoundaryCondition<1> &bc, const State<double> &U_m, const double n,
                  const double x, const double t, const Coefficients<double> &a) const
    {
      State<double> g;
      if (bc.data)
        {
          bc.data->set_time(t);
          for (unsigned int i = 0; i < n_components; ++i)
            g[i] = bc.data->value(Point<1>(x), i);
        }
      Tensor<1, 1> normal;
      normal[0]               = n;
      const State<double> U_p = phys.boundary_state(bc.kind, U_m, normal, g, a);
      return phys.numerical_flux(U_m, U_p, normal, a, a);
    }

    /// out(i, r) for every vector index i of the cells (of the active
    /// ones, if any) and its value r of M^{-1} R(t, src); a cell's entries
    /// after all reads of the cell and of its left neighbour's entries (so
    /// that out may overwrite src in place)
    template <unsigned int nm, typename Out>
    void
    apply_impl(const double t, const double *src, const Out &out) const
    {
      // the left trace of cell 0, the periodic partner of the last cell,
      // before any cell is overwritten
      State<double> first_left, unused;
      traces<nm>(src, 0, first_left, unused);
      if (blend.enabled())
        {
          raw_blending_factors<nm>(src);
          for_active_ranges(active, n_cells, [&](const unsigned int first, const unsigned int end) {
            apply_range<nm, true>(t, src, out, first, end, first_left);
          });
        }
      else
        for_active_ranges(active, n_cells, [&](const unsigned int first, const unsigned int end) {
          apply_range<nm, false>(t, src, out, first, end, first_left);
        });
    }

    /// traces of cell c at its left (xi = 0) and right (xi = 1) ends
    template <unsigned int nm>
    void
    traces(const double *src, const unsigned int c, State<double> &U0, State<double> &U1) const
    {
      const double *u = src + c * n_components * nm;
      for (unsigned int i = 0; i < n_components; ++i)
        {
          double s0 = 0, s1 = 0;
          for (unsigned int k = 0; k < nm; ++k)
            {
              const double x = u[i * nm + k];
              s0 += x * at_0[k];
              s1 += x * at_1[k];
            }
          U0[i] = s0;
          U1[i] = s1;
        }
    }

    /// apply_impl() on the cells [first, end), with subcell blending or not
    /// (without: the code of the engine before blending existed, so that
    /// the compiler's contraction into FMA stays as it was)
    template <unsigned int nm, bool blending, typename Out>
    void
    apply_range(const double t, const double *src, const Out &out, const unsigned int first,
                const unsigned int end, const State<double> &first_left) const
    {
      constexpr unsigned int nc = n_components, nq = nm + 1, dpc = nc * nm;
      Tensor<1, 1>           right;
      right[0] = 1.;

      // the flux through the left face of cell c (F*.n with n = +1, from
      // cell c-1 into c), kept from one cell to the next
      State<double> U0, U1, F_left;
      traces<nm>(src, first, U0, U1);
      if (first > 0 || periodic)
        {
          const unsigned int left = first > 0 ? first - 1 : n_cells - 1;
          State<double>      unused, U1_left;
          traces<nm>(src, left, unused, U1_left);
          F_left = phys.numerical_flux(U1_left, U0, right, coefficients[left], coefficients[first]);
        }
      else
        F_left = -boundary_flux(*left_bc, U0, -1., x_left[0], t, coefficients[0]);

      unsigned int c = first;
      if constexpr (batched && !blending)
        {
          // SIMD batches of cells in the range whose right neighbour exists
          // (it is only read); the rest cell by cell
          for (; simd_batches && c + batch_width < n_cells && c + batch_width <= end;
               c += batch_width)
            apply_batch<nm>(t, src, out, c, F_left);
          if (c != first)
            traces<nm>(src, c, U0, U1);
        }
      for (; c < end; ++c)
        {
          const double *u           = src + c * dpc;
          const auto   &a           = coefficients[c];
          double        res[nc][nm] = {};

          // volume: int F(u_h) phi_k' dx + int S(u_h) phi_k dx
          for (unsigned int q = 0; q < nq; ++q)
            {
              const auto         &B = basis[q];
              const auto         &D = derivative[q];
              const State<double> U = point_state<nm>(u, q);
              const auto          F = phys.flux(U, a);
              for (unsigned int i = 0; i < nc; ++i)
                {
                  const double wf = weights[q] * F[i][0];
                  for (unsigned int k = 0; k < nm; ++k)
                    res[i][k] += wf * D[k];
                }
              if constexpr (Physics::has_source_term)
                {
                  const auto S = phys.source(U, source_points[c * nq + q], t, a);
                  for (unsigned int i = 0; i < nc; ++i)
                    {
                      const double ws = h[c] * weights[q] * S[i];
                      for (unsigned int k = 0; k < nm; ++k)
                        res[i][k] += ws * B[k];
                    }
                }
            }

          // the right face: with the next cell, the periodic partner or the
          // boundary (U0, U1 hold the traces of cell c, V0, V1 those of c + 1)
          State<double> F_right, V0, V1;
          if (c + 1 < n_cells)
            {
              traces<nm>(src, c + 1, V0, V1);
              F_right = phys.numerical_flux(U1, V0, right, a, coefficients[c + 1]);
            }
          else if (periodic)
            F_right = phys.numerical_flux(U1, first_left, right, a, coefficients[0]);
          else
            F_right = boundary_flux(*right_bc, U1, 1., x_left[c] + h[c], t, a);

          // - [F* phi_k] over the cell: outward normal +1 on the right, -1 on the left
          const double inv_h   = inverse_h[c];
          const double blended = blending ? blending_factor(c) : 0.;
          if (blending && blended > 0)
            {
              // (1 - alpha) DG + alpha FV, the FV rate before any entry of
              // the cell is overwritten
              double fv[nc][nm];
              subcell_rate<nm>(u, c, t, F_left, F_right, fv);
              for (unsigned int i = 0; i < nc; ++i)
                for (unsigned int k = 0; k < nm; ++k)
                  out(c * dpc + i * nm + k,
                      (1. - blended) *
                          ((res[i][k] - F_right[i] * at_1[k] + F_left[i] * at_0[k]) * inv_h) +
                        blended * fv[i][k]);
            }
          else
            for (unsigned int i = 0; i < nc; ++i)
              for (unsigned int k = 0; k < nm; ++k)
                out(c * dpc + i * nm + k,
                    (res[i][k] - F_right[i] * at_1[k] + F_left[i] * at_0[k]) * inv_h);
          F_left = F_right;
          U0     = V0;
          U1     = V1;
        }
    }

    /// The cells [c, c + W) of apply_range() as one SIMD batch (lane l:
    /// cell c + l; c + W < n_cells): the same operations as the cell loop
    /// there, lane by lane. F_left is the flux through the batch's left
    /// face on entry and through its right face on return. Reads the cells
    /// c .. c + W before it writes c .. c + W - 1 (out may overwrite src).
    template <unsigned int nm, typename Out>
    void
    apply_batch(const double t, const double *src, const Out &out, const unsigned int c,
                State<double> &F_left) const
    {
      constexpr unsigned int nc = n_components, nq = nm + 1, dpc = nc * nm, W = batch_width;
      // the modes of the cells c + l (u) and c + 1 + l (v), their coefficients
      VA               u[dpc], v[dpc];
      Coefficients<VA> a, a_next;
      load_batch<nm>(src, c, u, a);
      load_batch<nm>(src, c + 1, v, a_next);
      VA h_c;
      h_c.load(&h[c]);

      VA res[nc][nm] = {};
      for (unsigned int q = 0; q < nq; ++q)
        {
          const auto     &B = basis[q];
          const auto     &D = derivative[q];
          const State<VA> U = point_state<nm>(u, q);
          const auto      F = phys.flux(U, a);
          for (unsigned int i = 0; i < nc; ++i)
            {
              const VA wf = weights[q] * F[i][0];
              for (unsigned int k = 0; k < nm; ++k)
                res[i][k] += wf * D[k];
            }
          if constexpr (Physics::has_source_term)
            {
              Point<1, VA> x;
              for (unsigned int l = 0; l < W; ++l)
                x[0][l] = source_points[(c + l) * nq + q][0];
              const auto S = phys.source(U, x, t, a);
              for (unsigned int i = 0; i < nc; ++i)
                {
                  const VA ws = h_c * weights[q] * S[i];
                  for (unsigned int k = 0; k < nm; ++k)
                    res[i][k] += ws * B[k];
                }
            }
        }

      // the faces c + l | c + l + 1: right traces of u, left traces of v
      State<VA> U1, V0;
      for (unsigned int i = 0; i < nc; ++i)
        {
          VA s0 = 0., s1 = 0.;
          for (unsigned int k = 0; k < nm; ++k)
            {
              s1 += u[i * nm + k] * at_1[k];
              s0 += v[i * nm + k] * at_0[k];
            }
          U1[i] = s1;
          V0[i] = s0;
        }
      Tensor<1, 1, VA> right;
      right[0]                  = 1.;
      const State<VA> F_right   = phys.numerical_flux(U1, V0, right, a, a_next);
      State<VA>       F_left_va;
      for (unsigned int i = 0; i < nc; ++i)
        {
          F_left_va[i] = shift_lanes<true>(F_right[i], F_left[i]);
          F_left[i]    = F_right[i][W - 1];
        }

      VA inv_h;
      inv_h.load(&inverse_h[c]);
      VA rate[dpc];
      for (unsigned int i = 0; i < nc; ++i)
        for (unsigned int k = 0; k < nm; ++k)
          rate[i * nm + k] = (res[i][k] - F_right[i] * at_1[k] + F_left_va[i] * at_0[k]) * inv_h;
      out.template cells<dpc>(c * dpc, rate);
    }

    /// The tables of subcell blending for the degree (if it is on).
    void
    setup_blending()
    {
      if (!blend.enabled() || n_cells == 0)
        return;
      blend.reinit(n_modes, blend.alpha_max);
      raw_alpha.assign(n_cells, 0.);
      alpha.assign(n_cells, 0.);
      if constexpr (Physics::has_source_term)
        {
          subcell_points.clear();
          for (unsigned int c = 0; c < n_cells; ++c)
            for (unsigned int j = 0; j < n_modes; ++j)
              subcell_points.push_back(internal::SourcePosition<Physics>::of(
                phys, Point<1>(x_left[c] + h[c] * (j + 0.5) / n_modes)));
        }
    }

    /// The blending factors before smoothing of the cells this apply
    /// computes and their neighbours, from the state src (before any of it
    /// is overwritten).
    template <unsigned int nm>
    void
    raw_blending_factors(const double *src) const
    {
      constexpr unsigned int dpc = n_components * nm, ic = Physics::indicator_component;
      // round-off-sized values (ahead of a front) are not a shock: the
      // limiter's floor, a fraction of the largest cell mean of the variable
      double scale = 0;
      for (unsigned int c = 0; c < n_cells; ++c)
        scale = std::max(scale, std::abs(src[c * dpc + ic * nm]));
      const double floor  = indicator_floor_fraction * scale;
      const double floor2 = floor * floor;
      const auto   raw = [&](const unsigned int c) {
        raw_alpha[c] = blend.raw_factor<nm>(src + c * dpc + ic * nm, floor2);
      };
      for_active_ranges(active, n_cells, [&](const unsigned int first, const unsigned int end) {
        for (unsigned int c = first > 0 ? first - 1 : 0; c < std::min(end + 1, n_cells); ++c)
          raw(c);
        if (periodic && first == 0)
          raw(n_cells - 1);
        if (periodic && end == n_cells)
          raw(0);
      });
    }

    /// The smoothed blending factor of cell c (kept for the output):
    /// max(alpha_c, alpha_N / 2) over the neighbours N.
    double
    blending_factor(const unsigned int c) const
    {
      const unsigned int last = n_cells - 1;
      double             a    = raw_alpha[c];
      if (c > 0 || periodic)
        a = std::max(a, 0.5 * raw_alpha[c > 0 ? c - 1 : last]);
      if (c < last || periodic)
        a = std::max(a, 0.5 * raw_alpha[c < last ? c + 1 : 0]);
      alpha[c] = a;
      return a;
    }

    /// The first-order finite-volume rate of the p + 1 subcells of cell c
    /// (modes u), as Legendre modes: the physics' numerical flux between
    /// subcell means inside, the DG fluxes F_left, F_right at the faces,
    /// the source at the subcell centres.
    template <unsigned int nm>
    void
    subcell_rate(const double *u, const unsigned int c, const double t,
                 const State<double> &F_left, const State<double> &F_right,
                 double (&fv)[n_components][nm]) const
    {
      constexpr unsigned int nc = n_components;
      const auto            &a  = coefficients[c];
      Tensor<1, 1>           right;
      right[0] = 1.;
      std::array<State<double>, nm> mean;
      for (unsigned int j = 0; j < nm; ++j)
        for (unsigned int i = 0; i < nc; ++i)
          {
            double s = 0;
            for (unsigned int k = 0; k < nm; ++k)
              s += u[i * nm + k] * blend.to_subcells[j][k];
            mean[j][i] = s;
          }
      double        rate[nc][nm];
      State<double> F_minus = F_left;
      const double  scale   = nm / h[c];
      for (unsigned int j = 0; j < nm; ++j)
        {
          const State<double> F_plus =
            j + 1 < nm ? phys.numerical_flux(mean[j], mean[j + 1], right, a, a) : F_right;
          for (unsigned int i = 0; i < nc; ++i)
            rate[i][j] = -(F_plus[i] - F_minus[i]) * scale;
          if constexpr (Physics::has_source_term)
            {
              const auto S = phys.source(mean[j], subcell_points[c * nm + j], t, a);
              for (unsigned int i = 0; i < nc; ++i)
                rate[i][j] += S[i];
            }
          F_minus = F_plus;
        }
      for (unsigned int i = 0; i < nc; ++i)
        for (unsigned int k = 0; k < nm; ++k)
          {
            double s = 0;
            for (unsigned int j = 0; j < nm; ++j)
              s += blend.from_subcells[k][j] * rate[i][j];
            fv[i][k] = s;
          }
    }

    static constexpr unsigned int max_points = max_modes + 1;

    Physics                           phys;
    BoundaryMap<1>                    boundary;
    ModalLayout<1>                    layout;
    unsigned int                      n_cells = 0, n_modes = 1, n_q = 1;
    std::size_t                       n_dofs   = 0;
    bool                              periodic = false, simd_batches = true;
    const BoundaryCondition<1>       *left_bc = nullptr, *right_bc = nullptr;
    /// cell sizes, their inverses (computed once) and left ends
    std::vector<double>               h, inverse_h, x_left;
    /// Gauss points and weights on [0, 1]; basis[q][k] = L_k(x_q), derivative[q][k] = L_k'(x_q)
    std::array<double, max_points>    weights{}, points{};
    std::array<std::array<double, max_modes>, max_points> basis{}, derivative{};
    std::array<double, max_modes>     at_0{}, at_1{};
    std::vector<Coefficients<double>> coefficients;
    /// the cells to compute (null: all), and the cached wave speeds / h of
    /// the cells with it (max_speed_impl) for the floor cell_speed_floor
    const ActiveCells                *active = nullptr;
    mutable std::vector<double>       cell_speed;
    mutable double                    cell_speed_floor = 0;
    /// the position argument of source() at every quadrature point
    std::vector<typename internal::SourcePosition<Physics>::type> source_points;
    /// subcell blending: its tables, the factors of the last apply() before
    /// and after smoothing, the source positions of the subcell centres
    SubcellBlending                                               blend;
    mutable std::vector<double>                                   raw_alpha, alpha;
    std::vector<typename internal::SourcePosition<Physics>::type> subcell_points;
  };
} // namespace granular_dg::dg
