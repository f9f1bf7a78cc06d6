#include <granular_dg/dg/instantiate_kernels.h>
#include <granular_dg/equations/layered_strip/system.h>

GRANULAR_DG_INSTANTIATE_KERNELS(2, granular_dg::layered_strip::System<2>, 3)
