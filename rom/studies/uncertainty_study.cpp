#include "rom/studies/uncertainty_study.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <sstream>

#include "common/error.hpp"
#include "common/option_names.hpp"
#include "common/statistics/distributions.hpp"
#include "common/text_parsing.hpp"
#include "rom/database/axis_lookup.hpp"
#include "rom/database/database_io.hpp"
#include "rom/interpolation/point_error_estimate.hpp"
#include "rom/offline/mpi_gather.hpp"
#include "rom/studies/uncertainty_errors.hpp"

namespace mastrom::rom {
namespace {

/// Every leaf of a TOML table as "path" → its TOML text ("v = 4"), for comparing two
/// configurations key by key.
void flatten(const toml::table& table, const std::string& prefix,
             std::map<std::string, std::string>& out) {
  for (auto&& [key, node] : table) {
    const std::string path =
        prefix.empty() ? std::string(key.str()) : prefix + "." + std::string(key.str());
    if (const toml::table* sub = node.as_table()) {
      flatten(*sub, path, out);
      continue;
    }
    if (const auto* f = node.as_floating_point()) {  // the shortest text that reads back
      out[path] = shortestText(f->get());
      continue;
    }
    toml::table wrap;
    wrap.insert_or_assign("v", node);
    std::ostringstream text;
    text << wrap;
    out[path] = text.str().substr(4);  // without "v = "
  }
}

/// Keys that choose how the modes and the full order are computed, not the mast: a study may
/// differ from the database in them (the full-order tail runs use the study's).
bool isSolverSetting(const std::string& key) {
  return key == "modes.count" || key == "modes.backend" || key == "simulation.adaptive" ||
         key == "simulation.tolerance" || key == "simulation.min_time_step" ||
         key == "simulation.max_time_step";
}

/// The configuration without its [uncertainty] section: what one deployment runs.
Config withoutUncertainty(Config c) {
  c.uncertainty.clear();
  return c;
}

/// Rows of `base` base samples from the sampler, appended as the uncertain keys' values.
void appendRows(stats::UnitSampler& sampler, const std::vector<UncertainInput>& inputs,
                bool sensitivity, long base, std::vector<double>& values) {
  const int k = static_cast<int>(inputs.size());
  std::vector<double> u(static_cast<std::size_t>(sampler.dimension()));
  std::vector<double> rows(static_cast<std::size_t>((k + 2) * k));
  for (long j = 0; j < base; ++j) {
    sampler.next(u.data());
    // Each unit coordinate through its input's inverse CDF: A and B of Saltelli's design are
    // coordinates [0, k) and [k, 2k), both of the inputs' laws.
    for (std::size_t d = 0; d < u.size(); ++d)
      u[d] = stats::inverseCdf(inputs[d % static_cast<std::size_t>(k)], u[d]);
    if (!sensitivity) {
      values.insert(values.end(), u.begin(), u.end());
      continue;
    }
    stats::saltelliRows(u.data(), k, rows.data());
    values.insert(values.end(), rows.begin(), rows.end());
  }
}

}  // namespace

std::vector<double> UqResult::point(long row) const {
  std::vector<double> p = nominal_point;
  for (int i = 0; i < inputs; ++i)
    p[static_cast<std::size_t>(input_axis[static_cast<std::size_t>(i)])] =
        input_values[static_cast<std::size_t>(row * inputs + i)];
  return p;
}

void checkUqConfig(const RomDatabase& db, const Config& config) {
  MASTROM_REQUIRE(!config.uncertainty.empty(), InputError,
                  "uq: the configuration has no uncertain input: give [uncertainty.\"KEY\"] tables "
                  "or --set uncertainty.KEY.distribution=... (database parameters: ",
                  axisKeys(db), ")");
  for (const auto& [key, input] : config.uncertainty) {
    (void)input;
    MASTROM_REQUIRE(axisIndex(db, key) >= 0, InputError, "uq: uncertainty.", key,
                    " is not a parameter of this database (parameters: ", axisKeys(db),
                    "): the ROM cannot vary it");
  }
  // The configuration at its own nominal point, as the database would build it: every key that
  // is neither a parameter nor free must come out the same.
  const Config base = parseConfigText(db.base_config_toml, "ROM database base configuration");
  const Config nominal =
      applyOverrides(base, parameterOverrides(db.axes, parameterPoint(db, config)));
  std::map<std::string, std::string> expected, given;
  flatten(toml::parse(toToml(nominal)), "", expected);
  flatten(toml::parse(toToml(withoutUncertainty(config))), "", given);
  for (const auto& [key, value] : given) {
    const auto it = expected.find(key);
    const std::string theirs = it == expected.end() ? "(not set)" : it->second;
    if (theirs == value || axisIndex(db, key) >= 0 || keyRole(key, base) == KeyRole::Free ||
        isSolverSetting(key))
      continue;
    throw InputError(detail::concat(
        "uq: the configuration's ", key, " = ", value, " differs from the database's ", theirs,
        ": the ROM holds it fixed (parameters: ", axisKeys(db),
        "; free keys: drive.*, simulation.end_time/time_step/rho_inf/accelerations, output.*, "
        "material.yield_strength)"));
  }
}

UqResult runUncertaintyStudy(const RomDatabase& db, const Config& config,
                             const UqOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  checkUqConfig(db, config);
  MASTROM_REQUIRE(options.samples >= 2, InputError, "uq: --samples ", options.samples,
                  " out of range: at least 2");
  for (const ColumnCondition& c : options.limits)
    MASTROM_REQUIRE(c.op != ColumnCondition::Op::Equal && c.op != ColumnCondition::Op::NotEqual,
                    InputError, "uq: --limit \"", c.text,
                    "\": the operator must be one of < <= > >= (an exceedance event)");

  UqResult r;
  r.sampling = options.sampling;
  r.seed = options.seed;
  r.confidence = options.confidence;
  r.config_toml = toToml(config);
  r.database_checksum = databaseChecksum(db);
  r.nominal_point = parameterPoint(db, config);
  std::vector<UncertainInput> inputs;
  for (const auto& [key, input] : config.uncertainty) {
    r.input_names.push_back(key);
    r.input_axis.push_back(axisIndex(db, key));
    inputs.push_back(input);
  }
  r.inputs = static_cast<int>(inputs.size());
  const int k = r.inputs;
  const bool sensitivity = options.sensitivity;
  const int dimension = sensitivity ? 2 * k : k;
  MASTROM_REQUIRE(
      options.sampling != stats::SamplingKind::Sobol || dimension <= stats::kMaxSobolDimension,
      InputError, "uq: ", k, " uncertain inputs need a Sobol sequence of dimension ", dimension,
      "; GSL's goes to ", stats::kMaxSobolDimension, " (use --sampling mc, or fewer inputs)");
  const long rows_per_base = sensitivity ? k + 2 : 1;

  const InterpolationMethod method = options.method.value_or(db.default_method);
  // The one deployment every sample runs, and the metrics the screen reduces it to.
  const Config run = withoutUncertainty(config);
  r.step_s = screenStep({}, options.step_s, PeakResolution::Continuous);
  const std::vector<FreeCase> cases{freeCaseOf(run, r.step_s)};
  if (r.step_s <= 0.0) r.step_s = cases.front().options.step_s;
  const ScreenStressColumns stress =
      options.stresses ? screenStressColumns(db, run, method) : ScreenStressColumns{};
  r.metric_names = screenMetricNames(stress);
  r.metric_units = screenMetricUnits(stress);
  for (const ColumnCondition& c : options.limits) {
    const auto it = std::find(r.metric_names.begin(), r.metric_names.end(), c.column);
    if (it != r.metric_names.end()) continue;
    std::string names;
    for (const std::string& n : r.metric_names) names += (names.empty() ? "" : ", ") + n;
    throw InputError(detail::concat("uq: --limit \"", c.text, "\": ", c.column,
                                    " is not a metric of this study (metrics: ", names, ")"));
  }
  const bool estimate = method == db.default_method;

  const std::unique_ptr<ModalInterpolator> interpolator = makeInterpolator(db, method);
  int rank = 0, size = 1;
  communicatorRankSize(options.communicator, rank, size);
  r.ranks = size;
  stats::UnitSampler sampler(options.sampling, dimension, options.seed);
  const std::size_t q = r.metric_names.size();
  std::vector<double> point;

  // Evaluate rows [first, last) of r.input_values over the ranks; rank 0 appends the results.
  const auto evaluate = [&](long first, long last) {
    // Every sample inside the box (or a valid configuration when extrapolating), before any work.
    for (long row = first; row < last; ++row) {
      point = r.point(row);
      if (db.contains(point)) continue;
      try {
        requireInsideBox(db, point, options.box);
        (void)applyOverrides(run, parameterOverrides(db.axes, point));
      } catch (const InputError& e) {
        throw InputError(detail::concat(
            "uq: sample ", row, ": ", e.what(),
            " (narrow the distribution, e.g. truncated_normal inside the box, or --extrapolate)"));
      }
    }
    const long lo = first + (last - first) * rank / size;
    const long hi = first + (last - first) * (rank + 1) / size;
    const DesignDecoder decode = [&r](long row, std::vector<double>& p, long& free_case) {
      p = r.point(row);
      free_case = 0;
    };
    std::vector<double> local, local_error;
    std::string error;
    bool numerical = false;
    try {
      const auto progress = [&options](long done, long total) {
        if (options.progress) options.progress("ROM samples", done, total);
      };
      screenDesignRange(*interpolator, cases, PeakResolution::Continuous, lo, hi, decode, progress,
                        local, stress);
      for (long row = lo; row < hi; ++row) {
        const auto [f, e] = estimate ? pointErrorUpperEstimate(db, r.point(row))
                                     : std::pair<double, double>{-1.0, -1.0};
        local_error.push_back(f);
        local_error.push_back(e);
      }
    } catch (const NumericalError& e) {
      error = e.what();
      numerical = true;
    } catch (const std::exception& e) {
      error = std::string("uq: ") + e.what();
    }
    throwIfAnyRankFailed(options.communicator, error, numerical);
    const std::vector<double> all = gatherToRoot(options.communicator, local);
    const std::vector<double> all_error = gatherToRoot(options.communicator, local_error);
    if (rank != 0) return;
    MASTROM_REQUIRE(all.size() == static_cast<std::size_t>(last - first) * q, NumericalError,
                    "uq: gathered ", all.size(), " metric values for ", last - first, " samples");
    r.metrics.insert(r.metrics.end(), all.begin(), all.end());
    r.rom_error.insert(r.rom_error.end(), all_error.begin(), all_error.end());
  };

  long base = options.samples;
  appendRows(sampler, inputs, sensitivity, base, r.input_values);
  evaluate(0, base * rows_per_base);
  // Sobol indices of every metric from the rows so far (rank 0), and the adaptive growth.
  const auto indices = [&]() {
    r.sobol.assign(q, {});
    std::vector<double> f(static_cast<std::size_t>(base * rows_per_base));
    stats::BootstrapOptions bootstrap{options.bootstrap_resamples, options.confidence,
                                      options.seed};
    for (std::size_t m = 0; m < q; ++m) {
      bool finite = true;
      for (std::size_t row = 0; row < f.size(); ++row) {
        f[row] = r.metrics[row * q + m];
        finite = finite && std::isfinite(f[row]);
      }
      if (finite) r.sobol[m] = stats::jansenIndices(f, k, bootstrap);
    }
  };
  while (sensitivity) {
    double widest = 0.0;
    if (rank == 0) {
      indices();
      for (const stats::SobolIndices& s : r.sobol) widest = std::max(widest, s.widestInterval());
    }
    int more = rank == 0 && options.target_width > 0.0 && widest > options.target_width &&
               2 * base * rows_per_base <= options.max_evaluations;
    if (options.communicator != MPI_COMM_NULL)
      MPI_Bcast(&more, 1, MPI_INT, 0, options.communicator);
    if (!more) break;
    // The next base samples continue the sequence: the larger sample the study would have drawn.
    appendRows(sampler, inputs, sensitivity, base, r.input_values);
    evaluate(base * rows_per_base, 2 * base * rows_per_base);
    base *= 2;
  }
  r.has_sensitivity = sensitivity;
  r.base_samples = base;
  r.rows = base * rows_per_base;
  if (rank != 0) return r;

  // The statistics' rows: A and B of Saltelli's design (2N samples of the inputs' laws), or all.
  for (long row = 0; row < r.rows; ++row)
    if (row % rows_per_base < 2) r.statistic_rows.push_back(row);
  for (std::size_t m = 0; m < q; ++m) {
    std::vector<double> values;
    for (const long row : r.statistic_rows)
      if (std::isfinite(r.metric(row, m))) values.push_back(r.metric(row, m));
    r.summaries.push_back(
        values.size() >= 2
            ? stats::summarize(values, stats::kDefaultQuantileLevels, options.confidence)
            : stats::SampleSummary{});
  }
  metricErrorBounds(r);
  for (const ColumnCondition& c : options.limits)
    r.limits.push_back(limitProbability(r, c, options.confidence));
  r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace mastrom::rom
