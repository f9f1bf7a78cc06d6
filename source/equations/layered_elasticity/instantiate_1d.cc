#include <granular_dg/dg/instantiate.h>
#include <granular_dg/equations/layered_elasticity/system.h>

GRANULAR_DG_INSTANTIATE(1, granular_dg::elasticity::System<1>)
