#include "rom/studies/screening.hpp"

#include <unistd.h>

#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>

#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "common/text_parsing.hpp"
#include "common/version.hpp"
#include "rom/database/axis_lookup.hpp"
#include "fullorder/deployment_result.hpp"
#include "fullorder/mast_config.hpp"
#include "rom/database/database_io.hpp"
#include "rom/database/h5_arrays.hpp"
#include "rom/database/stress_arrays.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/model/modal_stepping.hpp"
#include "rom/offline/mpi_gather.hpp"
#include "rom/studies/screen_kernel.hpp"

namespace mastrom::rom {
namespace {

constexpr const char* kGridExample =
    "e.g. --grid interface.thickness=0.001:0.002:5 or --grid drive.law=trapezoidal,cubic";

std::string trim(const std::string& s) { return trimBlanks(s); }
bool parseNumber(const std::string& text, double& out) { return parseStrictNumber(text, out); }

std::string shortest(double v) {
  char buf[64];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::vector<std::string> split(const std::string& text, char separator) {
  std::vector<std::string> parts = splitAt(text, separator);
  for (std::string& p : parts) p = trim(p);
  return parts;
}

/// The override that puts a configuration at value i of a screen axis.
std::string overrideFor(const ScreenAxis& axis, std::size_t i) {
  return axis.named ? axis.key + "=" + axis.labels[i] : formatOverride(axis.key, axis.values[i]);
}

}  // namespace

ScreenAxis parseScreenAxis(const std::string& text, const RomDatabase& db,
                           const std::vector<std::string>& overrides) {
  const auto eq = text.find('=');
  MASTROM_REQUIRE(eq != std::string::npos && eq > 0, InputError, "--grid '", text,
                  "' is malformed: expected KEY=LO:HI:N or KEY=V1,V2,…, ", kGridExample);
  ScreenAxis axis;
  axis.key = trim(text.substr(0, eq));
  const std::string rhs = trim(text.substr(eq + 1));
  // The configuration every design starts from (runScreen's), so --set applies before the axis.
  const Config base = evaluationConfig(db, overrides);
  const bool is_parameter = axisIndex(db, axis.key) >= 0;
  if (!is_parameter && keyRole(axis.key, base) != KeyRole::Free) {
    throw InputError(detail::concat(
        "--grid ", axis.key, ": not a parameter of this database (parameters: ", axisKeys(db),
        ") nor a free key (drive.*, simulation.end_time, simulation.time_step, output.every)"));
  }
  if (rhs.find(':') != std::string::npos) {
    const std::vector<std::string> parts = split(rhs, ':');
    double lo = 0, hi = 0, n = 0;
    MASTROM_REQUIRE(parts.size() == 3 && parseNumber(parts[0], lo) && parseNumber(parts[1], hi) &&
                        parseNumber(parts[2], n),
                    InputError, "--grid '", text,
                    "' is malformed: expected KEY=LO:HI:N with finite numbers, ", kGridExample);
    MASTROM_REQUIRE(n == std::floor(n) && n >= 1 && n <= 1e7, InputError, "--grid '", text,
                    "': N must be an integer >= 1");
    MASTROM_REQUIRE(lo < hi || (n == 1 && lo == hi), InputError, "--grid '", text,
                    "': LO = ", parts[0], " must be less than HI = ", parts[1]);
    const int count = static_cast<int>(n);
    for (int i = 0; i < count; ++i)
      axis.values.push_back(count == 1 ? lo : lo + (hi - lo) * i / (count - 1));
    axis.values.back() = hi;
    if (count == 1) axis.values.back() = lo;
    for (const double v : axis.values) axis.labels.push_back(shortest(v));
  } else {
    const std::vector<std::string> items = split(rhs, ',');
    bool numeric = true;
    std::vector<double> numbers;
    for (const std::string& item : items) {
      MASTROM_REQUIRE(!item.empty(), InputError, "--grid '", text, "': empty value in the list");
      double v = 0;
      numeric = numeric && parseNumber(item, v);
      numbers.push_back(v);
    }
    if (numeric) {
      axis.values = numbers;
      for (const double v : numbers) axis.labels.push_back(shortest(v));
    } else {
      MASTROM_REQUIRE(!is_parameter, InputError, "--grid '", text, "': ", axis.key,
                      " is a numeric database parameter");
      axis.named = true;
      axis.labels = items;
      for (std::size_t i = 0; i < items.size(); ++i) axis.values.push_back(static_cast<double>(i));
    }
  }
  // Every value must make a valid configuration on its own (names of drive laws, positive times…).
  for (std::size_t i = 0; i < axis.values.size(); ++i) {
    try {
      (void)applyOverrides(base, {overrideFor(axis, i)});
    } catch (const InputError& e) {
      throw InputError(detail::concat("--grid '", text, "': ", e.what()));
    }
  }
  return axis;
}

namespace {

/// Everything a screen settles before its first deployment: the configuration, the step, the
/// columns, the axes' roles and every free case (each validated).
struct ScreenPlan {
  Config base;
  double step = 0.0;
  ScreenStressColumns stress;
  std::vector<int> parameter_of;  ///< per grid axis: the database axis, or −1 for a free key
  std::vector<std::size_t> free_axes;
  long designs = 1;
  std::vector<FreeCase> cases;
  std::unique_ptr<DesignDescriber> describer;
  MetricColumns columns;
};

/// Why a screen has no strength columns (for the refusal of a stress metric asked for by name).
std::string noStressReason(const RomDatabase& db, const ScreenOptions& options) {
  if (!options.stresses) return "--no-stresses leaves them out";
  if (options.method == InterpolationMethod::Affine &&
      (!db.affine || db.affine->stress_rows.size() == 0))
    return "the database's affine terms carry no stress rows (written by an earlier mastrom)";
  if (!databaseHasStresses(db))
    return "the database carries no stress modes (built with --no-stresses or by an earlier "
           "mastrom)";
  return "";
}

ScreenPlan planScreen(const RomDatabase& db, const ScreenOptions& options) {
  MASTROM_REQUIRE(!options.axes.empty(), InputError,
                  "screen: no --grid axis (give at least one --grid KEY=LO:HI:N)");
  ScreenPlan plan;
  plan.base = evaluationConfig(db, options.overrides);
  // The ROM step of every deployment (screen_kernel.hpp): set on each free case below.
  plan.step = screenStep(options.overrides, options.step_s, options.peaks);
  plan.stress =
      options.stresses ? screenStressColumns(db, plan.base, options.method) : ScreenStressColumns{};

  // Axes: database parameters (index into the point) and free keys (their combinations).
  std::set<std::string> seen;
  plan.parameter_of.assign(options.axes.size(), -1);
  for (std::size_t a = 0; a < options.axes.size(); ++a) {
    const ScreenAxis& axis = options.axes[a];
    MASTROM_REQUIRE(seen.insert(axis.key).second, InputError, "screen: --grid ", axis.key,
                    " is given twice");
    MASTROM_REQUIRE(!axis.values.empty() && axis.values.size() == axis.labels.size(), InputError,
                    "screen: --grid ", axis.key, " has no values");
    plan.parameter_of[a] = axisIndex(db, axis.key);
    if (plan.parameter_of[a] < 0) plan.free_axes.push_back(a);
    plan.designs *= static_cast<long>(axis.values.size());
    // Only a guard of the count's integer range: whether the machine can hold the table is the
    // resource estimate's to say (cli/resource_estimates), with the keys that drive it.
    MASTROM_REQUIRE(plan.designs <= 1000000000000000L, InputError, "screen: --grid ", axis.key,
                    " makes more than 1e15 designs");
  }

  // Every free combination's deployment, validated before any work.
  std::vector<double> deployed_deg;  // each case's deployed angle Θ, for the frequencies
  long free_count = 1;
  for (const std::size_t a : plan.free_axes)
    free_count *= static_cast<long>(options.axes[a].values.size());
  plan.cases.reserve(static_cast<std::size_t>(free_count));
  for (long f = 0; f < free_count; ++f) {
    std::vector<std::string> overrides;
    long rest = f;
    for (const std::size_t a : plan.free_axes) {
      const long n = static_cast<long>(options.axes[a].values.size());
      overrides.push_back(overrideFor(options.axes[a], static_cast<std::size_t>(rest % n)));
      rest /= n;
    }
    const Config c = applyCombination(plan.base, overrides, "screen: ");
    plan.cases.push_back(freeCaseOf(c, plan.step));
    deployed_deg.push_back(c.drive.angle_deg);
  }
  plan.describer = std::make_unique<DesignDescriber>(db, plan.base, options.frequencies,
                                                     deployed_deg, options.box);
  plan.columns = plan.describer->columns(plan.stress.interfaces, plan.stress.margin,
                                         noStressReason(db, options));
  return plan;
}

}  // namespace

MetricColumns screenTableColumns(const RomDatabase& db, const ScreenOptions& options) {
  return planScreen(db, options).columns;
}

ScreenTable runScreen(const RomDatabase& db, const ScreenOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const ScreenPlan plan = planScreen(db, options);
  const Config& base = plan.base;
  const std::vector<int>& parameter_of = plan.parameter_of;
  const std::vector<FreeCase>& cases = plan.cases;
  const long designs = plan.designs;
  ScreenTable table;
  table.axes = options.axes;
  table.method = options.method;
  table.database_checksum = databaseChecksum(db);
  table.config_toml = toToml(base);
  table.step_s = plan.step > 0.0 ? plan.step : outputInterval(base);
  table.designs = designs;
  table.columns = plan.columns;
  table.metric_names = metricNames(designMetrics(plan.columns));
  table.metric_units = metricUnits(designMetrics(plan.columns));

  // Parameter point and free case of a design.
  const std::vector<double> base_point = parameterPoint(db, base);
  const auto decode = [&](long d, std::vector<double>& point, long& free_index) {
    point = base_point;
    free_index = 0;
    long stride = 1;
    for (std::size_t a = 0; a < options.axes.size(); ++a) {
      const long n = static_cast<long>(options.axes[a].values.size());
      const long i = d % n;
      d /= n;
      if (parameter_of[a] >= 0) {
        point[static_cast<std::size_t>(parameter_of[a])] =
            options.axes[a].values[static_cast<std::size_t>(i)];
      } else {
        free_index += stride * i;
        stride *= n;
      }
    }
  };
  // The box, for every design, before any work.
  std::vector<double> point;
  long free_index = 0;
  for (long d = 0; d < designs; ++d) {
    decode(d, point, free_index);
    if (options.box == BoxPolicy::Refuse && !db.contains(point))
      requireInsideBox(db, point, options.box);
  }
  const std::unique_ptr<ModalInterpolator> interpolator = makeInterpolator(db, options.method);

  int rank = 0, size = 1;
  communicatorRankSize(options.communicator, rank, size);
  table.ranks = size;
  const long lo = designs * rank / size, hi = designs * (rank + 1) / size;
  std::vector<double> local;
  local.reserve(static_cast<std::size_t>((hi - lo) * static_cast<long>(table.metric_names.size())));
  std::string error;
  bool numerical = false;
  try {
    screenDesignRange(*interpolator, cases, options.peaks, lo, hi, decode, options.progress, local,
                      plan.stress, plan.describer.get());
  } catch (const NumericalError& e) {
    error = e.what();
    numerical = true;
  } catch (const std::exception& e) {
    error = std::string("screen: ") + e.what();
  }
  throwIfAnyRankFailed(options.communicator, error, numerical);
  std::vector<double> all = gatherToRoot(options.communicator, local);
  if (rank != 0) return table;

  table.metrics = std::move(all);
  MASTROM_REQUIRE(
      table.metrics.size() == static_cast<std::size_t>(designs) * table.metric_names.size(),
      NumericalError, "screen: gathered ", table.metrics.size(), " metric values for ", designs,
      " designs");
  table.parameters.reserve(static_cast<std::size_t>(designs) * options.axes.size());
  for (long d = 0; d < designs; ++d) {
    long rest = d;
    for (const ScreenAxis& axis : options.axes) {
      const long n = static_cast<long>(axis.values.size());
      table.parameters.push_back(axis.values[static_cast<std::size_t>(rest % n)]);
      rest /= n;
    }
  }
  table.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return table;
}

void writeScreenCsv(std::ostream& out, const ScreenTable& table) {
  std::string line;
  for (const ScreenAxis& a : table.axes) line += (line.empty() ? "" : ",") + a.key;
  for (const std::string& m : table.metric_names) line += "," + m;
  out << line << '\n';
  const std::size_t p = table.axes.size(), q = table.metric_names.size();
  for (long d = 0; d < table.designs; ++d) {
    line.clear();
    for (std::size_t a = 0; a < p; ++a) {
      const ScreenAxis& axis = table.axes[a];
      const double v = table.parameters[static_cast<std::size_t>(d) * p + a];
      line += (a ? "," : "");
      line += axis.named ? axis.labels[static_cast<std::size_t>(v)] : shortest(v);
    }
    for (std::size_t m = 0; m < q; ++m)
      line += "," + shortest(table.metrics[static_cast<std::size_t>(d) * q + m]);
    out << line << '\n';
  }
}

void writeScreenCsv(const std::string& path, const ScreenTable& table) {
  h5::checkWritable(path);
  const std::string temporary = h5::temporaryPathFor(path);
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    MASTROM_REQUIRE(out.good(), IoError, "cannot write '", temporary, "'");
    writeScreenCsv(out, table);
    out.flush();
    if (!out.good()) {
      std::error_code ec;
      std::filesystem::remove(temporary, ec);
      throw IoError(detail::concat("cannot write '", temporary, "': write error"));
    }
  }
  std::error_code ec;
  std::filesystem::rename(temporary, path, ec);
  MASTROM_REQUIRE(!ec, IoError, "cannot rename '", temporary, "' to '", path, "': ", ec.message());
}

void writeScreenH5(const std::string& path, const ScreenTable& table) {
  for (const double v : table.metrics)
    MASTROM_REQUIRE(std::isfinite(v), NumericalError,
                    "screen: refusing to write a non-finite metric to '", path, "'");
  h5::AtomicH5Writer writer(path);
  h5::File& file = writer.file();
  const std::size_t n = static_cast<std::size_t>(table.designs), p = table.axes.size(),
                    q = table.metric_names.size();
  std::vector<std::string> names, units, levels;
  for (const ScreenAxis& a : table.axes) {
    names.push_back(a.key);
    units.push_back(a.named ? "1" : configKeyUnits(a.key));
    std::string level;
    if (a.named)
      for (const std::string& l : a.labels) level += (level.empty() ? "" : ",") + l;
    levels.push_back(level);
  }
  h5x::writeStrings(file, "/screen/parameter_names", names);
  h5x::writeDoubles(file, "/screen/parameters", {n, p}, table.parameters.data(), "per column");
  h5x::setStringArrayAttribute(file, "/screen/parameters", "units", units);
  h5x::setStringArrayAttribute(file, "/screen/parameters", "levels", levels);
  h5x::writeStrings(file, "/screen/metric_names", table.metric_names);
  h5x::writeDoubles(file, "/screen/metrics", {n, q}, table.metrics.data(), "per column");
  h5x::setStringArrayAttribute(file, "/screen/metrics", "units", table.metric_units);
  file.setStringAttribute("/", "source", "screen");
  file.setStringAttribute("/", "mastrom_version", kVersion);
  file.setStringAttribute("/", "config", table.config_toml);
  file.setStringAttribute("/", "database_checksum", table.database_checksum);
  file.setStringAttribute("/", "method", toString(table.method));
  file.setIntAttribute("/", "designs", static_cast<int>(table.designs));
  file.setDoubleAttribute("/", "wall_time_s", table.wall_s);
  if (!table.pareto_objectives.empty())
    file.setStringAttribute("/", "pareto_objectives", table.pareto_objectives);
  writer.commit();
}

}  // namespace mastrom::rom
