#pragma once

#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/matrix_free/matrix_free.h>

#include <granular_dg/dg/blended_cells.h>
#include <granular_dg/dg/cells_at_rest.h>
#include <granular_dg/dg/boundary.h>
#include <granular_dg/dg/numerical_flux.h>
#include <granular_dg/dg/operator.h>

#include <array>
#include <string>
#include <type_traits>

namespace granular_dg::dg
{
  using namespace dealii;
  template <int dim, typename Physics, int width = VectorizedArray<double>::size()>
  class DGOperator;

  namespace internal
  {
    /// Physics::max_compiled_degree if the physics sets it (-1: one
    /// run-time-degree instantiation of the kernels, cheap to compile), else
    /// the degrees 0-4 in 2D and the run-time degree in 1D.
    template <int dim, typename Physics, typename = void>
    struct MaxCompiledDegree
    {
      static constexpr int value = (dim == 1) ? -1 : 4;
    };
    template <int dim, typename Physics>
    struct MaxCompiledDegree<dim, Physics, std::void_t<decltype(Physics::max_compiled_degree)>>
    {
      static constexpr int value = (dim == 1) ? -1 : Physics::max_compiled_degree;
    };

    /// Physics::zero_is_rest_state if the physics sets it (the state zero
    /// has zero flux, zero numerical flux against itself and no source, with
    /// any coefficients: CellsAtRest may leave it out), else false.
    template <typename Physics, typename = void>
    struct ZeroIsRestState : std::false_type
    {};
    template <typename Physics>
    struct ZeroIsRestState<Physics, std::void_t<decltype(Physics::zero_is_rest_state)>>
      : std::bool_constant<Physics::zero_is_rest_state>
    {};
    template <typename Physics>
    inline constexpr bool zero_is_rest_state = ZeroIsRestState<Physics>::value;
  } // namespace internal

  namespace internal
  {
    /**
     * The loops of DGOperator that run in every time step (the operator's
     * cell, face and boundary kernels, the max wave speed, the admissibility
     * scan), compiled for one polynomial degree: FEEvaluation<dim, fe_degree,
     * fe_degree + 2>, so that the quadrature loops have fixed bounds and the
     * sum factorisation is inlined; fe_degree = -1 takes the degree at run
     * time. The members are defined in dg_operator.templates.h and
     * instantiated per degree (GRANULAR_DG_INSTANTIATE_KERNELS) in their own
     * translation units; DGOperator::dispatch() picks the one of its degree.
     */
    template <int dim, typename Physics, int fe_degree, int width = VectorizedArray<double>::size()>
    struct DGKernels
    {
      const DGOperator<dim, Physics, width> &op;

      /// dst = R(op.time, src) (before the inverse mass matrix)
      void
      apply(const VectorType &src, VectorType &dst) const;

      /// The largest max(lambda, min_speed) * sum_d |row_d J^{-1}| on this rank.
      double
      max_speed_over_h(const VectorType &solution, double min_speed) const;

      /// The first inadmissible quadrature point on this rank (cells, then
      /// points, then lanes).
      AdmissibilityReport
      check_admissibility(const VectorType &solution) const;

      void
      cell(const MatrixFree<dim, double, VectorizedArray<double, width>> &data,
           VectorType                                  &dst,
           const VectorType                            &src,
           const std::pair<unsigned int, unsigned int> &cell_range) const;
      void
      face(const MatrixFree<dim, double, VectorizedArray<double, width>> &data,
           VectorType                                  &dst,
           const VectorType                            &src,
           const std::pair<unsigned int, unsigned int> &face_range) const;
      void
      boundary_face(const MatrixFree<dim, double, VectorizedArray<double, width>> &data,
                    VectorType                                  &dst,
                    const VectorType                            &src,
                    const std::pair<unsigned int, unsigned int> &face_range) const;
    };
  } // namespace internal

