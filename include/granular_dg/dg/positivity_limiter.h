#pragma once

#include <deal.II/base/mpi.h>

#include <granular_dg/dg/cell_points.h>
#include <granular_dg/dg/scene_data.h>

#include <string>

namespace granular_dg::dg
{
  /**
   * The Zhang-Shu positivity limiter as a stage limiter: after the limiter
   * of every stage, the modes of component i above the mean are scaled by
   * theta = min(1, mean / (mean - low)) so that the component is >= 0 at
   * the Gauss points and face centres of every cell with a non-negative
   * mean (CellPoints); the mean, and so conservation, is kept. A cell whose
   * mean is below -tolerance is outside the admissible set the option
   * declares: the run stops there (check_admissibility()).
   */
  template <int dim>
  class PositivityLimiter : public SceneHooks<dim>
  {
  public:
    /// component: the limited component; name and symbol: its name and
    /// symbol in messages; parameter: the prm entry that switched it on
    PositivityLimiter(const unsigned int component, std::string name, std::string symbol,
                      std::string parameter, const double tolerance = 1e-10)
      : component(component)
      , name(std::move(name))
      , symbol(std::move(symbol))
      , parameter(std::move(parameter))
      , tolerance(tolerance)
    {}

    void
    initialize(const DoFHandler<dim> &, const Mapping<dim> &,
               const ModalLayout<dim> &cells) override
    {
      layout = &cells;
      points.reinit(cells);
    }

    std::string
    stage_operation() const override
    {
      return "the positivity limiter (" + parameter + ")";
    }

    void
    post_limiter(VectorType &u, double) override
    {
      for (unsigned int c = 0; c < layout->n_owned(); ++c)
        {
          const double mean = u.local_element(layout->index(c, component, 0));
          const double low  = points.min(u, c, component);
          // (a negative mean is outside the admissible set:
          // check_admissibility() stops the run)
          if (low >= 0. || mean <= 0.)
            continue;
          const double theta = std::min(1., mean / (mean - low));
          for (unsigned int m = 1; m < layout->n_modes(); ++m)
            u.local_element(layout->index(c, component, m)) *= theta;
          ++scaled_cells;
        }
    }

    AdmissibilityReport
    check_admissibility(const VectorType &u) const override
    {
      AdmissibilityReport report;
      for (unsigned int c = 0; c < layout->n_owned(); ++c)
        {
          // (round-off below -tolerance, e.g. ahead of a wave, is not a violation)
          if (u.local_element(layout->index(c, component, 0)) >= -tolerance)
            continue;
          report.ok    = false;
          const auto x = layout->cell(c)->center();
          for (int d = 0; d < dim; ++d)
            report.position[d] = x[d];
          for (unsigned int i = 0; i < layout->n_components(); ++i)
            report.state.push_back(u.local_element(layout->index(c, i, 0)));
          report.reason = "negative mean " + name + " with " + parameter +
                          " = true (the option declares " + symbol +
                          " >= 0; the scaling keeps the point values of a cell >= 0 only "
                          "while its mean is; the cell averages are shown)";
          break;
        }
      return report;
    }

    void
    save(ByteWriter &w) override
    {
      // summed over the ranks: the state of the whole run
      unsigned long long scaled = Utilities::MPI::sum(scaled_cells, MPI_COMM_WORLD);
      w.io(scaled);
    }

    void
    load(ByteReader &r) override
    {
      r.io(scaled_cells);
      // every rank read rank 0's sum; one of them keeps it
      if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
        scaled_cells = 0;
    }

    void
    finish(const VectorType &u, double, JsonObject &diagnostics, const std::string &,
           bool) override
    {
      diagnostics.add("positivity_scaled_cell_stages",
                      static_cast<long long>(
                        Utilities::MPI::sum(scaled_cells, u.get_mpi_communicator())));
    }

  private:
    const unsigned int      component;
    const std::string       name, symbol, parameter;
    const double            tolerance;
    const ModalLayout<dim> *layout = nullptr;
    CellPoints<dim>         points;
    unsigned long long      scaled_cells = 0;
  };
} // namespace granular_dg::dg
