// Modal-analysis result files: the /modes part of the HDF5 layout of docs/user_guide.md §5, plus
// what the ROM of §4.1 needs, written atomically (temporary name, renamed when complete).
//
//   /modes/frequency_hz [k]                 Hz         ascending (negative = unstable, see
//                                                       EigenResult::frequencies_hz)
//   /modes/angle_rad [1]                    rad        θ0, the locked joint angle
//   /modes/damping_ratio [k]                1
//   /modes/participation [k]                kg^0.5*m   Γ = ΦᵀMΩq₀
//   /modes/effective_mass_fraction [k]      1          Γ²/J
//   /modes/centrifugal_participation [k]    kg^0.5*m   Γc = ΦᵀMΩ²q₀
//   /modes/translation_participation [k,3]  kg^0.5     ΦᵀM u_{x,y,z}
//   /modes/coriolis [k,k]                   1          ΦᵀMΩΦ
//   /modes/shapes [k, ndof]                 kg^-0.5 (mixed: m/(kg^0.5*m) per slot)  ΦᵀMΦ = I
//   /modes/end_rotation [k,3]               rad/(kg^0.5*m)
//   /modes/end_displacement [k,3]           kg^-0.5
//   /modes/residual [k]                     1          projected residuals of the pairs
//   /modes/reference [ndof]                 m (mixed)  q₀, the linearisation point
//   /modes/labels [k]                       1          strings (modes/mode_labels.hpp)
//   /modes attributes: rotational_inertia_kg_m2 (J), backend, status, requested (int), stable
//                      (int: 1 stable, 0 unstable — written only with --allow-unstable —, −1 not
//                      checked), instability (text: the unstable directions, "" when stable)
//   /      attributes: config (resolved TOML), mastrom_version, source = "modes", wall_time_s
// A file never holds a NaN or an infinity: the data are checked before the file is created.
// Other groups (the ParaView data of modes/xdmf_writer.hpp) may be added to the same file before
// the writer commits.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "common/hdf5_file.hpp"
#include "modes/linearize.hpp"
#include "modes/modal_analysis.hpp"

namespace mastrom::modes {

/// Everything under /modes.
struct ModesData {
  double angle_rad = 0.0;
  std::string backend;  ///< "slepc", "arpack", "dense"
  std::string status;   ///< "converged", "not converged", "failed"
  int requested = 0;
  Eigen::VectorXd frequency_hz, damping_ratio, participation, effective_mass_fraction,
      centrifugal_participation, residual;
  Eigen::MatrixXd translation_participation;       ///< k × 3
  Eigen::MatrixXd coriolis;                        ///< k × k
  Eigen::MatrixXd shapes;                          ///< k × ndof (one mode per row)
  Eigen::MatrixXd end_rotation, end_displacement;  ///< k × 3
  Eigen::VectorXd reference;                       ///< ndof
  double rotational_inertia_kg_m2 = 0.0;
  std::vector<std::string> labels;
  /// Stability of the linearisation point (modes/stability.hpp).
  bool stability_checked = false;
  bool stable = true;
  std::string instability;

  int modeCount() const { return static_cast<int>(frequency_hz.size()); }
  /// UsageError if the sizes disagree; NumericalError naming the first non-finite value.
  void check(const std::string& file_path) const;
};

/// A whole modes file.
struct ModesFile {
  ModesData modes;
  std::string config_toml;
  std::string mastrom_version;
  std::string source;
  double wall_time_s = 0.0;
};

/// Collect the /modes data of an analysis at the locked angle `angle_rad`.
ModesData modesData(const ModalAnalysis& analysis, const Linearization& linearization,
                    double angle_rad);

/// Write /modes and the root attributes into an open file (for callers that add more before
/// committing an AtomicH5Writer). Checks everything first (ModesData::check).
void writeModes(h5::File& file, const ModesData& data, const std::string& resolved_config_toml,
                double wall_time_s);

/// Write a complete modes file atomically; on failure the final name is left untouched.
void writeModesFile(const std::string& path, const ModesData& data,
                    const std::string& resolved_config_toml, double wall_time_s);

/// Read a file written by writeModes. IoError when it is missing, not HDF5, not a modes file (the
/// message names what is missing) or inconsistent.
ModesFile readModesFile(const std::string& path);

}  // namespace mastrom::modes