  /**
   * Physics-free explicit DG operator on MatrixFree (after deal.II step-67):
   * dst = M^{-1} ( (F(U), grad v) - <F* . n, v> + (S(U), v) ) for a Physics
   * policy (the contract is in doc/engine.md): n_components, flux(),
   * max_wave_speed(), numerical_flux(U_m, U_p, n, a_m, a_p),
   * boundary_state(kind, U_m, n, g, a) and optionally source(). Every call
   * gets the per-cell coefficients a (Physics::coefficients(material_id),
   * e.g. density and modulus of a layer), stored per cell batch and lane and
   * per face batch side, so lanes of one batch may hold different materials.
   * The polynomial degree is a run-time value. The loops of every time step
   * run in internal::DGKernels: in 1D with the degree at run time
   * (FEEvaluation degree -1, one instantiation per Physics), in 2D compiled
   * for each degree 0-4 (max_compiled_degree); the setup uses the run-time
   * degree.
   *
   * The quadrature has degree+2 Gauss points per direction (over-integration
   * of the nonlinear flux). The Legendre basis is orthonormal, so on the
   * affine cells the engine accepts the inverse mass matrix is the diagonal
   * 1/|K|.
   *
   * width is the number of lanes of VectorizedArray<double, width>: the
   * machine's native width by default (cmake/simd.cmake). Another width (1:
   * the scalar operator of Debian's deal.II) runs the run-time-degree kernels
   * only; it exists to check the SIMD build (tests/performance/simd_widths_agree).
   */
  template <int dim, typename Physics, int width>
  class DGOperator : public Operator<dim>
  {
  public:
    static constexpr unsigned int n_components = Physics::n_components;
    using Number = double;
    static constexpr unsigned int n_coefficients = Physics::n_coefficients;
    /// The kernels are compiled for the degrees 0..max_compiled_degree (-1:
    /// none, the run-time-degree kernels serve every degree).
    static constexpr int max_compiled_degree = internal::MaxCompiledDegree<dim, Physics>::value;
    template <typename T>
    using State = Tensor<1, n_components, T>;
    template <typename T>
    using Coefficients = std::array<T, n_coefficients>;

    using RestUse = typename Operator<dim>::RestUse;

    DGOperator(const Physics &physics, BoundaryMap<dim> bc);

    std::string
    engine_name() const override
    {
      return "matrix_free";
    }

    std::size_t
    engine_memory() const override
    {
      const auto n = [](const auto &v) { return v.capacity() * sizeof(v[0]); };
      return data.memory_consumption() + n(inverse_cell_volume) +
             inverse_mass_diagonal.memory_consumption() + n(cell_coefficients) +
             n(face_coefficients_m) + n(face_coefficients_p) + blending.memory_consumption() +
             (rest ? rest->memory_consumption() + n(rest_speed) + n(sum_inverse_h) : 0);
    }

    /// Subcell blending (BlendedCells) on axis-aligned Cartesian meshes in
    /// 2D; false in 1D (the line engine blends there).
    bool
    set_subcell_blending(const double alpha_max) override
    {
      if constexpr (dim == 1)
        return false;
      else
        {
          blending_max = alpha_max;
          if (dof_handler != nullptr)
            blending.reinit(*dof_handler, phys, boundary, blending_max);
          return true;
        }
    }

    bool
    skip_cells_at_rest(double tolerance, unsigned int reach) override;

    void
    find_cells_at_rest(const VectorType &u) override;

    void
    use_cells_at_rest(const RestUse use) const override
    {
      rest_use = rest ? use : RestUse::off;
      if (rest_use == RestUse::step)
        rest->count_step();
    }

    std::pair<double, double>
    cell_updates_left_out() const override;

    void
    set_cell_updates_left_out(const std::pair<double, double> &counts) override;

    const std::vector<double> &
    blending_factors() const override
    {
      return blending.factors();
    }

    void
    reinit(const Mapping<dim> &mapping, const DoFHandler<dim> &dof_handler) override;

    void
    initialize_vector(VectorType &vector) const override;

