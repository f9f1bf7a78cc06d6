#pragma once

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/matrix_free/fe_evaluation.h>

#include <granular_dg/dg/dg_operator.h>

#include <limits>

namespace granular_dg::dg
{
  namespace internal
  {
    /// Gauss points per direction of the kernels of degree fe_degree
    /// (0: FEEvaluation takes them from the MatrixFree object).
    template <int fe_degree>
    constexpr int n_q_points_1d = fe_degree < 0 ? 0 : fe_degree + 2;

    template <int dim, typename Number, std::size_t width>
    Point<dim>
    lane_point(const Point<dim, VectorizedArray<Number, width>> &p, const unsigned int v)
    {
      Point<dim> x;
      for (int d = 0; d < dim; ++d)
        x[d] = p[d][v];
      return x;
    }

    /// sum_d |row_d(J^{-1})| of phi's cell batch (affine cells: the same at
    /// every point), the wave-speed scan's 1/h
    template <typename VA, typename Eval>
    VA
    sum_inverse_h(const Eval &phi)
    {
      constexpr int dim       = Eval::dimension;
      const auto    inv_jac   = phi.inverse_jacobian(0);
      VA            sum_inv_h = 0.;
      for (int d = 0; d < dim; ++d)
        {
          VA row = 0.;
          for (int e = 0; e < dim; ++e)
            row += inv_jac[d][e] * inv_jac[d][e];
          sum_inv_h += std::sqrt(row);
        }
      return sum_inv_h;
    }

    /// FEEvaluation returns a scalar (not a Tensor) for one component;
    /// these adapters let the kernels treat every system as a Tensor.
    template <int n, typename T, typename Eval>
    inline DEAL_II_ALWAYS_INLINE
    Tensor<1, n, T>
    get_state(const Eval &phi, const unsigned int q)
    {
      if constexpr (n == 1)
        {
          Tensor<1, 1, T> U;
          U[0] = phi.get_value(q);
          return U;
        }
      else
        return phi.get_value(q);
    }

    template <int n, int dim, typename T, typename Eval>
    inline DEAL_II_ALWAYS_INLINE
    void
    submit_flux(Eval &phi, const Tensor<1, n, Tensor<1, dim, T>> &F, const unsigned int q)
    {
      if constexpr (n == 1)
        phi.submit_gradient(F[0], q);
      else
        phi.submit_gradient(F, q);
    }

    template <int n, typename T, typename Eval>
    inline DEAL_II_ALWAYS_INLINE
    void
    submit_state(Eval &phi, const Tensor<1, n, T> &U, const unsigned int q)
    {
      if constexpr (n == 1)
        phi.submit_value(U[0], q);
      else
        phi.submit_value(U, q);
    }
  } // namespace internal

  template <int dim, typename Physics, int width>
  DGOperator<dim, Physics, width>::DGOperator(const Physics &physics, BoundaryMap<dim> bc)
    : phys(physics)
    , boundary(std::move(bc))
  {}

