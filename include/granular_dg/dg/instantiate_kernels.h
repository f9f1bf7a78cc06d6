#pragma once

// The per-step kernels of DGOperator<DIM, PHYSICS> compiled for one degree
// (see instantiate.h); one translation unit per degree keeps the build
// parallel and the compiler's memory per unit at 1.4-1.5 GB.

#include <granular_dg/dg/dg_operator.templates.h>

#define GRANULAR_DG_INSTANTIATE_KERNELS(DIM, PHYSICS, DEGREE)                       \
  template struct granular_dg::dg::internal::DGKernels<DIM, PHYSICS, DEGREE>;
