// The network engine (NetworkProblem) for the scalar laws of this scene.
#include <granular_dg/equations/network/system.h>
#include <granular_dg/network/network.templates.h>

template class granular_dg::network::NetworkProblem<granular_dg::network::EdgeLaw>;
