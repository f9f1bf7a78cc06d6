/**
 * The time loop of a network run (output, diagnostics, failure handling) and
 * the convergence study: the network counterpart of run_simulation() and
 * run_convergence_study(), built from the same base/ pieces.
 */

#include <deal.II/base/timer.h>

#include <granular_dg/base/errors.h>
#include <granular_dg/base/output.h>
#include <granular_dg/base/simulation.templates.h>
#include <granular_dg/network/network.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace granular_dg::network
{
  namespace
  {
    /// solution-NNNN.vtu with every edge drawn in the plane (a VTK line per
    /// cell through its sample points, the vertex as a VTK vertex at the
    /// origin), solution.pvd, and profile-NNNN-edge-K.csv per edge.
    class NetworkOutput
    {
    public:
      NetworkOutput(const std::string &directory, const unsigned int points_per_cell,
                    const bool write_vtu)
        : directory(directory)
        , points(points_per_cell)
        , write_vtu(write_vtu)
      {}

      /// Returns the name of the VTU written ("" if none).
      std::string
      write(const NetworkProblem &p, const ExactSolution *exact)
      {
        const unsigned int index = n_written++;
        const double       t     = p.time();
        const auto         samples = p.sample(std::max(2u, points));
        const Graph       &graph   = p.graph();
        std::string        name;
        if (write_vtu)
          {
            name = internal::snapshot_name("solution-", index, ".vtu");
            write_vtu_file(directory + "/" + name, p, samples, t);
            records.emplace_back(t, name);
            write_pvd(directory + "/solution.pvd", records);
          }
        const auto profile = points == std::max(2u, points) ? samples : p.sample(points);
        for (unsigned int k = 0; k < graph.edges.size(); ++k)
          {
            const Edge &e = graph.edges[k];
            std::vector<std::string> header{"x", "u", "flux"};
            if (exact)
              header.push_back("exact");
            std::ostringstream comment;
            comment << "time = " << format_number(t) << "\n# " << e.label << ": "
                    << direction_name(e.direction) << ", length " << format_number(e.length)
                    << ", " << e.flux.describe() << "; vertex value "
                    << format_number(p.vertex_value());
            CsvWriter csv;
            csv.open(directory + "/" +
                       internal::snapshot_name("profile-", index,
                                               "-edge-" + std::to_string(k + 1) + ".csv"),
                     header, comment.str());
            for (const auto &[x, u] : profile[k])
              {
                std::vector<double> row{x, u, e.flux.value(u)};
                if (exact)
                  row.push_back(exact->value(k, x, t));
                csv.row(row);
              }
          }
        return name;
      }

      /// The snapshot count and (time, file) records, for a checkpoint.
      template <typename Archive>
      void
      checkpoint_io(Archive &ar)
      {
        ar.io(n_written);
        ar.io(records);
      }

    private:
      void
      write_vtu_file(const std::string &filename, const NetworkProblem &p,
                     const std::vector<std::vector<std::pair<double, double>>> &samples,
                     const double t) const
      {
        const Graph &graph = p.graph();
        const unsigned int per_cell = std::max(2u, points);
        std::vector<Point<3>> xyz;
        std::vector<double>   u, flux, x_edge;
        std::vector<int>      edge_number;
        for (unsigned int k = 0; k < samples.size(); ++k)
          for (const auto &[x, value] : samples[k])
            {
              xyz.push_back(graph.embed(k, x));
              u.push_back(value);
              flux.push_back(graph.edges[k].flux.value(value));
              x_edge.push_back(x);
              edge_number.push_back(k + 1);
            }
        const unsigned int n_line_points = xyz.size();
        xyz.emplace_back(0., 0., 0.);
        u.push_back(p.vertex_value());
        flux.push_back(0.);
        x_edge.push_back(0.);
        edge_number.push_back(0);
        const unsigned int n_lines = n_line_points / per_cell;

        std::ostringstream out;
        out << std::setprecision(12);
        out << "<?xml version=\"1.0\"?>\n"
            << "<!-- granular_dg network: the edges drawn in the plane (ingoing on the left,"
               " outgoing on the right, loops as petals), the vertex at the origin -->\n"
            << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
            << "  <UnstructuredGrid>\n"
            << "    <FieldData>\n"
            << "      <DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" format=\"ascii\">"
            << t << "</DataArray>\n"
            << "    </FieldData>\n"
            << "    <Piece NumberOfPoints=\"" << xyz.size() << "\" NumberOfCells=\""
            << n_lines + 1 << "\">\n"
            << "      <Points>\n"
            << "        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
        for (const auto &q : xyz)
          out << "          " << q[0] << ' ' << q[1] << ' ' << q[2] << '\n';
        out << "        </DataArray>\n      </Points>\n      <Cells>\n"
            << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
        for (unsigned int c = 0; c < n_lines; ++c)
          {
            out << "         ";
            for (unsigned int j = 0; j < per_cell; ++j)
              out << ' ' << c * per_cell + j;
            out << '\n';
          }
        out << "          " << n_line_points << "\n        </DataArray>\n"
            << "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n         ";
        for (unsigned int c = 0; c < n_lines; ++c)
          out << ' ' << (c + 1) * per_cell;
        out << ' ' << n_line_points + 1 << "\n        </DataArray>\n"
            << "        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n         ";
        // 4 = VTK_POLY_LINE, 1 = VTK_VERTEX
        for (unsigned int c = 0; c < n_lines; ++c)
          out << " 4";
        out << " 1\n        </DataArray>\n      </Cells>\n"
            << "      <PointData Scalars=\"u\">\n";
        auto array = [&](const char *name, const auto &values, const char *type) {
          out << "        <DataArray type=\"" << type << "\" Name=\"" << name
              << "\" format=\"ascii\">\n         ";
          for (const auto v : values)
            out << ' ' << v;
          out << "\n        </DataArray>\n";
        };
        array("u", u, "Float64");
        array("flux", flux, "Float64");
        array("x_edge", x_edge, "Float64");
        array("edge", edge_number, "Int32");
        out << "      </PointData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
        std::ofstream file(filename);
        file << out.str();
      }

      std::string                                 directory;
      unsigned int                                points;
      bool                                        write_vtu;
      unsigned int                                n_written = 0;
      std::vector<std::pair<double, std::string>> records;
    };

    /// CPU and wall time of the time steps (time step size included).
    struct LoopTime
    {
      double cpu = 0, wall = 0;
      void
      operator+=(const LoopTime &o)
      {
        cpu += o.cpu;
        wall += o.wall;
      }
    };

    /// Steps from the current time to t_end, the last step landing on it;
    /// after_step runs after every step (not timed) and may stop the loop
    /// early by returning true.
    LoopTime
    advance_to(NetworkProblem &p, const double t_end, const std::function<bool()> &after_step,
               NetworkState *last_good = nullptr)
    {
      Timer    timer;
      LoopTime stepping;
      while (p.time() < t_end * (1 - 1e-14))
        {
          if (last_good)
            *last_good = p.state();
          timer.restart();
          double dt = p.time_step();
          if (!(std::isfinite(dt) && dt > 0))
            throw RunError("time step is " + format_number(dt) + " at t = " +
                           format_number(p.time()) +
                           " (all characteristic speeds vanish or are not finite)");
          if (p.time() + dt >= t_end * (1 - 1e-14))
            dt = t_end - p.time();
          p.step(dt);
          timer.stop();
          stepping.cpu += timer.cpu_time();
          stepping.wall += timer.wall_time();
          if (after_step())
            break;
        }
      return stepping;
    }

    std::string
    failure_message(const StateFailure &f, const unsigned long step, const Graph &g)
    {
      std::ostringstream msg;
      msg << "inadmissible state at t = " << format_number(f.time) << " (step " << step + 1
          << "), ";
      if (f.edge < 0)
        msg << "vertex";
      else
        msg << g.edges[f.edge].label << " x = " << format_number(f.x);
      msg << ", state (u = " << format_number(f.u) << "): " << f.reason;
      return msg.str();
    }

    /// The mass balance of a run: R = (mass(t) - mass(0) - far-end inflow) /
    /// ||u(0)||_L1 after every step; its largest |R| (the drift) and its
    /// largest change in one step (the conservation error of a step).
    struct MassBalance
    {
      double mass0 = 0, scale = 1, last = 0, max_residual = 0, max_step = 0;
      template <typename Archive>
      void
      checkpoint_io(Archive &ar)
      {
        for (double *x : {&mass0, &scale, &last, &max_residual, &max_step})
          ar.io(*x);
      }
      void
      start(const NetworkProblem &p)
      {
        mass0 = p.mass();
        scale = p.l1_norm() > 0 ? p.l1_norm() : 1.;
        last  = 0;
      }
      double
      residual(const NetworkProblem &p) const
      {
        return (p.mass() - mass0 - p.boundary_inflow()) / scale;
      }
      void
      update(const NetworkProblem &p)
      {
        const double r = residual(p);
        max_residual   = std::max(max_residual, std::abs(r));
        max_step       = std::max(max_step, std::abs(r - last));
        last           = r;
      }
    };

    std::string
    integrator_name(const NetworkProblem &p)
    {
      return p.n_stages() == 1 ? "forward_euler" : "ssprk3";
    }

    /// "level" of a number of cells per unit length (log2 when a power of 2)
    double
    level_of(const double cells)
    {
      const double l = std::log2(cells);
      return std::abs(l - std::round(l)) < 1e-12 ? std::round(l) : l;
    }
  } // namespace

  RunResult
  run_network(const Graph &graph, const std::vector<EdgeData> &data,
              const Discretisation &discretisation, const std::optional<double> vertex_value,
              const ExactSolution *exact, const CommonParameters &params,
              const bool write_files, const std::string &scene)
  {
    Timer          wall_timer;
    NetworkProblem p(graph, discretisation, data);
    RunResult      result;
    try
      {
        p.initialize(vertex_value);
      }
    catch (const RunError &e)
      {
        // a vertex without volume that no state balances at t = 0
        result.status = std::string("failed: ") + e.what();
        if (write_files)
          write_summary(params.directory, scene, 1, discretisation.degree, result);
        throw;
      }

    result.n_dofs  = p.n_dofs();
    result.n_cells = p.n_cells();
    result.h_min   = p.min_cell_size();

    NetworkOutput snapshots(params.directory, params.profile_points > 0 ? params.profile_points :
                                                std::max(2u, discretisation.degree + 1),
                            params.write_vtu);
    CsvWriter     timeseries;
    if (write_files)
      {
        std::vector<std::string> header{"time", "step", "dt", "mass", "mass_balance_residual",
                                        "boundary_inflow", "vertex_value", "total_variation",
                                        "rh_residual"};
        if (exact)
          for (const char *n : {"vertex_exact", "l1_error", "l1_error_vertex"})
            header.emplace_back(n);
        if (!params.resume)
          timeseries.open(params.directory + "/timeseries.csv", header,
                          "mass_balance_residual = |mass - mass(0) - boundary_inflow| / "
                          "||u(0)||_L1; rh_residual = sum_in F - sum_out F at the vertex");
        std::cout << "  " << graph.edges.size() << " edges, " << p.junction().ends().size()
                  << " vertex ends, vertex width " << format_number(p.junction().width())
                  << ", " << result.n_cells << " cells, " << result.n_dofs << " DoFs, degree "
                  << discretisation.degree << ", " << integrator_name(p)
                  << "; output to " << params.directory
                  << "/ (solution.pvd, profile-NNNN-edge-K.csv, timeseries.csv, summary.json)"
                  << std::endl;
      }

    MassBalance balance;
    balance.start(p);
    double tv0 = p.total_variation(), u00 = p.vertex_value();
    double tv_max = tv0, dt = 0;

    // a checkpoint: the problem's state, the loop's diagnostics and the
    // output records (written and read by the same io() sequence)
    const CheckpointIdentity identity{scene,          System::name, 1, discretisation.degree,
                                      result.n_cells, result.n_dofs};
    auto checkpoint_io = [&](auto &ar, std::uint64_t &timeseries_size) {
      p.checkpoint_io(ar);
      balance.checkpoint_io(ar);
      for (double *x : {&tv0, &u00, &tv_max, &dt})
        ar.io(*x);
      snapshots.checkpoint_io(ar);
      ar.io(timeseries_size);
    };
    const bool resume = params.resume && write_files;
    if (resume)
      {
        const Checkpoint c =
          read_checkpoint(params.directory, identity, params.parameters, MPI_COMM_WORLD);
        require_beyond_checkpoint(params, c, "t");
        ByteReader    r(c.payload);
        std::uint64_t timeseries_size = 0;
        checkpoint_io(r, timeseries_size);
        timeseries.reopen(params.directory + "/timeseries.csv", timeseries_size);
        result.resumed_from_step = p.n_steps();
        std::cout << "  resuming from " << c.file << ": t = " << format_number(p.time())
                  << ", step " << p.n_steps() << std::endl;
      }
    const unsigned long first_step   = p.n_steps();
    const auto          output_times = internal::output_schedule(params, p.time());
    auto         record = [&]() {
      if (!write_files)
        return;
      snapshots.write(p, exact);
      std::vector<double> row{p.time(), double(p.n_steps()), dt, p.mass(),
                              std::abs(balance.residual(p)),
                              p.boundary_inflow(), p.vertex_value(), p.total_variation(),
                              p.rh_residual()};
      if (exact)
        {
          const auto e = p.errors(*exact);
          row.insert(row.end(), {exact->vertex_value(p.time()), e.l1, e.l1_vertex});
        }
      timeseries.row(row);
    };
    if (params.benchmark.enabled)
      {
        const std::string load = load_average();
        NetworkState      copy;
        std::vector<BenchmarkRepetition> reps;
        try
          {
            reps = run_benchmark(params.benchmark, [&](StepPhases *ph) {
              p.set_phases(ph);
              {
                StepPhases::Scope scope(ph, StepPhases::state_copy);
                copy = p.state();
              }
              double dt_step;
              {
                StepPhases::Scope scope(ph, StepPhases::time_step);
                dt_step = p.time_step();
              }
              if (!(std::isfinite(dt_step) && dt_step > 0))
                throw RunError("benchmark: time step is " + format_number(dt_step));
              p.step(dt_step);
              // the per-step diagnostics of the time loop
              StepPhases::Scope scope(ph, StepPhases::end_of_step_hook);
              balance.update(p);
              tv_max = std::max(tv_max, p.total_variation());
            });
          }
        catch (const StateFailure &f)
          {
            throw RunError("benchmark: " + failure_message(f, p.n_steps(), graph));
          }
        p.set_phases(nullptr);
        JsonObject c;
        c.add("scene", scene);
        c.add("physics", System::name);
        c.add("dim", 1ll);
        c.add("degree", discretisation.degree);
        c.add("engine", "line");
        c.add("n_cells", static_cast<long long>(result.n_cells));
        c.add("n_edges", static_cast<long long>(graph.edges.size()));
        c.add("limiter", static_cast<long long>(discretisation.limiter));
        write_benchmark(params.directory, c, reps, result.n_dofs, p.n_stages(), load);
        result.status  = "benchmark";
        result.n_steps = p.n_steps();
        return result;
      }

    if (!resume)
      record();

    Progress progress(p.time(), params.final_time, write_files ? params.progress_interval : 0.);
    LoopTime     loop;
    NetworkState last_good;
    const InterruptHandlers interrupt_handlers;
    CheckpointSchedule      schedule(params.checkpoint_steps, params.checkpoint_seconds,
                                write_files ? params.max_steps : 0, write_files,
                                MPI_COMM_WORLD);
    // after a step (and the snapshot of a step landing on an output time):
    // checkpoint and stop when due; true: stop
    std::string stopped;
    auto        poll = [&]() {
      const auto  d = schedule.poll(p.n_steps());
      std::string file;
      if (d.write)
        {
          ByteWriter    w;
          std::uint64_t timeseries_size = timeseries.size();
          checkpoint_io(w, timeseries_size);
          file = write_checkpoint(params.directory, identity, params.parameters, p.n_steps(),
                                  p.time(), w.bytes, MPI_COMM_WORLD);
          schedule.written();
          if (!d.stop() && params.progress_interval > 0)
            std::cout << "  checkpoint " << file << " (t = " << format_number(p.time())
                      << ", step " << p.n_steps() << ")" << std::endl;
        }
      if (!d.stop())
        return false;
      stopped = stop_status(d, "t", p.time(), p.n_steps(), file);
      if (d.signal != 0)
        {
          result.status      = stopped;
          result.n_steps     = p.n_steps();
          result.final_time  = p.time();
          result.wall_time_s = wall_timer.wall_time();
          if (write_files)
            write_summary(params.directory, scene, 1, discretisation.degree, result);
          throw Interrupted(d.signal, stopped);
        }
      return true;
    };
    try
      {
        for (const double t_out : output_times)
          {
            loop += advance_to(
              p, t_out,
              [&]() {
                balance.update(p);
                tv_max = std::max(tv_max, p.total_variation());
                dt = p.last_time_step();
                progress.update(p.n_steps(), p.time(), dt);
                // a step landing on t_out: first the snapshot (below)
                return p.time() < t_out * (1 - 1e-14) && poll();
              },
              &last_good);
            if (!stopped.empty())
              break;
            record();
            if (poll())
              break;
          }
      }
    catch (const StateFailure &f)
      {
        std::string msg = failure_message(f, p.n_steps(), graph);
        result.status   = "failed: " + msg;
        if (write_files)
          {
            p.state() = last_good;
            const std::string file = snapshots.write(p, exact);
            msg += "; last good state (t = " + format_number(p.time()) + ") written to " +
                   params.directory + "/" +
                   (file.empty() ? "profile files" : file);
          }
        result.n_steps     = p.n_steps();
        result.final_time  = p.time();
        result.wall_time_s = wall_timer.wall_time();
        if (write_files)
          write_summary(params.directory, scene, 1, discretisation.degree, result);
        throw RunError(msg);
      }
    catch (const RunError &e)
      {
        result.status     = std::string("failed: ") + e.what();
        result.n_steps    = p.n_steps();
        result.final_time = p.time();
        if (write_files)
          {
            p.state() = last_good;
            snapshots.write(p, exact);
            write_summary(params.directory, scene, 1, discretisation.degree, result);
          }
        throw;
      }

    result.n_steps           = p.n_steps();
    result.final_time        = p.time();
    if (!stopped.empty())
      {
        // stopped at max steps: a checkpoint to continue from, no results
        result.status      = stopped;
        result.wall_time_s = wall_timer.wall_time();
        write_summary(params.directory, scene, 1, discretisation.degree, result);
        std::cout << "  " << stopped << std::endl;
        return result;
      }
    result.time_loop_s       = loop.wall;
    const double updates     = double(result.n_dofs) * p.n_stages() * (p.n_steps() - first_step);
    result.dof_updates_per_s = loop.wall > 0 ? updates / loop.wall : 0;
    JsonObject &d = result.diagnostics;
    d.add("n_edges", static_cast<long long>(graph.edges.size()));
    d.add("n_vertex_ends", static_cast<long long>(p.junction().ends().size()));
    d.add("vertex_width", p.junction().width());
    d.add("integrator", integrator_name(p));
    d.add("cfl", discretisation.cfl);
    d.add("mass_initial", balance.mass0);
    d.add("mass_final", p.mass());
    d.add("boundary_inflow", p.boundary_inflow());
    d.add("mass_balance_residual_max", balance.max_residual);
    d.add("mass_step_residual_max", balance.max_step);
    d.add("vertex_value_initial", u00);
    d.add("vertex_value_final", p.vertex_value());
    d.add("rh_residual_final", p.rh_residual());
    d.add("total_variation_initial", tv0);
    d.add("total_variation_final", p.total_variation());
    d.add("total_variation_max", tv_max);
    d.add("cpu_time_loop_s", loop.cpu);
    d.add("dof_updates_per_cpu_s", loop.cpu > 0 ? updates / loop.cpu : 0.);
    if (exact)
      {
        const auto e = p.errors(*exact);
        result.errors.push_back({{e.l1, e.l2, e.linf}});
        result.l2_error = e.l2;
        d.add("exact_solution", exact->name());
        d.add("vertex_exact_final", exact->vertex_value(p.time()));
        d.add("l1_error", e.l1);
        d.add("l1_error_edges", e.l1_edges);
        d.add("l1_error_vertex", e.l1_vertex);
        d.add("linf_error", e.linf);
      }
    result.wall_time_s = wall_timer.wall_time();
    if (write_files)
      {
        write_summary(params.directory, scene, 1, discretisation.degree, result);
        std::cout << "  completed " << p.n_steps() << " steps to t = " << format_number(p.time())
                  << " in " << format_duration(result.wall_time_s) << " ("
                  << format_number(updates / std::max(loop.cpu, 1e-300) / 1e6)
                  << " MDoF-stage updates per CPU second); mass balance residual "
                  << format_number(balance.max_residual) << " (per step "
                  << format_number(balance.max_step) << ")";
        if (exact)
          std::cout << "; L1 error " << format_number(p.errors(*exact).l1);
        std::cout << std::endl;
      }
    return result;
  }

  void
  run_network_convergence(const Graph &graph, const std::vector<EdgeData> &data,
                          const Discretisation &discretisation,
                          const std::optional<double> vertex_value, const ExactSolution &exact,
                          const CommonParameters &params, const std::vector<double> &cfl)
  {
    CsvWriter                table, rates;
    std::vector<std::string> header{"degree", "level", "cells_per_unit_length", "dx", "dofs",
                                    "cfl", "time_steps", "l1_error", "eoc", "l1_error_edges",
                                    "l1_error_vertex", "l2_error", "linf_error",
                                    "mass_balance_residual_max", "mass_step_residual_max",
                                    "cpu_time_s", "wall_time_s"};
    for (unsigned int k = 0; k < graph.edges.size(); ++k)
      header.push_back("l1_error_edge_" + std::to_string(k + 1));
    rates.open(params.directory + "/convergence-rates.csv", {"degree", "eoc_finest"},
               "L1 error rate of the two finest meshes");
    table.open(params.directory + "/convergence.csv", header,
               "L1 error over all edges and the vertex cell at t = " +
                 format_number(params.final_time) + " against " + exact.name() +
                 "; eoc = log2(e(l-1)/e(l)) per level");
    JsonObject errors;
    for (unsigned int i = 0; i < params.convergence_degrees.size(); ++i)
      {
        Discretisation d = discretisation;
        d.degree         = params.convergence_degrees[i];
        d.cfl            = cfl[i];
        std::cout << "  degree " << d.degree << ", CFL " << format_number(d.cfl) << "\n"
                  << "  level    cells      dofs   steps      L1 error    EOC   L1 vertex"
                     "    CPU s"
                  << std::endl;
        double              e_prev = -1, h_prev = -1;
        std::vector<double> errs, eocs;
        for (const unsigned int cells : params.convergence_cells)
          {
            d.cells_per_unit_length = cells;
            Timer          wall;
            NetworkProblem p(graph, d, data);
            p.initialize(vertex_value);
            MassBalance balance;
            balance.start(p);
            const double cpu =
              advance_to(p, params.final_time, [&]() {
                balance.update(p);
                return false;
              }).cpu;
            const auto   e   = p.errors(exact);
            const double eoc = e_prev > 0 ? std::log(e_prev / e.l1) /
                                              std::log(h_prev / p.min_cell_size()) :
                                            NAN;
            std::vector<double> row{double(d.degree), level_of(cells), double(cells),
                                    p.min_cell_size(), double(p.n_dofs()), d.cfl,
                                    double(p.n_steps()), e.l1, eoc, e.l1_edges, e.l1_vertex,
                                    e.l2, e.linf, balance.max_residual, balance.max_step, cpu,
                                    wall.wall_time()};
            row.insert(row.end(), e.l1_per_edge.begin(), e.l1_per_edge.end());
            table.row(row);
            std::cout << std::setw(7) << level_of(cells) << std::setw(9) << cells
                      << std::setw(10) << p.n_dofs() << std::setw(8) << p.n_steps()
                      << std::setw(14) << std::scientific << std::setprecision(5) << e.l1
                      << std::defaultfloat << std::setw(7) << std::fixed
                      << std::setprecision(2) << eoc << std::defaultfloat << std::setw(12)
                      << std::scientific << std::setprecision(2) << e.l1_vertex
                      << std::defaultfloat << std::setw(9) << std::fixed
                      << std::setprecision(2) << cpu << std::defaultfloat << std::endl;
            e_prev = e.l1;
            h_prev = p.min_cell_size();
            errs.push_back(e.l1);
            eocs.push_back(eoc);
          }
        rates.row({double(d.degree), eocs.back()});
        errors.add("degree_" + std::to_string(d.degree) + "_l1_errors", errs);
        errors.add("degree_" + std::to_string(d.degree) + "_eoc", eocs);
      }
    JsonObject summary;
    summary.add("scene", "network");
    summary.add("mode", "convergence study");
    summary.add("dim", 1ll);
    summary.add("status", "completed");
    summary.add("exact_solution", exact.name());
    summary.add("cells_per_unit_length",
                std::vector<double>(params.convergence_cells.begin(),
                                    params.convergence_cells.end()));
    summary.add_object("errors", errors);
    summary.write(params.directory + "/summary.json");
  }
} // namespace granular_dg::network
