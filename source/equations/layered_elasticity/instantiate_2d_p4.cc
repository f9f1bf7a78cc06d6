#include <granular_dg/dg/instantiate_kernels.h>
#include <granular_dg/equations/layered_elasticity/system.h>

GRANULAR_DG_INSTANTIATE_KERNELS(2, granular_dg::elasticity::System<2>, 4)
