#pragma once

#include <granular_dg/dg/cell_points.h>
#include <granular_dg/dg/scene_data.h>
#include <granular_dg/equations/layered_strip/system.h>

#include <string>
#include <vector>

namespace granular_dg::layered_strip
{
  /**
   * What the layered strip measures: the range of the strain (at the Gauss
   * points and face centres of every cell), the jumps of stress and normal
   * velocity across material interfaces (traces at the face centres: the
   * interface-aware flux keeps them small), and in 2D the profile along a
   * line y = slice_y at every output time (slice-NNNN.csv, the cells the
   * line crosses gathered on rank 0).
   */
  template <int dim>
  class LayeredDiagnostics : public dg::SceneHooks<dim>
  {
  public:
    /// directory empty: no slice files; slice_y NaN: no slice (2D only)
    LayeredDiagnostics(const System<dim> &system, const std::string &directory, double slice_y);

    void
    initialize(const DoFHandler<dim> &, const Mapping<dim> &,
               const dg::ModalLayout<dim> &layout) override;
    void
    save(ByteWriter &w) override;
    void
    load(ByteReader &r) override;
    std::vector<std::string>
    timeseries_names() const override;
    std::vector<double>
    timeseries_values(const dg::VectorType &U, double t) override;
    void
    finish(const dg::VectorType &U, double t, JsonObject &diagnostics, const std::string &,
           bool) override;

  private:
    struct Diagnosis
    {
      double min_strain = 0, max_strain = 0, stress_jump_max = 0, stress_jump_mean = 0,
             velocity_jump_max = 0;
    };

    void
    setup_slice();
    void
    write_slice(const dg::VectorType &U, double t);
    Diagnosis
    diagnose(const dg::VectorType &solution) const;

    const System<dim>                system;
    const std::string                directory;
    const double                     slice_y;
    const dg::ModalLayout<dim>      *layout = nullptr;
    dg::CellPoints<dim>              points;
    std::vector<unsigned int>        slice_cells;
    std::vector<std::vector<double>> slice_y_values, slice_x_values;
    unsigned int                     n_slices = 0;
  };
} // namespace granular_dg::layered_strip
