/**
 * The `elasticity` scene: nonlinear elasticity (system.h) in a homogeneous
 * medium on an interval (1D) or a rectangle (2D), with boundary conditions by
 * side (periodic, outflow, moving wall, traction, Dirichlet), initial data and
 * an optional exact solution as expressions.
 */

#include <deal.II/distributed/tria.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <granular_dg/base/parameters.h>
#include <granular_dg/base/simulation.h>
#include <granular_dg/equations/layered_elasticity/system.h>
#include <granular_dg/scenes/scenes.h>

#include <iostream>

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

    /// (strain, velocity) expressions -> conserved (strain, rho velocity).
    template <int dim>
    class PrimitiveToConserved : public Function<dim>
    {
    public:
      PrimitiveToConserved(std::shared_ptr<Function<dim>> f, const double rho)
        : Function<dim>(dim + 1)
        , f(std::move(f))
        , rho(rho)
      {}
      double
      value(const Point<dim> &p, const unsigned int c) const override
      {
        return (c == 0 ? 1. : rho) * f->value(p, c);
      }
      void
      set_time(const double t) override
      {
        Function<dim>::set_time(t);
        f->set_time(t);
      }

    private:
      std::shared_ptr<Function<dim>> f;
      const double                   rho;
    };

    /// Boundary data in the layout System::boundary_state() expects.
    template <int dim>
    class BoundaryData : public Function<dim>
    {
    public:
      BoundaryData(std::shared_ptr<Function<dim>> f, const Side side, const double rho)
        : Function<dim>(dim + 1)
        , f(std::move(f))
        , side(side)
        , rho(rho)
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
              return (c == 0 ? 1. : rho) * f->value(p, c);
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
      const double                   rho;
    };

    void
    declare(ParameterHandler &prm)
    {
      prm.enter_subsection("Mesh");
      prm.declare_entry("dimension", "1", Patterns::Integer(1, 2), "1 or 2.");
      prm.declare_entry("x min", "0", Patterns::Double(), "Left end of the domain.");
      prm.declare_entry("x max", "1", Patterns::Double(), "Right end of the domain.");
      prm.declare_entry("cells x", "64", Patterns::Integer(1), "Cells in x.");
      prm.declare_entry("y min", "0", Patterns::Double(), "Bottom (2D).");
      prm.declare_entry("y max", "1", Patterns::Double(), "Top (2D).");
      prm.declare_entry("cells y", "4", Patterns::Integer(1), "Cells in y (2D).");
      prm.leave_subsection();

      prm.enter_subsection("Physics");
      prm.declare_entry("stress law", "quadratic", law_names.pattern(),
                        "quadratic: sigma = K eps + beta K^2 eps^2 (seed 001 (1.4); "
                        "linear for beta = 0); exponential: sigma = exp(K eps) - 1 (1.5).");
      prm.declare_entry("density", "1", Patterns::Double(), "rho > 0.");
      prm.declare_entry("modulus K", "1", Patterns::Double(), "K > 0.");
      prm.declare_entry("beta", "0", Patterns::Double(),
                        "Nonlinearity of the quadratic law.");
      prm.leave_subsection();

      prm.enter_subsection("Initial condition");
      prm.declare_entry("strain", "0", Patterns::Anything(),
                        "eps(x[,y]) as an expression (constant pi).");
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
      prm.leave_subsection();

      prm.enter_subsection("Exact solution");
      prm.declare_entry("available", "false", Patterns::Bool(),
                        "Whether the expressions below are the exact solution; then "
                        "errors are reported and convergence studies are possible.");
      prm.declare_entry("strain", "0", Patterns::Anything(), "eps(x[,y],t).");
      prm.declare_entry("velocity", "0", Patterns::Anything(), "u(x[,y],t) ('u; v' in 2D).");
      prm.leave_subsection();
    }

    template <int dim>
    std::shared_ptr<Function<dim>>
    primitive_function(ParameterHandler &prm, const std::string &section,
                       const double rho, const bool time_dependent)
    {
      prm.enter_subsection(section);
      const std::string strain = prm.get("strain"), velocity = prm.get("velocity");
      prm.leave_subsection();
      auto v = split_expressions(velocity);
      require(v.size() == dim, section + "/velocity", velocity,
              std::to_string(dim) + " expression(s) separated by ';'");
      std::vector<std::string> all{strain};
      all.insert(all.end(), v.begin(), v.end());
      std::vector<std::string> names{section + "/strain"};
      names.resize(all.size(), section + "/velocity");
      return std::make_shared<PrimitiveToConserved<dim>>(
        make_function<dim>(all, names, time_dependent), rho);
    }

    template <int dim>
    SceneData<dim, System<dim>>
    make_scene(ParameterHandler &prm, const int cells_override)
    {
      prm.enter_subsection("Physics");
      const StressLaw law = law_names.parse("Physics/stress law", prm.get("stress law"));
      Material        m;
      m.rho  = prm.get_double("density");
      m.K    = prm.get_double("modulus K");
      m.beta = prm.get_double("beta");
      prm.leave_subsection();
      require(m.rho > 0, "Physics/density", m.rho, "must be > 0");
      require(m.K > 0, "Physics/modulus K", m.K, "must be > 0");

      prm.enter_subsection("Mesh");
      const Point<2> lo(prm.get_double("x min"), prm.get_double("y min"));
      const Point<2> hi(prm.get_double("x max"), prm.get_double("y max"));
      std::vector<unsigned int> cells{static_cast<unsigned int>(prm.get_integer("cells x")),
                                      static_cast<unsigned int>(prm.get_integer("cells y"))};
      prm.leave_subsection();
      require(hi[0] > lo[0], "Mesh/x max", hi[0], "must be > x min");
      require(dim == 1 || hi[1] > lo[1], "Mesh/y max", hi[1], "must be > y min");
      if (cells_override > 0)
        cells[0] = cells_override;

      SceneData<dim, System<dim>> scene{"elasticity", System<dim>(law, m), {}, {}, {}, {}};
      if constexpr (dim == 1)
        {
          scene.triangulation = std::make_shared<Triangulation<1>>();
          GridGenerator::subdivided_hyper_rectangle(*scene.triangulation, std::vector<unsigned int>{cells[0]},
                                                    Point<1>(lo[0]), Point<1>(hi[0]), true);
        }
      else
        {
          scene.triangulation =
            std::make_shared<parallel::distributed::Triangulation<2>>(MPI_COMM_WORLD);
          GridGenerator::subdivided_hyper_rectangle(*scene.triangulation, cells, lo, hi,
                                                    true);
        }

      // one material (deal.II's 1D generator colours cells with material ids)
      for (const auto &cell : scene.triangulation->active_cell_iterators())
        cell->set_material_id(0);

      prm.enter_subsection("Boundary conditions");
      std::vector<Side> sides;
      for (unsigned int b = 0; b < 2 * dim; ++b)
        sides.push_back(side_names.parse(std::string("Boundary conditions/") + side_label[b],
                                         prm.get(side_label[b])));
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
              unsigned int expected = 0;
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
                    bc.kind  = dg::BoundaryKind::traction;
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
                    make_function<dim>(expr, {name}, true), sides[b], m.rho);
                }
              scene.boundary[b] = bc;
            }
        }
      prm.leave_subsection();
      if (!periodic.empty())
        scene.triangulation->add_periodicity(periodic);

      scene.initial = primitive_function<dim>(prm, "Initial condition", m.rho, false);
      prm.enter_subsection("Exact solution");
      const bool exact = prm.get_bool("available");
      prm.leave_subsection();
      if (exact)
        scene.exact = primitive_function<dim>(prm, "Exact solution", m.rho, true);
      return scene;
    }

    template <int dim>
    void
    run(ParameterHandler &prm, const CommonParameters &common)
    {
      // build (and so validate) everything before anything is written
      auto scene = make_scene<dim>(prm, common.convergence ? common.convergence_cells.front() : 0);
      if (common.convergence)
        require(static_cast<bool>(scene.exact), "Exact solution/available", "false",
                "true: a convergence study needs the exact solution");
      begin_output(prm, common);
      if (common.convergence)
        run_convergence_study<dim, System<dim>>(
          [&](unsigned int cells) { return make_scene<dim>(prm, cells); }, common);
      else
        run_simulation(scene, common, common.degree, true);
    }
  } // namespace

  Scene
  scene()
  {
    Scene s;
    s.name        = "elasticity";
    s.description = "nonlinear elasticity eps_t - div u = 0, (rho u)_t - grad sigma(eps) = 0 "
                    "in a homogeneous medium, 1D or 2D";
    s.fluxes      = "local_lax_friedrichs|impedance";
    s.declare     = declare;
    s.run         = [](ParameterHandler &prm) {
      CommonParameters common;
      common.parse(prm);
      prm.enter_subsection("Mesh");
      const int dim = prm.get_integer("dimension");
      prm.leave_subsection();
      if (dim == 1)
        run<1>(prm, common);
      else
        run<2>(prm, common);
    };
    return s;
  }
} // namespace granular_dg::elasticity
