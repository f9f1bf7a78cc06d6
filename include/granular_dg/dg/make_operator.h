#pragma once

#include <deal.II/base/mpi.h>

#include <granular_dg/dg/boundary.h>
#include <granular_dg/dg/dg_operator.h>
#include <granular_dg/dg/line_operator.h>
#include <granular_dg/dg/operator.h>

#include <memory>

namespace granular_dg::dg
{
  /// The operator of an engine: the line engine for serial 1D runs (or when
  /// asked for), MatrixFree otherwise. (DGOperator<dim, Physics> is
  /// instantiated with GRANULAR_DG_INSTANTIATE in the physics' folder.)
  /// Whether a run of dimension dim with this Discretization/engine gets the
  /// line engine: 1D and engine line, or auto in a serial run.
  inline bool
  runs_line_engine(const int dim, const Engine engine)
  {
    return dim == 1 &&
           (engine == Engine::line ||
            (engine == Engine::automatic && (!Utilities::MPI::job_supports_mpi() ||
                                             Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) == 1)));
  }

  template <int dim, typename Physics>
  std::unique_ptr<Operator<dim>>
  make_operator(const Engine engine, const Physics &physics, const BoundaryMap<dim> &bc)
  {
    if constexpr (dim == 1)
      if (runs_line_engine(dim, engine))
        return std::make_unique<LineOperator<Physics>>(physics, bc);
    return std::make_unique<DGOperator<dim, Physics>>(physics, bc);
  }
} // namespace granular_dg::dg
