// Speed of the ROM's online stage (issue targets: one 8 s Scheme 3 deployment from the ROM ≤ 1 ms
// CPU; a screen of 10⁴ designs ≤ 10 s on 2 cores):
//  * RomDeployment/<modes>/<step µs>: simulateModalDeployment of the paper's Scheme 3 (default
//    config: 4 modules, 2 × 8 interface meshes) over 8 s, trapezoidal drive, 10 or 20 modes, output
//    step 1 ms or 0.1 ms;
//  * Interpolate/<method>: one modal model from a 3 × 3 Scheme 3 database (thickness × inner
//    diameter), tracked and manifold;
//  * RomDeploymentMetrics/<modes>/<step µs>: the same deployment reduced to the DESIGN §1 metrics
//    while stepping (rom/deployment_metrics.hpp) — what the screen runs per design;
//  * Screen: designs per second of rom::runScreen on that database (one rank; under mpirun the
//    CLI shares the designs), output step 1 ms — the counter `designs_per_s`.
// The modal models come from dense modal solves done once before timing (≈ 10 s).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <memory>

#include "fullorder/mast_config.hpp"
#include "modes/eigen_solver.hpp"
#include "modes/linearize.hpp"
#include "rom/database_build.hpp"
#include "rom/deployment_metrics.hpp"
#include "rom/interpolator.hpp"
#include "rom/modal_extraction.hpp"
#include "rom/parameter_space.hpp"
#include "rom/screening.hpp"

namespace {
using namespace mastrom;

rom::ModalModel scheme3Model(int modes) {
  const Config c;  // defaults = Scheme 3 (DESIGN §1)
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

// The screen's per-design path: the same deployment reduced to its metrics while stepping.
void RomDeploymentMetrics(benchmark::State& state) {
  const rom::ModalModel& m = model(static_cast<int>(state.range(0)));
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(Config{}));
  rom::ModalDeploymentOptions o;
  o.end_time_s = 8.0;
  o.step_s = 1e-6 * static_cast<double>(state.range(1));
  for (auto _ : state) {
    fullorder::DeploymentMetrics r = rom::modalDeploymentMetrics(m, drive, o, 6.1);
    benchmark::DoNotOptimize(r.peak_drive_torque);
  }
}
BENCHMARK(RomDeploymentMetrics)
    ->ArgNames({"modes", "step_us"})
    ->Args({10, 1000})
    ->Args({20, 1000})
    ->Args({10, 100})
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
  long designs = 0;
  for (auto _ : state) {
    const rom::ScreenTable t = rom::runScreen(db, o);
    designs += t.designs;
  }
  state.counters["designs_per_s"] =
      benchmark::Counter(static_cast<double>(designs), benchmark::Counter::kIsRate);
  state.SetLabel(rom::toString(o.method));
}
BENCHMARK(Screen)
    ->Arg(static_cast<int>(rom::InterpolationMethod::Tracked))
    ->Arg(static_cast<int>(rom::InterpolationMethod::Manifold))
    ->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  std::fprintf(stderr, "bench_rom_deployment: dense modal solves of Scheme 3 (once) ...\n");
  model(10);
  database();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