  template <int dim, typename Physics, int width>
  void
  DGOperator<dim, Physics, width>::reinit(const Mapping<dim>    &mapping,
                                   const DoFHandler<dim> &dof_handler)
  {
    degree = dof_handler.get_fe().degree;
    AssertThrow(max_compiled_degree < 0 || degree <= unsigned(max_compiled_degree),
                ExcMessage("the DG kernels in " + std::to_string(dim) +
                           "D are compiled for degrees 0-" +
                           std::to_string(max_compiled_degree) + ", not " +
                           std::to_string(degree)));
    const std::vector<Quadrature<1>> quadratures = {QGauss<1>(degree + 2)};
    const AffineConstraints<double> constraints;

    typename MatrixFree<dim, Number, VA>::AdditionalData additional_data;
    additional_data.mapping_update_flags =
      (update_gradients | update_JxW_values | update_quadrature_points |
       update_values);
    additional_data.mapping_update_flags_inner_faces =
      (update_JxW_values | update_quadrature_points | update_normal_vectors |
       update_values);
    additional_data.mapping_update_flags_boundary_faces =
      (update_JxW_values | update_quadrature_points | update_normal_vectors |
       update_values);
    additional_data.tasks_parallel_scheme =
      MatrixFree<dim, Number, VA>::AdditionalData::none;

    const std::vector<const DoFHandler<dim> *>          dof_handlers = {&dof_handler};
    const std::vector<const AffineConstraints<double> *> constraint_list = {&constraints};
    data.reinit(mapping, dof_handlers, constraint_list, quadratures, additional_data);

    // per-cell coefficients from the material ids, packed per batch
    cell_coefficients.resize(data.n_cell_batches());
    for (unsigned int cell = 0; cell < data.n_cell_batches(); ++cell)
      cell_coefficients[cell] =
        pack_coefficients(data.n_active_entries_per_cell_batch(cell), [&](const unsigned int v) {
          return data.get_cell_iterator(cell, v);
        });
    const unsigned int n_faces = data.n_inner_face_batches() + data.n_boundary_face_batches();
    face_coefficients_m.resize(n_faces);
    face_coefficients_p.resize(data.n_inner_face_batches());
    for (unsigned int face = 0; face < n_faces; ++face)
      {
        const unsigned int lanes = data.n_active_entries_per_face_batch(face);
        face_coefficients_m[face] = pack_coefficients(lanes, [&](const unsigned int v) {
          return data.get_face_iterator(face, v, true).first;
        });
        if (face < data.n_inner_face_batches())
          face_coefficients_p[face] = pack_coefficients(lanes, [&](const unsigned int v) {
            return data.get_face_iterator(face, v, false).first;
          });
      }

    // FE_DGQLegendre is orthonormal on the unit cell, so on affine cells the
    // mass matrix is |K| times the identity: its inverse is a diagonal vector
    data.initialize_dof_vector(inverse_mass_diagonal);
    FEEvaluation<dim, -1, 0, n_components, Number, VA> phi(data);
    for (unsigned int cell = 0; cell < data.n_cell_batches(); ++cell)
      {
        AssertThrow(data.get_mapping_info().get_cell_type(cell) <=
                      dealii::internal::MatrixFreeFunctions::affine,
                    ExcMessage("the DG engine assumes affine cells"));
        phi.reinit(cell);
        VA volume = 0.;
        for (unsigned int q = 0; q < phi.n_q_points; ++q)
          volume += phi.JxW(q);
        for (unsigned int i = 0; i < phi.dofs_per_cell; ++i)
          phi.begin_dof_values()[i] = VA(1.) / volume;
        phi.set_dof_values(inverse_mass_diagonal);
      }
    compress_inverse_mass(phi.dofs_per_cell);
    this->dof_handler = &dof_handler;
    if constexpr (dim > 1)
      blending.reinit(dof_handler, phys, boundary, blending_max);
    if (rest)
      reinit_cells_at_rest();
  }

  template <int dim, typename Physics, int width>
  bool
  DGOperator<dim, Physics, width>::skip_cells_at_rest(const double       tolerance,
                                                      const unsigned int reach)
  {
    rest = std::make_unique<CellsAtRest<dim, VA>>(tolerance, reach);
    if (dof_handler != nullptr)
      reinit_cells_at_rest();
    return true;
  }

  template <int dim, typename Physics, int width>
  void
  DGOperator<dim, Physics, width>::reinit_cells_at_rest()
  {
    rest->reinit(data, *dof_handler, [&](const types::boundary_id id) {
      const auto it = boundary.find(id);
      return it != boundary.end() && it->second.data != nullptr;
    });
    // the rest state is zero (Physics::zero_is_rest_state)
    FEEvaluation<dim, -1, 0, n_components, Number, VA> phi(data);
    rest_speed.resize(data.n_cell_batches());
    sum_inverse_h.resize(data.n_cell_batches());
    for (unsigned int cell = 0; cell < data.n_cell_batches(); ++cell)
      {
        phi.reinit(cell);
        sum_inverse_h[cell] = internal::sum_inverse_h<VA>(phi);
        rest_speed[cell]    = phys.max_wave_speed(State<VA>(), cell_coefficients[cell]);
      }
  }

