// Pareto fronts of a screen (see pareto_front.hpp).
#include "rom/studies/pareto_front.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <set>

#include "common/error.hpp"
#include "common/text_parsing.hpp"

namespace mastrom::rom {

std::vector<ParetoObjective> parseParetoObjectives(const std::string& text,
                                                   const std::string& option) {
  std::vector<ParetoObjective> out;
  std::set<std::string> seen;
  for (const std::string& raw : splitAt(text, ',')) {
    const std::string item = trimBlanks(raw);
    ParetoObjective o;
    const std::size_t colon = item.rfind(':');
    o.metric = trimBlanks(colon == std::string::npos ? item : item.substr(0, colon));
    const std::string sense =
        colon == std::string::npos ? "min" : trimBlanks(item.substr(colon + 1));
    MASTROM_REQUIRE(!o.metric.empty() && (sense == "min" || sense == "max"), InputError, option,
                    " '", text, "': '", item,
                    "' is not OBJ, OBJ:min or OBJ:max (e.g. mass:min,frequency_1:max)");
    o.maximize = sense == "max";
    MASTROM_REQUIRE(seen.insert(o.metric).second, InputError, option, " '", text, "': ", o.metric,
                    " is given twice");
    out.push_back(o);
  }
  MASTROM_REQUIRE(out.size() >= 2, InputError, option, " '", text,
                  "': a front needs at least two objectives (e.g. mass:min,frequency_1:max)");
  return out;
}

std::string paretoText(const std::vector<ParetoObjective>& objectives) {
  std::string s;
  for (const ParetoObjective& o : objectives)
    s += (s.empty() ? "" : ",") + o.metric + (o.maximize ? ":max" : ":min");
  return s;
}

std::vector<char> nonDominated(const std::vector<double>& values, std::size_t k,
                               const std::vector<bool>& maximize) {
  MASTROM_REQUIRE(k >= 1 && maximize.size() == k && values.size() % k == 0, InputError,
                  "pareto: ", values.size(), " values for ", k, " objectives");
  const std::size_t n = values.size() / k;
  // Every objective minimised.
  std::vector<double> v(values.size());
  for (std::size_t r = 0; r < n; ++r)
    for (std::size_t j = 0; j < k; ++j)
      v[r * k + j] = maximize[j] ? -values[r * k + j] : values[r * k + j];
  std::vector<std::size_t> order;
  for (std::size_t r = 0; r < n; ++r) {
    bool finite = true;
    for (std::size_t j = 0; j < k; ++j) finite = finite && !std::isnan(v[r * k + j]);
    if (finite) order.push_back(r);
  }
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::lexicographical_compare(
        v.begin() + static_cast<long>(a * k), v.begin() + static_cast<long>((a + 1) * k),
        v.begin() + static_cast<long>(b * k), v.begin() + static_cast<long>((b + 1) * k));
  });
  const auto dominates = [&](std::size_t a, std::size_t b) {
    bool better = false;
    for (std::size_t j = 0; j < k; ++j) {
      if (v[a * k + j] > v[b * k + j]) return false;
      better = better || v[a * k + j] < v[b * k + j];
    }
    return better;
  };
  std::vector<char> on_front(n, 0);
  std::vector<std::size_t> front;
  for (const std::size_t r : order) {
    if (std::any_of(front.begin(), front.end(), [&](std::size_t f) { return dominates(f, r); }))
      continue;
    front.push_back(r);
    on_front[r] = 1;
  }
  return on_front;
}

void checkParetoObjectives(const MetricColumns& columns,
                           const std::vector<ParetoObjective>& objectives,
                           const std::string& option) {
  for (const ParetoObjective& o : objectives) (void)metricIndex(columns, o.metric, option);
}

void markParetoFront(ScreenTable& table, const std::vector<ParetoObjective>& objectives) {
  checkParetoObjectives(table.columns, objectives);
  const std::size_t q = table.metric_names.size(), k = objectives.size();
  std::vector<std::size_t> column;
  std::vector<bool> maximize;
  for (const ParetoObjective& o : objectives) {
    const auto it = std::find(table.metric_names.begin(), table.metric_names.end(), o.metric);
    MASTROM_REQUIRE(it != table.metric_names.end(), InputError, "--pareto ", o.metric,
                    ": not a column of this screen");
    column.push_back(static_cast<std::size_t>(it - table.metric_names.begin()));
    maximize.push_back(o.maximize);
  }
  const auto n = static_cast<std::size_t>(table.designs);
  std::vector<double> values(n * k);
  for (std::size_t r = 0; r < n; ++r)
    for (std::size_t j = 0; j < k; ++j) values[r * k + j] = table.metrics[r * q + column[j]];
  const std::vector<char> front = nonDominated(values, k, maximize);
  // The new column appended to every row.
  std::vector<double> metrics;
  metrics.reserve(n * (q + 1));
  for (std::size_t r = 0; r < n; ++r) {
    metrics.insert(metrics.end(), table.metrics.begin() + static_cast<long>(r * q),
                   table.metrics.begin() + static_cast<long>((r + 1) * q));
    metrics.push_back(front[r] ? 1.0 : 0.0);
  }
  table.metrics = std::move(metrics);
  table.metric_names.push_back(kParetoColumn);
  table.metric_units.push_back("flag");
  table.pareto_objectives = paretoText(objectives);
}

long keepParetoFront(ScreenTable& table) {
  const auto it = std::find(table.metric_names.begin(), table.metric_names.end(), kParetoColumn);
  MASTROM_REQUIRE(it != table.metric_names.end(), InputError,
                  "--pareto-only needs --pareto OBJ[:min|max],… (the objectives of the front)");
  const auto c = static_cast<std::size_t>(it - table.metric_names.begin());
  const std::size_t p = table.axes.size(), q = table.metric_names.size();
  std::vector<double> parameters, metrics;
  long kept = 0;
  for (long r = 0; r < table.designs; ++r) {
    const auto ru = static_cast<std::size_t>(r);
    if (table.metrics[ru * q + c] != 1.0) continue;
    parameters.insert(parameters.end(), table.parameters.begin() + static_cast<long>(ru * p),
                      table.parameters.begin() + static_cast<long>((ru + 1) * p));
    metrics.insert(metrics.end(), table.metrics.begin() + static_cast<long>(ru * q),
                   table.metrics.begin() + static_cast<long>((ru + 1) * q));
    ++kept;
  }
  const long removed = table.designs - kept;
  table.parameters = std::move(parameters);
  table.metrics = std::move(metrics);
  table.designs = kept;
  return removed;
}

}  // namespace mastrom::rom
