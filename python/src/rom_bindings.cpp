// mastrom.RomDatabase (a ROM database file: one deployment with evaluate, many designs with screen)
// and mastrom.build_database (the offline stage, as `mastrom rom build`). The interpolator of each
// method is made once per database object and reused by every call, so a call costs what the
// deployment costs.
#include <pybind11/stl.h>

#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <optional>

#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "fullorder/interface_stress_io.hpp"
#include "fullorder/results_io.hpp"
#include "python/src/arrays.hpp"
#include "python/src/bindings.hpp"
#include "python/src/design_columns.hpp"
#include "python/src/optimize_bindings.hpp"
#include "python/src/overrides.hpp"
#include "python/src/runtime.hpp"
#include "rom/database/database_io.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/interpolation/point_error_estimate.hpp"
#include "rom/offline/adaptive_build.hpp"
#include "rom/offline/database_build.hpp"
#include "rom/offline/modulus_reduction.hpp"
#include "rom/studies/design_metrics.hpp"
#include "rom/studies/design_screen.hpp"
#include "rom/studies/rom_evaluation.hpp"
#include "rom/studies/uncertainty_study.hpp"
#include "rom/studies/uncertainty_tails.hpp"

namespace py = pybind11;

namespace mastrom::python {
namespace {

/// A database in memory plus its interpolators, made on first use (thread-safe).
class Database {
public:
  Database(rom::RomDatabase db, std::optional<std::string> path)
      : db_(std::move(db)), path_(std::move(path)), checksum_(rom::databaseChecksum(db_)) {}

  const rom::RomDatabase& db() const { return db_; }
  const std::optional<std::string>& path() const { return path_; }
  const std::string& checksum() const { return checksum_; }

  /// The method a call asked for (None: the database's default).
  rom::InterpolationMethod method(const std::optional<std::string>& name) const {
    if (!name) return db_.default_method;
    return rom::interpolationMethodOr(*name, db_.default_method, "method");
  }

