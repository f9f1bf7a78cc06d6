#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>

#include <granular_dg/base/errors.h>
#include <granular_dg/base/time_loop.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <sstream>

namespace granular_dg
{
  using namespace dealii;

  namespace
  {
    CheckpointIdentity
    identity_of(const EvolutionInfo &info)
    {
      return {info.scene, info.physics, info.dim, info.degree, info.n_cells, info.n_dofs};
    }

    /// "inadmissible state at t = 1.5 (step 12), x = (3), state (u = 2): why"
    std::string
    describe(const Inadmissible &f, const std::string &time_name, const unsigned long step)
    {
      std::ostringstream msg;
      if (f.initial)
        msg << "inadmissible initial state at " << f.where;
      else
        msg << "inadmissible state at " << time_name << " = " << format_number(f.time)
            << " (step " << step + 1 << "), " << f.where;
      msg << ", state (";
      for (unsigned int c = 0; c < f.state.size(); ++c)
        msg << (c ? ", " : "") << (c < f.names.size() ? f.names[c] : "?") << " = "
            << format_number(f.state[c]);
      msg << "): " << f.reason;
      return msg.str();
    }

    /// Seconds since start on the steady clock.
    double
    seconds_since(const std::chrono::steady_clock::time_point start)
    {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
  } // namespace

