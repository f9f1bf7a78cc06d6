#pragma once

#include <deal.II/base/function.h>

#include <string>
#include <vector>

namespace granular_dg::dg
{
  /**
   * A 1D discrete solution read back from a modes-NNNN.csv file (written with
   * Output/write modes = true): per cell x_left, h and the Legendre modes of
   * every component. It evaluates the DG polynomial exactly, so a fine run
   * serves as the reference solution of coarser ones (errors where no exact
   * solution is known). Time-independent: it is the reference at the time of
   * its file (`time()`).
   */
  class ModalReference : public dealii::Function<1>
  {
  public:
    /// n_components must match the file; errors name the file.
    ModalReference(const std::string &filename, unsigned int n_components);

    double
    value(const dealii::Point<1> &p, unsigned int component) const override;

    double
    time() const
    {
      return file_time;
    }

  private:
    unsigned int               n_modes = 1;
    double                     file_time = 0;
    std::vector<double>        x_left, h, modes; ///< modes[(cell * n_comp + c) * n_modes + k]
  };
} // namespace granular_dg::dg