  const rom::ModalInterpolator& interpolator(rom::InterpolationMethod m) {
    const std::lock_guard<std::mutex> guard(mutex_);
    std::unique_ptr<rom::ModalInterpolator>& slot = interpolators_[m];
    if (!slot) slot = rom::makeInterpolator(db_, m);
    return *slot;
  }

private:
  rom::RomDatabase db_;
  std::optional<std::string> path_;
  std::string checksum_;
  std::mutex mutex_;
  std::map<rom::InterpolationMethod, std::unique_ptr<rom::ModalInterpolator>> interpolators_;
};

bool isParameter(const rom::RomDatabase& db, const std::string& key) {
  for (const rom::ParameterAxis& a : db.axes)
    if (a.key == key) return true;
  return false;
}

std::string parameterList(const rom::RomDatabase& db) {
  std::string keys;
  for (const rom::ParameterAxis& a : db.axes) keys += (keys.empty() ? "" : ", ") + a.key;
  return keys;
}

rom::BoxPolicy boxPolicy(bool extrapolate) {
  return extrapolate ? rom::BoxPolicy::Extrapolate : rom::BoxPolicy::Refuse;
}

/// A frequency request from Python: None = the default (3 where the database can give them).
rom::FrequencyRequest frequencyRequest(const std::optional<int>& frequencies) {
  if (!frequencies) return {};
  return {*frequencies, true, "frequencies ="};
}

py::dict evaluate(Database& self, py::handle point, py::handle set,
                  const std::optional<std::string>& method, bool extrapolate,
                  const std::optional<std::string>& path, bool stress_history,
                  const std::optional<int>& frequencies) {
  // The point first, then the free keys: the order `--set` would apply them in.
  std::vector<std::string> overrides;
  if (!point.is_none()) {
    if (!py::hasattr(point, "items"))
      throw py::type_error("RomDatabase.evaluate: point= takes a mapping {\"key\": value}");
    for (const std::string& o : overridesFrom(point)) {
      const std::string key = o.substr(0, o.find('='));
      MASTROM_REQUIRE(isParameter(self.db(), key), InputError, "rom: point: ", key,
                      " is not a parameter of this database (parameters: ",
                      parameterList(self.db()), "); give free keys with set=");
      overrides.push_back(o);
    }
  }
  for (const std::string& o : overridesFrom(set)) overrides.push_back(o);
  const rom::InterpolationMethod m = self.method(method);

  std::optional<rom::RomEvaluationInput> input;
  std::optional<rom::RomEvaluation> e;
  std::optional<rom::EvaluationDescription> design;
  {
    py::gil_scoped_release release;
    const auto start = std::chrono::steady_clock::now();
    input = rom::romEvaluationInput(self.db(), overrides, boxPolicy(extrapolate));
    input->stress_history = stress_history;
    if (path) h5::checkWritable(*path);
    e = rom::evaluateRomDeployment(self.interpolator(m), *input);
    design = rom::describeEvaluation(self.db(), self.interpolator(m), *input, e->model,
                                     frequencyRequest(frequencies), boxPolicy(extrapolate));
    if (path) {
      const double wall =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      fullorder::writeDeploymentFileWithStresses(*path, e->series, e->metrics,
                                                 toToml(input->config), wall, e->stresses,
                                                 input->config.material.yield_strength_pa,
                                                 fullorder::ResultSource::Rom);
    }
  }
  py::dict result = seriesDict(std::move(e->series));
  py::dict metrics = metricsDict(e->metrics);
  // The interface stresses' metrics (docs/theory.md §6.5), named as in the file's /metrics and
  // as the full order's mastrom.simulate names them.
  if (e->stresses) {
    for (const auto& [name, value] : fullorder::interfaceStressMetricAttributes(
             *e->stresses, input->config.material.yield_strength_pa))
      metrics[py::str(name)] = value;
    if (stress_history) {
      py::dict histories;
      for (std::size_t k = 0; k < e->stresses->history.size(); ++k)
        histories[py::str("interface_" + std::to_string(k + 1))] =
            copyVector(Eigen::Map<const Eigen::VectorXd>(
                e->stresses->history[k].max_von_mises_pa.data(),
                static_cast<Eigen::Index>(e->stresses->history[k].max_von_mises_pa.size())));
      result["max_von_mises"] = histories;
    }
  }
  // The design's mass and natural frequencies (docs/theory.md §1.7), named as a screen's columns.
  for (const rom::MetricDefinition& d : rom::designMetrics(design->columns))
    if (d.name.rfind("mass", 0) == 0 || d.name.rfind("frequency_", 0) == 0)
      metrics[py::str(d.name)] = d.value(design->values);
  result["metrics"] = metrics;
  py::dict p;
  for (std::size_t a = 0; a < self.db().axes.size(); ++a)
    p[py::str(self.db().axes[a].key)] = input->point[a];
  result["point"] = p;
  result["frequencies_hz"] = copyVector(e->model.omega_rad_s / (2.0 * 3.14159265358979323846));
  result["damping_ratio"] = copyVector(e->model.damping_ratio);
  result["inside_box"] = self.db().contains(input->point);
  // The database's estimate at this point (docs/theory.md (4.13) on a grid, (4.14) scattered),
  // where it has one for `m`.
  const auto [point_f, point_r] = rom::pointErrorEstimate(self.db(), input->point);
  if (point_r >= 0 && m == self.db().default_method) {
    py::dict estimate;
    estimate["frequency"] = point_f;
    estimate["response_nrmse"] = point_r;
    // Scattered samples: also the upper value e⁺ of (4.14); on a grid the same as the estimate.
    estimate["response_nrmse_upper"] = rom::pointErrorUpperEstimate(self.db(), input->point).second;
    result["error_estimate"] = estimate;
  } else {
    result["error_estimate"] = py::none();
  }
  result["method"] = rom::toString(m);
  result["interpolation_s"] = e->interpolation_s;
  result["deployment_s"] = e->deployment_s;
  result["metrics_s"] = e->metrics_s;
  result["metrics_step_s"] = e->metrics_step_s;
  result["stress_s"] = e->stress_s;
  result["stress_history_s"] = e->stress_history_s;
  result["source"] = "rom";
  result["config"] = input->config;
  return result;
}

py::dict screen(Database& self, py::handle designs, py::handle set,
                const std::optional<std::string>& method, bool extrapolate,
                const std::string& peaks, const std::optional<double>& step,
                const py::object& progress, const std::optional<int>& frequencies) {
  const std::vector<rom::DesignColumn> columns = designColumns(designs);
  rom::DesignScreenOptions options;
  options.overrides = overridesFrom(set);
  options.box = boxPolicy(extrapolate);
  MASTROM_REQUIRE(peaks == "continuous" || peaks == "samples", InputError, "peaks = '", peaks,
                  "' (allowed: continuous, samples)");
  options.peaks =
      peaks == "continuous" ? rom::PeakResolution::Continuous : rom::PeakResolution::Samples;
  if (step) {
    rom::checkScreenStep(*step, options.overrides, "step =");
    options.step_s = *step;
  }
  options.frequencies = frequencyRequest(frequencies);
  const rom::InterpolationMethod m = self.method(method);
  PythonPoller poller(progress, 0.5);
  options.progress = [&poller](long done, long total) { poller.poll(done == total, done, total); };

  std::optional<rom::DesignScreenTable> table;
  try {
    py::gil_scoped_release release;
    table = rom::screenDesigns(self.db(), self.interpolator(m), columns, options);
  } catch (const PythonPoller::Aborted&) {
    poller.rethrowIfAborted();
  }
  return screenTableDict(columns, *table);
}

/// Intervals as three arrays of `shape` (estimate, lower, upper) in `out` under `name`.
void putIntervals(py::dict& out, const std::string& name, const std::vector<stats::Interval>& v,
                  std::size_t rows, std::size_t cols) {
  std::vector<double> e, lo, hi;
  for (const stats::Interval& i : v) {
    e.push_back(i.estimate);
    lo.push_back(i.lower);
    hi.push_back(i.upper);
  }
  out[py::str(name)] = copyRows(e, rows, cols);
  out[py::str(name + "_lower")] = copyRows(lo, rows, cols);
  out[py::str(name + "_upper")] = copyRows(hi, rows, cols);
}

/// `mastrom uq` on this database (rom/studies/uncertainty_study.hpp): the same numbers as the
/// command, as arrays.
py::dict uq(Database& self, const Config& config, const std::vector<std::string>& limits,
            long samples, const std::string& sampling, unsigned long seed, bool sensitivity,
            double confidence, bool tail_runs, const std::optional<std::string>& method,
            bool extrapolate) {
  rom::UqOptions o;
  const std::optional<stats::SamplingKind> kind = stats::parseSamplingKind(sampling);
  MASTROM_REQUIRE(kind.has_value(), InputError, "sampling = '", sampling, "' (allowed: sobol, mc)");
  o.sampling = *kind;
  o.samples = samples;
  o.seed = seed;
  o.sensitivity = sensitivity;
  o.confidence = confidence;
  for (const std::string& l : limits) o.limits.push_back(rom::parseColumnCondition(l));
  o.method = self.method(method);
  o.box = boxPolicy(extrapolate);
  rom::UqResult r;
  std::vector<rom::TailCheck> tails;
  {
    py::gil_scoped_release release;
    r = rom::runUncertaintyStudy(self.db(), config, o);
    tails = rom::tailChecks(r);
    if (tail_runs) {
      // The tail runs solve the start's modes for their first step (SLEPc where configured).
      const std::unique_lock<std::mutex> lock = lockEigenSolvers(true);
      rom::runTailChecks(self.db(), config, r, tails);
    }
  }
  const std::size_t rows = static_cast<std::size_t>(r.rows), k = r.input_names.size(),
                    q = r.metric_names.size();
  py::dict out;
  out["input_names"] = r.input_names;
  out["inputs"] = copyRows(r.input_values, rows, k);
  out["metric_names"] = r.metric_names;
  out["metric_units"] = r.metric_units;
  out["metrics"] = copyRows(r.metrics, rows, q);
  out["rom_error"] = copyRows(r.rom_error, rows, 2);
  out["metric_error"] = copyRows(r.metric_error, rows, q);
  out["statistic_rows"] = r.statistic_rows;
  std::vector<stats::Interval> mean, sd, quantiles;
  const stats::Interval none{NAN, NAN, NAN};
  for (const stats::SampleSummary& s : r.summaries) {
    mean.push_back(s.count ? s.mean : none);
    sd.push_back(s.count ? s.std_dev : none);
    for (std::size_t i = 0; i < stats::kDefaultQuantileLevels.size(); ++i)
      quantiles.push_back(s.count ? s.quantiles[i] : none);
  }
  putIntervals(out, "mean", mean, q, 1);
  putIntervals(out, "std", sd, q, 1);
  out["quantile_levels"] = stats::kDefaultQuantileLevels;
  putIntervals(out, "quantiles", quantiles, q, stats::kDefaultQuantileLevels.size());
  py::list limit_list;
  for (const rom::LimitProbability& p : r.limits) {
    py::dict d;
    d["limit"] = p.limit.text;
    d["probability"] =
        py::make_tuple(p.probability.estimate, p.probability.lower, p.probability.upper);
    d["conservative"] =
        py::make_tuple(p.conservative.estimate, p.conservative.lower, p.conservative.upper);
    d["has_error_estimate"] = p.has_error_estimate;
    d["critical_row"] = p.critical_row;
    limit_list.append(d);
  }
  out["limits"] = limit_list;
  if (r.has_sensitivity) {
    std::vector<stats::Interval> first, total;
    for (const stats::SobolIndices& s : r.sobol)
      for (std::size_t i = 0; i < k; ++i) {
        first.push_back(s.first.empty() ? none : s.first[i]);
        total.push_back(s.total.empty() ? none : s.total[i]);
      }
    putIntervals(out, "sobol_first", first, q, k);
    putIntervals(out, "sobol_total", total, q, k);
  }
  py::list tail_list;
  for (const rom::TailCheck& c : tails) {
    py::dict d;
    d["limit"] = r.limits[c.limit].limit.text;
    d["label"] = c.label;
    d["row"] = c.row;
    d["rom_value"] = c.rom_value;
    d["rom_error_bound"] = c.rom_error_bound;
    if (tail_runs) {
      d["full_value"] = c.full_value;
      d["full_error_estimate"] = c.full_error_estimate;
    }
    tail_list.append(d);
  }
  out["tails"] = tail_list;
  return out;
}

/// The axes of `params`: {key: (low, high, count)} for a grid, {key: (low, high)} for a range
/// (form Range), or the command line's "key=..." strings.
std::vector<rom::ParameterAxis> parameterAxes(const Config& config, py::handle params,
                                              rom::AxisForm form = rom::AxisForm::Grid) {
  const bool grid = form == rom::AxisForm::Grid;
  const char* caller = grid ? "build_database" : "build_adaptive_database";
  std::vector<std::string> texts;
  if (py::hasattr(params, "items")) {
    for (const py::handle item : params.attr("items")()) {
      const py::tuple kv = py::reinterpret_borrow<py::tuple>(item);
      const py::sequence range = py::reinterpret_borrow<py::sequence>(kv[1]);
      if (!py::isinstance<py::sequence>(kv[1]) || py::len(range) != (grid ? 3u : 2u))
        throw py::type_error(std::string(caller) + ": params[\"" + kv[0].cast<std::string>() +
                             (grid ? "\"] takes (low, high, count)" : "\"] takes (low, high)"));
      std::string text =
          kv[0].cast<std::string>() + "=" + tomlValue(range[0]) + ":" + tomlValue(range[1]);
      if (grid) text += ":" + tomlValue(range[2]);
      texts.push_back(text);
    }
  } else {
    texts = overridesFrom(params);
  }
  std::vector<rom::ParameterAxis> axes;
  for (const std::string& t : texts) axes.push_back(rom::parseParameterAxis(t, config, form));
  return axes;
}

/// build_database's and build_adaptive_database's modes= and backend=, checked.
void setModesAndBackend(std::optional<int> modes, const std::optional<std::string>& backend,
                        rom::DatabaseBuildOptions& options) {
  MASTROM_REQUIRE(!modes || *modes >= 1, InputError, "modes = ", *modes, " must be >= 1");
  options.modes = modes.value_or(0);
  if (backend) {
    options.backend = parseEigenBackendKind(*backend);
    MASTROM_REQUIRE(options.backend.has_value(), InputError, "backend = '", *backend,
                    "' is not a backend (allowed: ", allowedEigenBackendNames(), ")");
  }
}

std::unique_ptr<Database> buildDatabase(const Config& config, py::handle params,
                                        std::optional<int> modes,
                                        const std::optional<std::string>& backend,
                                        const std::optional<std::string>& path,
                                        const py::object& progress,
                                        const std::optional<std::string>& method,
                                        bool compare_methods) {
  rom::DatabaseBuildOptions options;
  options.compare_methods = compare_methods;
  if (method)
    options.method =
        rom::interpolationMethodOr(*method, rom::InterpolationMethod::Manifold, "method");
  options.axes = parameterAxes(config, params);
  setModesAndBackend(modes, backend, options);
  PythonPoller poller(progress, 0.5);
  options.progress = [&poller](int done, int total) { poller.poll(done == total, done, total); };
  std::optional<rom::RomDatabase> db;
  try {
    py::gil_scoped_release release;
    if (path) h5::checkWritable(*path);  // before any work
    rom::BuildReport report;
    {
      // PETSc always: every linearisation's stability check factorises with MUMPS.
      const std::unique_lock<std::mutex> lock = lockEigenSolvers(true);
      db = rom::buildDatabase(config, options, &report);
    }
    if (path) rom::writeDatabase(*path, *db, &report);
  } catch (const PythonPoller::Aborted&) {
    poller.rethrowIfAborted();
  }
  return std::make_unique<Database>(std::move(*db), path);
}

std::unique_ptr<Database> buildAdaptive(const Config& config, py::handle params, double tolerance,
                                        int max_samples, std::optional<int> modes,
                                        const std::optional<std::string>& backend,
                                        const std::optional<std::string>& path,
                                        const py::object& progress) {
  rom::DatabaseBuildOptions options;
  options.axes = parameterAxes(config, params, rom::AxisForm::Range);
  rom::AdaptiveBuildOptions adaptive;
  adaptive.tolerance = tolerance;
  adaptive.max_samples = max_samples;
  // Over the axes actually sampled (Young's modulus may be handled exactly), before any work.
  const bool exact_modulus = rom::planModulusReduction(config, options.axes).applies();
  rom::checkAdaptiveBuildOptions(adaptive,
                                 static_cast<int>(options.axes.size()) - (exact_modulus ? 1 : 0));
  setModesAndBackend(modes, backend, options);
  PythonPoller poller(progress, 0.0);  // once per round: rounds are seconds apart
  const auto on_round = [&poller](const rom::AdaptiveRound& r) {
    poller.poll(true, r.samples, r.response_estimate);
  };
  std::optional<rom::RomDatabase> db;
  try {
    py::gil_scoped_release release;
    if (path) h5::checkWritable(*path);
    rom::BuildReport report;
    {
      const std::unique_lock<std::mutex> lock = lockEigenSolvers(true);
      db = rom::buildAdaptiveDatabase(config, options, adaptive, &report, on_round);
    }
    if (path) rom::writeDatabase(*path, *db, &report);
  } catch (const PythonPoller::Aborted&) {
    poller.rethrowIfAborted();
  }
  return std::make_unique<Database>(std::move(*db), path);
}

}  // namespace

void bindRom(py::module_& m) {
  py::class_<Database>(m, "RomDatabase",
                       R"doc(A ROM database (from build_database or `mastrom rom build`).

RomDatabase(path) reads and verifies a database file (FileError when it is missing, not a
database, or corrupted). evaluate() runs one deployment, screen() the metrics of many designs.)doc")
      .def(py::init([](const std::string& path) {
             py::gil_scoped_release release;
             return std::make_unique<Database>(rom::readDatabase(path), path);
           }),
           py::arg("path"))
      .def_property_readonly(
          "path", [](const Database& d) { return d.path(); },
          "The file it was read from or written to (None: in memory only).")
      .def_property_readonly(
          "parameters",
          [](const Database& d) {
            std::vector<std::string> keys;
            for (const rom::ParameterAxis& a : d.db().axes) keys.push_back(a.key);
            return keys;
          },
          "The configuration keys the database spans, in axis order.")
      .def_property_readonly(
          "box",
          [](const Database& d) {
            py::dict box;
            for (const rom::ParameterAxis& a : d.db().axes)
              box[py::str(a.key)] = py::make_tuple(a.values.front(), a.values.back());
            return box;
          },
          "{key: (low, high)}: the sampled range of each parameter (SI units).")
      .def_property_readonly(
          "grid",
          [](const Database& d) {
            py::dict grid;
            for (const rom::ParameterAxis& a : d.db().axes)
              grid[py::str(a.key)] = copyVector(Eigen::Map<const Eigen::VectorXd>(
                  a.values.data(), static_cast<Eigen::Index>(a.values.size())));
            return grid;
          },
          "{key: (n_k,) array}: the sample values of each parameter.")
      .def_property_readonly("modes_per_sample",
                             [](const Database& d) { return d.db().modes_per_sample; })
      .def_property_readonly("sample_count",
                             [](const Database& d) { return d.db().samples.size(); })
      .def_property_readonly(
          "method", [](const Database& d) { return rom::toString(d.db().default_method); },
          "The default interpolation method: 'tracked', 'manifold', 'affine' or 'cubic'.")
      .def_property_readonly("checksum", &Database::checksum,
                             "Content checksum, as stored in the file ('fnv1a64:…').")
      .def_property_readonly(
          "base_config",
          [](const Database& d) {
            return parseConfigText(d.db().base_config_toml, "ROM database base configuration");
          },
          "The Config the samples were built from.")
      .def_property_readonly(
          "error_estimate",
          [](const Database& d) -> py::object {
            const auto [f, r] = rom::databaseErrorEstimate(d.db());
            if (f < 0) return py::none();
            py::dict e;
            e["frequency"] = f;
            e["response_nrmse"] = r;
            return std::move(e);
          },
          "The database's own error estimate between samples (relative error of the lowest "
          "frequency, NRMSE of the relative end angular acceleration), or None.")
      .def("evaluate", &evaluate, py::arg("point") = py::none(), py::arg("set") = py::none(),
           py::arg("method") = py::none(), py::arg("extrapolate") = false,
           py::arg("path") = py::none(), py::arg("stress_history") = false,
           py::arg("frequencies") = py::none(),
           R"doc(One deployment from the ROM, as `mastrom rom eval`.

point: {parameter: value} inside the box (missing parameters: the base configuration's value).
set: free keys of the deployment, e.g. {"drive.law": "cubic", "simulation.end_time": 8.0}; the
output step is simulation.time_step * output.every. method: 'tracked', 'manifold', 'affine' or 'cubic'
(default: the database's). extrapolate: allow a point outside the box. path: also write the
result file there (the layout of `mastrom rom eval -o`, source "rom").

Returns the dict of mastrom.simulate (same keys, shapes and units; the solver columns are zeros),
with metrics whose peaks are those of the continuous ROM response (as `rom eval` and screen), plus
"point", "inside_box", "frequencies_hz" and "damping_ratio" (k,) of the interpolated modal model,
"method", the wall times "interpolation_s", "deployment_s" (the series), "metrics_s", "stress_s"
(the peaks) and "stress_history_s", "metrics_step_s" (the metrics' pass: a screen's step unless
set gives the output interval), and "error_estimate": the database's estimate of the
error at this point ({"frequency", "response_nrmse", "response_nrmse_upper"}, relative) for its
default method where it carries held-out probes — a grid whose cubic error was measured at its
cells' centres (docs/theory.md (4.13); upper = the estimate), or an adaptive database ((4.14), a
typical value e, and its upper value e⁺) — or None. With a database that carries stress modes the metrics
also hold peak_von_mises_interface_K [Pa] (and, with set={"material.yield_strength": ...}, the
margins of safety), and with stress_history=True (rom eval --stress-history) "max_von_mises" maps
"interface_K" to its (N,) history [Pa] (docs/theory.md §6.5).
The metrics also hold the design's mass [kg] (mass, mass_module_K,
mass_interface_K) and the lowest natural frequencies of the mast locked at the deployed angle
(frequency_K [Hz], frequency_K_error: the database's estimate of the relative error, -1 none;
docs/theory.md §1.7); frequencies: how many (default None: 3 where the database can give them,
else none; an explicit number the database cannot give raises). The GIL is released while it
runs.)doc")
      .def(
          "screen", &screen, py::arg("designs"), py::arg("set") = py::none(),
          py::arg("method") = py::none(), py::arg("extrapolate") = false,
          py::arg("peaks") = "continuous", py::arg("step") = py::none(),
          py::arg("progress") = py::none(), py::arg("frequencies") = py::none(),
          R"doc(Metrics of many designs at once, as `mastrom screen` (one ROM deployment per design).

designs: {key: values}: a database parameter or a free key (drive.*, simulation.end_time,
simulation.time_step, output.every) mapped to a 1-D array of N values (numbers; names for
drive.law) or to one value, broadcast to all N designs. set: fixed values for every design.
method, extrapolate: as evaluate. peaks: 'continuous' (default; peaks of the continuous response)
or 'samples' (over the output samples). step: the ROM step [s] (default 2e-3, or output.step when
given in set; with peaks='continuous' every metric is taken on the continuous response, so the
step sets the cost, not the answer). progress: None or a callable(done, total).

Returns a dict of (N,) arrays: the design columns as given, then the metrics in SI units
(peak_abs_end_angular_acceleration, peak_rel_…, rms_rel_…, residual_rel_… [rad/s^2],
settling_time [s], settled (bool), peak_joint_force [N], peak_drive_torque [N*m],
drive_end_time [s], settling_band [rad/s^2]; with stress modes peak_von_mises_interface_K and
max_peak_von_mises [Pa], and min_margin_of_safety when material.yield_strength is set; the mass
mass, mass_module_K, mass_interface_K [kg]; the natural frequencies frequency_K [Hz] and
frequency_K_error as evaluate, frequencies as evaluate). Every input error is raised before the
first design;
the GIL is released while it runs.)doc")
      .def("uq", &uq, py::arg("config"), py::arg("limits") = std::vector<std::string>{},
           py::arg("samples") = 4096, py::arg("sampling") = "sobol", py::arg("seed") = 1,
           py::arg("sensitivity") = true, py::arg("confidence") = 0.95, py::arg("tail_runs") = true,
           py::arg("method") = py::none(), py::arg("extrapolate") = false,
           R"doc(Uncertainty and sensitivity as `mastrom uq DB CONFIG` (docs/user_guide.md "uq").

config: a Config with [uncertainty] tables. limits: ["METRIC OP VALUE", ...]. Returns a dict of
arrays: inputs (R, k), metrics (R, q), rom_error (R, 2), metric_error (R, q), statistic_rows; mean,
std (q, 1) and quantiles (q, 5) each with _lower/_upper; limits (a list of dicts with probability
and conservative as (estimate, lower, upper)); sobol_first / sobol_total (q, k) with _lower/_upper;
tails (a list of dicts: ROM and, with tail_runs, full-order values at the tail samples).)doc")
      .def(
          "optimize",
          [](const Database& d, const std::optional<std::string>& minimize,
             const std::optional<std::string>& maximize, const std::vector<std::string>& subject_to,
             py::handle set, py::handle bounds, int rounds, int starts, int candidates,
             const std::optional<std::string>& path) {
            return optimizeDatabase(d.db(), minimize, maximize, subject_to, set, bounds, rounds,
                                    starts, candidates, path);
          },
          py::arg("minimize") = py::none(), py::arg("maximize") = py::none(),
          py::arg("subject_to") = std::vector<std::string>{}, py::arg("set") = py::none(),
          py::arg("bounds") = py::none(), py::arg("rounds") = 3, py::arg("starts") = 4,
          py::arg("candidates") = 0, py::arg("path") = py::none(), kOptimizeDoc)
      .def(
          "save",
          [](const Database& d, const std::string& path) {
            py::gil_scoped_release release;
            rom::writeDatabase(path, d.db());
          },
          py::arg("path"), "Write the database file (atomically).")
      .def("__repr__", [](const Database& d) {
        std::string axes;
        for (const rom::ParameterAxis& a : d.db().axes)
          axes += (axes.empty() ? "" : ", ") + a.key + " x" + std::to_string(a.values.size());
        return "<mastrom.RomDatabase " + d.path().value_or("(in memory)") + ": " + axes + ", " +
               std::to_string(d.db().modes_per_sample) + " modes, " +
               rom::toString(d.db().default_method) + ">";
      });

  m.def("build_database", &buildDatabase, py::arg("config"), py::arg("params"),
        py::arg("modes") = py::none(), py::arg("backend") = py::none(),
        py::arg("path") = py::none(), py::arg("progress") = py::none(),
        py::arg("method") = py::none(), py::arg("compare_methods") = false,
        R"doc(Build a ROM database, as `mastrom rom build` (one modal solve per grid sample).

config: the base Config. params: {key: (low, high, count)} — one axis per floating-point key,
count >= 2 evenly spaced values, low and high included (SI units) — or a list of
"key=low:high:count" strings. modes: modes per sample (default: modes.count). backend: 'slepc',
'arpack' or 'dense' (default: modes.backend). path: also write the database file there.
progress: None or a callable(done, total) after each sample. method: the database's default
interpolation, 'tracked', 'manifold', 'affine' or 'cubic' (default: affine where its exact terms
apply, else cubic where the drive-excited modes track cleanly, else manifold; rom build --method).
compare_methods: also estimate every other method's error for the build report (rom build
--compare-methods; only the default's otherwise). Runs in this process (no MPI ranks); the GIL is
released while it runs. Returns the RomDatabase.)doc");
  m.def("build_adaptive_database", &buildAdaptive, py::arg("config"), py::arg("params"),
        py::arg("tolerance"), py::arg("max_samples") = 100, py::arg("modes") = py::none(),
        py::arg("backend") = py::none(), py::arg("path") = py::none(),
        py::arg("progress") = py::none(),
        R"doc(Build a ROM database of scattered samples, as `mastrom rom build --adaptive` on one rank.

Starts from the box centre and 2p Halton points, then adds, round by round, the candidates where
the radial-basis leave-one-out estimate is largest, until the NRMSE of the relative end angular
acceleration measured at held-out probes (Halton points that are never samples) is <= tolerance at
the worst of them and a fresh set of probes confirms it, or max_samples are used (docs/theory.md
§4.3). Its error_estimate is the worst over the stopping probes and the last fresh set.
config: the base Config. params: {key: (low, high)} — the box, one floating-point key each (SI
units) — or a list of "key=low:high" strings; material.youngs_modulus is handled exactly where
gravity is off (not sampled). tolerance: in (0, 1), e.g. 0.03. max_samples: the budget, at least
2p + 1 for p sampled parameters. modes, backend, path: as build_database. progress: None or a
callable(samples, estimate) after each round (estimate: the round's largest NRMSE measured at
the probes, relative). The interpolation method is rbf. The design equals the command line's on one rank (it
depends on the number of ranks). Raises InputError for a bad option before any work; the GIL is
released while it runs. Returns the RomDatabase.)doc");
}

}  // namespace mastrom::python
