#include <granular_dg/dg/instantiate.h>
#include <granular_dg/equations/skeleton/system.h>

GRANULAR_DG_INSTANTIATE(1, granular_dg::skeleton::System<1>)
GRANULAR_DG_INSTANTIATE(2, granular_dg::skeleton::System<2>)
