#pragma once

// Explicit instantiation of the engine and the driver for one (dim, Physics);
// included by one translation unit per pair, so each template is compiled once.

#include <granular_dg/base/simulation.templates.h>
#include <granular_dg/dg/dg_operator.templates.h>
#include <granular_dg/dg/limiter.templates.h>

#define GRANULAR_DG_INSTANTIATE(DIM, PHYSICS)                                      \
  template class granular_dg::dg::DGOperator<DIM, PHYSICS>;                       \
  template class granular_dg::dg::ModalLimiter<DIM, PHYSICS>;                     \
  template granular_dg::RunResult granular_dg::run_simulation<DIM, PHYSICS>(      \
    const granular_dg::SceneData<DIM, PHYSICS> &,                                 \
    const granular_dg::CommonParameters &, unsigned int, bool, double);           \
  template void granular_dg::run_convergence_study<DIM, PHYSICS>(                 \
    const std::function<granular_dg::SceneData<DIM, PHYSICS>(unsigned int)> &,    \
    const granular_dg::CommonParameters &);