  template <int dim, typename Physics, int width>
  void
  DGOperator<dim, Physics, width>::find_cells_at_rest(const VectorType &u)
  {
    if (rest)
      rest->find(u);
  }

  template <int dim, typename Physics, int width>
  void
  DGOperator<dim, Physics, width>::set_cell_updates_left_out(
    const std::pair<double, double> &counts)
  {
    // rank 0 holds the sums, so that cell_updates_left_out() adds up to them
    if (rest)
      rest->set_updates(Utilities::MPI::this_mpi_process(
                          data.get_vector_partitioner()->get_mpi_communicator()) == 0 ?
                          counts :
                          std::pair<double, double>(0., 0.));
  }

  template <int dim, typename Physics, int width>
  std::pair<double, double>
  DGOperator<dim, Physics, width>::cell_updates_left_out() const
  {
    if (!rest)
      return {0., 0.};
    const auto [left_out, all] = rest->updates();
    const MPI_Comm comm        = data.get_vector_partitioner()->get_mpi_communicator();
    return {Utilities::MPI::sum(left_out, comm), Utilities::MPI::sum(all, comm)};
  }

  template <int dim, typename Physics, int width>
  void
  DGOperator<dim, Physics, width>::compress_inverse_mass(const unsigned int n)
  {
    // one value per cell if the diagonal is constant on consecutive runs of
    // a cell's DoFs (DG numbering: always); the same products bit for bit
    dofs_per_cell                = n;
    const unsigned int n_entries = inverse_mass_diagonal.locally_owned_size();
    const double      *d         = inverse_mass_diagonal.begin();
    inverse_cell_volume.clear();
    bool uniform = n > 0 && n_entries % n == 0;
    for (unsigned int c = 0; uniform && c < n_entries / n; ++c)
      {
        for (unsigned int i = 1; i < n; ++i)
          uniform = uniform && d[c * n + i] == d[c * n];
        inverse_cell_volume.push_back(d[c * n]);
      }
    if (!uniform)
      {
        inverse_cell_volume = std::vector<double>();
        return;
      }
    inverse_mass_diagonal.reinit(0);
  }

  template <int dim, typename Physics, int width>
  template <typename CellOfLane>
  typename DGOperator<dim, Physics, width>::template Coefficients<VectorizedArray<double, width>>
  DGOperator<dim, Physics, width>::pack_coefficients(const unsigned int n_lanes,
                                              const CellOfLane  &cell_of_lane) const
  {
    Coefficients<VA> packed;
    if constexpr (n_coefficients > 0)
      {
        for (auto &a : packed)
          a = 0.;
        for (unsigned int v = 0; v < VA::size(); ++v)
          {
            // unused lanes repeat lane 0, so that they hold valid data
            const auto a = phys.coefficients(cell_of_lane(v < n_lanes ? v : 0)->material_id());
            for (unsigned int i = 0; i < n_coefficients; ++i)
              packed[i][v] = a[i];

          }
      }
    return packed;
  }

  template <int dim, typename Physics, int width>
  void
  DGOperator<dim, Physics, width>::initialize_vector(VectorType &vector) const
  {
    data.initialize_dof_vector(vector);
  }

  template <int dim, typename Physics, int width>
  template <typename F>
  decltype(auto)
  DGOperator<dim, Physics, width>::dispatch(const F &f) const
  {
    if constexpr (max_compiled_degree < 0 || width != VectorizedArray<double>::size())
      return f(internal::DGKernels<dim, Physics, -1, width>{*this});
    else
      {
        static_assert(max_compiled_degree == 4, "dispatch() lists the degrees 0-4");
        switch (degree)
          {
            case 0:
              return f(internal::DGKernels<dim, Physics, 0, width>{*this});
            case 1:
              return f(internal::DGKernels<dim, Physics, 1, width>{*this});
            case 2:
              return f(internal::DGKernels<dim, Physics, 2, width>{*this});
            case 3:
              return f(internal::DGKernels<dim, Physics, 3, width>{*this});
            default:
              // reinit() admits no other degree
              return f(internal::DGKernels<dim, Physics, 4, width>{*this});
          }
      }
  }

