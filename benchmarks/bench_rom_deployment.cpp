// Speed of the ROM's online stage (targets: one 8 s Scheme 3 deployment from the ROM ≤ 1 ms
// CPU; a screen of 10⁴ designs ≤ 10 s on 2 cores):
//  * RomDeployment/<modes>/<step µs>: simulateModalDeployment of the paper's Scheme 3 (default
//    config: 4 modules, 2 × 8 interface meshes) over 8 s, trapezoidal drive, 10 or 20 modes, output
//    step 1 ms or 0.1 ms;
//  * Interpolate/<method>: one modal model from a 3 × 3 Scheme 3 database (thickness × inner
//    diameter), tracked and manifold;
//  * RomDeploymentMetrics/<modes>/<step µs>/<continuous>: the same deployment reduced to the
//    docs/theory.md §1 metrics while stepping (rom/model/deployment_metrics.hpp) — what the screen runs
// per
//    design; continuous = 1: peaks of the continuous response (refined between samples, the
//    default now), 0: peaks over the samples (before);
//  * RomDeploymentMetricsSampled/…: the same with the drive sampled once outside the loop
//    (rom/model/modal_stepping.hpp), as the screen shares it between designs;
//  * Screen/<method>/<step µs>/<continuous>: designs per second of rom::runScreen on that database
//    (one rank; under mpirun the CLI shares the designs), ROM step 2 ms (the screen's default),
//    1 ms or 0.1 ms — the counter `designs_per_s`;
//  * FullOrderSteps/<steps>: the full-order Scheme 3 deployment (same default config) at
//    Δt = 25 µs over 200 and 400 steps; the difference / 200 is the CPU time per step without
//    the set-up, extrapolated to the 320 000 steps of 8 s. The first 10 ms are the start of the
//    acceleration ramp: Newton iteration counts there may differ from the rest of the run.
// At the end a summary prints the CPU times against the targets and the ROM / full-order
// ratio. The modal models come from dense modal solves done once before timing (≈ 10 s).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <memory>
#include <string>

#include "fullorder/deployment.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/mast_model.hpp"
#include "modes/eigen_solver.hpp"
#include "modes/linearize.hpp"
#include "modes/slepc_session.hpp"
#include "rom/offline/database_build.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/model/modal_extraction.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/studies/screening.hpp"
#include "tests/rom/reference_modal_deployment.hpp"

namespace {
using namespace mastrom;

rom::ModalModel scheme3Model(int modes) {
  const Config c;  // defaults = Scheme 3 (docs/theory.md §1)
  const fullorder::MastModel model =
      modes::buildLockedMast(fullorder::mastParametersFromConfig(c), c.modes.angleRad());
  const modes::Linearization lin = modes::linearizeMast(model);
  modes::EigenSolverOptions eo;
  eo.count = modes;
  eo.backend = EigenBackendKind::Dense;
  const modes::EigenResult r = modes::solveConstrainedEigenproblem(lin.problem, eo);
  rom::LinearizedModes lm;
  lm.q_reference = lin.q;
  lm.mass = lin.problem.mass;
  lm.damping = lin.damping;
  lm.omega_squared = r.eigenvalues_rad2_s2;
  lm.modes = r.modes;
  return rom::extractModalModel(model, lm);
}

const rom::ModalModel& model(int modes) {
  static const rom::ModalModel m10 = scheme3Model(10), m20 = scheme3Model(20);
  return modes == 10 ? m10 : m20;
}

const rom::RomDatabase& database() {
  static const rom::RomDatabase db = [] {
    Config c;
    c.simulation.time_step_s = 1e-3;  // the screen's output step
    rom::DatabaseBuildOptions o;
    o.axes = {rom::parseParameterAxis("interface.thickness=0.001:0.002:3", c),
              rom::parseParameterAxis("interface.inner_diameter=0.085:0.1:3", c)};
    o.modes = 10;
    o.backend = EigenBackendKind::Dense;
    return rom::buildDatabase(c, o);
  }();
  return db;
}

void RomDeployment(benchmark::State& state) {
  const rom::ModalModel& m = model(static_cast<int>(state.range(0)));
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(Config{}));
  rom::ModalDeploymentOptions o;
  o.end_time_s = 8.0;
  o.step_s = 1e-6 * static_cast<double>(state.range(1));
  for (auto _ : state) {
    fullorder::DeploymentSeries s = rom::simulateModalDeployment(m, drive, o);
    benchmark::DoNotOptimize(s.joint_torque_nm.data());
  }
  state.counters["samples"] = 8.0 / o.step_s + 1;
}
BENCHMARK(RomDeployment)
    ->ArgNames({"modes", "step_us"})
    ->Args({10, 1000})
    ->Args({20, 1000})
    ->Args({10, 100})
    ->Args({20, 100})
    ->Unit(benchmark::kMicrosecond);

