#include <granular_dg/dg/instantiate.h>
#include <granular_dg/equations/hopper/system.h>

GRANULAR_DG_INSTANTIATE(1, granular_dg::hopper::System)