  template <int dim, typename Physics, int fe_degree, int width>
  void
  internal::DGKernels<dim, Physics, fe_degree, width>::apply(const VectorType &src,
                                                      VectorType       &dst) const
  {
    op.data.loop(&DGKernels::cell,
                 &DGKernels::face,
                 &DGKernels::boundary_face,
                 this,
                 dst,
                 src,
                 true,
                 MatrixFree<dim, double, VectorizedArray<double, width>>::DataAccessOnFaces::values,
                 MatrixFree<dim, double, VectorizedArray<double, width>>::DataAccessOnFaces::values);
  }

  template <int dim, typename Physics, int fe_degree, int width>
  void
  internal::DGKernels<dim, Physics, fe_degree, width>::cell(
    const MatrixFree<dim, double, VectorizedArray<double, width>> &,
    VectorType                                  &dst,
    const VectorType                            &src,
    const std::pair<unsigned int, unsigned int> &cell_range) const
  {
    constexpr unsigned int n_components = Physics::n_components;
    using VA                            = VectorizedArray<double, width>;
    FEEvaluation<dim, fe_degree, n_q_points_1d<fe_degree>, n_components, double, VA> phi(op.data);
    for (unsigned int cell = cell_range.first; cell < cell_range.second; ++cell)
      {
        if (op.left_out_cell_batch(cell))
          continue;
        phi.reinit(cell);
        phi.gather_evaluate(src, EvaluationFlags::values);
        const auto &a = op.cell_coefficients[cell];
        for (unsigned int q = 0; q < phi.n_q_points; ++q)
          {
            const auto U = get_state<n_components, VA>(phi, q);
            submit_flux<n_components, dim, VA>(phi, op.phys.flux(U, a), q);
            if constexpr (Physics::has_source_term)
              submit_state<n_components, VA>(
                phi, op.phys.source(U, phi.quadrature_point(q), op.time, a), q);
          }
        if constexpr (Physics::has_source_term)
          phi.integrate_scatter(EvaluationFlags::values |
                                  EvaluationFlags::gradients,
                                dst);
        else
          phi.integrate_scatter(EvaluationFlags::gradients, dst);
      }
  }

  template <int dim, typename Physics, int fe_degree, int width>
  void
  internal::DGKernels<dim, Physics, fe_degree, width>::face(
    const MatrixFree<dim, double, VectorizedArray<double, width>> &,
    VectorType                                  &dst,
    const VectorType                            &src,
    const std::pair<unsigned int, unsigned int> &face_range) const
  {
    constexpr unsigned int n_components = Physics::n_components;
    using VA                            = VectorizedArray<double, width>;
    using FaceEval =
      FEFaceEvaluation<dim, fe_degree, n_q_points_1d<fe_degree>, n_components, double, VA>;
    FaceEval phi_m(op.data, true);
    FaceEval phi_p(op.data, false);
    for (unsigned int face = face_range.first; face < face_range.second; ++face)
      {
        if (op.left_out_face_batch(face))
          continue;
        phi_m.reinit(face);
        phi_m.gather_evaluate(src, EvaluationFlags::values);
        phi_p.reinit(face);
        phi_p.gather_evaluate(src, EvaluationFlags::values);
        const auto &a_m = op.face_coefficients_m[face];
        const auto &a_p = op.face_coefficients_p[face];
        for (unsigned int q = 0; q < phi_m.n_q_points; ++q)
          {
            const auto F = op.phys.numerical_flux(get_state<n_components, VA>(phi_m, q),
                                                  get_state<n_components, VA>(phi_p, q),
                                                  phi_m.get_normal_vector(q),
                                                  a_m,
                                                  a_p);
            submit_state<n_components, VA>(phi_m, -F, q);
            submit_state<n_components, VA>(phi_p, F, q);
          }
        phi_m.integrate_scatter(EvaluationFlags::values, dst);
        phi_p.integrate_scatter(EvaluationFlags::values, dst);
      }
  }

