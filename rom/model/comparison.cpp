#include "rom/model/comparison.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace mastrom::rom {
namespace {
double relativeError(double rom, double full) {
  const double scale = std::abs(full);
  return scale > 0.0 ? std::abs(rom - full) / scale : std::abs(rom - full);
}
}  // namespace

double DeploymentComparison::worst() const {
  const std::vector<double> v = values();
  return *std::max_element(v.begin(), v.end());
}

std::vector<std::string> DeploymentComparison::names() {
  return {"nrmse_rel_end_angular_acceleration", "peak_abs_end_angular_acceleration",
          "peak_rel_end_angular_acceleration",  "rms_rel_end_angular_acceleration",
          "residual_rel_end_angular_acceleration", "peak_joint_force",
          "peak_drive_torque"};
}

std::vector<double> DeploymentComparison::values() const {
  return {nrmse_relative_acceleration, peak_abs_error, peak_rel_error, rms_rel_error,
          residual_error, peak_force_error, peak_torque_error};
}

DeploymentComparison compareDeployments(const fullorder::DeploymentSeries& full,
                                        const fullorder::DeploymentMetrics& fm,
                                        const fullorder::DeploymentSeries& rom,
                                        const fullorder::DeploymentMetrics& rm) {
  MASTROM_REQUIRE(full.size() == rom.size() && !full.empty(), InputError,
                  "comparison: the full-order and ROM series have ", full.size(), " and ",
                  rom.size(), " samples; they must be sampled at the same instants");
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < full.size(); ++i) {
    MASTROM_REQUIRE(std::abs(full.time_s[i] - rom.time_s[i]) <= 1e-9, InputError,
                    "comparison: sample ", i, " is at t = ", full.time_s[i], " s (full order) and ",
                    rom.time_s[i], " s (ROM)");
    const double a = full.end_relative_angular_acceleration_rad_s2[i];
    const double b = rom.end_relative_angular_acceleration_rad_s2[i];
    num += (b - a) * (b - a);
    den += a * a;
  }
  DeploymentComparison c;
  c.nrmse_relative_acceleration = den > 0.0 ? std::sqrt(num / den) : std::sqrt(num);
  c.peak_abs_error = relativeError(rm.peak_abs_end_angular_acceleration,
                                   fm.peak_abs_end_angular_acceleration);
  c.peak_rel_error = relativeError(rm.peak_rel_end_angular_acceleration,
                                   fm.peak_rel_end_angular_acceleration);
  c.rms_rel_error =
      relativeError(rm.rms_rel_end_angular_acceleration, fm.rms_rel_end_angular_acceleration);
  c.residual_error = relativeError(rm.residual_rel_end_angular_acceleration,
                                   fm.residual_rel_end_angular_acceleration);
  c.peak_force_error = relativeError(rm.peak_joint_force, fm.peak_joint_force);
  c.peak_torque_error = relativeError(rm.peak_drive_torque, fm.peak_drive_torque);
  return c;
}

double StressComparison::worst() const {
  double w = 0.0;
  for (const double e : nrmse_max_von_mises) w = std::max(w, e);
  for (const double e : peak_error) w = std::max(w, e);
  return w;
}

StressComparison compareInterfaceStresses(const std::vector<std::vector<double>>& full_history,
                                          const std::vector<double>& full_peaks,
                                          const std::vector<std::vector<double>>& rom_history,
                                          const std::vector<double>& rom_peaks) {
  MASTROM_REQUIRE(full_history.size() == rom_history.size() &&
                      full_peaks.size() == full_history.size() &&
                      rom_peaks.size() == rom_history.size(),
                  InputError, "compare: ", full_history.size(), " interfaces against ",
                  rom_history.size());
  StressComparison c;
  // A file may carry the peaks alone (rom eval without --stress-history): then no NRMSE.
  const auto without = [](const std::vector<double>& h) { return h.empty(); };
  c.histories = std::none_of(full_history.begin(), full_history.end(), without) &&
                std::none_of(rom_history.begin(), rom_history.end(), without);
  for (std::size_t k = 0; k < full_history.size(); ++k) {
    const std::vector<double>& a = full_history[k];
    const std::vector<double>& b = rom_history[k];
    if (c.histories) {
      MASTROM_REQUIRE(a.size() == b.size(), InputError, "compare: interface ", k + 1, " has ",
                      a.size(), " and ", b.size(), " stress samples");
      double num = 0.0, den = 0.0;
      for (std::size_t i = 0; i < a.size(); ++i) {
        num += (b[i] - a[i]) * (b[i] - a[i]);
        den += a[i] * a[i];
      }
      c.nrmse_max_von_mises.push_back(den > 0.0 ? std::sqrt(num / den) : 0.0);
    }
    c.peak_error.push_back(full_peaks[k] != 0.0
                               ? std::abs(rom_peaks[k] - full_peaks[k]) / std::abs(full_peaks[k])
                               : 0.0);
  }
  return c;
}

}  // namespace mastrom::rom