  TimeLoop::TimeLoop(Evolution &problem, const RunParameters &params, const bool write_files,
                     const double dt_factor)
    : problem(problem)
    , params(params)
    , write_files(write_files && !params.benchmark.enabled)
    , root(Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
    , dt_factor(dt_factor)
    , info(problem.info())
    , timer_out(std::make_unique<ConditionalOStream>(std::cout, root))
  {}

  TimeLoop::~TimeLoop() = default;

  template <typename Archive>
  void
  TimeLoop::loop_state(Archive &ar, std::uint64_t &timeseries_size)
  {
    ar.io(t);
    ar.io(step);
    ar.io(dt);
    ar.io(n_snapshots);
    ar.io(last_record_time);
    ar.io(last_main_file);
    ar.io(snapshots);
    ar.io(xdmf_grids);
    ar.io(rest_from);
    ar.io(timeseries_size);
  }

  RunResult
  TimeLoop::run()
  {
    start();
    if (params.benchmark.enabled)
      return benchmark();
    progress = std::make_unique<Progress>(t, params.final_time,
                                          (write_files && root) ? params.progress_interval : 0.);
    schedule = std::make_unique<CheckpointSchedule>(params.checkpoint_steps,
                                                    params.checkpoint_seconds,
                                                    write_files ? params.max_steps : 0,
                                                    write_files, MPI_COMM_WORLD);
    const InterruptHandlers interrupt_handlers;
    problem.store(Evolution::Slot::last_good);
    try
      {
        if (result.resumed_from_step == 0)
          {
            record();
            problem.check_initial_state(t);
          }
        steps();
      }
    catch (const Inadmissible &failure)
      {
        fail(failure);
      }
    catch (const RunError &e)
      {
        fail(e);
      }
    if (result.status != "completed")
      return result; // stopped at max steps
    return complete();
  }

  void
  TimeLoop::start()
  {
    result.n_dofs  = info.n_dofs;
    result.n_cells = info.n_cells;
    result.h_min   = info.h_min;
    if (params.resume && write_files)
      {
        const Checkpoint c = read_checkpoint(params.directory, identity_of(info),
                                             params.parameters, MPI_COMM_WORLD);
        require_beyond_checkpoint(params, c, info.time_name);
        if (root)
          begin_manifest(params.directory, true);
        resume(c);
      }
    else
      try
        {
          t = problem.initialize();
        }
      catch (const RunError &e)
        {
          // a failure at set-up: summary.json has the status (no state yet)
          result.status = std::string("failed: ") + e.what();
          if (write_files)
            write_summary();
          throw;
        }
    first_step = step;
    // a run that writes nothing (a convergence study) steps straight to the end
    output_times =
      write_files ? params.output_schedule(t) : std::vector<double>{params.final_time};
    if (write_files && root)
      std::cout << "  " << info.description << "; output to " << params.directory << "/ ("
                << info.snapshot_files << (info.snapshot_files.empty() ? "" : ", ")
                << "timeseries.csv, summary.json)" << std::endl;
    if (write_files && result.resumed_from_step == 0)
      open_timeseries();
    // (only now: a TimerOutput destroyed by an exception of the checks
    // above would print MPI warnings)
    timer.emplace(MPI_COMM_WORLD, *timer_out, TimerOutput::never, TimerOutput::wall_times);
  }

  void
  TimeLoop::open_timeseries()
  {
    if (!root)
      return;
    std::vector<std::string> header{"time", "step", "dt"};
    for (const auto &n : problem.timeseries_names())
      header.push_back(n);
    timeseries.open(params.directory + "/timeseries.csv", header, problem.timeseries_comment());
  }

  void
  TimeLoop::resume(const Checkpoint &c)
  {
    ByteReader    r(c.payload, &c.blocks);
    std::uint64_t timeseries_size = 0;
    std::string   state;
    loop_state(r, timeseries_size);
    r.io(state);
    ByteReader s = r.nested(state);
    problem.load(s);
    if (root)
      timeseries.reopen(params.directory + "/timeseries.csv", timeseries_size);
    result.resumed_from_step = step;
    if (root)
      std::cout << "  resuming from " << c.file << ": " << info.time_name << " = "
                << format_number(t) << ", step " << step << std::endl;
  }

  std::string
  TimeLoop::save_checkpoint()
  {
    TimerOutput::Scope scope(*timer, "checkpoint");
    ByteWriter         w;
    std::uint64_t      timeseries_size = root ? timeseries.size() : 0;
    loop_state(w, timeseries_size);
    ByteWriter s;
    problem.save(s);
    w.io(std::move(s));
    return write_checkpoint(params.directory, identity_of(info), params.parameters, step, t, w,
                            MPI_COMM_WORLD);
  }

  double
  TimeLoop::next_step(const double t_out, bool &lands)
  {
    double dt_step = dt_factor * problem.time_step(t);
    // a step that would leave a sliver before t_out takes it with it
    lands = t + dt_step * (1. + sliver_fraction) >= t_out * (1 - 1e-14);
    if (lands)
      dt_step = t_out - t;
    return dt_step;
  }

  void
  TimeLoop::take_step(const double dt_step, const bool lands, const double t_out)
  {
    {
      TimerOutput::Scope scope(*timer, "time stepping");
      loop_timer.start();
      problem.advance(t, dt_step);
      loop_timer.stop();
    }
    t  = lands ? t_out : t + dt_step;
    dt = dt_step;
    ++step;
    problem.end_of_step(t, dt, step);
  }

  void
  TimeLoop::skip_step(const double dt_step)
  {
    t += dt_step;
    dt = dt_step;
    ++step;
    problem.end_of_step(t, dt, step);
  }

  void
  TimeLoop::steps()
  {
    loop_timer.stop();
    loop_timer.reset();
    while (next_output < output_times.size())
      {
        // at rest the state is the last good one (the last step kept every
        // value): stored only before a step that is computed
        const bool resting = problem.at_rest();
        if (!resting)
          problem.store(Evolution::Slot::last_good);
        bool         lands   = false;
        const double t_out   = output_times[next_output];
        const double dt_step = next_step(t_out, lands);
        const bool   repeats = !lands && dt_step == dt;
        if (resting && !lands && problem.skip_step(dt_step))
          skip_step(dt_step);
        else
          {
            if (resting)
              problem.store(Evolution::Slot::last_good);
            take_step(dt_step, lands, t_out);
            watch_rest(repeats);
          }
        if (lands)
          {
            record();
            ++next_output;
          }
        progress->update(step, t, dt);
        if (poll())
          return;
      }
  }

  void
  TimeLoop::watch_rest(const bool repeats)
  {
    if (!problem.at_rest())
      {
        // a step of another size than the last computes every cell and may
        // change the state; only a repeated step that did not come to rest
        // shows motion
        if (repeats)
          rest_from = -1;
        return;
      }
    if (rest_from >= 0)
      return;
    rest_from = t;
    if (!rest_announced && root && write_files && params.progress_interval > 0)
      std::cout << "  at rest from " << info.time_name << " = " << format_number(t) << " (step "
                << step << "): steps of this size change nothing and are not computed"
                << std::endl;
    rest_announced = true;
  }

  void
  TimeLoop::record()
  {
    if (!write_files)
      return;
    TimerOutput::Scope scope(*timer, "output");
    // a file that cannot be written, on any rank, stops every rank (after
    // the collective parts: the snapshot, then the time series' values)
    const std::string at = " at " + info.time_name + " = " + format_number(t);
    SnapshotFiles     files;
    last_record_time = t; // (on every rank, also if a write fails: no retry)
    agree_on_run_error(
      MPI_COMM_WORLD,
      [&] {
        files          = problem.write_snapshot(params.directory, n_snapshots++, t);
        last_main_file = files.main_file;
      },
      at);
    std::vector<double> row{t, double(step), dt};
    for (const double v : problem.timeseries_values(t))
      row.push_back(v);
    agree_on_run_error(
      MPI_COMM_WORLD,
      [&] {
        if (!files.pvd_entry.empty())
          {
            snapshots.emplace_back(t, files.pvd_entry);
            if (root)
              write_pvd(params.directory + "/solution.pvd", snapshots);
          }
        if (!files.xdmf_entry.empty())
          {
            xdmf_grids.push_back(files.xdmf_entry);
            if (root)
              write_xdmf(params.directory + "/solution.xdmf", xdmf_grids);
          }
        if (root)
          timeseries.row(row);
      },
      at);
  }

  bool
  TimeLoop::poll()
  {
    // a run that reached its final time has completed, whatever the step
    // counter says; it writes a checkpoint only when one is due anyway
    const bool finished = next_output >= output_times.size();
    auto       d        = schedule->poll(step);
    if (finished)
      d = {d.scheduled, 0, false, d.scheduled};
    std::string file;
    if (d.write)
      {
        file = save_checkpoint();
        schedule->written();
        if (root && !d.stop() && params.progress_interval > 0)
          std::cout << "  checkpoint " << file << " (" << info.time_name << " = "
                    << format_number(t) << ", step " << step << ")" << std::endl;
      }
    if (!d.stop())
      return false;
    stop(stop_status(d, info.time_name, t, step, file), d.signal);
    return true;
  }

  void
  TimeLoop::stop(const std::string &status, const int signal)
  {
    result.status = status;
    record_end();
    if (write_files)
      write_summary();
    timer.reset();
    if (signal != 0)
      throw Interrupted(signal, status);
    if (root)
      std::cout << "  " << status << std::endl;
  }

  void
  TimeLoop::fail(const Inadmissible &failure)
  {
    std::string msg = describe(failure, info.time_name, step);
    result.status   = "failed: " + msg;
    const auto written = [&] {
      if (write_files && failure.initial)
        msg += "; initial state written to " + params.directory + "/";
      else if (write_files)
        {
          problem.restore(Evolution::Slot::last_good);
          if (last_record_time != t)
            record();
          msg += "; last good state (" + info.time_name + " = " + format_number(t) +
                 ") written to " + params.directory + "/" +
                 (last_main_file.empty() ? "summary.json only (Output/write vtu = false)" :
                                           last_main_file);
        }
    };
    const std::string then = finish_failed(written); // (appends to msg first)
    throw RunError(msg + then);
  }

  void
  TimeLoop::fail(const RunError &e)
  {
    result.status = std::string("failed: ") + e.what();
    problem.restore(Evolution::Slot::last_good);
    throw RunError(e.what() + finish_failed([&] {
                     if (write_files && last_record_time != t)
                       record();
                   }));
  }

  template <typename WriteState>
  std::string
  TimeLoop::finish_failed(const WriteState &write_state)
  {
    std::string then;
    try
      {
        write_state();
        record_end();
        problem.finish(t, result, write_files);
        if (write_files)
          write_summary();
      }
    catch (const RunError &also)
      {
        // (a file that cannot be written either: say so after the cause)
        then = std::string("; then: ") + also.what();
      }
    timer.reset();
    return then;
  }

  RunResult
  TimeLoop::complete()
  {
    result.at_rest_from = rest_from;
    record_end();
    problem.finish(t, result, write_files);
    result.wall_time_s = wall_timer.wall_time();
    if (!write_files)
      return result;
    try
      {
        write_summary();
      }
    catch (const RunError &)
      {
        timer.reset(); // (its destructor would warn of the exception)
        throw;
      }
    if (root)
      std::cout << "  completed " << step << " steps to " << info.time_name << " = "
                << format_number(t) << " in " << format_duration(result.wall_time_s) << " ("
                << format_number(result.dof_updates_per_s / 1e6)
                << " MDoF-stage updates/s in the time loop)"
                << (result.at_rest_from >= 0 ?
                      "; at rest from " + info.time_name + " = " +
                        format_number(result.at_rest_from) :
                      "")
                << std::endl;
    // collective: every rank takes part, rank 0 prints
    timer->print_wall_time_statistics(MPI_COMM_WORLD);
    return result;
  }

  void
  TimeLoop::record_end()
  {
    result.n_steps         = step;
    result.final_time      = t;
    result.wall_time_s     = wall_timer.wall_time();
    result.time_loop_s     = loop_timer.wall_time();
    result.time_loop_cpu_s = loop_timer.cpu_time();
    const double updates   = double(info.n_dofs) * info.n_stages * (step - first_step);
    result.dof_updates_per_s = result.time_loop_s > 0 ? updates / result.time_loop_s : 0;
    result.dof_updates_per_cpu_s_per_rank =
      result.time_loop_cpu_s > 0 ?
        updates / Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD) / result.time_loop_cpu_s :
        0;
  }