  template <int dim, typename Physics, int fe_degree, int width>
  void
  internal::DGKernels<dim, Physics, fe_degree, width>::boundary_face(
    const MatrixFree<dim, double, VectorizedArray<double, width>> &,
    VectorType                                  &dst,
    const VectorType                            &src,
    const std::pair<unsigned int, unsigned int> &face_range) const
  {
    constexpr unsigned int n_components = Physics::n_components;
    using VA                            = VectorizedArray<double, width>;
    FEFaceEvaluation<dim, fe_degree, n_q_points_1d<fe_degree>, n_components, double, VA> phi(op.data,
                                                                                        true);
    for (unsigned int face = face_range.first; face < face_range.second; ++face)
      {
        if (op.left_out_face_batch(face))
          continue;
        phi.reinit(face);
        phi.gather_evaluate(src, EvaluationFlags::values);
        const auto bc_it = op.boundary.find(op.data.get_boundary_id(face));
        AssertThrow(bc_it != op.boundary.end(),
                    ExcMessage("no boundary condition for boundary id " +
                               std::to_string(op.data.get_boundary_id(face))));
        const BoundaryCondition<dim> &bc = bc_it->second;
        if (bc.data)
          bc.data->set_time(op.time);
        const auto &a = op.face_coefficients_m[face];

        for (unsigned int q = 0; q < phi.n_q_points; ++q)
          {
            const auto U_m = get_state<n_components, VA>(phi, q);
            const auto n   = phi.get_normal_vector(q);
            Tensor<1, n_components, VA> g;
            if (bc.data)
              {
                const auto x = phi.quadrature_point(q);
                for (unsigned int v = 0; v < VA::size(); ++v)
                  {
                    const Point<dim> p = lane_point<dim>(x, v);
                    for (unsigned int c = 0; c < n_components; ++c)
                      g[c][v] = bc.data->value(p, c);
                  }
              }
            const auto U_p = op.phys.boundary_state(bc.kind, U_m, n, g, a);
            const auto F   = op.phys.numerical_flux(U_m, U_p, n, a, a);
            submit_state<n_components, VA>(phi, -F, q);
          }
        phi.integrate_scatter(EvaluationFlags::values, dst);
      }
  }

  template <int dim, typename Physics, int fe_degree, int width>
  double
  internal::DGKernels<dim, Physics, fe_degree, width>::max_speed_over_h(const VectorType &solution,
                                                                 const double      min_speed) const
  {
    constexpr unsigned int n_components = Physics::n_components;
    using VA                            = VectorizedArray<double, width>;
    double result = 0;
    FEEvaluation<dim, fe_degree, n_q_points_1d<fe_degree>, n_components, double, VA> phi(op.data);
    for (unsigned int cell = 0; cell < op.data.n_cell_batches(); ++cell)
      {
        // affine cells (asserted in reinit()): J^{-1} is the same at every
        // point, and max_q (s_q * h) = (max_q s_q) * h in floating point
        VA local = 0.;
        if (op.rest_use != Operator<dim>::RestUse::off && op.rest->cell_batch_at_rest(cell))
          local = std::max(op.rest_speed[cell], VA(min_speed)) * op.sum_inverse_h[cell];
        else
          {
            phi.reinit(cell);
            phi.gather_evaluate(solution, EvaluationFlags::values);
            const VA    sum_inv_h = sum_inverse_h<VA>(phi);
            const auto &a         = op.cell_coefficients[cell];
            for (unsigned int q = 0; q < phi.n_q_points; ++q)
              local =
                std::max(local,
                         std::max(op.phys.max_wave_speed(get_state<n_components, VA>(phi, q), a),
                                  VA(min_speed)));
            local = local * sum_inv_h;
          }
        for (unsigned int v = 0; v < op.data.n_active_entries_per_cell_batch(cell); ++v)
          result = std::max(result, local[v]);
      }
    return result;
  }

