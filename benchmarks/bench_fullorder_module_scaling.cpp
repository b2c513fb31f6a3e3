// Cost and memory of the full order against the number of modules (target: linear, at most 1.2 ×
// the linear ratio at 64 modules against 4).
//
//   bench_fullorder_module_scaling [--modules 4,8,16,32,64] [--end-time 0.01] [--fixed-step S]
//                                  [--config FILE]
//
// Every mast is run in a process of its own (this program started again with --row N), so that
// its peak resident memory is its own: configs/scheme3.toml's defaults (Scheme 3 geometry, 2 × 8
// interface meshes, adaptive steps at tolerance 1e-5) with mast.modules = N, simulation.end_time =
// 10 ms, 1 thread, through runConfiguredDeployment — the run `mastrom simulate` makes, without the
// file. Per step: the CPU time between the first step and the last over the steps between them
// (the step count differs a little between masts: their start-up ringing differs); set-up: the CPU
// time until the first step (building the mast and its eliminated system, the drive's compliance,
// the first factorisations). With --fixed-step every mast takes the same steps of S seconds
// (simulation.adaptive = false), so that a step is the same work on every mast: the adaptive
// steps lengthen with the mast (its start-up ringing is slower), which spreads the fixed costs
// (factorisations, recoveries) over fewer steps. Ratios are to the first row, and "/ linear"
// divides a ratio by the ratio of the DOFs: 1 is linear cost, the target ≤ 1.2.
#include <sys/resource.h>

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <sstream>
#include <string>
#include <vector>

#include "common/config.hpp"
#include "fullorder/configured_deployment.hpp"

namespace {
using namespace mastrom;

double cpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Row {
  int modules = 0, dofs = 0, constraints = 0;
  long steps = 0;
  double setup_s = 0.0, per_step_s = 0.0, peak_mb = 0.0;
};

/// One mast in this process; prints "row modules dofs constraints steps setup_s per_step_s
/// peak_mb".
int runRow(int modules, double end_time_s, double fixed_step_s, const std::string& config_path) {
  Config c = config_path.empty() ? Config{} : loadConfig(config_path, {});
  std::vector<std::string> overrides{"mast.modules=" + std::to_string(modules),
                                     "simulation.end_time=" + std::to_string(end_time_s)};
  if (fixed_step_s > 0.0) {
    char step[64];
    std::snprintf(step, sizeof step, "simulation.time_step=%.17g", fixed_step_s);
    overrides.insert(overrides.end(), {"simulation.adaptive=false", step});
  }
  c = applyConfigOverrides(c, overrides);
  const double start = cpuSeconds();
  double first_cpu = -1.0, last_cpu = 0.0;
  long first_steps = 0, last_steps = 0;
  fullorder::ConfiguredDeploymentOptions o;
  o.threads = 1;
  o.progress = [&](double, double, const fullorder::DeploymentStatistics& s) {
    const double now = cpuSeconds();
    if (first_cpu < 0.0) {
      first_cpu = now;
      first_steps = s.steps;
    }
    last_cpu = now;
    last_steps = s.steps;
  };
  const fullorder::ConfiguredDeployment run = fullorder::runConfiguredDeployment(c, o);
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf("row %d %d %d %ld %.6f %.9f %.1f\n", modules, run.dofs, run.constraints,
              run.statistics.steps, first_cpu - start,
              (last_cpu - first_cpu) / static_cast<double>(last_steps - first_steps),
              static_cast<double>(usage.ru_maxrss) / 1024.0);
  return 0;
}

bool readRow(const std::string& command, Row& r) {
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return false;
  char line[512];
  bool found = false;
  while (std::fgets(line, sizeof line, pipe) != nullptr)
    if (std::sscanf(line, "row %d %d %d %ld %lf %lf %lf", &r.modules, &r.dofs, &r.constraints,
                    &r.steps, &r.setup_s, &r.per_step_s, &r.peak_mb) == 7)
      found = true;
  return pclose(pipe) == 0 && found;
}
}  // namespace

int main(int argc, char** argv) {
  std::vector<int> modules{4, 8, 16, 32, 64};
  double end_time_s = 0.01, fixed_step_s = 0.0;
  std::string config_path;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i], value = argv[i + 1];
    if (flag == "--row")
      return runRow(std::atoi(value.c_str()), end_time_s, fixed_step_s, config_path);
    if (flag == "--end-time") {
      end_time_s = std::atof(value.c_str());
    } else if (flag == "--fixed-step") {
      fixed_step_s = std::atof(value.c_str());
    } else if (flag == "--config") {
      config_path = value;
    } else if (flag == "--modules") {
      modules.clear();
      std::stringstream list(value);
      for (std::string item; std::getline(list, item, ',');)
        modules.push_back(std::atoi(item.c_str()));
    } else {
      std::fprintf(stderr,
                   "bench_fullorder_module_scaling: unknown flag %s (--modules LIST, --end-time S, "
                   "--fixed-step S, --config FILE)\n",
                   flag.c_str());
      return 2;
    }
  }
  char steps[64] = "adaptive steps";
  if (fixed_step_s > 0.0) std::snprintf(steps, sizeof steps, "fixed steps of %g s", fixed_step_s);
  std::printf("# full order vs mast.modules: %s, end_time %g s, %s, 1 thread, CPU times\n",
              config_path.empty() ? "configs/scheme3.toml defaults" : config_path.c_str(),
              end_time_s, steps);
  std::printf("# %7s %6s %6s %6s %9s %9s %8s | %7s %7s %7s %7s | %9s %9s %9s\n", "modules", "DOFs",
              "constr", "steps", "setup_s", "ms/step", "peak_MB", "DOFs", "step", "memory", "setup",
              "step/lin", "mem/lin", "setup/lin");
  std::vector<Row> rows;
  for (int n : modules) {
    char times[128];
    std::snprintf(times, sizeof times, " --end-time %.17g --fixed-step %.17g", end_time_s,
                  fixed_step_s);
    std::string command = std::string("'") + argv[0] + "'" + times +
                          (config_path.empty() ? "" : " --config '" + config_path + "'") +
                          " --row " + std::to_string(n);
    Row r;
    if (!readRow(command, r)) {
      std::fprintf(stderr, "bench_fullorder_module_scaling: the run of %d modules failed\n", n);
      return 1;
    }
    rows.push_back(r);
    const Row& b = rows.front();
    const double dofs = double(r.dofs) / b.dofs, step = r.per_step_s / b.per_step_s,
                 memory = r.peak_mb / b.peak_mb, setup = r.setup_s / b.setup_s;
    std::printf(
        "  %7d %6d %6d %6ld %9.3f %9.4f %8.1f | %7.2f %7.2f %7.2f %7.2f | %9.2f %9.2f %9.2f\n",
        r.modules, r.dofs, r.constraints, r.steps, r.setup_s, 1e3 * r.per_step_s, r.peak_mb, dofs,
        step, memory, setup, step / dofs, memory / dofs, setup / dofs);
    std::fflush(stdout);
  }
  std::printf(
      "# ratios to %d modules; x/lin = ratio / DOF ratio (1 = linear; target <= 1.2 at 64)\n",
      rows.front().modules);
  return 0;
}
