// What `mastrom optimize` is asked (docs/theory.md §4.5): an objective metric to minimise or
// maximise, constraints "METRIC OP VALUE" on other metrics, and the conservative margin each
// constraint is taken with — the ROM's estimated error at the design, carried to the metric.
//
// The metrics are the columns of a screen (rom/studies/screen_kernel.hpp screenMetricNames), so a
// metric the screen gains is a metric optimize takes. How the ROM's error reaches a metric is
// decided by the metric's kind (metricErrorKind): the response NRMSE e_r of the database's estimate
// (rom/interpolation/point_error_estimate.hpp) for everything computed from the elastic response
// (accelerations, loads, stresses), its ω₁ error e_ω for frequencies, none for what the ROM
// computes exactly (mass). The margin is kMarginFactor times the upper estimate e⁺ times the
// metric's scale (see conservativeMargin).
#pragma once

#include <string>
#include <vector>

namespace mastrom::rom {

enum class OptimizationSense { Minimize, Maximize };

/// One constraint: metric ≤ bound (at_most) or metric ≥ bound.
struct MetricConstraint {
  std::string metric;
  bool at_most = true;
  double bound = 0.0;
  std::string op;    ///< the operator as written (<=, ≤, <, >=, ≥, >): tables print it so
  std::string text;  ///< as given, for messages
};

/// Parse "METRIC OP VALUE", OP one of <= ≤ >= ≥ (< and > mean the same: a margin makes a strict
/// inequality of every bound). InputError naming the text and the form otherwise.
MetricConstraint parseMetricConstraint(const std::string& text);

/// How the ROM's estimated error at a design carries to a metric.
enum class MetricErrorKind {
  Exact,            ///< computed by the ROM exactly (mass): no margin
  Frequency,        ///< a natural frequency: max(e_ω, its own estimate frequency_K_error) × value
  Response,         ///< of the elastic response r (peaks, RMS, residual): e_r × value
  AbsolutePeak,     ///< peak of θ̈ + r: the error is r's, e_r × peak |r|
  Load,             ///< joint force, drive torque: e_r × value (the rigid part counted too)
  Stress,           ///< a von Mises peak: e_r × value
  MarginOfSafety,   ///< yield / σ − 1: e_r × (1 + value), the stress's relative error
  NoEstimate,       ///< a result without an error bound (settling time): objective only
  NotADesignResult  ///< an input of the metrics (settled flag, drive end, band): neither
};

/// The kind of a screen metric (by its name: rules for the families of names).
MetricErrorKind metricErrorKind(const std::string& metric);

/// The conservative margin counts this many times the database's upper error estimate: on a grid
/// the estimate (4.13) read ≥ ½ of the measured error at every point checked; on scattered samples
/// e⁺ of (4.14) was at or above it at 80 of 80 (docs/theory.md §4.3). The full-order check of
/// every optimum measures what is left.
inline constexpr double kMarginFactor = 2.0;

/// The margin δ ≥ 0 of metric `index` of `names` at a design with metric `values` and the upper
/// error estimates (e_ω, e_r): kMarginFactor · e · scale by the metric's kind (see
/// MetricErrorKind); 0 for Exact. A constraint counts as met when value + δ ≤ bound (≤) or
/// value − δ ≥ bound (≥).
double conservativeMargin(const std::vector<std::string>& names, const std::vector<double>& values,
                          std::size_t index, double frequency_error, double response_error);

/// What a database can give: the metric names of its screen. InputError (one line) when `metric`
/// (the argument of `option`, e.g. "--minimize") is not among `available`: unknown, or a stress
/// metric of a database without stress modes, or the margin of safety without a yield strength
/// (each said so); also when the metric is NotADesignResult, or NoEstimate in a constraint.
void requireOptimizable(const std::string& metric, const std::string& option,
                        const std::string& text, bool constraint,
                        const std::vector<std::string>& available, bool database_has_stresses);

}  // namespace mastrom::rom
