#include "rom/studies/uncertainty_output.hpp"

#include <cmath>
#include <sstream>

#include "common/hdf5_file.hpp"
#include "common/text_file.hpp"
#include "common/text_parsing.hpp"
#include "common/version.hpp"
#include "rom/database/h5_arrays.hpp"

namespace mastrom::rom {
namespace {

/// Files never hold NaN: a value that does not exist is −1 (every such array says so).
double orMinusOne(double v) { return std::isfinite(v) ? v : -1.0; }

std::string levelName(double level) {
  const int percent = static_cast<int>(std::lround(100.0 * level));
  return (percent < 10 ? "q0" : "q") + std::to_string(percent);
}

void writeIntervals(h5::File& f, const std::string& path, const std::vector<stats::Interval>& v,
                    const std::vector<std::size_t>& dims, const std::string& units) {
  std::vector<double> e, lo, hi;
  for (const stats::Interval& i : v) {
    e.push_back(orMinusOne(i.estimate));
    lo.push_back(orMinusOne(i.lower));
    hi.push_back(orMinusOne(i.upper));
  }
  h5x::writeDoubles(f, path, dims, e.data(), units);
  h5x::writeDoubles(f, path + "_lower", dims, lo.data(), units);
  h5x::writeDoubles(f, path + "_upper", dims, hi.data(), units);
}

}  // namespace

void writeUqH5(const std::string& path, const UqResult& r, const std::vector<TailCheck>& tails) {
  const std::size_t rows = static_cast<std::size_t>(r.rows), k = r.input_names.size(),
                    q = r.metric_names.size(), l = r.limits.size();
  h5::AtomicH5Writer writer(path);
  h5::File& f = writer.file();
  f.createGroup("/uq");
  std::vector<std::string> input_units;
  for (const std::string& key : r.input_names) input_units.push_back(configKeyUnits(key));
  h5x::writeStrings(f, "/uq/input_names", r.input_names);
  h5x::writeDoubles(f, "/uq/inputs", {rows, k}, r.input_values.data(), "per column");
  h5x::setStringArrayAttribute(f, "/uq/inputs", "units", input_units);
  h5x::writeStrings(f, "/uq/metric_names", r.metric_names);
  std::vector<double> metrics(r.metrics.size());
  for (std::size_t i = 0; i < metrics.size(); ++i) metrics[i] = orMinusOne(r.metrics[i]);
  h5x::writeDoubles(f, "/uq/metrics", {rows, q}, metrics.data(), "per column");
  h5x::setStringArrayAttribute(f, "/uq/metrics", "units", r.metric_units);
  h5x::writeDoubles(f, "/uq/rom_error", {rows, 2}, r.rom_error.data(), "1 (-1: none)");
  h5x::writeDoubles(f, "/uq/metric_error", {rows, q}, r.metric_error.data(), "per column");
  std::vector<double> statistic_rows(r.statistic_rows.begin(), r.statistic_rows.end());
  h5x::writeDoubles(f, "/uq/statistic_rows", {statistic_rows.size()}, statistic_rows.data(), "1");

  f.createGroup("/uq/summary");
  std::vector<stats::Interval> mean, sd, quantiles;
  const std::vector<double>& levels = stats::kDefaultQuantileLevels;
  for (const stats::SampleSummary& s : r.summaries) {
    mean.push_back(s.count ? s.mean : stats::Interval{NAN, NAN, NAN});
    sd.push_back(s.count ? s.std_dev : stats::Interval{NAN, NAN, NAN});
    for (std::size_t i = 0; i < levels.size(); ++i)
      quantiles.push_back(s.count ? s.quantiles[i] : stats::Interval{NAN, NAN, NAN});
  }
  writeIntervals(f, "/uq/summary/mean", mean, {q}, "per metric (-1: none)");
  writeIntervals(f, "/uq/summary/std", sd, {q}, "per metric (-1: none)");
  h5x::writeDoubles(f, "/uq/summary/quantile_levels", {levels.size()}, levels.data(), "1");
  writeIntervals(f, "/uq/summary/quantiles", quantiles, {q, levels.size()}, "per metric");

  if (l > 0) {
    f.createGroup("/uq/limits");
    std::vector<std::string> text;
    std::vector<stats::Interval> p, c;
    std::vector<double> critical;
    for (const LimitProbability& lp : r.limits) {
      text.push_back(lp.limit.text);
      p.push_back(lp.probability);
      c.push_back(lp.conservative);
      critical.push_back(static_cast<double>(lp.critical_row));
    }
    h5x::writeStrings(f, "/uq/limits/text", text);
    writeIntervals(f, "/uq/limits/probability", p, {l}, "1");
    writeIntervals(f, "/uq/limits/conservative", c, {l}, "1");
    h5x::writeDoubles(f, "/uq/limits/critical_row", {l}, critical.data(), "1");
  }
  if (r.has_sensitivity) {
    f.createGroup("/uq/sobol");
    std::vector<stats::Interval> first, total;
    std::vector<double> variance;
    for (const stats::SobolIndices& s : r.sobol) {
      variance.push_back(s.first.empty() ? -1.0 : s.variance);
      for (std::size_t i = 0; i < k; ++i) {
        first.push_back(s.first.empty() ? stats::Interval{NAN, NAN, NAN} : s.first[i]);
        total.push_back(s.total.empty() ? stats::Interval{NAN, NAN, NAN} : s.total[i]);
      }
    }
    writeIntervals(f, "/uq/sobol/first", first, {q, k}, "1 (-1: none)");
    writeIntervals(f, "/uq/sobol/total", total, {q, k}, "1 (-1: none)");
    h5x::writeDoubles(f, "/uq/sobol/variance", {q}, variance.data(), "metric^2 (-1: none)");
  }
  if (!tails.empty()) {
    f.createGroup("/uq/tails");
    const std::size_t t = tails.size();
    std::vector<int> limit, row;
    std::vector<std::string> label;
    std::vector<double> rom, rom_bound, full, full_error, wall;
    for (const TailCheck& c : tails) {
      limit.push_back(static_cast<int>(c.limit));
      row.push_back(static_cast<int>(c.row));
      label.push_back(c.label);
      rom.push_back(c.rom_value);
      rom_bound.push_back(c.rom_error_bound);
      full.push_back(orMinusOne(c.full_value));
      full_error.push_back(orMinusOne(c.full_error_estimate));
      wall.push_back(c.full_wall_s);
    }
    h5x::writeInts(f, "/uq/tails/limit", {t}, limit.data(), "1");
    h5x::writeInts(f, "/uq/tails/row", {t}, row.data(), "1");
    h5x::writeStrings(f, "/uq/tails/label", label);
    h5x::writeDoubles(f, "/uq/tails/rom_value", {t}, rom.data(), "the limit's metric");
    h5x::writeDoubles(f, "/uq/tails/rom_error_bound", {t}, rom_bound.data(), "the limit's metric");
    h5x::writeDoubles(f, "/uq/tails/full_value", {t}, full.data(), "the limit's metric");
    h5x::writeDoubles(f, "/uq/tails/full_error_estimate", {t}, full_error.data(),
                      "the limit's metric (-1: none)");
    h5x::writeDoubles(f, "/uq/tails/full_wall_time", {t}, wall.data(), "s");
  }
  f.setStringAttribute("/", "source", "uq");
  f.setStringAttribute("/", "mastrom_version", kVersion);
  f.setStringAttribute("/", "config", r.config_toml);
  f.setStringAttribute("/", "database_checksum", r.database_checksum);
  f.setStringAttribute("/", "sampling", stats::toString(r.sampling));
  f.setDoubleAttribute("/", "seed", static_cast<double>(r.seed));
  f.setIntAttribute("/", "base_samples", static_cast<int>(r.base_samples));
  f.setIntAttribute("/", "rows", static_cast<int>(r.rows));
  f.setDoubleAttribute("/", "confidence", r.confidence);
  f.setDoubleAttribute("/", "rom_step_s", r.step_s);
  f.setIntAttribute("/", "ranks", r.ranks);
  f.setDoubleAttribute("/", "wall_time_s", r.wall_s);
  writer.commit();
}

std::string uqCsvSummary(const UqResult& r, const std::vector<TailCheck>& tails) {
  std::ostringstream os;
  os << "kind,name,statistic,estimate,lower,upper\n";
  const auto line = [&os](const std::string& kind, const std::string& name,
                          const std::string& statistic, const stats::Interval& i) {
    os << kind << ',' << name << ',' << statistic << ',' << shortestText(i.estimate) << ','
       << shortestText(i.lower) << ',' << shortestText(i.upper) << '\n';
  };
  for (std::size_t m = 0; m < r.metric_names.size(); ++m) {
    const stats::SampleSummary& s = r.summaries[m];
    if (s.count == 0) continue;
    line("metric", r.metric_names[m], "mean", s.mean);
    line("metric", r.metric_names[m], "std", s.std_dev);
    for (std::size_t i = 0; i < s.quantile_levels.size(); ++i)
      line("metric", r.metric_names[m], levelName(s.quantile_levels[i]), s.quantiles[i]);
  }
  for (const LimitProbability& lp : r.limits) {
    line("limit", lp.limit.text, "probability", lp.probability);
    line("limit", lp.limit.text, "conservative", lp.conservative);
  }
  for (std::size_t m = 0; m < r.sobol.size(); ++m) {
    const stats::SobolIndices& s = r.sobol[m];
    for (std::size_t i = 0; i < s.first.size(); ++i) {
      const std::string name = r.metric_names[m] + ":" + r.input_names[i];
      line("sobol_first", name, "index", s.first[i]);
      line("sobol_total", name, "index", s.total[i]);
    }
  }
  for (const TailCheck& c : tails) {
    const std::string name = r.limits[c.limit].limit.text + ":" + c.label;
    line("tail", name, "rom",
         {c.rom_value, c.rom_value - c.rom_error_bound, c.rom_value + c.rom_error_bound});
    line(
        "tail", name, "full",
        {c.full_value, c.full_value - c.full_error_estimate, c.full_value + c.full_error_estimate});
  }
  return os.str();
}

void writeUqCsv(const std::string& path, const UqResult& r, const std::vector<TailCheck>& tails) {
  writeTextFileAtomically(path, uqCsvSummary(r, tails));
}

}  // namespace mastrom::rom
