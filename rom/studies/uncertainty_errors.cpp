#include "rom/studies/uncertainty_errors.hpp"

#include <cmath>
#include <limits>

namespace mastrom::rom {
namespace {

enum class ErrorKind { None, Response, Margin, Frequency };

ErrorKind errorKindOf(const std::string& name, const std::string& unit) {
  if (name == "min_margin_of_safety") return ErrorKind::Margin;
  if (name == "settling_band") return ErrorKind::None;  // a constant of the configuration
  if (unit == "Hz") return ErrorKind::Frequency;
  if (unit == "rad/s^2" || unit == "N" || unit == "N*m" || unit == "Pa") return ErrorKind::Response;
  return ErrorKind::None;
}

}  // namespace

bool limitHolds(const ColumnCondition& c, double v) {
  switch (c.op) {
    case ColumnCondition::Op::Less:
      return v < c.value;
    case ColumnCondition::Op::LessEqual:
      return v <= c.value;
    case ColumnCondition::Op::Greater:
      return v > c.value;
    case ColumnCondition::Op::GreaterEqual:
      return v >= c.value;
    case ColumnCondition::Op::Equal:
      return v == c.value;
    case ColumnCondition::Op::NotEqual:
      return v != c.value;
  }
  return false;
}

void metricErrorBounds(UqResult& r) {
  const std::size_t q = r.metric_names.size();
  std::vector<ErrorKind> kinds;
  for (std::size_t m = 0; m < q; ++m)
    kinds.push_back(errorKindOf(r.metric_names[m], r.metric_units[m]));
  bool estimated = r.rows > 0;
  for (long row = 0; row < r.rows; ++row)
    estimated = estimated && r.rom_error[static_cast<std::size_t>(2 * row + 1)] >= 0.0;
  r.metric_has_error.assign(q, false);
  for (std::size_t m = 0; m < q; ++m)
    r.metric_has_error[m] = estimated && kinds[m] != ErrorKind::None;
  r.metric_error.assign(static_cast<std::size_t>(r.rows) * q, 0.0);
  if (!estimated) return;
  for (long row = 0; row < r.rows; ++row) {
    const double e_omega = r.rom_error[static_cast<std::size_t>(2 * row)];
    const double e = r.rom_error[static_cast<std::size_t>(2 * row + 1)];
    for (std::size_t m = 0; m < q; ++m) {
      const double v = r.metric(row, m);
      double bound = 0.0;
      switch (kinds[m]) {
        case ErrorKind::Response:
          bound = e * std::abs(v);
          break;
        case ErrorKind::Frequency:
          bound = e_omega * std::abs(v);
          break;
        case ErrorKind::Margin:
          // σ within σ(1 ± e): M ∈ [(1 + M)/(1 + e) − 1, (1 + M)/(1 − e) − 1]; the wider side.
          bound =
              e < 1.0 ? std::abs(1.0 + v) * e / (1.0 - e) : std::numeric_limits<double>::infinity();
          break;
        case ErrorKind::None:
          break;
      }
      r.metric_error[static_cast<std::size_t>(row) * q + m] = bound;
    }
  }
}

LimitProbability limitProbability(const UqResult& r, const ColumnCondition& limit,
                                  double confidence) {
  const std::size_t q = r.metric_names.size();
  std::size_t m = 0;
  while (r.metric_names[m] != limit.column) ++m;
  const bool upward =
      limit.op == ColumnCondition::Op::Greater || limit.op == ColumnCondition::Op::GreaterEqual;
  std::size_t hits = 0, conservative = 0;
  LimitProbability p;
  p.limit = limit;
  p.has_error_estimate = r.metric_has_error[m];
  double most =
      upward ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
  for (const long row : r.statistic_rows) {
    const double v = r.metric(row, m);
    const double bound = r.metric_error[static_cast<std::size_t>(row) * q + m];
    hits += limitHolds(limit, v);
    conservative += limitHolds(limit, upward ? v + bound : v - bound);
    if (std::isfinite(v) && (upward ? v > most : v < most)) {
      most = v;
      p.critical_row = row;
    }
  }
  p.probability = stats::proportionInterval(hits, r.statistic_rows.size(), confidence);
  p.conservative = stats::proportionInterval(conservative, r.statistic_rows.size(), confidence);
  return p;
}

}  // namespace mastrom::rom
