#include <deal.II/base/mpi.h>

#include <granular_dg/base/benchmark.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <fstream>
#include <iostream>
#include <sstream>

namespace granular_dg
{
  const char *
  StepPhases::name(const Phase p)
  {
    static const char *names[] = {"operator",      "vector_updates",   "post_stage_hook",
                                  "limiter",       "post_limiter_hook", "admissibility",
                                  "time_step",     "end_of_step_hook", "state_copy"};
    return names[p];
  }

  double
  StepPhases::total() const
  {
    double sum = 0;
    for (const double s : seconds)
      sum += s;
    return sum;
  }

  double
  process_cpu_time()
  {
    timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
  }

  std::string
  load_average()
  {
    std::ifstream in("/proc/loadavg");
    std::string   a, b, c;
    if (!(in >> a >> b >> c))
      return "";
    return a + " " + b + " " + c;
  }

  std::vector<BenchmarkRepetition>
  run_benchmark(const BenchmarkParameters &params, const std::function<double(StepPhases *)> &step)
  {
    using dealii::Utilities::MPI::max;
    using dealii::Utilities::MPI::sum;
    const MPI_Comm comm  = MPI_COMM_WORLD;
    using Clock          = std::chrono::steady_clock;
    auto run_block = [&](const unsigned long n, StepPhases *phases, BenchmarkRepetition &r) {
      MPI_Barrier(comm);
      const double cpu0    = process_cpu_time();
      const auto   wall0   = Clock::now();
      double       untimed = 0;
      for (unsigned long i = 0; i < n; ++i)
        untimed += step(phases);
      const double cpu  = process_cpu_time() - cpu0 - untimed;
      const double wall = std::chrono::duration<double>(Clock::now() - wall0).count() - untimed;
      r.steps  = n;
      r.cpu_s  = sum(cpu, comm);
      r.wall_s = max(wall, comm);
      return max(cpu, comm);
    };

    for (unsigned int i = 0; i < params.warmup_steps; ++i)
      step(nullptr);
    unsigned long n = params.steps;
    if (n == 0)
      {
        // the same decision on every rank: from the slowest rank's CPU time
        n = 1;
        BenchmarkRepetition probe;
        while (true)
          {
            const double cpu = run_block(n, nullptr, probe);
            if (cpu >= params.min_time || n >= (1ul << 24))
              break;
            const double factor = 1.2 * params.min_time / std::max(cpu, 1e-9);
            n = static_cast<unsigned long>(std::ceil(n * std::min(8., std::max(2., factor))));
          }
      }
    std::vector<BenchmarkRepetition> reps(params.repetitions);
    for (auto &r : reps)
      run_block(n, &r.phases, r);
    return reps;
  }

  namespace
  {
    double
    median(std::vector<double> v)
    {
      std::sort(v.begin(), v.end());
      const std::size_t n = v.size();
      return n == 0 ? 0. : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
    }
  } // namespace

  void
  write_benchmark(const std::string &directory, const JsonObject &run_case,
                  const std::vector<BenchmarkRepetition> &reps, const double n_dofs,
                  const unsigned int n_stages, const std::string &load_before)
  {
    if (dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) != 0)
      return;
    const unsigned int ranks = dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
    // per repetition: CPU per step summed over ranks (the cost per core),
    // wall per step, and the share of operator + vector updates in the
    // phases (wall clocks of rank 0)
    std::vector<double> cpu, wall, rate, rk_rate, wall_rate;
    std::array<std::vector<double>, StepPhases::n_phases> phase;
    for (const auto &r : reps)
      {
        const double c = r.cpu_s / r.steps, w = r.wall_s / r.steps;
        const double total = r.phases.total();
        const double rk    = r.phases.seconds[StepPhases::operator_apply] +
                          r.phases.seconds[StepPhases::vector_updates];
        cpu.push_back(c);
        wall.push_back(w);
        rate.push_back(n_dofs * n_stages / c);
        rk_rate.push_back(total > 0 && rk > 0 ? n_dofs * n_stages / (c * rk / total) : 0.);
        wall_rate.push_back(n_dofs * n_stages / w);
        for (unsigned int p = 0; p < StepPhases::n_phases; ++p)
          phase[p].push_back(1e6 * r.phases.seconds[p] / r.steps);
      }
    JsonObject j;
    j.add_object("case", run_case);
    j.add("n_dofs", n_dofs);
    j.add("n_stages", n_stages);
    j.add("n_mpi_ranks", ranks);
    j.add("steps_per_repetition", static_cast<long long>(reps.empty() ? 0 : reps[0].steps));
    j.add("repetitions", static_cast<long long>(reps.size()));
    j.add("load_before", load_before);
    j.add("load_after", load_average());
    j.add("cpu_s_per_step", cpu);
    j.add("cpu_s_per_step_min", *std::min_element(cpu.begin(), cpu.end()));
    j.add("cpu_s_per_step_median", median(cpu));
    j.add("wall_s_per_step_min", *std::min_element(wall.begin(), wall.end()));
    j.add("wall_s_per_step_median", median(wall));
    // DoF-stage updates per second per core (CPU time): the whole step as the
    // time loop runs it, and operator + vector updates alone
    j.add("step_dof_updates_per_s_per_core_best", *std::max_element(rate.begin(), rate.end()));
    j.add("step_dof_updates_per_s_per_core_median", median(rate));
    j.add("rk_dof_updates_per_s_per_core_best", *std::max_element(rk_rate.begin(), rk_rate.end()));
    j.add("rk_dof_updates_per_s_per_core_median", median(rk_rate));
    j.add("step_dof_updates_per_s_wall_best", *std::max_element(wall_rate.begin(), wall_rate.end()));
    j.add("step_dof_updates_per_s_wall_median", median(wall_rate));
    JsonObject phases;
    for (unsigned int p = 0; p < StepPhases::n_phases; ++p)
      phases.add(StepPhases::name(StepPhases::Phase(p)), median(phase[p]));
    j.add_object("phases_us_per_step_median", phases);
    j.write(directory + "/benchmark.json");

    std::ostringstream line;
    line << "  benchmark: " << reps.size() << " x " << (reps.empty() ? 0 : reps[0].steps)
         << " steps, " << format_number(median(cpu) * 1e6) << " us CPU per step (median), "
         << format_number(median(rate) / 1e6) << " MDoF-stage updates/s per core (whole step), "
         << format_number(median(rk_rate) / 1e6) << " (operator + vector updates); load "
         << load_before << " -> " << load_average();
    std::cout << line.str() << std::endl;
  }
} // namespace granular_dg
