// The full order at one design with its own error estimate (see full_order_check.hpp).
#include "rom/studies/full_order_check.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>

#include "common/error.hpp"
#include "fullorder/deployment_accuracy.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/mast_model.hpp"
#include "modes/mast_modes.hpp"
#include "rom/studies/default_output_step.hpp"
#include "rom/studies/design_description.hpp"
#include "rom/studies/design_metrics.hpp"

namespace mastrom::rom {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The factor of the estimate's second run and the error ratio of the two runs (docs/theory.md
/// §5.5: global error ∝ tol^(2/3), so 8 tol errs 4 × as much and e(tol) ≈ difference / 3).
constexpr double kEstimateToleranceFactor = 8.0;
constexpr double kEstimateDivisor = 3.0;

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

/// One run of `config` with first step `first_step_s` (0: the configuration's); its values by the
/// screen's names.
std::map<std::string, double> runOnce(const Config& config, double first_step_s, double max_step_s,
                                      const fullorder::DeploymentProgress& progress) {
  fullorder::MastModel model = fullorder::buildMast(fullorder::mastParametersFromConfig(config));
  fullorder::DeploymentOptions run = fullorder::deploymentFromConfig(config);
  if (run.adaptive) {
    run.step_control.initial_step_s = first_step_s;
    run.step_control.max_step_s = max_step_s;
  }
  const FullOrderStressRun r = runWithStressesAtEveryStep(model, run, config, progress);
  return fullOrderValuesByName(r.metrics, r.stresses, config);
}

/// The lowest `count` natural frequencies of the mast locked at the deployed angle and the
/// eigen-solver's bound on each (see the header).
void solveFrequencies(const Config& config, int count, std::vector<double>& hz,
                      std::vector<double>& error_hz) {
  Config locked = config;
  locked.modes.angle_deg = std::fmod(std::fmod(config.drive.angle_deg, 360.0) + 360.0, 360.0);
  locked.modes.count = count;
  const modes::MastModes m = modes::solveMastModes(locked);
  for (int k = 0; k < m.data.modeCount() && k < count; ++k) {
    const double f = m.data.frequency_hz[k];
    hz.push_back(f);
    error_hz.push_back(k < m.data.residual.size() ? 0.5 * m.data.residual[k] * f : kNaN);
  }
}

}  // namespace

FullOrderStressRun runWithStressesAtEveryStep(fullorder::MastModel& model,
                                              fullorder::DeploymentOptions options,
                                              const Config& config,
                                              const fullorder::DeploymentProgress& progress) {
  // Interval 0: at every accepted step, the continuous peaks the ROM's are compared with.
  fullorder::InterfaceStressMonitor monitor(model, 0.0, options.end_time_s);
  options.state_observer = fullorder::observeInterfaceStresses(monitor);
  FullOrderStressRun r;
  r.series = fullorder::simulateDeployment(model, options, &r.statistics, progress);
  r.metrics = fullorder::fullOrderMetrics(r.series, r.statistics, config.drive.duration_s);
  r.stresses = monitor.resample(r.series.time_s);
  return r;
}

std::map<std::string, double> fullOrderValuesByName(
    const fullorder::DeploymentMetrics& metrics,
    const std::optional<fullorder::InterfaceStressResult>& stresses, const Config& config) {
  std::map<std::string, double> by_name;
  // The deployment's metrics through the shared table, then the mass of the configuration (exact)
  // and the strength columns.
  const std::vector<MetricDefinition> deployment = designMetrics(MetricColumns{});
  const std::vector<std::string> deployment_names = metricNames(deployment);
  DesignValues design;
  design.deployment = metrics;
  std::vector<double> deployment_values;
  appendMetricValues(deployment, design, deployment_values);
  by_name["mass"] = configuredMass(config).total_kg;
  for (std::size_t i = 0; i < deployment_names.size(); ++i)
    by_name[deployment_names[i]] = deployment_values[i];
  if (stresses && !stresses->peak.empty()) {
    double largest = 0.0;
    for (std::size_t k = 0; k < stresses->peak.size(); ++k) {
      const double vm = stresses->peak[k].von_mises_pa;
      by_name["peak_von_mises_interface_" + std::to_string(k + 1)] = vm;
      largest = std::max(largest, vm);
    }
    by_name["max_peak_von_mises"] = largest;
    if (config.material.yield_strength_pa)
      by_name["min_margin_of_safety"] =
          fullorder::marginOfSafety(*config.material.yield_strength_pa, largest);
  }
  return by_name;
}