  RunResult
  TimeLoop::benchmark()
  {
    try
      {
        problem.check_initial_state(t);
      }
    catch (const Inadmissible &f)
      {
        throw RunError("benchmark: inadmissible initial state: " + f.reason);
      }
    if (root)
      std::cout << "  benchmark: " << info.description << "; writes " << params.directory
                << "/benchmark.json only" << std::endl;
    problem.store(Evolution::Slot::benchmark_start);
    const double      t0   = t;
    const std::string load = load_average();
    std::vector<BenchmarkRepetition> reps;
    try
      {
        reps = run_benchmark(params.benchmark, [&](StepPhases *phases) {
          problem.set_phases(phases);
          {
            StepPhases::Scope scope(phases, StepPhases::state_copy);
            problem.store(Evolution::Slot::last_good);
          }
          double dt_step = 0, untimed = 0;
          {
            StepPhases::Scope scope(phases, StepPhases::time_step);
            dt_step = dt_factor * problem.time_step(t);
          }
          if (t + dt_step > params.final_time)
            {
              // the case's own dynamics only: start again from the initial state
              const auto start = std::chrono::steady_clock::now();
              problem.restore(Evolution::Slot::benchmark_start);
              t       = t0;
              dt_step = dt_factor * problem.time_step(t);
              untimed = seconds_since(start);
            }
          const double before = phases ? phases->total() : 0.;
          const auto   start  = std::chrono::steady_clock::now();
          problem.advance(t, dt_step);
          if (phases)
            // what the problem did not charge to a phase: the vector updates
            phases->seconds[StepPhases::vector_updates] +=
              seconds_since(start) - (phases->total() - before);
          t += dt_step;
          dt = dt_step;
          ++step;
          StepPhases::Scope scope(phases, StepPhases::end_of_step_hook);
          problem.end_of_step(t, dt, step);
          return untimed;
        });
      }
    catch (const Inadmissible &f)
      {
        timer.reset(); // (its destructor would warn of the exception)
        throw RunError("benchmark: " + describe(f, info.time_name, step));
      }
    catch (const RunError &)
      {
        timer.reset();
        throw;
      }
    problem.set_phases(nullptr);
    JsonObject c;
    c.add("scene", info.scene);
    c.add("physics", info.physics);
    c.add("dim", static_cast<long long>(info.dim));
    c.add("degree", info.degree);
    c.add("n_cells", static_cast<long long>(info.n_cells));
    c.add_fields(info.method);
    write_benchmark(params.directory, c, reps, info.n_dofs, info.n_stages, load);
    result.status     = "benchmark";
    result.n_steps    = step;
    result.final_time = t;
    timer.reset();
    return result;
  }

