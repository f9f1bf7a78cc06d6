/**
 * The `layered_strip` scene: nonlinear elasticity (system.h) in a layered
 * medium on an interval (1D) or a rectangle (2D) whose cell faces align with
 * the material interfaces (layers of width l of two materials A and B, vertical
 * or horizontal strips in 2D; layer width 0 is a homogeneous medium of
 * material A). Boundary conditions by side (periodic, outflow, moving wall,
 * traction, Dirichlet), optionally switched to periodic in x at a given time
 * (a second run started from the first one's final state), initial data as
 * strain or stress expressions, an exact or reference solution for errors,
 * interface diagnostics and an optional positivity scaling of the strain.
 */

#include <deal.II/base/polynomial.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <granular_dg/base/parameters.h>
#include <granular_dg/base/run_parameters.h>
#include <granular_dg/base/scene.h>
#include <granular_dg/dg/parameters.h>
#include <granular_dg/dg/reference_solution.h>
#include <granular_dg/dg/solver.h>
#include <granular_dg/equations/layered_elasticity/system.h>

#include <cmath>
#include <algorithm>
#include <functional>
#include <limits>
#include <iostream>
#include <sstream>

namespace granular_dg::elasticity
{
  namespace
  {
    const EnumNames<StressLaw> law_names({{StressLaw::quadratic, "quadratic"},
                                          {StressLaw::exponential, "exponential"}});

    enum class Side
    {
      periodic,
      outflow,
      wall,
      traction,
      dirichlet
    };
    const EnumNames<Side> side_names({{Side::periodic, "periodic"},
                                      {Side::outflow, "outflow"},
                                      {Side::wall, "wall"},
                                      {Side::traction, "traction"},
                                      {Side::dirichlet, "dirichlet"}});

    const char *side_label[] = {"left", "right", "bottom", "top"};

    /// The layered medium: material A (id 0) on the even layers
    /// [origin + 2j l, origin + (2j+1) l), B (id 1) on the odd ones, along x
    /// (vertical strips) or y (horizontal strips); l = 0: A everywhere.
    struct Layers
    {
      double       width     = 0.;
      double       origin    = 0.;
      unsigned int direction = 0;
      Material     A, B;

      template <int dim>
      types::material_id
      id(const Point<dim> &p) const
      {
        if (width <= 0)
          return 0;
        const double s = (p[direction] - origin) / width;
        return static_cast<long>(std::floor(s)) % 2 == 0 ? 0 : 1;
      }

      std::vector<Material>
      table() const
      {
        return width > 0 ? std::vector<Material>{A, B} : std::vector<Material>{A};
      }
    };

    /// (strain or stress, velocity) expressions -> conserved (strain, rho u),
    /// with the material of the point.
    template <int dim>
    class PrimitiveToConserved : public Function<dim>
    {
    public:
      PrimitiveToConserved(std::shared_ptr<Function<dim>> f, const System<dim> &system,
                           const Layers &layers, const bool stress_given)
        : Function<dim>(dim + 1)
        , f(std::move(f))
        , system(system)
        , layers(layers)
        , stress_given(stress_given)
      {}
      double
      value(const Point<dim> &p, const unsigned int c) const override
      {
        const auto a = system.coefficients(layers.id(p));
        if (c > 0)
          return a[density] * f->value(p, c);
        return stress_given ? system.strain_of_stress(f->value(p, 0), a) : f->value(p, 0);
      }
      void
      set_time(const double t) override
      {
        Function<dim>::set_time(t);
        f->set_time(t);
      }

    private:
      std::shared_ptr<Function<dim>> f;
      const System<dim>              system;
      const Layers                   layers;
      const bool                     stress_given;
    };

    /// Boundary data in the layout System::boundary_state() expects.
    template <int dim>
    class BoundaryData : public Function<dim>
    {
    public:
      BoundaryData(std::shared_ptr<Function<dim>> f, const Side side, const Layers &layers)
        : Function<dim>(dim + 1)
        , f(std::move(f))
        , side(side)
        , layers(layers)
      {}
      double
      value(const Point<dim> &p, const unsigned int c) const override
      {
        switch (side)
          {
            case Side::wall:
              return c == 0 ? 0. : f->value(p, c - 1);
            case Side::traction:
              return c == 0 ? f->value(p, 0) : 0.;
            case Side::dirichlet:
              return (c == 0 ? 1. : (layers.id(p) == 0 ? layers.A : layers.B).rho) *
                     f->value(p, c);
            default:
              return 0.;
          }
      }
      void
      set_time(const double t) override
      {
        Function<dim>::set_time(t);
        f->set_time(t);
      }

    private:
      std::shared_ptr<Function<dim>> f;
      const Side                     side;
      const Layers                   layers;
    };

