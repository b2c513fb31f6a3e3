#include "rom/studies/design_metrics.hpp"

#include <algorithm>
#include <string>

#include "common/error.hpp"

namespace mastrom::rom {
namespace {

using Values = DesignValues;

/// K of "<prefix>K<suffix>" (K ≥ 1, decimal digits only); 0 when `name` has another form.
int itemNumber(const std::string& name, const std::string& prefix, const std::string& suffix) {
  if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return 0;
  const std::string digits =
      name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (digits.empty() || digits.size() > 6 ||
      digits.find_first_not_of("0123456789") != std::string::npos || digits[0] == '0')
    return 0;
  return std::stoi(digits);
}

std::string label(int k) { return std::to_string(k); }

}  // namespace

std::vector<MetricDefinition> designMetrics(const MetricColumns& c) {
  std::vector<MetricDefinition> m{
      {"peak_abs_end_angular_acceleration", "rad/s^2",
       "peak |end angular acceleration about Z| (continuous response)",
       [](const Values& v) { return v.deployment.peak_abs_end_angular_acceleration; }},
      {"peak_rel_end_angular_acceleration", "rad/s^2",
       "peak |relative end angular acceleration| (the vibration)",
       [](const Values& v) { return v.deployment.peak_rel_end_angular_acceleration; }},
      {"rms_rel_end_angular_acceleration", "rad/s^2",
       "RMS of the relative end angular acceleration",
       [](const Values& v) { return v.deployment.rms_rel_end_angular_acceleration; }},
      {"residual_rel_end_angular_acceleration", "rad/s^2",
       "peak |relative end angular acceleration| after the drive stops",
       [](const Values& v) { return v.deployment.residual_rel_end_angular_acceleration; }},
      {"settling_time", "s", "time after which the vibration stays within the settling band",
       [](const Values& v) { return v.deployment.settling_time; }},
      {"settled", "flag", "1 when the record ends inside the settling band",
       [](const Values& v) { return v.deployment.settled ? 1.0 : 0.0; }},
      {"peak_joint_force", "N", "peak |base joint reaction force|",
       [](const Values& v) { return v.deployment.peak_joint_force; }},
      {"peak_drive_torque", "N*m", "peak |drive torque|",
       [](const Values& v) { return v.deployment.peak_drive_torque; }},
      {"drive_end_time", "s", "the drive's duration T",
       [](const Values& v) { return v.deployment.drive_end_time; }},
      {"settling_band", "rad/s^2", "the settling band b",
       [](const Values& v) { return v.deployment.settling_band; }},
  };
  for (int k = 1; k <= c.stress_interfaces; ++k)
    m.push_back({"peak_von_mises_interface_" + label(k), "Pa",
                 "peak von Mises stress of interface " + label(k), [k](const Values& v) {
                   return v.peak_von_mises_pa.at(static_cast<std::size_t>(k - 1));
                 }});
  if (c.stress_interfaces > 0) {
    m.push_back({"max_peak_von_mises", "Pa", "largest peak von Mises stress of all interfaces",
                 [](const Values& v) {
                   double largest = 0.0;
                   for (const double s : v.peak_von_mises_pa) largest = std::max(largest, s);
                   return largest;
                 }});
    if (c.margin)
      m.push_back({"min_margin_of_safety", "1", "yield strength / max_peak_von_mises - 1",
                   [](const Values& v) { return v.min_margin_of_safety; }});
  }
  if (c.modules > 0) {
    m.push_back({"mass", "kg", "mass of the whole mast (modules and interfaces)",
                 [](const Values& v) { return v.mass.total_kg; }});
    for (int k = 1; k <= c.modules; ++k)
      m.push_back(
          {"mass_module_" + label(k), "kg", "mass of module " + label(k),
           [k](const Values& v) { return v.mass.module_kg.at(static_cast<std::size_t>(k - 1)); }});
    for (int k = 1; k < c.modules; ++k)
      m.push_back({"mass_interface_" + label(k), "kg",
                   "mass of interface " + label(k) + " (shell volume times density)",
                   [k](const Values& v) {
                     return v.mass.interface_kg.at(static_cast<std::size_t>(k - 1));
                   }});
  }
  for (int k = 1; k <= c.frequencies; ++k)
    m.push_back(
        {"frequency_" + label(k), "Hz",
         "natural frequency " + label(k) + " of the mast locked at the deployed angle",
         [k](const Values& v) { return v.frequency_hz.at(static_cast<std::size_t>(k - 1)); }});
  for (int k = 1; k <= c.frequencies; ++k)
    m.push_back(
        {"frequency_" + label(k) + "_error", "1",
         "the database's estimate of the relative error of frequency_" + label(k) + " (-1: none)",
         [k](const Values& v) { return v.frequency_error.at(static_cast<std::size_t>(k - 1)); }});
  return m;
}

std::vector<std::string> metricNames(const std::vector<MetricDefinition>& metrics) {
  std::vector<std::string> out;
  for (const MetricDefinition& d : metrics) out.push_back(d.name);
  return out;
}

std::vector<std::string> metricUnits(const std::vector<MetricDefinition>& metrics) {
  std::vector<std::string> out;
  for (const MetricDefinition& d : metrics) out.push_back(d.units);
  return out;
}

void appendMetricValues(const std::vector<MetricDefinition>& metrics, const DesignValues& values,
                        std::vector<double>& out) {
  for (const MetricDefinition& d : metrics) out.push_back(d.value(values));
}

std::string metricFamilies() {
  return "peak_abs_end_angular_acceleration, peak_rel_end_angular_acceleration, "
         "rms_rel_end_angular_acceleration, residual_rel_end_angular_acceleration, "
         "settling_time, settled, peak_joint_force, peak_drive_torque, drive_end_time, "
         "settling_band, peak_von_mises_interface_K, max_peak_von_mises, min_margin_of_safety, "
         "mass, mass_module_K, mass_interface_K, frequency_K, frequency_K_error";
}

std::size_t metricIndex(const MetricColumns& c, const std::string& name,
                        const std::string& option) {
  const std::vector<MetricDefinition> metrics = designMetrics(c);
  for (std::size_t i = 0; i < metrics.size(); ++i)
    if (metrics[i].name == name) return i;
  // Not a column: say why — a family these columns lack, an item beyond the mast, or unknown.
  const auto refuse = [&](const std::string& why) {
    throw InputError(detail::concat(option, " ", name, ": ", why));
  };
  const int interface_k = itemNumber(name, "peak_von_mises_interface_", "");
  if (interface_k > 0 || name == "max_peak_von_mises" || name == "min_margin_of_safety") {
    if (c.stress_interfaces == 0) refuse("no stresses here: " + c.no_stress_reason);
    if (name == "min_margin_of_safety") refuse("no margin of safety here: " + c.no_margin_reason);
    refuse(detail::concat("the mast has ", c.stress_interfaces, " interfaces (K = 1 … ",
                          c.stress_interfaces, ")"));
  }
  const int module_k = itemNumber(name, "mass_module_", "");
  const int shell_k = itemNumber(name, "mass_interface_", "");
  if (module_k > 0 || shell_k > 0 || name == "mass") {
    if (c.modules == 0) refuse("no mass columns here");
    if (module_k > 0)
      refuse(detail::concat("the mast has ", c.modules, " modules (K = 1 … ", c.modules, ")"));
    refuse(detail::concat("the mast has ", c.modules - 1, " interfaces (K = 1 … ", c.modules - 1,
                          ")"));
  }
  const int frequency_k =
      std::max(itemNumber(name, "frequency_", ""), itemNumber(name, "frequency_", "_error"));
  if (frequency_k > 0) {
    if (c.frequencies == 0) refuse("no natural frequencies here: " + c.no_frequency_reason);
    refuse(detail::concat("only the lowest ", c.frequencies,
                          " frequencies are computed (allowed K = 1 … ", c.frequencies,
                          "; --frequencies N asks for more)"));
  }
  refuse("unknown metric (known: " + metricFamilies() + ")");
  return 0;  // not reached
}

}  // namespace mastrom::rom
