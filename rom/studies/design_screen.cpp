#include "rom/studies/design_screen.hpp"

#include "rom/database/stress_arrays.hpp"

#include <chrono>
#include <cmath>
#include <map>
#include <set>

#include "common/error.hpp"
#include "rom/database/axis_lookup.hpp"
#include "rom/studies/screen_kernel.hpp"

namespace mastrom::rom {
namespace {

/// The override that gives design i's value of a column.
std::string overrideFor(const DesignColumn& column, std::size_t i) {
  return column.names.empty() ? formatOverride(column.key, column.values[i])
                              : column.key + "=" + column.names[i];
}

std::size_t lengthOf(const DesignColumn& c) {
  return c.names.empty() ? c.values.size() : c.names.size();
}

}  // namespace

DesignScreenTable screenDesigns(const RomDatabase& db, const ModalInterpolator& interpolator,
                                const std::vector<DesignColumn>& columns,
                                const DesignScreenOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  MASTROM_REQUIRE(!columns.empty(), InputError, "screen: no design column given");
  const Config base = evaluationConfig(db, options.overrides);
  // The ROM step of every deployment (screen_kernel.hpp): set on each free case below.
  const double step = screenStep(options.overrides, options.step_s, options.peaks);
  const Config database_base =
      parseConfigText(db.base_config_toml, "ROM database base configuration");

  // Roles and lengths of the columns.
  const std::size_t designs = lengthOf(columns.front());
  std::set<std::string> seen;
  std::vector<int> parameter_of(columns.size(), -1);
  std::vector<std::size_t> free_columns;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const DesignColumn& column = columns[c];
    MASTROM_REQUIRE(seen.insert(column.key).second, InputError, "screen: ", column.key,
                    " is given twice");
    MASTROM_REQUIRE(column.values.empty() || column.names.empty(), InputError,
                    "screen: ", column.key, " has both numbers and names");
    MASTROM_REQUIRE(lengthOf(column) == designs, InputError, "screen: ", column.key, " has ",
                    lengthOf(column), " values, ", columns.front().key, " has ", designs,
                    " (every column needs one value per design)");
    parameter_of[c] = axisIndex(db, column.key);
    if (parameter_of[c] >= 0) {
      MASTROM_REQUIRE(column.names.empty(), InputError, "screen: ", column.key,
                      " is a numeric database parameter");
      for (std::size_t i = 0; i < designs; ++i)
        MASTROM_REQUIRE(std::isfinite(column.values[i]), InputError, "screen: ", column.key, " = ",
                        column.values[i], " (design ", i, ") is not a finite number");
    } else {
      MASTROM_REQUIRE(keyRole(column.key, database_base) == KeyRole::Free, InputError,
                      "screen: ", column.key,
                      ": not a parameter of this database (parameters: ", axisKeys(db),
                      ") nor a free key (drive.*, simulation.end_time, simulation.time_step, "
                      "output.every)");
      free_columns.push_back(c);
    }
  }
  MASTROM_REQUIRE(designs >= 1, InputError, "screen: the design columns are empty");

  // The distinct combinations of free values, each validated once, in order of first appearance.
  std::vector<FreeCase> cases;
  std::vector<double> deployed_deg;  // each case's deployed angle Θ, for the frequencies
  std::vector<long> case_of(designs, 0);
  if (free_columns.empty()) {
    cases.push_back(freeCaseOf(base, step));
    deployed_deg.push_back(base.drive.angle_deg);
  } else {
    std::map<std::vector<std::string>, long> index_of;
    std::vector<std::string> overrides(free_columns.size());
    for (std::size_t i = 0; i < designs; ++i) {
      for (std::size_t f = 0; f < free_columns.size(); ++f)
        overrides[f] = overrideFor(columns[free_columns[f]], i);
      const auto [it, inserted] = index_of.emplace(overrides, static_cast<long>(cases.size()));
      case_of[i] = it->second;
      if (!inserted) continue;
      const Config c =
          applyCombination(base, overrides, detail::concat("screen: design ", i, ": "));
      cases.push_back(freeCaseOf(c, step));
      deployed_deg.push_back(c.drive.angle_deg);
    }
  }
  const DesignDescriber describer(db, base, options.frequencies, deployed_deg, options.box);

  // Parameter points. Inside the sampled box every value is valid (the box's corners are valid
  // configurations and the configuration's limits are linear in each key); a point outside it is
  // refused, or, when extrapolating, checked as a whole configuration.
  const std::vector<double> base_point = parameterPoint(db, base);
  const DesignDecoder decode = [&](long d, std::vector<double>& point, long& free_index) {
    point = base_point;
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (parameter_of[c] >= 0)
        point[static_cast<std::size_t>(parameter_of[c])] =
            columns[c].values[static_cast<std::size_t>(d)];
    free_index = case_of[static_cast<std::size_t>(d)];
  };
  std::vector<double> point;
  long free_index = 0;
  for (std::size_t i = 0; i < designs; ++i) {
    decode(static_cast<long>(i), point, free_index);
    if (db.contains(point)) continue;
    try {
      requireInsideBox(db, point, options.box);
      (void)applyOverrides(base, parameterOverrides(db.axes, point));
    } catch (const InputError& e) {
      throw InputError(detail::concat("screen: design ", i, ": ", e.what()));
    }
  }

  DesignScreenTable table;
  table.designs = static_cast<long>(designs);
  // Strength columns when the database carries stress modes and this interpolator recovers them
  // (the affine one does not): one probe evaluation at the base point says which.
  ScreenStressColumns stress;
  if (databaseHasStresses(db) && !interpolator.evaluateWithStresses(base_point).stress.empty())
    stress = {db.samples.front().modal.stress.interfaceCount(),
              base.material.yield_strength_pa.has_value()};
  table.columns = screenColumns(stress, &describer);
  table.metric_names = metricNames(designMetrics(table.columns));
  table.metric_units = metricUnits(designMetrics(table.columns));
  table.config_toml = toToml(base);
  table.metrics.reserve(designs * table.metric_names.size());
  screenDesignRange(interpolator, cases, options.peaks, 0, static_cast<long>(designs), decode,
                    options.progress, table.metrics, stress, &describer);
  table.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return table;
}

}  // namespace mastrom::rom