    /**
     * Interface diagnostics (stress and velocity jumps across material
     * interfaces, from the traces at the face centres), the strain range,
     * and the Zhang-Shu positivity scaling of the strain after every stage.
     */
    template <int dim>
    class LayeredHooks : public dg::SceneHooks<dim>
    {
    public:
      /// directory empty: no slice files; slice_y NaN: no slice (2D only)
      LayeredHooks(const System<dim> &system, const bool positivity, const std::string &directory,
                   const double slice_y)
        : system(system)
        , positivity(positivity)
        , directory(directory)
        , slice_y(slice_y)
      {}

      void
      initialize(const DoFHandler<dim> &, const Mapping<dim> &,
                 const dg::ModalLayout<dim> &cell_layout) override
      {
        layout                 = &cell_layout;
        const unsigned int n1d = layout->degree() + 1;
        // 1D Legendre values at the Gauss points (p + 2, the operator's) and
        // at 0, 1/2 and 1
        const QGauss<1> q(n1d + 1);
        gauss.resize(q.size() * n1d);
        for (unsigned int k = 0; k < n1d; ++k)
          {
            const Polynomials::Legendre L(k);
            for (unsigned int i = 0; i < q.size(); ++i)
              gauss[i * n1d + k] = L.value(q.point(i)[0]);
            at[0].push_back(L.value(0.));
            at[1].push_back(L.value(0.5));
            at[2].push_back(L.value(1.));
          }
        n_gauss = q.size();

        // the cells the slice y = slice_y runs through, and the Legendre
        // values in y there and at p + 2 equally spaced points in x
        if constexpr (dim == 2)
          if (std::isfinite(slice_y) && !directory.empty())
            {
              for (unsigned int k = 0; k < n1d; ++k)
                {
                  const Polynomials::Legendre L(k);
                  for (unsigned int i = 0; i <= n1d; ++i)
                    slice_x_values.push_back(L.value(double(i) / n1d));
                }
              for (unsigned int c = 0; c < layout->n_owned(); ++c)
                {
                  const auto  &cell = layout->cell(c);
                  const double y0 = cell->vertex(0)[1], hy = layout->extent(c, 1);
                  if (slice_y >= y0 && slice_y < y0 + hy)
                    {
                      slice_cells.push_back(c);
                      std::vector<double> v;
                      for (unsigned int k = 0; k < n1d; ++k)
                        v.push_back(Polynomials::Legendre(k).value((slice_y - y0) / hy));
                      slice_y_values.push_back(v);
                    }
                }
            }
      }

      void
      post_limiter(dg::VectorType &U, double) override
      {
        if (!positivity)
          return;
        // theta scales the higher strain modes so that eps >= 0 at the points
        // the scheme uses (Zhang & Shu); the cell average (mass) is kept
        for (unsigned int c = 0; c < layout->n_owned(); ++c)
          {
            const double mean = U.local_element(layout->index(c, 0, 0));
            double       low  = min_strain_in_cell(U, c);
            // (a negative mean is outside the admissible set the option
            // declares: check_admissibility() stops the run)
            if (low >= 0. || mean <= 0.)
              continue;
            const double theta = std::min(1., mean / (mean - low));
            for (unsigned int m = 1; m < layout->n_modes(); ++m)
              U.local_element(layout->index(c, 0, m)) *= theta;
            ++scaled_cells;
          }
      }

      /// With the positivity option the model declares eps >= 0: a cell
      /// whose mean strain is negative (below -1e-10; the scaling can only
      /// fix the point values of a cell with a non-negative mean) is
      /// inadmissible.
      dg::AdmissibilityReport
      check_admissibility(const dg::VectorType &U) const override
      {
        dg::AdmissibilityReport report;
        if (!positivity)
          return report;
        for (unsigned int c = 0; c < layout->n_owned(); ++c)
          {
            // (round-off below a strain of 1e-10, e.g. ahead of a wave, is
            // not tension)
            const double mean = U.local_element(layout->index(c, 0, 0));
            if (mean >= -1e-10)
              continue;
            report.ok        = false;
            const auto x     = layout->cell(c)->center();
            for (int d = 0; d < dim; ++d)
              report.position[d] = x[d];
            for (unsigned int i = 0; i < layout->n_components(); ++i)
              report.state.push_back(U.local_element(layout->index(c, i, 0)));
            report.reason = "negative mean strain with Limiter/strain positivity = true (the "
                            "option declares eps >= 0; the scaling keeps the point values of a "
                            "cell >= 0 only while its mean is; the cell averages are shown)";
            break;
          }
        return report;
      }

      void
      save(ByteWriter &w) override
      {
        // counters summed over the ranks: the state of the whole run
        const MPI_Comm     comm   = MPI_COMM_WORLD;
        unsigned long long scaled = Utilities::MPI::sum(scaled_cells, comm);
        w.io(n_slices);
        w.io(scaled);
      }