// The plain first implementation (kept as the tests' reference), for the speed-up in the same run.
void RomDeploymentPlain(benchmark::State& state) {
  const rom::ModalModel& m = model(static_cast<int>(state.range(0)));
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(Config{}));
  rom::ModalDeploymentOptions o;
  o.end_time_s = 8.0;
  o.step_s = 1e-6 * static_cast<double>(state.range(1));
  for (auto _ : state) {
    fullorder::DeploymentSeries s = rom::testing::referenceModalDeployment(m, drive, o);
    benchmark::DoNotOptimize(s.joint_torque_nm.data());
  }
}
BENCHMARK(RomDeploymentPlain)
    ->ArgNames({"modes", "step_us"})
    ->Args({10, 1000})
    ->Args({20, 1000})
    ->Unit(benchmark::kMicrosecond);

// The screen's per-design path: the same deployment reduced to its metrics while stepping.
rom::PeakResolution peaksOf(const benchmark::State& state) {
  return state.range(2) != 0 ? rom::PeakResolution::Continuous : rom::PeakResolution::Samples;
}

void RomDeploymentMetrics(benchmark::State& state) {
  const rom::ModalModel& m = model(static_cast<int>(state.range(0)));
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(Config{}));
  rom::ModalDeploymentOptions o;
  o.end_time_s = 8.0;
  o.step_s = 1e-6 * static_cast<double>(state.range(1));
  for (auto _ : state) {
    fullorder::DeploymentMetrics r = rom::modalDeploymentMetrics(
        m, drive, o, 6.1, fullorder::kDefaultSettlingBandRadS2, peaksOf(state));
    benchmark::DoNotOptimize(r.peak_drive_torque);
  }
  const rom::PeakRefinementStats stats = rom::lastPeakRefinementStats();
  state.counters["refined_steps"] = static_cast<double>(stats.refined_steps);
  state.counters["sub_steps"] = static_cast<double>(stats.sub_steps);
}
BENCHMARK(RomDeploymentMetrics)
    ->ArgNames({"modes", "step_us", "continuous"})
    ->Args({20, 2000, 1})
    ->Args({10, 1000, 1})
    ->Args({20, 1000, 1})
    ->Args({10, 1000, 0})
    ->Args({20, 1000, 0})
    ->Args({10, 100, 1})
    ->Args({10, 100, 0})
    ->Unit(benchmark::kMicrosecond);

// The screen's kernel alone: the drive sampled once, shared by all iterations.
void RomDeploymentMetricsSampled(benchmark::State& state) {
  const rom::ModalModel& m = model(static_cast<int>(state.range(0)));
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(Config{}));
  rom::ModalDeploymentOptions o;
  o.end_time_s = 8.0;
  o.step_s = 1e-6 * static_cast<double>(state.range(1));
  const rom::SampledDrive sampled = rom::sampleDrive(drive, o);
  for (auto _ : state) {
    fullorder::DeploymentMetrics r = rom::modalDeploymentMetrics(
        m, sampled, false, 6.1, fullorder::kDefaultSettlingBandRadS2, peaksOf(state));
    benchmark::DoNotOptimize(r.peak_drive_torque);
  }
}
BENCHMARK(RomDeploymentMetricsSampled)
    ->ArgNames({"modes", "step_us", "continuous"})
    ->Args({20, 2000, 1})
    ->Args({10, 1000, 1})
    ->Args({20, 1000, 1})
    ->Args({10, 1000, 0})
    ->Args({20, 1000, 0})
    ->Unit(benchmark::kMicrosecond);

