// The network engine's line operator for the scalar laws of this scene (a
// unit of its own: its kernels compiled alone).
#include <granular_dg/equations/network/system.h>
#include <granular_dg/network/edge_lines.templates.h>

template class granular_dg::network::EdgeLines<granular_dg::network::EdgeLaw>;