      void
      load(ByteReader &r) override
      {
        r.io(n_slices);
        r.io(scaled_cells);
        // every rank read rank 0's sum; one of them keeps it
        if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
          scaled_cells = 0;
      }

      std::vector<std::string>
      timeseries_names() const override
      {
        return {"min_strain", "max_strain", "interface_stress_jump_max",
                "interface_stress_jump_mean", "interface_velocity_jump_max"};
      }

      std::vector<double>
      timeseries_values(const dg::VectorType &U, const double t) override
      {
        if constexpr (dim == 2)
          if (std::isfinite(slice_y) && !directory.empty())
            write_slice(U, t);
        const auto d = diagnose(U);
        return {d.min_strain, d.max_strain, d.stress_jump_max, d.stress_jump_mean,
                d.velocity_jump_max};
      }

      void
      finish(const dg::VectorType &U, double, JsonObject &diagnostics, const std::string &,
             bool) override
      {
        const auto d = diagnose(U);
        diagnostics.add("min_strain", d.min_strain);
        diagnostics.add("max_strain", d.max_strain);
        diagnostics.add("interface_stress_jump_max", d.stress_jump_max);
        diagnostics.add("interface_stress_jump_mean", d.stress_jump_mean);
        diagnostics.add("interface_velocity_jump_max", d.velocity_jump_max);
        if (positivity)
          {
            const MPI_Comm comm = U.get_mpi_communicator();
            diagnostics.add("positivity_scaled_cell_stages",
                            static_cast<long long>(Utilities::MPI::sum(scaled_cells, comm)));
          }
      }

    private:
      struct Diagnosis
      {
        double min_strain = 0, max_strain = 0, stress_jump_max = 0, stress_jump_mean = 0,
               velocity_jump_max = 0;
      };

      /// slice-NNNN.csv: strain, stress and velocity along y = slice_y (all
      /// ranks' cells gathered on rank 0, sorted by x)
      void
      write_slice(const dg::VectorType &U, const double t)
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
                std::vector<double> xv(n1d);
                for (unsigned int k = 0; k < n1d; ++k)
                  xv[k] = slice_x_values[k * (n1d + 1) + i];
                std::array<const double *, dim> v{{xv.data(), slice_y_values[s].data()}};
                const double eps = evaluate(U, c, 0, v);
                rows.insert(rows.end(), {x0 + hx * i / n1d, eps, system.stress(eps, a),
                                         evaluate(U, c, 1, v) / a[density],
                                         evaluate(U, c, 2, v) / a[density]});
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

      /// value of component i of cell c at the tensor point with 1D Legendre
      /// values v[d] in direction d
      double
      evaluate(const dg::VectorType &U, const unsigned int c, const unsigned int i,
               const std::array<const double *, dim> &v) const
      {
        const unsigned int n1d = layout->degree() + 1;
        double             sum = 0;
        for (unsigned int m = 0; m < layout->n_modes(); ++m)
          {
            double w = 1, r = m;
            for (int d = 0; d < dim; ++d)
              {
                const unsigned int k = static_cast<unsigned int>(r) % n1d;
                r                    = std::floor(r / n1d);
                w *= v[d][k];
              }
            sum += U.local_element(layout->index(c, i, m)) * w;
          }
        return sum;
      }

      /// min of the strain over the tensor Gauss points and the face centres
      double
      min_strain_in_cell(const dg::VectorType &U, const unsigned int c) const
      {
        const unsigned int n1d = layout->degree() + 1;
        double             low = std::numeric_limits<double>::max();
        std::array<const double *, dim> v;
        const unsigned int              n_points = Utilities::pow(n_gauss, dim);
        for (unsigned int p = 0; p < n_points; ++p)
          {
            unsigned int r = p;
            for (int d = 0; d < dim; ++d, r /= n_gauss)
              v[d] = &gauss[(r % n_gauss) * n1d];
            low = std::min(low, evaluate(U, c, 0, v));
          }
        for (unsigned int f = 0; f < 2 * dim; ++f)
          {
            for (int d = 0; d < dim; ++d)
              v[d] = at[1].data();
            v[f / 2] = (f % 2 == 0 ? at[0] : at[2]).data();
            low      = std::min(low, evaluate(U, c, 0, v));
          }
        return low;
      }