void Interpolate(benchmark::State& state) {
  const auto method = static_cast<rom::InterpolationMethod>(state.range(0));
  if (!rom::interpolationMethodAvailable(method)) {
    state.SkipWithError("method not available in this build");
    return;
  }
  const std::unique_ptr<rom::ModalInterpolator> interp = rom::makeInterpolator(database(), method);
  const std::vector<double> p{0.00137, 0.0912};
  for (auto _ : state) {
    rom::ModalModel m = interp->evaluate(p);
    benchmark::DoNotOptimize(m.omega_rad_s.data());
  }
  state.SetLabel(rom::toString(method));
}
BENCHMARK(Interpolate)
    ->Arg(static_cast<int>(rom::InterpolationMethod::Tracked))
    ->Arg(static_cast<int>(rom::InterpolationMethod::Manifold))
    ->Unit(benchmark::kMicrosecond);

void Screen(benchmark::State& state) {
  const rom::RomDatabase& db = database();
  rom::ScreenOptions o;
  o.method = static_cast<rom::InterpolationMethod>(state.range(0));
  if (!rom::interpolationMethodAvailable(o.method)) {
    state.SkipWithError("method not available in this build");
    return;
  }
  o.axes = {rom::parseScreenAxis("interface.thickness=0.001:0.002:10", db),
            rom::parseScreenAxis("interface.inner_diameter=0.085:0.1:10", db),
            rom::parseScreenAxis("drive.law=trapezoidal,cycloidal", db)};
  // The step of the argument for both peak resolutions (an explicit output.step wins over the
  // screen's default step, rom/studies/screen_kernel.hpp).
  o.overrides = {"output.step=" + std::to_string(1e-6 * static_cast<double>(state.range(1)))};
  o.peaks = peaksOf(state);
  long designs = 0;
  for (auto _ : state) {
    const rom::ScreenTable t = rom::runScreen(db, o);
    designs += t.designs;
  }
  state.counters["designs_per_s"] =
      benchmark::Counter(static_cast<double>(designs), benchmark::Counter::kIsRate);
  state.SetLabel(rom::toString(o.method));
}
constexpr int kTracked = static_cast<int>(rom::InterpolationMethod::Tracked);
BENCHMARK(Screen)
    ->ArgNames({"method", "step_us", "continuous"})
    ->Args({kTracked, 2000, 1})
    ->Args({kTracked, 1000, 1})
    ->Args({static_cast<int>(rom::InterpolationMethod::Manifold), 1000, 1})
    ->Args({kTracked, 1000, 0})
    ->Args({kTracked, 100, 1})
    ->Args({kTracked, 100, 0})
    ->Unit(benchmark::kMillisecond);

// The full order on the same Scheme 3 case, Δt = 25 µs, state.range(0) steps (set-up included).
void FullOrderSteps(benchmark::State& state) {
  Config c;
  c.simulation.time_step_s = 25e-6;
  fullorder::DeploymentOptions o;
  o.integrator = fullorder::integratorFromConfig(c);
  o.end_time_s = 25e-6 * static_cast<double>(state.range(0));
  for (auto _ : state) {
    fullorder::MastModel mast = fullorder::buildMast(fullorder::mastParametersFromConfig(c));
    fullorder::DeploymentSeries s = fullorder::simulateDeployment(mast, o);
    benchmark::DoNotOptimize(s.joint_torque_nm.data());
  }
}
BENCHMARK(FullOrderSteps)->Arg(200)->Arg(400)->Iterations(1)->Unit(benchmark::kMillisecond);

/// The console report, plus each run's CPU time [s] and counters kept for the summary.
class SummaryReporter : public benchmark::ConsoleReporter {
public:
  void ReportRuns(const std::vector<Run>& reports) override {
    benchmark::ConsoleReporter::ReportRuns(reports);
    for (const Run& r : reports) {
      if (r.error_occurred) continue;
      cpu_s[r.benchmark_name()] =
          r.GetAdjustedCPUTime() / benchmark::GetTimeUnitMultiplier(r.time_unit);
      for (const auto& [name, counter] : r.counters)
        counters[r.benchmark_name() + ":" + name] = counter.value;
    }
  }
  std::map<std::string, double> cpu_s, counters;
};

/// CPU time of a run [s], or 0 when it was filtered out or failed.
double cpuOf(const SummaryReporter& r, const std::string& name) {
  const auto it = r.cpu_s.find(name);
  return it == r.cpu_s.end() ? 0.0 : it->second;
}

