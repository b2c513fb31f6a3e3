// ROM-versus-full-order comparison of two deployments sampled at the same instants (docs/theory.md
// §4, "always checked against the full order").
//
// NRMSE of the relative end angular acceleration r (the vibration, [LW24] Fig. 14):
//     NRMSE = ‖r_rom − r_full‖₂ / ‖r_full‖₂      (sums over the common samples; RMS-normalised,
//                                                  so 0.03 means an error of 3 % of the signal's RMS)
// Metric errors are relative: |m_rom − m_full| / |m_full| for each scalar metric of docs/theory.md
// §1.
#pragma once

#include <string>
#include <vector>

#include "fullorder/deployment_result.hpp"

namespace mastrom::rom {

struct DeploymentComparison {
  double nrmse_relative_acceleration = 0.0;
  double peak_abs_error = 0.0;       ///< relative error of peak |absolute| end angular acceleration
  double peak_rel_error = 0.0;       ///< relative error of peak |relative| end angular acceleration
  double rms_rel_error = 0.0;        ///< relative error of the RMS of the relative acceleration
  double residual_error = 0.0;       ///< relative error of the residual vibration after the drive
  double peak_force_error = 0.0;     ///< relative error of the peak joint force
  double peak_torque_error = 0.0;    ///< relative error of the peak drive torque
  /// The largest of the above (what a tolerance is checked against).
  double worst() const;
  /// Names and values in a fixed order (tables, HDF5 columns).
  static std::vector<std::string> names();
  std::vector<double> values() const;
};

/// Compare two series sampled at the same times (IoError-free: InputError if the time columns
/// differ by more than 1e-9 s or in length).
DeploymentComparison compareDeployments(const fullorder::DeploymentSeries& full,
                                        const fullorder::DeploymentMetrics& full_metrics,
                                        const fullorder::DeploymentSeries& rom,
                                        const fullorder::DeploymentMetrics& rom_metrics);

/// The interfaces' stresses of the two deployments (docs/theory.md §6.5), per interface: the
/// NRMSE of the history of its largest von Mises stress (as above, over the common samples) and
/// the relative error of its peak. Without a history on either side (a ROM result of rom eval
/// without --stress-history) only the peaks are compared: histories false, no NRMSE.
struct StressComparison {
  bool histories = false;
  std::vector<double> nrmse_max_von_mises;
  std::vector<double> peak_error;
  double worst() const;
};
/// InputError when the interface counts or the history lengths differ.
StressComparison compareInterfaceStresses(const std::vector<std::vector<double>>& full_history,
                                          const std::vector<double>& full_peaks,
                                          const std::vector<std::vector<double>>& rom_history,
                                          const std::vector<double>& rom_peaks);

}  // namespace mastrom::rom
