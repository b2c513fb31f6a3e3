// CPU cost per time step of the full-order Scheme 3 deployment (target: ≤ 1 × real time,
// i.e. ≤ 0.1 ms CPU per 100 µs step). Default config (4 modules, 2 × 8 interface meshes, 486
// unknowns after the elimination, Δt = 100 µs, output every step with the index-1 recovery, as
// `mastrom simulate configs/scheme3.toml` runs it).
//  * DeploymentSteps/<steps>: build + initialise + <steps> steps; the difference of 1000 and 3000
//    steps per 2000 is the per-step time without the set-up (printed at the end, CPU and wall).
// The first steps are the start of the acceleration ramp (0.1 s = 1000 steps): Newton counts there
// are representative of the ramp phases of the drive law, which are the most expensive.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>

#include "common/config.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/mast_model.hpp"

namespace {
using namespace mastrom;

/// Build the mast of `c` and run `o` on `threads` threads, once per benchmark iteration.
fullorder::DeploymentStatistics runDeployments(benchmark::State& state, const Config& c,
                                               const fullorder::DeploymentOptions& o,
                                               int threads) {
  fullorder::DeploymentStatistics stats;
  for (auto _ : state) {
    fullorder::MastModel mast = fullorder::buildMast(fullorder::mastParametersFromConfig(c));
    mast.system().setThreadCount(threads);
    fullorder::DeploymentSeries s = fullorder::simulateDeployment(mast, o, &stats);
    benchmark::DoNotOptimize(s.joint_torque_nm.data());
  }
  return stats;
}

void DeploymentSteps(benchmark::State& state) {
  const Config c;  // the defaults = configs/scheme3.toml
  fullorder::DeploymentOptions o;
  o.integrator = fullorder::integratorFromConfig(c);
  o.integrator.time_step_s = 1e-4;  // fixed steps of 100 µs: the per-step cost
  o.end_time_s = o.integrator.time_step_s * static_cast<double>(state.range(0));
  const fullorder::DeploymentStatistics stats =
      runDeployments(state, c, o, static_cast<int>(state.range(1)));
  state.counters["newton_per_step"] =
      static_cast<double>(stats.newton_iterations) / static_cast<double>(stats.steps);
  state.counters["factorizations"] = static_cast<double>(stats.factorizations);
}
// Three repetitions, the fastest counts (the machine is shared; noise only ever adds time).
BENCHMARK(DeploymentSteps)
    ->ArgNames({"steps", "threads"})
    ->Args({1000, 1})
    ->Args({3000, 1})
    ->Args({1000, 2})
    ->Args({3000, 2})
    ->Iterations(1)
    ->Repetitions(3)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

/// The first 0.3 s of the Scheme 3 deployment (the start-up ringing, the hardest stretch for the
/// step control), with the default adaptive steps (range 0 = 1) or fixed 10 µs steps (0), the
/// step that reaches ≈ 0.3 % NRMSE there (docs/user_guide.md §7). Counters: accepted steps,
/// rejected steps, factorisations.
void StartUpRinging(benchmark::State& state) {
  Config c;
  c.simulation.end_time_s = 0.3;
  c.simulation.adaptive = state.range(0) == 1;
  c.simulation.time_step_s = 1e-5;
  const fullorder::DeploymentStatistics stats = runDeployments(
      state, c, fullorder::deploymentFromConfig(c), static_cast<int>(state.range(1)));
  state.counters["steps"] = static_cast<double>(stats.steps);
  state.counters["rejected"] = static_cast<double>(stats.rejected_steps);
  state.counters["factorizations"] = static_cast<double>(stats.factorizations);
}
BENCHMARK(StartUpRinging)
    ->ArgNames({"adaptive", "threads"})
    ->Args({1, 1})
    ->Args({0, 1})
    ->Iterations(1)
    ->Repetitions(1)
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

class Reporter : public benchmark::ConsoleReporter {
public:
  Reporter() : benchmark::ConsoleReporter(OO_Tabular) {}  // no colour codes in logs
  void ReportRuns(const std::vector<Run>& runs) override {
    benchmark::ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs) {
      if (r.error_occurred || r.run_type != Run::RT_Iteration) continue;
      const std::string name = r.run_name.function_name + "/" + r.run_name.args;
      const double multiplier = benchmark::GetTimeUnitMultiplier(r.time_unit);
      const double cpu = r.GetAdjustedCPUTime() / multiplier;
      const double wall = r.GetAdjustedRealTime() / multiplier;
      if (!cpu_s.count(name) || cpu < cpu_s[name]) cpu_s[name] = cpu;
      if (!wall_s.count(name) || wall < wall_s[name]) wall_s[name] = wall;
    }
  }
  std::map<std::string, double> cpu_s, wall_s;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  Reporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const double step_s = 1e-4;  // DeploymentSteps' fixed step
  for (int threads : {1, 2}) {
    const std::string t = ":" + std::to_string(threads);
    const std::string short_run = "DeploymentSteps/steps:1000/threads" + t,
                      long_run = "DeploymentSteps/steps:3000/threads" + t;
    if (!reporter.cpu_s.count(short_run) || !reporter.cpu_s.count(long_run)) continue;
    const double cpu_per_step = (reporter.cpu_s[long_run] - reporter.cpu_s[short_run]) / 2000.0;
    const double wall_per_step = (reporter.wall_s[long_run] - reporter.wall_s[short_run]) / 2000.0;
    std::printf("full order Scheme 3, %d thread%s: %.4f ms wall (%.4f ms CPU) per step (3000 - 1000 "
                "steps, best of 3) = %.2f x real time (target <= 1)\n",
                threads, threads == 1 ? "" : "s", 1e3 * wall_per_step, 1e3 * cpu_per_step,
                wall_per_step / step_s);
  }
  const std::string adaptive = "StartUpRinging/adaptive:1/threads:1",
                    fixed = "StartUpRinging/adaptive:0/threads:1";
  if (reporter.wall_s.count(adaptive) && reporter.wall_s.count(fixed)) {
    std::printf("Scheme 3, first 0.3 s, 1 thread: adaptive %.2f s, fixed 10 us %.2f s: "
                "fixed / adaptive = %.2f (wall)\n",
                1e-3 * reporter.wall_s[adaptive], 1e-3 * reporter.wall_s[fixed],
                reporter.wall_s[fixed] / reporter.wall_s[adaptive]);
  }
  benchmark::Shutdown();
  return 0;
}
