// At degree 0, deal.II 9.4.1's Raviart-Thomas branch of the cell evaluation
// (never taken for FE_DGQLegendre) has arrays of zero rows, on which GCC 12
// reports -Warray-bounds in VectorizedArray's arithmetic: a false positive
// in unreachable code, silenced for this unit only.
#pragma GCC diagnostic ignored "-Warray-bounds"

#include <granular_dg/dg/instantiate_kernels.h>
#include <granular_dg/equations/layered_strip/system.h>

GRANULAR_DG_INSTANTIATE_KERNELS(2, granular_dg::layered_strip::System<2>, 0)