    /// dst = M^{-1} R(t, src)
    void
    apply(double time, const VectorType &src, VectorType &dst) const override;

    /// Operator::apply_stage(); while a step leaves out cells at rest, the
    /// stage updates only the entries of the computed cells, and the others
    /// keep the source's values.
    void
    apply_stage(double time, const VectorType &src, VectorType &dst,
                const StageUpdate<> &s) const override;

    /// max over quadrature points of max(lambda(U), min_speed) *
    /// sum_d |row_d(J^{-1})|; the stable step is CFL / this value.
    double
    max_speed_over_h(const VectorType &solution, double min_speed) const override;

    /// Check every quadrature point against the Physics'
    /// admissibility_violation(); the first failure is reported.
    AdmissibilityReport
    check_admissibility(const VectorType &solution) const override;

    const MatrixFree<dim, Number, VectorizedArray<Number, width>> &
    matrix_free() const
    {
      return data;
    }

    const Physics &
    physics() const
    {
      return phys;
    }

    /// The coefficients of lane v of cell batch `cell`.
    Coefficients<double>
    lane_coefficients(const unsigned int cell, const unsigned int v) const
    {
      Coefficients<double> a;
      for (unsigned int i = 0; i < n_coefficients; ++i)
        a[i] = cell_coefficients[cell][i][v];
      return a;
    }

  private:
    template <int, typename, int, int>
    friend struct internal::DGKernels;
    using VA = VectorizedArray<Number, width>;

    /// f(kernels) with the kernels compiled for the degree of the element.
    template <typename F>
    decltype(auto)
    dispatch(const F &f) const;

    /// The coefficients of the cells behind the lanes of a batch, packed.
    template <typename CellOfLane>
    Coefficients<VA>
    pack_coefficients(const unsigned int n_lanes, const CellOfLane &cell_of_lane) const;

    /// inverse_mass_diagonal -> inverse_cell_volume where possible
    void
    compress_inverse_mass(unsigned int dofs_per_cell);

    Physics                 phys;
    BoundaryMap<dim>        boundary;
    MatrixFree<dim, Number, VA> data;
    /// The inverse mass matrix: 1/|K| per owned cell (its DoFs are the
    /// vector's entries [c n, (c + 1) n), n = dofs_per_cell); the diagonal
    /// as a vector only where that does not hold (then inverse_cell_volume
    /// is empty).
    std::vector<double>     inverse_cell_volume;
    VectorType              inverse_mass_diagonal;
    unsigned int            dofs_per_cell = 0;
    unsigned int            degree = 0;
    /// per cell batch; per face batch, interior (m) and exterior (p) side
    std::vector<Coefficients<VA>> cell_coefficients, face_coefficients_m,
      face_coefficients_p;
    mutable double time = 0.;
    /// the cells at rest (Time stepping/skip cells at rest; null: off), how
    /// the kernels use them now, and per cell batch the rest state's wave
    /// speed and sum_d |row_d(J^{-1})| (the wave-speed scan of a batch at rest)
    std::unique_ptr<CellsAtRest<dim, VA>> rest;
    mutable RestUse                       rest_use = RestUse::off;
    std::vector<VA>                       rest_speed, sum_inverse_h;
    /// whether the kernels leave out cell batch b or face batch f
    bool
    left_out_cell_batch(const unsigned int b) const
    {
      return rest_use == RestUse::step && !rest->cell_batch(b);
    }
    bool
    left_out_face_batch(const unsigned int f) const
    {
      return rest_use == RestUse::step && !rest->face_batch(f);
    }
    /// rest's tables for this mesh, and rest_speed and sum_inverse_h of
    /// every cell batch
    void
    reinit_cells_at_rest();
    /// subcell blending (2D; off while blending_max = 0)
    const DoFHandler<dim>           *dof_handler  = nullptr;
    double                           blending_max = 0.;
    BlendedCells<dim, Physics>       blending;
  };
} // namespace granular_dg::dg
