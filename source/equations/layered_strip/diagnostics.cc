#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <granular_dg/base/output.h>
#include <granular_dg/equations/layered_strip/diagnostics.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace granular_dg::layered_strip
{
  template <int dim>
  LayeredDiagnostics<dim>::LayeredDiagnostics(const System<dim> &system,
                                              const std::string &directory, const double slice_y)
    : system(system)
    , directory(directory)
    , slice_y(slice_y)
  {}

  template <int dim>
  void
  LayeredDiagnostics<dim>::initialize(const DoFHandler<dim> &, const Mapping<dim> &,
                                      const dg::ModalLayout<dim> &cells)
  {
    layout = &cells;
    points.reinit(cells);
    if (dim == 2 && std::isfinite(slice_y) && !directory.empty())
      setup_slice();
  }

  /// the cells the slice y = slice_y runs through, and the Legendre values
  /// in y there and at p + 2 equally spaced points in x
  template <int dim>
  void
  LayeredDiagnostics<dim>::setup_slice()
  {
    const unsigned int n1d = layout->degree() + 1;
    for (unsigned int i = 0; i <= n1d; ++i)
      slice_x_values.push_back(dg::legendre_values(n1d, double(i) / n1d));
    for (unsigned int c = 0; c < layout->n_owned(); ++c)
      {
        const double y0 = layout->cell(c)->vertex(0)[1], hy = layout->extent(c, dim - 1);
        if (slice_y >= y0 && slice_y < y0 + hy)
          {
            slice_cells.push_back(c);
            slice_y_values.push_back(dg::legendre_values(n1d, (slice_y - y0) / hy));
          }
      }
  }

  template <int dim>
  void
  LayeredDiagnostics<dim>::save(ByteWriter &w)
  {
    w.io(n_slices);
  }

  template <int dim>
  void
  LayeredDiagnostics<dim>::load(ByteReader &r)
  {
    r.io(n_slices);
  }

  template <int dim>
  std::vector<std::string>
  LayeredDiagnostics<dim>::timeseries_names() const
  {
    return {"min_strain", "max_strain", "interface_stress_jump_max",
            "interface_stress_jump_mean", "interface_velocity_jump_max"};
  }

  template <int dim>
  std::vector<double>
  LayeredDiagnostics<dim>::timeseries_values(const dg::VectorType &U, const double t)
  {
    if (dim == 2 && std::isfinite(slice_y) && !directory.empty())
      write_slice(U, t);
    const auto d = diagnose(U);
    return {d.min_strain, d.max_strain, d.stress_jump_max, d.stress_jump_mean,
            d.velocity_jump_max};
  }

  template <int dim>
  void
  LayeredDiagnostics<dim>::finish(const dg::VectorType &U, double, JsonObject &diagnostics,
                                  const std::string &, bool)
  {
    const auto d = diagnose(U);
    diagnostics.add("min_strain", d.min_strain);
    diagnostics.add("max_strain", d.max_strain);
    diagnostics.add("interface_stress_jump_max", d.stress_jump_max);
    diagnostics.add("interface_stress_jump_mean", d.stress_jump_mean);
    diagnostics.add("interface_velocity_jump_max", d.velocity_jump_max);
  }

  /// slice-NNNN.csv: strain, stress and velocity along y = slice_y (all
  /// ranks' cells gathered on rank 0, sorted by x)
  template <int dim>
  void
  LayeredDiagnostics<dim>::write_slice(const dg::VectorType &U, const double t)
  {
    const unsigned int  n1d = layout->degree() + 1;
    std::vector<double> rows; // x, strain, stress, u, v
    for (unsigned int s = 0; s < slice_cells.size(); ++s)
      {
        const unsigned int c  = slice_cells[s];
        const double       x0 = layout->cell(c)->vertex(0)[0], hx = layout->extent(c, 0);
        const auto         a  = system.coefficients(layout->cell(c)->material_id());
        for (unsigned int i = 0; i <= n1d; ++i)
          {
            std::array<const double *, dim> v;
            v[0]           = slice_x_values[i].data();
            v[dim - 1]     = slice_y_values[s].data();
            const double eps = layout->value(U, c, 0, v);
            rows.insert(rows.end(), {x0 + hx * i / n1d, eps, system.stress(eps, a),
                                     layout->value(U, c, 1, v) / a[density],
                                     layout->value(U, c, dim, v) / a[density]});
          }
      }
    const MPI_Comm comm = U.get_mpi_communicator();
    const auto     all  = Utilities::MPI::gather(comm, rows, 0);
    if (Utilities::MPI::this_mpi_process(comm) == 0)
      {
        std::vector<std::array<double, 5>> sorted;
        for (const auto &part : all)
          for (unsigned int i = 0; i + 4 < part.size(); i += 5)
            sorted.push_back({{part[i], part[i + 1], part[i + 2], part[i + 3], part[i + 4]}});
        std::stable_sort(sorted.begin(), sorted.end(),
                         [](const auto &a, const auto &b) { return a[0] < b[0]; });
        CsvWriter csv;
        csv.open(directory + "/slice-" + Utilities::int_to_string(n_slices, 4) + ".csv",
                 {"x", "strain", "stress", "velocity_x", "velocity_y"},
                 "time = " + format_number(t) + ", y = " + format_number(slice_y));
        for (const auto &r : sorted)
          csv.row(std::vector<double>(r.begin(), r.end()));
      }
    ++n_slices;
  }

  template <int dim>
  typename LayeredDiagnostics<dim>::Diagnosis
  LayeredDiagnostics<dim>::diagnose(const dg::VectorType &solution) const
  {
    // the neighbours' traces: ghost cells included
    const dg::VectorType &U = layout->with_ghosts(solution);
    Diagnosis             r;
    double                low = std::numeric_limits<double>::max(), high = -low;
    double                jump_sum = 0, count = 0;
    for (unsigned int c = 0; c < layout->n_owned(); ++c)
      {
        low           = std::min(low, points.min(U, c, 0));
        high          = std::max(high, U.local_element(layout->index(c, 0, 0)));
        const auto id = layout->cell(c)->material_id();
        const auto a  = system.coefficients(id);
        // the interface faces on the upper side of the cell
        for (int d = 0; d < dim; ++d)
          {
            const int nb = layout->neighbor(c, 2 * d + 1);
            if (nb < 0 || layout->cell(nb)->material_id() == id)
              continue;
            const auto a_nb = system.coefficients(layout->cell(nb)->material_id());
            std::array<const double *, dim> here, there;
            for (int e = 0; e < dim; ++e)
              here[e] = there[e] = points.at_half().data();
            here[d]  = points.at_1().data();
            there[d] = points.at_0().data();
            const double s_jump = std::abs(system.stress(layout->value(U, c, 0, here), a) -
                                           system.stress(layout->value(U, nb, 0, there), a_nb));
            const double u_jump = std::abs(layout->value(U, c, 1 + d, here) / a[density] -
                                           layout->value(U, nb, 1 + d, there) / a_nb[density]);
            r.stress_jump_max   = std::max(r.stress_jump_max, s_jump);
            r.velocity_jump_max = std::max(r.velocity_jump_max, u_jump);
            jump_sum += s_jump;
            count += 1;
          }
      }
    const MPI_Comm comm = U.get_mpi_communicator();
    r.min_strain        = Utilities::MPI::min(low, comm);
    r.max_strain        = Utilities::MPI::max(high, comm);
    r.stress_jump_max   = Utilities::MPI::max(r.stress_jump_max, comm);
    r.velocity_jump_max = Utilities::MPI::max(r.velocity_jump_max, comm);
    jump_sum            = Utilities::MPI::sum(jump_sum, comm);
    count               = Utilities::MPI::sum(count, comm);
    r.stress_jump_mean  = count > 0 ? jump_sum / count : 0.;
    layout->release_ghosts(); // (U is invalid from here)
    return r;
  }

  template class LayeredDiagnostics<1>;
  template class LayeredDiagnostics<2>;
} // namespace granular_dg::layered_strip