int frequencyMetricIndex(const std::string& name) {
  const std::string prefix = "frequency_";
  if (name.compare(0, prefix.size(), prefix) != 0) return 0;
  const std::string rest = name.substr(prefix.size());
  if (rest.empty() ||
      !std::all_of(rest.begin(), rest.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return 0;
  return std::stoi(rest);
}

double resolvedFirstStep(const Config& config, std::string& note) {
  // Bytes per sample do not change the wanted step, only the cap on the output series.
  return resolvedFirstStep(config, fullOrderOutputStep(config, 1.0), note);
}

double resolvedFirstStep(const Config& config, const OutputStepChoice& choice, std::string& note) {
  note.clear();
  const double given = config.simulation.time_step_s;
  // Cut only a step that takes fewer than 10 steps per period (twice the wanted step): the
  // default 1e-5 s, validated on Schemes 1–3 (15.8 steps per period of Scheme 1's 6.3 kHz mode),
  // stays as it is.
  if (choice.mode.mode < 0 || !(2.0 * choice.wanted_step_s < given)) return given;
  const double step = std::max(choice.wanted_step_s, config.simulation.min_time_step_s);
  // Three significant digits: the step is a division's result, not a round number.
  char step_text[32], given_text[32];
  std::snprintf(step_text, sizeof step_text, "%.3g", step);
  std::snprintf(given_text, sizeof given_text, "%.3g", given);
  note = detail::concat("first step after each breakpoint ", step_text,
                        " s: simulation.time_step = ", given_text,
                        " s takes fewer than 10 steps per period of mode ", choice.mode.mode + 1,
                        " at ", std::lround(choice.mode.frequency_hz),
                        " Hz, the highest the drive excites, where the error control cannot judge "
                        "them (docs/theory.md §5.3)");
  return step;
}

FullOrderCheck checkWithFullOrder(const Config& config, const std::vector<std::string>& names,
                                  const fullorder::DeploymentProgress& progress) {
  FullOrderCheck check;
  auto start = std::chrono::steady_clock::now();
  const bool adaptive = config.simulation.adaptive;
  if (adaptive) check.first_step_s = resolvedFirstStep(config, check.first_step_note);
  int frequencies = 0;
  for (const std::string& n : names) frequencies = std::max(frequencies, frequencyMetricIndex(n));
  std::vector<double> hz, hz_error;
  if (frequencies > 0) solveFrequencies(config, frequencies, hz, hz_error);
  check.modes_wall_s = seconds(start);

  start = std::chrono::steady_clock::now();
  const double max_step = config.simulation.max_time_step_s;
  const std::map<std::string, double> fine =
      runOnce(config, check.first_step_s, max_step, progress);
  check.wall_s = seconds(start);
  std::map<std::string, double> coarse;
  if (adaptive) {
    Config looser = config;
    looser.simulation.tolerance *= kEstimateToleranceFactor;
    const double factor =
        fullorder::looserStepFactor(config.simulation.tolerance, looser.simulation.tolerance);
    start = std::chrono::steady_clock::now();
    coarse = runOnce(looser, factor * check.first_step_s, factor * max_step, progress);
    check.estimate_wall_s = seconds(start);
  }
  for (const std::string& n : names) {
    const int k = frequencyMetricIndex(n);
    if (k > 0) {
      const bool have = k <= static_cast<int>(hz.size());
      check.values.push_back(have ? hz[static_cast<std::size_t>(k - 1)] : kNaN);
      check.estimated_error.push_back(have ? hz_error[static_cast<std::size_t>(k - 1)] : kNaN);
      continue;
    }
    const auto it = fine.find(n);
    const double v = it == fine.end() ? kNaN : it->second;
    check.values.push_back(v);
    const auto c = coarse.find(n);
    check.estimated_error.push_back(c == coarse.end() ? kNaN
                                                      : std::abs(c->second - v) / kEstimateDivisor);
  }
  return check;
}

}  // namespace mastrom::rom
