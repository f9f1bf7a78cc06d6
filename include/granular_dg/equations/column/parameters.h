#pragma once

#include <deal.II/base/parameter_handler.h>

#include <granular_dg/base/run_parameters.h>
#include <granular_dg/dg/parameters.h>
#include <granular_dg/equations/column/system.h>

namespace granular_dg::column
{
  using namespace dealii;

  /// Everything the column scene reads from the prm file (subsections
  /// Physics, Mesh, Diagnostics): each entry declared, read and checked in
  /// bind() (ParameterBinding; the defaults are the initial values here).
  struct ColumnParameters
  {
    Parameters   physics;
    double       u_b             = -1.;
    double       length          = 40.;
    unsigned int cells           = 1600;
    double       sample_dt       = 0.;
    double       threshold       = 1e-3;
    double       probe           = 0.5;
    bool         closed_form     = false;
    bool         write_sgn_map   = true;
    bool         closed_end      = false;
    bool         printed_weights = false;

    /// (the closed form's range depends on Time stepping/final time)
    void
    bind(ParameterBinding &b, const RunParameters &run,
         const dg::DiscretizationParameters &method);
  };
} // namespace granular_dg::column
