#include <granular_dg/dg/operator.h>

#include <boost/serialization/string.hpp>
#include <boost/serialization/utility.hpp>
#include <boost/serialization/vector.hpp>

namespace granular_dg::dg
{
  AdmissibilityReport
  first_failure(AdmissibilityReport report, const MPI_Comm comm)
  {
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(comm);
    if (n_ranks == 1)
      return report;
    const unsigned int first =
      Utilities::MPI::min(report.ok ? n_ranks : Utilities::MPI::this_mpi_process(comm), comm);
    if (first == n_ranks)
      return report;
    std::vector<double> numbers = report.state;
    for (unsigned int d = 0; d < 3; ++d)
      numbers.push_back(report.position[d]);
    const auto data =
      Utilities::MPI::broadcast(comm, std::make_pair(report.reason, numbers), first);
    report.ok     = false;
    report.reason = data.first;
    report.state.assign(data.second.begin(), data.second.end() - 3);
    for (unsigned int d = 0; d < 3; ++d)
      report.position[d] = data.second[data.second.size() - 3 + d];
    return report;
  }
} // namespace granular_dg::dg