      Diagnosis
      diagnose(const dg::VectorType &solution) const
      {
        // the neighbours' traces: ghost cells included
        const dg::VectorType &U = layout->with_ghosts(solution);
        Diagnosis          r;
        double             low = std::numeric_limits<double>::max(), high = -low;
        double             jump_sum = 0, count = 0;
        for (unsigned int c = 0; c < layout->n_owned(); ++c)
          {
            low  = std::min(low, min_strain_in_cell(U, c));
            high = std::max(high, U.local_element(layout->index(c, 0, 0)));
            const auto id = layout->cell(c)->material_id();
            const auto a  = system.coefficients(id);
            // the interface faces on the upper side of the cell
            for (int d = 0; d < dim; ++d)
              {
                const int nb = layout->neighbor(c, 2 * d + 1);
                if (nb < 0 || layout->cell(nb)->material_id() == id)
                  continue;
                const auto                      a_nb = system.coefficients(layout->cell(nb)->material_id());
                std::array<const double *, dim> here, there;
                for (int e = 0; e < dim; ++e)
                  here[e] = there[e] = at[1].data();
                here[d]  = at[2].data();
                there[d] = at[0].data();
                const double s_jump = std::abs(system.stress(evaluate(U, c, 0, here), a) -
                                               system.stress(evaluate(U, nb, 0, there), a_nb));
                const double u_jump =
                  std::abs(evaluate(U, c, 1 + d, here) / a[density] -
                           evaluate(U, nb, 1 + d, there) / a_nb[density]);
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
        return r;
      }

      const System<dim>           system;
      const bool                  positivity;
      const std::string           directory;
      const double                slice_y;
      std::vector<unsigned int>        slice_cells;
      std::vector<std::vector<double>> slice_y_values;
      std::vector<double>              slice_x_values;
      unsigned int                     n_slices = 0;
      const dg::ModalLayout<dim> *layout  = nullptr;
      unsigned int                n_gauss = 1;
      std::vector<double>         gauss;
      std::array<std::vector<double>, 3> at; ///< L_k at 0, 1/2, 1
      unsigned long long          scaled_cells = 0;
    };

    void
    declare(ParameterHandler &prm)
    {
      prm.enter_subsection("Mesh");
      prm.declare_entry("dimension", "1", Patterns::Integer(1, 2), "1 or 2.");
      prm.declare_entry("x min", "0", Patterns::Double(), "Left end of the domain.");
      prm.declare_entry("x max", "1", Patterns::Double(), "Right end of the domain.");
      prm.declare_entry("cells x", "64", Patterns::Integer(1),
                        "Cells in x; with layers across x, an integer number per layer.");
      prm.declare_entry("y min", "0", Patterns::Double(), "Bottom (2D).");
      prm.declare_entry("y max", "1", Patterns::Double(), "Top (2D).");
      prm.declare_entry("cells y", "4", Patterns::Integer(1),
                        "Cells in y (2D); with horizontal layers, an integer number per layer.");
      prm.leave_subsection();

      prm.enter_subsection("Physics");
      prm.declare_entry("stress law", "quadratic", law_names.pattern(),
                        "quadratic: sigma = K eps + beta K^2 eps^2 (seed 001 (1.4); "
                        "linear for beta = 0); exponential: sigma = exp(K eps) - 1 (1.5).");
      prm.declare_entry("density", "1", Patterns::Double(),
                        "rho > 0 of material A (the homogeneous medium, or the even layers).");
      prm.declare_entry("modulus K", "1", Patterns::Double(), "K > 0 of material A.");
      prm.declare_entry("beta", "0", Patterns::Double(),
                        "Nonlinearity of the quadratic law (both materials).");
      prm.leave_subsection();

      prm.enter_subsection("Layers");
      prm.declare_entry("layer width", "0", Patterns::Double(0),
                        "l >= 0: material A on [origin + 2jl, origin + (2j+1)l), B on the "
                        "others; every interface must be a mesh face. 0: homogeneous "
                        "(material A everywhere).");
      prm.declare_entry("origin", "0", Patterns::Double(), "Where the first A layer starts.");
      prm.declare_entry("orientation", "vertical", Patterns::Selection("vertical|horizontal"),
                        "vertical: the material varies with x (strips x = const in 2D); "
                        "horizontal: with y (2D only).");
      prm.declare_entry("density B", "1", Patterns::Double(), "rho > 0 of material B.");
      prm.declare_entry("modulus K B", "1", Patterns::Double(), "K > 0 of material B.");
      prm.leave_subsection();

      prm.enter_subsection("Initial condition");
      prm.declare_entry("strain", "0", Patterns::Anything(),
                        "eps(x[,y]) as an expression (constant pi).");
      prm.declare_entry("stress", "", Patterns::Anything(),
                        "sigma(x[,y]) instead of the strain (empty: use the strain); the "
                        "strain follows from each material's law.");
      prm.declare_entry("velocity", "0", Patterns::Anything(),
                        "u(x[,y]) in 1D, 'u; v' in 2D.");
      prm.leave_subsection();

      prm.enter_subsection("Boundary conditions");
      for (const char *side : side_label)
        {
          prm.declare_entry(side, "outflow", side_names.pattern(),
                            std::string("Kind of the ") + side +
                              " boundary (bottom/top: 2D only). periodic pairs with "
                              "the opposite side; outflow: transmissive; wall: a wall "
                              "moving with the velocity in the data; traction: "
                              "prescribed stress; dirichlet: prescribed strain and "
                              "velocity.");
          prm.declare_entry(std::string(side) + " data", "0", Patterns::Anything(),
                            "Expressions in x[,y],t separated by ';': wall: velocity "
                            "(dim values); traction: sigma; dirichlet: strain; velocity.");
        }
      prm.declare_entry("periodic from", "0", Patterns::Double(0),
                        "t_p > 0: left and right become periodic at t = t_p (the run to "
                        "t_p goes to Output/directory/before-periodic, the rest continues "
                        "from its final state); 0: never.");
      prm.leave_subsection();

      prm.enter_subsection("Output");
      prm.declare_entry("slice y", "", Patterns::Anything(),
                        "2D: write slice-NNNN.csv (strain, stress, velocity along the line "
                        "y = this value) at every output time; empty: none.");
      prm.leave_subsection();

      prm.enter_subsection("Limiter");
      prm.declare_entry("strain positivity", "false", Patterns::Bool(),
                        "Scale the higher strain modes after every stage so that eps >= 0 "
                        "at the Gauss points and face centres of every cell with a "
                        "non-negative mean (Zhang-Shu). The paper's scheme keeps eps >= 0; "
                        "the exact solutions have small tensile tails (eps < 0), so this is "
                        "off by default.");
      prm.leave_subsection();

      prm.enter_subsection("Exact solution");
      prm.declare_entry("available", "false", Patterns::Bool(),
                        "Whether the expressions below are the exact solution; then "
                        "errors are reported and convergence studies are possible.");
      prm.declare_entry("strain", "0", Patterns::Anything(), "eps(x[,y],t).");
      prm.declare_entry("velocity", "0", Patterns::Anything(), "u(x[,y],t) ('u; v' in 2D).");
      prm.declare_entry("reference file", "", Patterns::Anything(),
                        "1D: a modes-NNNN.csv of a finer run (Output/write modes = true) "
                        "as the reference solution at the final time, instead of the "
                        "expressions (errors in summary.json).");
      prm.leave_subsection();
    }

    Layers
    parse_layers(ParameterHandler &prm, const int dim, Material &A)
    {
      Layers l;
      prm.enter_subsection("Physics");
      A.rho  = prm.get_double("density");
      A.K    = prm.get_double("modulus K");
      A.beta = prm.get_double("beta");
      prm.leave_subsection();
      require(A.rho > 0, "Physics/density", A.rho, "must be > 0");
      require(A.K > 0, "Physics/modulus K", A.K, "must be > 0");
      prm.enter_subsection("Layers");
      l.width     = prm.get_double("layer width");
      l.origin    = prm.get_double("origin");
      l.direction = prm.get("orientation") == "vertical" ? 0 : 1;
      l.A         = A;
      l.B         = A;
      l.B.rho     = prm.get_double("density B");
      l.B.K       = prm.get_double("modulus K B");
      prm.leave_subsection();
      require(l.B.rho > 0, "Layers/density B", l.B.rho, "must be > 0");
      require(l.B.K > 0, "Layers/modulus K B", l.B.K, "must be > 0");
      require(dim == 2 || l.direction == 0, "Layers/orientation", "horizontal",
              "vertical in 1D");
      return l;
    }

    template <int dim>
    std::shared_ptr<Function<dim>>
    primitive_function(ParameterHandler &prm, const std::string &section,
                       const System<dim> &system, const Layers &layers,
                       const bool time_dependent)
    {
      prm.enter_subsection(section);
      const std::string strain = prm.get("strain"), velocity = prm.get("velocity");
      const std::string stress = section == "Initial condition" ? prm.get("stress") : "";
      prm.leave_subsection();
      auto v = split_expressions(velocity);
      require(v.size() == dim, section + "/velocity", velocity,
              std::to_string(dim) + " expression(s) separated by ';'");
      const bool stress_given = !Utilities::trim(stress).empty();
      require(!stress_given || Utilities::trim(strain) == "0", section + "/stress", stress,
              "empty when the strain is given (strain = '" + strain + "')");
      std::vector<std::string> all{stress_given ? stress : strain};
      all.insert(all.end(), v.begin(), v.end());
      std::vector<std::string> names{section + (stress_given ? "/stress" : "/strain")};
      names.resize(all.size(), section + "/velocity");
      return std::make_shared<PrimitiveToConserved<dim>>(
        make_function<dim>(all, names, time_dependent), system, layers, stress_given);
    }

    /// Initial data outside the admissible set (a stress the law cannot
    /// reach, sigma' <= 0) are bad input: checked at 3^dim Gauss points of
    /// every cell (all ranks see all coarse cells, so all agree).
    template <int dim>
    void
    require_admissible_initial_state(ParameterHandler &prm,
                                     const dg::SceneData<dim, System<dim>> &scene)
    {
      prm.enter_subsection("Initial condition");
      const std::string stress = Utilities::trim(prm.get("stress"));
      const std::string name   = stress.empty() ? "strain" : "stress";
      const std::string text   = stress.empty() ? prm.get("strain") : stress;
      prm.leave_subsection();
      const QGauss<dim> q(3);
      Vector<double>    U(dim + 1);
      for (const auto &cell : scene.triangulation->active_cell_iterators())
        for (const auto &xi : q.get_points())
          {
            Point<dim> x = cell->vertex(0);
            for (int d = 0; d < dim; ++d)
              x[d] += xi[d] * (cell->vertex(GeometryInfo<dim>::vertices_per_cell - 1)[d] -
                               cell->vertex(0)[d]);
            scene.initial->vector_value(x, U);
            Tensor<1, dim + 1> s;
            for (unsigned int c = 0; c <= dim; ++c)
              s[c] = U[c];
            const std::string why =
              scene.physics.admissibility_violation(s, scene.physics.coefficients(cell->material_id()));
            if (why.empty())
              continue;
            // the message is built only for the point that fails
            std::ostringstream at;
            at << "initial data in the admissible set; at x = (";
            for (int d = 0; d < dim; ++d)
              at << (d ? ", " : "") << format_number(x[d]);
            at << ") the strain is " << format_number(s[0]) << ": "
               << (!stress.empty() && !std::isfinite(s[0]) ?
                     "no strain gives this stress (the law's range: sigma > -1 for the "
                     "exponential law, 1 + 4 beta sigma >= 0 for the quadratic one)" :
                     why);
            require(false, "Initial condition/" + name, text, at.str());
          }
    }

    /// force_periodic_x: the second part of a run with "periodic from";
    /// output_directory: where the scene's own files go (empty: none).
    template <int dim>
    dg::SceneData<dim, System<dim>>
    make_scene(ParameterHandler &prm, const int cells_override, const std::string &output_directory,
               const bool force_periodic_x = false)
    {
      prm.enter_subsection("Physics");
      const StressLaw law = law_names.parse("Physics/stress law", prm.get("stress law"));
      prm.leave_subsection();
      Material     A;
      const Layers layers = parse_layers(prm, dim, A);

      prm.enter_subsection("Mesh");
      const Point<2> lo(prm.get_double("x min"), prm.get_double("y min"));
      const Point<2> hi(prm.get_double("x max"), prm.get_double("y max"));
      std::vector<unsigned int> cells{static_cast<unsigned int>(prm.get_integer("cells x")),
                                      static_cast<unsigned int>(prm.get_integer("cells y"))};
      prm.leave_subsection();
      prm.enter_subsection("Discretization");
      const NumericalFlux flux =
        numerical_flux_names.parse("Discretization/numerical flux", prm.get("numerical flux"));
      prm.leave_subsection();
      require(hi[0] > lo[0], "Mesh/x max", hi[0], "must be > x min");
      require(dim == 1 || hi[1] > lo[1], "Mesh/y max", hi[1], "must be > y min");
      // a convergence study refines every direction: cells_override per direction
      if (cells_override > 0)
        cells[0] = cells[1] = cells_override;
      if (layers.width > 0)
        {
          // every material interface a mesh face: a whole number of cells per
          // layer, and the interfaces on the grid lines
          const unsigned int d     = layers.direction;
          const double       h     = (hi[d] - lo[d]) / cells[d];
          const double       per   = layers.width / h;
          const double       shift = (layers.origin - lo[d]) / h;
          require(std::abs(per - std::round(per)) < 1e-9 && std::round(per) >= 1 &&
                    std::abs(shift - std::round(shift)) < 1e-9,
                  d == 0 ? "Mesh/cells x" : "Mesh/cells y", cells[d],
                  "a number of cells that puts every material interface (layer width " +
                    format_number(layers.width) + ", origin " + format_number(layers.origin) +
                    ") on a mesh face (cell size " + format_number(h) + ")");
        }

      dg::SceneData<dim, System<dim>> scene{
        "layered_strip", System<dim>(law, layers.table(), flux), {}, {}, {}, {}};
      if constexpr (dim == 1)
        {
          scene.triangulation = std::make_shared<Triangulation<1>>();
          GridGenerator::subdivided_hyper_rectangle(*scene.triangulation,
                                                    std::vector<unsigned int>{cells[0]},
                                                    Point<1>(lo[0]), Point<1>(hi[0]), true);
        }
      else
        {
          scene.triangulation =
            std::make_shared<parallel::distributed::Triangulation<2>>(MPI_COMM_WORLD);
          GridGenerator::subdivided_hyper_rectangle(*scene.triangulation, cells, lo, hi, true);
        }
      for (const auto &cell : scene.triangulation->active_cell_iterators())
        cell->set_material_id(layers.id(cell->center()));

      prm.enter_subsection("Boundary conditions");
      std::vector<Side> sides;
      for (unsigned int b = 0; b < 2 * dim; ++b)
        sides.push_back(side_names.parse(std::string("Boundary conditions/") + side_label[b],
                                         prm.get(side_label[b])));
      if (force_periodic_x)
        sides[0] = sides[1] = Side::periodic;
      std::vector<GridTools::PeriodicFacePair<typename Triangulation<dim>::cell_iterator>>
        periodic;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const bool p0 = sides[2 * d] == Side::periodic, p1 = sides[2 * d + 1] == Side::periodic;
          require(p0 == p1, std::string("Boundary conditions/") + side_label[2 * d],
                  side_names.name(sides[2 * d]),
                  std::string("periodic only together with ") + side_label[2 * d + 1] +
                    " = periodic (it is " + side_names.name(sides[2 * d + 1]) + ")");
          if (p0)
            GridTools::collect_periodic_faces(*scene.triangulation, 2 * d, 2 * d + 1, d,
                                              periodic);
          for (unsigned int b = 2 * d; b < 2 * d + 2 && !p0; ++b)
            {
              const std::string name = std::string("Boundary conditions/") + side_label[b] + " data";
              const std::string text = prm.get(std::string(side_label[b]) + " data");
              const auto        expr = split_expressions(text);
              dg::BoundaryCondition<dim> bc;
              unsigned int               expected = 0;
              switch (sides[b])
                {
                  case Side::outflow:
                    bc.kind = dg::BoundaryKind::outflow;
                    break;
                  case Side::wall:
                    bc.kind  = dg::BoundaryKind::wall;
                    expected = dim;
                    break;
                  case Side::traction:
                    bc.kind  = System<dim>::traction;
                    expected = 1;
                    break;
                  case Side::dirichlet:
                    bc.kind  = dg::BoundaryKind::dirichlet;
                    expected = dim + 1;
                    break;
                  default:
                    break;
                }
              if (expected > 0)
                {
                  require(expr.size() == expected, name, text,
                          side_names.name(sides[b]) + " takes " + std::to_string(expected) +
                            " expression(s) separated by ';'");
                  bc.data = std::make_shared<BoundaryData<dim>>(
                    make_function<dim>(expr, {name}, true), sides[b], layers);
                }
              scene.boundary[b] = bc;
            }
        }
      prm.leave_subsection();
      if (!periodic.empty())
        scene.triangulation->add_periodicity(periodic);

      scene.initial = primitive_function<dim>(prm, "Initial condition", scene.physics, layers, false);
      require_admissible_initial_state(prm, scene);
      prm.enter_subsection("Exact solution");
      const bool        exact     = prm.get_bool("available");
      const std::string reference = Utilities::trim(prm.get("reference file"));
      prm.leave_subsection();
      require(!(exact && !reference.empty()), "Exact solution/reference file", reference,
              "empty when Exact solution/available = true");
      require(reference.empty() || dim == 1, "Exact solution/reference file", reference,
              "empty in 2D (reference files are 1D)");
      if (exact)
        scene.exact = primitive_function<dim>(prm, "Exact solution", scene.physics, layers, true);
      else if (!reference.empty())
        {
          if constexpr (dim == 1)
            {
              auto file = std::make_shared<dg::ModalReference>(reference, dim + 1);
              prm.enter_subsection("Time stepping");
              const double final_time = prm.get_double("final time");
              prm.leave_subsection();
              // a reference of another time is no reference for this run
              require(std::abs(file->time() - final_time) <= 1e-12 * std::abs(final_time),
                      "Exact solution/reference file", reference,
                      "a solution at the run's final time " + format_number(final_time) +
                        " (the file holds t = " + format_number(file->time()) + ")");
              scene.exact = file;
            }
        }

      prm.enter_subsection("Limiter");
      const bool positivity = prm.get_bool("strain positivity");
      prm.leave_subsection();
      prm.enter_subsection("Output");
      const std::string slice = Utilities::trim(prm.get("slice y"));
      prm.leave_subsection();
      double slice_y = std::numeric_limits<double>::quiet_NaN();
      if (!slice.empty())
        {
          char *end = nullptr;
          slice_y   = std::strtod(slice.c_str(), &end);
          require(dim == 2 && end != slice.c_str() && *end == '\0' && slice_y >= lo[1] &&
                    slice_y < hi[1],
                  "Output/slice y", slice,
                  "empty, or in 2D a number in [y min, y max) = [" + format_number(lo[1]) +
                    ", " + format_number(hi[1]) + ")");
        }
      scene.hooks = std::make_shared<LayeredHooks<dim>>(scene.physics, positivity,
                                                        output_directory, slice_y);
      return scene;
    }

