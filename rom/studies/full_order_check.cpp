// The full order at one design with its own error estimate (see full_order_check.hpp).
#include "rom/studies/full_order_check.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>

#include "common/error.hpp"
#include "rom/studies/design_description.hpp"
#include "rom/studies/screen_kernel.hpp"

namespace mastrom::rom {
namespace {

/// The factor of the estimate's second run and the error ratio of the two runs (docs/theory.md
/// §5.5: global error ∝ tol^(2/3), so 8 tol errs 4 × as much and e(tol) ≈ difference / 3).
constexpr double kEstimateToleranceFactor = 8.0;
constexpr double kEstimateDivisor = 3.0;

double seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

}  // namespace

std::vector<double> fullOrderMetricValues(const fullorder::ConfiguredDeployment& run,
                                          const Config& config,
                                          const std::vector<std::string>& names) {
  std::map<std::string, double> by_name;
  // The deployment's metrics through the shared table, then the mass of the configuration (exact)
  // and the strength columns below; the full order gives no modal frequencies here.
  const std::vector<MetricDefinition> deployment = designMetrics(MetricColumns{});
  const std::vector<std::string> deployment_names = metricNames(deployment);
  DesignValues design;
  design.deployment = run.metrics;
  std::vector<double> deployment_values;
  appendMetricValues(deployment, design, deployment_values);
  by_name["mass"] = configuredMass(config).total_kg;
  for (std::size_t i = 0; i < deployment_names.size(); ++i)
    by_name[deployment_names[i]] = deployment_values[i];
  if (run.stresses && !run.stresses->peak.empty()) {
    double largest = 0.0;
    for (std::size_t k = 0; k < run.stresses->peak.size(); ++k) {
      const double vm = run.stresses->peak[k].von_mises_pa;
      by_name["peak_von_mises_interface_" + std::to_string(k + 1)] = vm;
      largest = std::max(largest, vm);
    }
    by_name["max_peak_von_mises"] = largest;
    if (config.material.yield_strength_pa)
      by_name["min_margin_of_safety"] =
          fullorder::marginOfSafety(*config.material.yield_strength_pa, largest);
  }
  std::vector<double> values;
  for (const std::string& n : names) {
    const auto it = by_name.find(n);
    values.push_back(it == by_name.end() ? std::numeric_limits<double>::quiet_NaN() : it->second);
  }
  return values;
}

FullOrderCheck checkWithFullOrder(const Config& config, const std::vector<std::string>& names,
                                  const fullorder::DeploymentProgress& progress) {
  fullorder::ConfiguredDeploymentOptions options;
  options.progress = progress;
  FullOrderCheck check;
  auto start = std::chrono::steady_clock::now();
  check.values =
      fullOrderMetricValues(fullorder::runConfiguredDeployment(config, options), config, names);
  check.wall_s = seconds(start);
  check.estimated_error.assign(names.size(), std::numeric_limits<double>::quiet_NaN());
  if (!config.simulation.adaptive) return check;

  Config coarse = config;
  coarse.simulation.tolerance *= kEstimateToleranceFactor;
  start = std::chrono::steady_clock::now();
  const std::vector<double> coarse_values =
      fullOrderMetricValues(fullorder::runConfiguredDeployment(coarse, options), coarse, names);
  check.estimate_wall_s = seconds(start);
  for (std::size_t i = 0; i < names.size(); ++i)
    check.estimated_error[i] = std::abs(coarse_values[i] - check.values[i]) / kEstimateDivisor;
  return check;
}

}  // namespace mastrom::rom
