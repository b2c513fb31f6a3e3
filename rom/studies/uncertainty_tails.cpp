#include "rom/studies/uncertainty_tails.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>

#include "common/error.hpp"
#include "fullorder/deployment_accuracy.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/mast_model.hpp"
#include "rom/offline/mpi_gather.hpp"
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

FullOrderSample runFullOrder(const Config& given) {
  const auto start = std::chrono::steady_clock::now();
  // The first step after each breakpoint resolves the ringing the drive excites (as the
  // optimiser's check, rom/studies/full_order_check.hpp): no error estimate judges those steps.
  Config config = given;
  if (config.simulation.adaptive) {
    std::string note;
    config.simulation.time_step_s = resolvedFirstStep(config, note);
  }
  fullorder::MastModel model = fullorder::buildMast(fullorder::mastParametersFromConfig(config));
  const fullorder::DeploymentOptions run = fullorder::deploymentFromConfig(config);
  // Stresses at every accepted step, not only at the output instants: the ROM's peaks are those of
  // its continuous response, and the interfaces' ringing peaks within a fraction of a millisecond
  // of each jump of θ̈, between the outputs (docs/theory.md §7.5; on coarse Scheme 1 the 0.1 ms
  // outputs read the peak 1.8 % low).
  FullOrderStressRun r = runWithStressesAtEveryStep(model, run, config);
  fullorder::DeploymentMetrics& metrics = r.metrics;
  // The second run at 8 × the tolerance (its own error estimate) needs no stresses.
  if (run.adaptive) fullorder::estimateDiscretisationError(model, run, r.series, metrics);
  FullOrderSample s;
  // The screen's names (rom/studies/design_metrics.hpp), as the optimiser's check names them.
  for (const auto& [name, v] : fullOrderValuesByName(metrics, r.stresses, config))
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
  runTailChecks(db, config, &r, &checks, progress, MPI_COMM_NULL);
}

void runTailChecks(const RomDatabase& db, const Config& config, const UqResult* root_result,
                   std::vector<TailCheck>* root_checks,
                   const std::function<void(long, long)>& progress, MPI_Comm comm) {
  int rank = 0, size = 1;
  communicatorRankSize(comm, rank, size);
  // Rank 0 knows the rows and the metrics the checks need; the others get the rows' points and
  // the metrics' names.
  std::vector<long> rows;          // distinct rows, in the checks' order (rank 0)
  std::vector<double> points;      // their points, one after the other (every rank)
  std::vector<std::string> names;  // the checks' metrics, distinct (every rank)
  if (rank == 0) {
    for (const TailCheck& c : *root_checks) {
      if (std::find(rows.begin(), rows.end(), c.row) == rows.end()) {
        rows.push_back(c.row);
        const std::vector<double> p = root_result->point(c.row);
        MASTROM_REQUIRE(p.size() == db.axes.size(), UsageError, "tail checks: a point of ",
                        p.size(), " values for ", db.axes.size(), " database axes");
        points.insert(points.end(), p.begin(), p.end());
      }
      if (std::find(names.begin(), names.end(), c.metric) == names.end()) names.push_back(c.metric);
    }
  }
  const std::size_t dims = db.axes.size();
  if (size > 1) {
    long counts[2] = {static_cast<long>(rows.size()), static_cast<long>(names.size())};
    MPI_Bcast(counts, 2, MPI_LONG, 0, comm);
    points.resize(static_cast<std::size_t>(counts[0]) * dims);
    MPI_Bcast(points.data(), static_cast<int>(points.size()), MPI_DOUBLE, 0, comm);
    std::string joined;
    for (const std::string& n : names) joined += n + '\n';
    long length = static_cast<long>(joined.size());
    MPI_Bcast(&length, 1, MPI_LONG, 0, comm);
    joined.resize(static_cast<std::size_t>(length));
    MPI_Bcast(joined.data(), static_cast<int>(length), MPI_CHAR, 0, comm);
    names.clear();
    for (std::size_t a = 0, b; (b = joined.find('\n', a)) != std::string::npos; a = b + 1)
      names.push_back(joined.substr(a, b - a));
  }
  const std::size_t distinct = dims ? points.size() / dims : 0;
  // Row k runs on rank k mod size. Per row: each metric's value and error, then the wall time;
  // zeros on the ranks that do not run it, so that the sum over the ranks is the runner's values.
  const std::size_t width = 2 * names.size() + 1;
  std::vector<double> local(distinct * width, 0.0);
  Config run = config;
  run.uncertainty.clear();
  long mine = 0, done = 0;
  for (std::size_t k = static_cast<std::size_t>(rank); k < distinct;
       k += static_cast<std::size_t>(size))
    ++mine;
  const auto runMine = [&] {
    for (std::size_t k = static_cast<std::size_t>(rank); k < distinct;
         k += static_cast<std::size_t>(size)) {
      const std::vector<double> point(points.begin() + static_cast<long>(k * dims),
                                      points.begin() + static_cast<long>((k + 1) * dims));
      const Config sample = applyOverrides(run, parameterOverrides(db.axes, point));
      const FullOrderSample s = runFullOrder(sample);
      double* out = local.data() + k * width;
      for (std::size_t m = 0; m < names.size(); ++m) {
        const auto v = s.value.find(names[m]);
        const auto e = s.error.find(names[m]);
        out[2 * m] = v == s.value.end() ? kNaN : v->second;
        out[2 * m + 1] = e == s.error.end() ? kNaN : e->second;
      }
      out[width - 1] = s.wall_s;
      if (progress) progress(++done, mine);
    }
  };
  if (size == 1) {
    runMine();  // errors propagate as they are
  } else {
    std::string error;
    bool numerical = false;
    try {
      runMine();
    } catch (const NumericalError& e) {
      error = e.what();
      numerical = true;
    } catch (const std::exception& e) {
      error = e.what();
    }
    throwIfAnyRankFailed(comm, error, numerical);
    MPI_Allreduce(MPI_IN_PLACE, local.data(), static_cast<int>(local.size()), MPI_DOUBLE, MPI_SUM,
                  comm);
  }
  if (rank != 0) return;
  for (TailCheck& c : *root_checks) {
    const std::size_t k =
        static_cast<std::size_t>(std::find(rows.begin(), rows.end(), c.row) - rows.begin());
    const std::size_t m =
        static_cast<std::size_t>(std::find(names.begin(), names.end(), c.metric) - names.begin());
    const double* in = local.data() + k * width;
    c.full_value = in[2 * m];
    c.full_error_estimate = in[2 * m + 1];
    c.full_wall_s = in[width - 1];
  }
}

}  // namespace mastrom::rom