  void
  TimeLoop::write_summary() const
  {
    agree_on_run_error(MPI_COMM_WORLD,
                       [&] { granular_dg::write_summary(params.directory, info, result); });
  }

  void
  write_summary(const std::string &directory, const EvolutionInfo &info, const RunResult &r)
  {
    if (Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
      return;
    JsonObject s;
    s.add("scene", info.scene);
    s.add("dim", static_cast<long long>(info.dim));
    s.add("degree", info.degree);
    s.add("n_cells", static_cast<long long>(r.n_cells));
    s.add("n_dofs", static_cast<long long>(r.n_dofs));
    s.add("n_time_steps", static_cast<long long>(r.n_steps));
    s.add("final_time", r.final_time);
    s.add("wall_time_s", r.wall_time_s);
    s.add("time_loop_s", r.time_loop_s);
    s.add("time_loop_cpu_s", r.time_loop_cpu_s);
    s.add("dof_updates_per_s", r.dof_updates_per_s);
    s.add("dof_updates_per_cpu_s_per_rank", r.dof_updates_per_cpu_s_per_rank);
    s.add("n_mpi_ranks", static_cast<long long>(Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD)));
    s.add("status", r.status);
    if (r.resumed_from_step > 0)
      s.add("resumed_from_step", static_cast<long long>(r.resumed_from_step));
    if (r.at_rest_from >= 0)
      s.add("at_rest_from", r.at_rest_from);
    if (!r.errors.empty())
      {
        JsonObject e;
        e.add("l2_all_components", r.l2_error);
        for (unsigned int c = 0; c < r.errors.size(); ++c)
          e.add("component_" + std::to_string(c) + "_l1_l2_linf",
                std::vector<double>(r.errors[c].begin(), r.errors[c].end()));
        s.add_object("errors", e);
      }
    s.add_object("diagnostics", r.diagnostics);
    s.write(directory + "/summary.json");
  }
} // namespace granular_dg