  template <int dim, typename Physics, int fe_degree, int width>
  AdmissibilityReport
  internal::DGKernels<dim, Physics, fe_degree, width>::check_admissibility(
    const VectorType &solution) const
  {
    constexpr unsigned int n_components = Physics::n_components;
    using VA                            = VectorizedArray<double, width>;
    AdmissibilityReport report;
    FEEvaluation<dim, fe_degree, n_q_points_1d<fe_degree>, n_components, double, VA> phi(op.data);
    for (unsigned int cell = 0; cell < op.data.n_cell_batches(); ++cell)
      {
        // a batch the step leaves out keeps its state, which was at rest
        if (op.left_out_cell_batch(cell))
          continue;
        phi.reinit(cell);
        phi.gather_evaluate(solution, EvaluationFlags::values);
        const unsigned int lanes = op.data.n_active_entries_per_cell_batch(cell);
        for (unsigned int q = 0; q < phi.n_q_points; ++q)
          {
            const auto U = get_state<n_components, VA>(phi, q);
            for (unsigned int v = 0; v < lanes; ++v)
              {
                Tensor<1, n_components> u;
                for (unsigned int c = 0; c < n_components; ++c)
                  u[c] = U[c][v];
                const auto a = op.lane_coefficients(cell, v);
                if (!admissible(op.phys, u, a))
                  {
                    report.ok          = false;
                    report.reason      = op.phys.admissibility_violation(u, a);
                    const Point<dim> p = lane_point<dim>(phi.quadrature_point(q), v);
                    for (int d = 0; d < dim; ++d)
                      report.position[d] = p[d];
                    report.state.assign(u.begin_raw(), u.end_raw());
                    return report;
                  }
              }
          }
      }
    return report;
  }

  template <int dim, typename Physics, int width>
  void
  DGOperator<dim, Physics, width>::apply(const double      t,
                                  const VectorType &src,
                                  VectorType       &dst) const
  {
    time = t;
    dispatch([&](const auto &kernels) { kernels.apply(src, dst); });
    if (inverse_cell_volume.empty())
      dst.scale(inverse_mass_diagonal);
    else
      {
        // (the rate of a cell left out is zero)
        const unsigned int n    = dofs_per_cell;
        double            *x    = dst.begin();
        const auto         cells = [&](const std::size_t first, const std::size_t end) {
          for (std::size_t c = first; c < end; ++c)
            {
              const double v = inverse_cell_volume[c];
              for (unsigned int i = 0; i < n; ++i)
                x[c * n + i] *= v;
            }
        };
        if (rest_use == RestUse::step)
          for (const auto &[begin, end] : rest->computed_entries())
            cells(begin / n, end / n);
        else
          cells(0, inverse_cell_volume.size());
      }
    if constexpr (dim > 1)
      if (blending.enabled())
        blending.apply(t, src, dst);
  }

  template <int dim, typename Physics, int width>
  void
  DGOperator<dim, Physics, width>::apply_stage(const double time, const VectorType &src,
                                               VectorType &dst, const StageUpdate<> &s) const
  {
    if (rest_use != RestUse::step)
      return Operator<dim>::apply_stage(time, src, dst, s);
    VectorType &k = this->rate_vector(src, dst, s);
    apply(time, src, k);
    for (const auto &[begin, end] : rest->computed_entries())
      this->update_stage(src, dst, k, s, begin, end);
    if (&dst != &src)
      for (const auto &[begin, end] : rest->left_out_entries())
        std::copy(src.begin() + begin, src.begin() + end, dst.begin() + begin);
  }

  template <int dim, typename Physics, int width>
  double
  DGOperator<dim, Physics, width>::max_speed_over_h(const VectorType &solution,
                                             const double      min_speed) const
  {
    const double result =
      dispatch([&](const auto &kernels) { return kernels.max_speed_over_h(solution, min_speed); });
    return Utilities::MPI::max(result, solution.get_mpi_communicator());
  }

  template <int dim, typename Physics, int width>
  AdmissibilityReport
  DGOperator<dim, Physics, width>::check_admissibility(const VectorType &solution) const
  {
    AdmissibilityReport report =
      dispatch([&](const auto &kernels) { return kernels.check_admissibility(solution); });
    // every rank learns whether someone failed and gets the report of the
    // lowest failing rank (rank 0 prints it)
    return first_failure(report, solution.get_mpi_communicator());
  }
} // namespace granular_dg::dg
