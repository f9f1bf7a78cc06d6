// The network engine's output, single run and convergence study for the
// scalar laws of this scene.
#include <granular_dg/equations/network/system.h>
#include <granular_dg/network/output.templates.h>

namespace granular_dg::network
{
  template SnapshotFiles
  NetworkProblem<EdgeLaw>::write_snapshot(const std::string &, unsigned int, double);

  template RunResult
  run_network(const Graph &, std::vector<EdgeLaw>, const std::vector<EdgeData> &,
              const dg::DiscretizationParameters &, const NetworkOptions &, const ExactSolution *,
              const RunParameters &, bool, const std::string &);

  template void
  run_network_convergence(const Graph &, const std::vector<EdgeLaw> &,
                          const std::vector<EdgeData> &, const dg::DiscretizationParameters &,
                          const NetworkOptions &, const ExactSolution &, const RunParameters &);
} // namespace granular_dg::network