void printSummary(const SummaryReporter& r) {
  std::printf("\nSummary (CPU times, against the ROM's speed targets in benchmarks/README.md):\n");
  const double rom10 = cpuOf(r, "RomDeployment/modes:10/step_us:1000");
  const double rom20 = cpuOf(r, "RomDeployment/modes:20/step_us:1000");
  const double metrics10 = cpuOf(r, "RomDeploymentMetrics/modes:10/step_us:1000/continuous:1");
  const double sampled10 =
      cpuOf(r, "RomDeploymentMetricsSampled/modes:10/step_us:1000/continuous:1");
  const double samples10 =
      cpuOf(r, "RomDeploymentMetricsSampled/modes:10/step_us:1000/continuous:0");
  if (rom10 > 0)
    std::printf("  8 s deployment, 10 modes, 1 ms output: %.3f ms (target <= 1 ms: %.2fx)\n",
                1e3 * rom10, rom10 / 1e-3);
  if (rom20 > 0)
    std::printf("  8 s deployment, 20 modes, 1 ms output: %.3f ms (%.2fx target)\n", 1e3 * rom20,
                rom20 / 1e-3);
  const double plain10 = cpuOf(r, "RomDeploymentPlain/modes:10/step_us:1000");
  const double plain20 = cpuOf(r, "RomDeploymentPlain/modes:20/step_us:1000");
  if (plain10 > 0 && rom10 > 0)
    std::printf("  plain implementation / fast, 10 modes: %.2f (%.3f ms)\n", plain10 / rom10,
                1e3 * plain10);
  if (plain20 > 0 && rom20 > 0)
    std::printf("  plain implementation / fast, 20 modes: %.2f (%.3f ms)\n", plain20 / rom20,
                1e3 * plain20);
  if (metrics10 > 0)
    std::printf("  metrics only, 10 modes:               %.3f ms\n", 1e3 * metrics10);
  if (sampled10 > 0)
    std::printf("  metrics only, drive sampled once:     %.3f ms\n", 1e3 * sampled10);
  const double screen20 =
      cpuOf(r, "RomDeploymentMetricsSampled/modes:20/step_us:2000/continuous:1");
  if (screen20 > 0)
    std::printf("  a screen's deployment, 20 modes, 2 ms (its default step): %.3f ms\n",
                1e3 * screen20);
  if (samples10 > 0 && sampled10 > 0)
    std::printf("  the same with peaks over the samples: %.3f ms (continuous / samples %.2f)\n",
                1e3 * samples10, sampled10 / samples10);
  const double f200 = cpuOf(r, "FullOrderSteps/200/iterations:1");
  const double f400 = cpuOf(r, "FullOrderSteps/400/iterations:1");
  if (f200 > 0 && f400 > f200) {
    const double per_step = (f400 - f200) / 200.0;
    const double full_8s = per_step * 8.0 / 25e-6;  // extrapolated, 320 000 steps
    std::printf(
        "  full order, dt = 25 us: %.3f ms CPU per step (400 - 200 steps) -> %.0f s for 8 s "
        "(extrapolated)\n",
        1e3 * per_step, full_8s);
    if (rom10 > 0)
      std::printf("  full order / ROM (10 modes): %.3g (target >= 1e4)\n", full_8s / rom10);
    if (rom20 > 0) std::printf("  full order / ROM (20 modes): %.3g\n", full_8s / rom20);
  }
  for (const auto& [name, value] : r.counters) {
    const std::string suffix = ":designs_per_s";
    if (name.rfind("Screen/", 0) != 0 || value <= 0 || name.size() < suffix.size() ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    std::printf(
        "  %s: %.0f designs/s on 1 rank -> %.2f s CPU for 1e4 designs (target <= 10 s on 2 "
        "cores)\n",
        name.substr(0, name.size() - suffix.size()).c_str(), value, 1e4 / value);
  }
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  // The linearisation checks the equilibrium's stability with PETSc's inertia (modes/stability).
  const modes::SlepcSession session(&argc, &argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  std::fprintf(stderr, "bench_rom_deployment: dense modal solves of Scheme 3 (once) ...\n");
  model(10);
  database();
  SummaryReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  printSummary(reporter);
  benchmark::Shutdown();
  return 0;
}
