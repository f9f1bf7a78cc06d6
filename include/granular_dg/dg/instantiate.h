#pragma once

// Explicit instantiation of the engine and the solver for one (dim, Physics);
// included by one translation unit per pair, so each template is compiled once.
// The per-step kernels of DGOperator in 2D are compiled per degree, each in
// its own translation unit (instantiate_2d_p<K>.cc, 1.4-1.5 GB of compiler
// memory each): GRANULAR_DG_INSTANTIATE declares them extern, and
// GRANULAR_DG_INSTANTIATE_KERNELS (instantiate_kernels.h) instantiates one.
// In 1D the run-time-degree kernels are instantiated with the operator.

#include <granular_dg/dg/dg_operator.templates.h>
#include <granular_dg/dg/limiter.templates.h>
#include <granular_dg/dg/solver.templates.h>

#define GRANULAR_DG_EXTERN_KERNELS(DIM, PHYSICS, DEGREE)                           \
  extern template struct granular_dg::dg::internal::DGKernels<DIM, PHYSICS, DEGREE>;

#define GRANULAR_DG_INSTANTIATE(DIM, PHYSICS)                                      \
  GRANULAR_DG_EXTERN_KERNELS(DIM, PHYSICS, 0)                                      \
  GRANULAR_DG_EXTERN_KERNELS(DIM, PHYSICS, 1)                                      \
  GRANULAR_DG_EXTERN_KERNELS(DIM, PHYSICS, 2)                                      \
  GRANULAR_DG_EXTERN_KERNELS(DIM, PHYSICS, 3)                                      \
  GRANULAR_DG_EXTERN_KERNELS(DIM, PHYSICS, 4)                                      \
  template class granular_dg::dg::DGOperator<DIM, PHYSICS>;                       \
  template class granular_dg::dg::ModalLimiter<DIM, PHYSICS>;                     \
  template class granular_dg::dg::Solver<DIM, PHYSICS>;                           \
  template granular_dg::RunResult granular_dg::dg::run_simulation<DIM, PHYSICS>(  \
    const granular_dg::dg::SceneData<DIM, PHYSICS> &,                             \
    const granular_dg::RunParameters &,                                           \
    const granular_dg::dg::DiscretizationParameters &, bool, double,              \
    granular_dg::dg::VectorType *);                                               \
  template void granular_dg::dg::require_scheme_fits<DIM, PHYSICS>(               \
    const granular_dg::dg::DiscretizationParameters &,                            \
    const granular_dg::dg::SceneData<DIM, PHYSICS> &);                            \
  template void granular_dg::dg::run_convergence_study<DIM, PHYSICS>(             \
    const std::function<granular_dg::dg::SceneData<DIM, PHYSICS>(unsigned int)> &, \
    const granular_dg::RunParameters &,                                           \
    const granular_dg::dg::DiscretizationParameters &);
