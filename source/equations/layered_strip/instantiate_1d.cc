#include <granular_dg/dg/instantiate.h>
#include <granular_dg/equations/layered_strip/system.h>

GRANULAR_DG_INSTANTIATE(1, granular_dg::layered_strip::System<1>)
