#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <granular_dg/base/run_parameters.h>
#include <granular_dg/dg/parameters.h>

#include <string>

namespace granular_dg::skeleton
{
  using namespace dealii;

  /// What the skeleton scene reads from the prm file (subsections Mesh,
  /// Physics, Initial condition), parsed and checked once.
  struct SkeletonParameters
  {
    int            dim   = 1;
    unsigned int   cells = 16; ///< per direction of the unit square
    Tensor<1, 2>   velocity;
    std::string    initial = "sin(2*pi*x)";
    bool           periodic = true;

    /// Every entry, declared and read in one place (ParameterBinding; the
    /// defaults are the initial values above).
    void
    bind(ParameterBinding &b, const RunParameters &run,
         const dg::DiscretizationParameters &method);

  private:
    void
    read_velocity(const std::string &text);
  };
} // namespace granular_dg::skeleton
