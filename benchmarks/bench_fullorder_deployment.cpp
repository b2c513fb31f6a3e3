// CPU cost per time step of the full-order Scheme 3 deployment (issue #7 target: ≤ 1 × real time,
// i.e. ≤ 0.1 ms CPU per 100 µs step). Default config (4 modules, 2 × 8 interface meshes, 486
// unknowns after the elimination, Δt = 100 µs, output every step with the index-1 recovery, as
// `mastrom simulate configs/scheme3.toml` runs it).
//  * DeploymentSteps/<steps>: build + initialise + <steps> steps; the difference of 1000 and 2000
//    steps per 1000 is the per-step CPU time without the set-up (printed at the end).
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

void DeploymentSteps(benchmark::State& state) {
  const Config c;  // the DESIGN §1 defaults = configs/scheme3.toml
  fullorder::DeploymentOptions o;
  o.integrator = fullorder::integratorFromConfig(c);
  o.end_time_s = c.simulation.time_step_s * static_cast<double>(state.range(0));
  fullorder::DeploymentStatistics stats;
  for (auto _ : state) {
    fullorder::MastModel mast = fullorder::buildMast(fullorder::mastParametersFromConfig(c));
    fullorder::DeploymentSeries s = fullorder::simulateDeployment(mast, o, &stats);
    benchmark::DoNotOptimize(s.joint_torque_nm.data());
  }
  state.counters["newton_per_step"] =
      static_cast<double>(stats.newton_iterations) / static_cast<double>(stats.steps);
  state.counters["factorizations"] = static_cast<double>(stats.factorizations);
}
BENCHMARK(DeploymentSteps)->Arg(1000)->Arg(2000)->Iterations(1)->Unit(benchmark::kMillisecond);

class Reporter : public benchmark::ConsoleReporter {
public:
  Reporter() : benchmark::ConsoleReporter(OO_Tabular) {}  // no colour codes in logs
  void ReportRuns(const std::vector<Run>& runs) override {
    benchmark::ConsoleReporter::ReportRuns(runs);
    for (const Run& r : runs)
      if (!r.error_occurred)
        cpu_s[r.benchmark_name()] =
            r.GetAdjustedCPUTime() / benchmark::GetTimeUnitMultiplier(r.time_unit);
  }
  std::map<std::string, double> cpu_s;
};

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  Reporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  const auto a = reporter.cpu_s.find("DeploymentSteps/1000/iterations:1");
  const auto b = reporter.cpu_s.find("DeploymentSteps/2000/iterations:1");
  if (a != reporter.cpu_s.end() && b != reporter.cpu_s.end() && b->second > a->second) {
    const double per_step_s = (b->second - a->second) / 1000.0;
    const double step_s = Config{}.simulation.time_step_s;
    std::printf("full order Scheme 3: %.4f ms CPU per step (2000 - 1000 steps) = %.2f x real time "
                "(target <= 1)\n",
                1e3 * per_step_s, per_step_s / step_s);
  }
  benchmark::Shutdown();
  return 0;
}
