// The metrics that describe a design, in one table: each metric's name, units, meaning and how its
// value is read from what one design's evaluation produced. `mastrom screen`'s columns, the Python
// module's screen, `--where`/`--sort-by`/`--pareto` and the optimiser's objectives and constraints
// all name metrics through this table, so a name means the same number everywhere.
//
// Families, in column order:
//  * the deployment (docs/theory.md (1.6)): peak_abs_end_angular_acceleration … settling_band;
//  * the interfaces' strength (§6.5), when the database carries stress modes:
//    peak_von_mises_interface_K, max_peak_von_mises, and min_margin_of_safety when
//    material.yield_strength is set;
//  * the mass (§1.7, (1.12)): mass (the whole mast), mass_module_K, mass_interface_K;
//  * the natural frequencies of the mast locked at the deployed angle (§1.7): frequency_K [Hz] and
//    frequency_K_error, the database's estimate of its relative error (−1: none).
// K counts from 1 at the base, as the configuration's items do.
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "fullorder/deployment_result.hpp"
#include "fullorder/mast_mass.hpp"

namespace mastrom::rom {

/// Which columns a design description has, and why a family is absent (for the one-line refusal
/// of a metric asked for by name).
struct MetricColumns {
  int stress_interfaces = 0;  ///< peak von Mises per interface; 0: no strength columns
  bool margin = false;        ///< min_margin_of_safety (needs the stresses and a yield strength)
  int modules = 0;            ///< the mast's modules; 0: no mass columns
  int frequencies = 0;        ///< frequency_K, frequency_K_error for K = 1 … frequencies
  std::string no_stress_reason = "the database carries no stress modes";
  std::string no_margin_reason = "the configuration sets no material.yield_strength";
  std::string no_frequency_reason = "no frequencies were asked for";
};

/// Everything one design's evaluation gives: what the metrics read.
struct DesignValues {
  fullorder::DeploymentMetrics deployment;
  std::vector<double> peak_von_mises_pa;  ///< per interface (when stresses are recovered)
  double min_margin_of_safety = std::numeric_limits<double>::quiet_NaN();
  fullorder::MastMass mass;
  std::vector<double> frequency_hz;     ///< lowest first
  std::vector<double> frequency_error;  ///< relative, per frequency; −1: no estimate
};

struct MetricDefinition {
  std::string name;
  std::string units;    ///< SI
  std::string meaning;  ///< one line, for help texts
  std::function<double(const DesignValues&)> value;
};

/// The metrics of a design with `columns`, in column order.
std::vector<MetricDefinition> designMetrics(const MetricColumns& columns);

std::vector<std::string> metricNames(const std::vector<MetricDefinition>& metrics);
std::vector<std::string> metricUnits(const std::vector<MetricDefinition>& metrics);

/// Append every metric's value of one design, in the order of `metrics` (`settled` as 0/1).
void appendMetricValues(const std::vector<MetricDefinition>& metrics, const DesignValues& values,
                        std::vector<double>& out);

/// The index of metric `name` in designMetrics(columns). InputError, one line naming `option`
/// (e.g. "--pareto") and the metric, when the name is unknown (with the known families) or when it
/// is one these columns cannot give (with the reason: no stress modes, no yield strength, more
/// frequencies than asked, an item the mast does not have…).
std::size_t metricIndex(const MetricColumns& columns, const std::string& name,
                        const std::string& option);

/// The families of metric names, for help texts and messages.
std::string metricFamilies();

}  // namespace mastrom::rom