    template <int dim>
    void
    run(ParameterHandler &prm, const RunParameters &common,
        const dg::DiscretizationParameters &method)
    {
      prm.enter_subsection("Boundary conditions");
      const double periodic_from = prm.get_double("periodic from");
      prm.leave_subsection();
      // build (and so validate) everything before anything is written
      auto              scene     = make_scene<dim>(
        prm, common.convergence ? common.convergence_cells.front() : 0,
        periodic_from > 0 ? common.directory + "/before-periodic" : common.scene_directory());
      if (common.convergence)
        require(static_cast<bool>(scene.exact), "Exact solution/available", "false",
                "true: a convergence study needs the exact solution");
      if (periodic_from > 0)
        {
          require(periodic_from < common.final_time, "Boundary conditions/periodic from",
                  periodic_from,
                  "a time before the final time " + format_number(common.final_time));
          require(!common.convergence, "Boundary conditions/periodic from", periodic_from,
                  "0 in a convergence study");
          prm.enter_subsection("Boundary conditions");
          require(prm.get("left") != "periodic", "Boundary conditions/periodic from",
                  periodic_from, "0 when left and right are periodic from the start");
          prm.leave_subsection();
          make_scene<dim>(prm, 0, "", true); // validates the second part too
        }
      require_reasonable_snapshot_count(
        common, dg::snapshot_bytes(scene.triangulation->n_global_active_cells(), method.degree,
                                   dim, 2 * dim + 2, common.write_vtu));
      begin_output(common);
      if (common.convergence)
        dg::run_convergence_study<dim, System<dim>>(
          [&](unsigned int cells) { return make_scene<dim>(prm, cells, ""); }, common, method);
      else if (periodic_from > 0)
        {
          // two runs: part 1 in DIR/before-periodic, part 2 in DIR. A resumed
          // run continues part 2 if it wrote a checkpoint, else part 1.
          const bool resume_second = common.resume && has_checkpoints(common.directory);
          const bool root          = Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
          std::shared_ptr<dg::VectorType> part_1_end;
          if (!resume_second)
            {
              RunParameters first = common;
              first.final_time       = periodic_from;
              first.directory        = common.directory + "/before-periodic";
              first.output_times.erase(std::remove_if(first.output_times.begin(),
                                                      first.output_times.end(),
                                                      [&](const double t) {
                                                        return t >= periodic_from;
                                                      }),
                                       first.output_times.end());
              if (root && !common.resume)
                prepare_output_directory(first.directory, common.overwrite);
              MPI_Barrier(MPI_COMM_WORLD);
              if (root)
                std::cout << "  part 1: t in [0, " << format_number(periodic_from)
                          << "] with the boundary conditions of the file" << std::endl;
              part_1_end        = std::make_shared<dg::VectorType>();
              const auto before =
                dg::run_simulation(scene, first, method, true, 1., part_1_end.get());
              if (before.status != "completed")
                return; // stopped at max steps: part 2 comes with --resume
            }
          auto after       = make_scene<dim>(prm, 0, common.directory, true);
          after.start_time = periodic_from;
          after.initial_vector = part_1_end; // none when part 2 resumes
          RunParameters second = common;
          second.resume           = resume_second;
          if (root)
            std::cout << "  part 2: t in [" << format_number(periodic_from) << ", "
                      << format_number(common.final_time) << "], periodic in x" << std::endl;
          dg::run_simulation(after, second, method);
        }
      else
        dg::run_simulation(scene, common, method);
    }

    void
    declare_all(ParameterHandler &prm)
    {
      RunParameters::declare(prm);
      dg::DiscretizationParameters::declare(prm, numerical_flux_names.selection(),
                                            System<1>::limiting_variables_name);
      declare(prm);
    }

    void
    run_scene(ParameterHandler &prm)
    {
      RunParameters common;
      common.parse(prm);
      dg::DiscretizationParameters method;
      method.parse(prm, common, System<1>::limiting_variables_name);
      prm.enter_subsection("Mesh");
      const int dim = prm.get_integer("dimension");
      prm.leave_subsection();
      if (dim == 1)
        run<1>(prm, common, method);
      else
        run<2>(prm, common, method);
    }

    const RegisterScene registration(
      {"layered_strip",
       "nonlinear elasticity eps_t - div u = 0, (rho u)_t - grad sigma(eps) = 0 in a layered "
       "(or homogeneous) medium, 1D or 2D",
       declare_all, run_scene});
  } // namespace
} // namespace granular_dg::elasticity
