#include "rom/studies/uncertainty_tails.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <map>

#include "common/error.hpp"
#include "fullorder/deployment_accuracy.hpp"
#include "fullorder/interface_stress.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/mast_model.hpp"
#include "rom/studies/design_metrics.hpp"
#include "rom/studies/full_order_check.hpp"

namespace mastrom::rom {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// One full-order run at a sample: its metrics by the screen's names, with the estimated error of
/// each (NaN where the run has none).
struct FullOrderSample {
  std::map<std::string, double> value, error;
  double wall_s = 0.0;
};

FullOrderSample runFullOrder(const Config& config) {
  const auto start = std::chrono::steady_clock::now();
  fullorder::MastModel model = fullorder::buildMast(fullorder::mastParametersFromConfig(config));
  fullorder::DeploymentOptions run = fullorder::deploymentFromConfig(config);
  // Stresses at every accepted step, not only at the output instants: the ROM's peaks are those of
  // its continuous response, and the interfaces' ringing peaks within a fraction of a millisecond
  // of each jump of θ̈, between the outputs (docs/theory.md §7.5; on coarse Scheme 1 the 0.1 ms
  // outputs read the peak 1.8 % low).
  fullorder::InterfaceStressMonitor monitor(model, 0.0, run.end_time_s);
  run.state_observer = fullorder::observeInterfaceStresses(monitor);
  fullorder::DeploymentStatistics statistics;
  const fullorder::DeploymentSeries series = fullorder::simulateDeployment(model, run, &statistics);
  fullorder::DeploymentMetrics metrics =
      fullorder::fullOrderMetrics(series, statistics, config.drive.duration_s);
  const fullorder::InterfaceStressResult stresses = monitor.resample(series.time_s);
  if (run.adaptive) {
    // The second run at 8 × the tolerance (its own error estimate) needs no stresses.
    fullorder::DeploymentOptions plain = run;
    plain.state_observer = {};
    fullorder::estimateDiscretisationError(model, plain, series, metrics);
  }
  FullOrderSample s;
  // The screen's names (rom/studies/design_metrics.hpp), as the optimiser's check names them.
  for (const auto& [name, v] : fullOrderValuesByName(metrics, stresses, config))
    if (name != "mass") s.value[name] = v;
  // Absolute error estimates: the peaks' own where the run has them, else NRMSE × |value| for
  // the response's metrics (the margin through σ as in uncertainty_errors.hpp).
  const double nrmse = metrics.estimated_nrmse_rel_end_angular_acceleration;
  for (const auto& [name, v] : s.value) {
    double e = kNaN;
    if (name == "peak_rel_end_angular_acceleration")
      e = metrics.estimated_error_peak_rel_end_angular_acceleration * std::abs(v);
    else if (name == "peak_abs_end_angular_acceleration")
      e = metrics.estimated_error_peak_abs_end_angular_acceleration * std::abs(v);
    else if (name == "peak_joint_force")
      e = metrics.estimated_error_peak_joint_force * std::abs(v);
    else if (name == "min_margin_of_safety")
      e = nrmse * std::abs(1.0 + v);
    else if (name.rfind("peak_", 0) == 0 || name.rfind("rms_", 0) == 0 ||
             name.rfind("residual_", 0) == 0 || name == "max_peak_von_mises")
      e = nrmse * std::abs(v);
    s.error[name] = e;
  }
  s.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

/// The statistics row whose value of metric m is nearest `target`.
long nearestRow(const UqResult& r, std::size_t m, double target) {
  long best = -1;
  double distance = std::numeric_limits<double>::infinity();
  for (const long row : r.statistic_rows) {
    const double d = std::abs(r.metric(row, m) - target);
    if (d < distance) {
      distance = d;
      best = row;
    }
  }
  return best;
}

}  // namespace

std::vector<TailCheck> tailChecks(const UqResult& r) {
  std::vector<TailCheck> checks;
  const std::size_t q = r.metric_names.size();
  for (std::size_t l = 0; l < r.limits.size(); ++l) {
    const LimitProbability& p = r.limits[l];
    std::size_t m = 0;
    while (r.metric_names[m] != p.limit.column) ++m;
    const stats::SampleSummary& s = r.summaries[m];
    std::vector<std::pair<std::string, long>> rows;
    for (std::size_t i = 0; i < s.quantile_levels.size(); ++i) {
      if (s.quantile_levels[i] == 0.01)
        rows.emplace_back("q01", nearestRow(r, m, s.quantiles[i].estimate));
      if (s.quantile_levels[i] == 0.99)
        rows.emplace_back("q99", nearestRow(r, m, s.quantiles[i].estimate));
    }
    rows.emplace_back("critical", p.critical_row);
    for (const auto& [label, row] : rows) {
      if (row < 0) continue;
      TailCheck c;
      c.limit = l;
      c.label = label;
      c.row = row;
      c.metric = p.limit.column;
      c.rom_value = r.metric(row, m);
      c.rom_error_bound =
          r.metric_error.empty() ? 0.0 : r.metric_error[static_cast<std::size_t>(row) * q + m];
      checks.push_back(c);
    }
  }
  return checks;
}

void runTailChecks(const RomDatabase& db, const Config& config, const UqResult& r,
                   std::vector<TailCheck>& checks,
                   const std::function<void(long, long)>& progress) {
  Config run = config;
  run.uncertainty.clear();
  std::map<long, FullOrderSample> done;
  long distinct = 0;
  {
    std::map<long, int> rows;
    for (const TailCheck& c : checks) rows[c.row] = 1;
    distinct = static_cast<long>(rows.size());
  }
  for (TailCheck& c : checks) {
    auto it = done.find(c.row);
    if (it == done.end()) {
      const Config sample = applyOverrides(run, parameterOverrides(db.axes, r.point(c.row)));
      it = done.emplace(c.row, runFullOrder(sample)).first;
      if (progress) progress(static_cast<long>(done.size()), distinct);
    }
    const FullOrderSample& s = it->second;
    const auto v = s.value.find(c.metric);
    c.full_value = v == s.value.end() ? kNaN : v->second;
    const auto e = s.error.find(c.metric);
    c.full_error_estimate = e == s.error.end() ? kNaN : e->second;
    c.full_wall_s = s.wall_s;
  }
}

}  // namespace mastrom::rom
