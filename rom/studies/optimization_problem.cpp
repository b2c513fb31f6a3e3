// Objective, constraints and margins of `mastrom optimize` (see optimization_problem.hpp).
#include "rom/studies/optimization_problem.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "rom/studies/screen_filter.hpp"

namespace mastrom::rom {
namespace {

bool startsWith(const std::string& s, const std::string& prefix) {
  return s.compare(0, prefix.size(), prefix) == 0;
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

bool isStressMetric(const std::string& m) {
  return startsWith(m, "peak_von_mises_interface_") || m == "max_peak_von_mises" ||
         m == "min_margin_of_safety";
}

std::string list(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

}  // namespace

MetricConstraint parseMetricConstraint(const std::string& text) {
  const ColumnCondition c = parseColumnCondition(text, "--subject-to");
  MASTROM_REQUIRE(c.op != ColumnCondition::Op::Equal && c.op != ColumnCondition::Op::NotEqual,
                  InputError, "--subject-to '", text,
                  "': OP must be <= (≤) or >= (≥), < and > alike; an equality is no design "
                  "constraint");
  MetricConstraint m;
  m.metric = c.column;
  m.at_most = c.op == ColumnCondition::Op::Less || c.op == ColumnCondition::Op::LessEqual;
  m.bound = c.value;
  m.op = c.op_text;
  m.text = text;
  return m;
}

MetricErrorKind metricErrorKind(const std::string& m) {
  if (m == "settled" || m == "drive_end_time" || m == "settling_band")
    return MetricErrorKind::NotADesignResult;
  if (m == "settling_time") return MetricErrorKind::NoEstimate;
  if (m == "peak_abs_end_angular_acceleration") return MetricErrorKind::AbsolutePeak;
  if (endsWith(m, "_rel_end_angular_acceleration")) return MetricErrorKind::Response;
  if (m == "peak_joint_force" || m == "peak_drive_torque") return MetricErrorKind::Load;
  if (m == "min_margin_of_safety") return MetricErrorKind::MarginOfSafety;
  if (isStressMetric(m)) return MetricErrorKind::Stress;
  // The design descriptions of the screen: masses from the configuration (exact), natural
  // frequencies from the interpolated model (ω's own error estimate).
  if (m == "mass" || startsWith(m, "mass_") || endsWith(m, "_mass")) return MetricErrorKind::Exact;
  if (m.find("frequency") != std::string::npos) return MetricErrorKind::Frequency;
  return MetricErrorKind::NoEstimate;
}

double conservativeMargin(const std::vector<std::string>& names, const std::vector<double>& values,
                          std::size_t index, double frequency_error, double response_error) {
  const double v = values[index];
  const double er = std::max(response_error, 0.0), ef = std::max(frequency_error, 0.0);
  switch (metricErrorKind(names[index])) {
    case MetricErrorKind::Exact:
      return 0.0;
    case MetricErrorKind::Frequency: {
      // frequency_K's own estimate (4.15) where the screen carries it (frequency_K_error), not
      // only ω₁'s: a higher frequency interpolates less well (coarse Scheme 1: f₃ off by 2.0e-5
      // where ω₁'s estimate read 5e-6).
      const auto own = std::find(names.begin(), names.end(), names[index] + "_error");
      const double e_own =
          own == names.end() ? -1.0 : values[static_cast<std::size_t>(own - names.begin())];
      return kMarginFactor * std::max(ef, e_own) * std::abs(v);
    }
    case MetricErrorKind::Response:
    case MetricErrorKind::Load:
    case MetricErrorKind::Stress:
      return kMarginFactor * er * std::abs(v);
    case MetricErrorKind::AbsolutePeak: {
      // a = θ̈ + r with θ̈ exact: the peak moves by at most the largest error of r.
      const auto rel = std::find(names.begin(), names.end(), "peak_rel_end_angular_acceleration");
      const double peak_r =
          rel == names.end() ? v : values[static_cast<std::size_t>(rel - names.begin())];
      return kMarginFactor * er * std::abs(peak_r);
    }
    case MetricErrorKind::MarginOfSafety:
      // MS = σ_y/σ − 1: a relative error ε of σ moves MS by (1 + MS) ε/(1 + ε) ≤ (1 + MS) ε.
      return kMarginFactor * er * std::abs(1.0 + v);
    case MetricErrorKind::NoEstimate:
    case MetricErrorKind::NotADesignResult:
      break;
  }
  throw UsageError("conservativeMargin: " + names[index] + " has no error estimate");
}

void requireOptimizable(const std::string& metric, const std::string& option,
                        const std::string& text, bool constraint,
                        const std::vector<std::string>& available, bool database_has_stresses) {
  const std::string what = option + " '" + text + "': ";
  if (std::find(available.begin(), available.end(), metric) == available.end()) {
    if (isStressMetric(metric) && !database_has_stresses)
      throw InputError(what +
                       "this database carries no stress modes (built with --no-stresses), "
                       "so it cannot give " +
                       metric);
    if (metric == "min_margin_of_safety")
      throw InputError(what +
                       "min_margin_of_safety needs a yield strength (e.g. --set "
                       "material.yield_strength=2.7e8)");
    if (startsWith(metric, "peak_von_mises_interface_"))
      throw InputError(what + metric +
                       " is not an interface of this mast (metrics: " + list(available) + ")");
    throw InputError(what + metric + " is not a metric (metrics: " + list(available) + ")");
  }
  const MetricErrorKind kind = metricErrorKind(metric);
  MASTROM_REQUIRE(kind != MetricErrorKind::NotADesignResult, InputError, what, metric,
                  " is a setting of the metrics, not a result of the design");
  MASTROM_REQUIRE(!(constraint && kind == MetricErrorKind::NoEstimate), InputError, what,
                  "no estimate of the ROM's error bounds ", metric,
                  " (a crossing of the settling band), so it may be the objective but not a "
                  "constraint");
}

}  // namespace mastrom::rom
