#include <granular_dg/dg/instantiate.h>
#include <granular_dg/equations/network_scalar/system.h>

GRANULAR_DG_INSTANTIATE(1, granular_dg::network::System)
