// The online part of the exact affine model in (h, E, ρ) at a fixed mid-surface radius
// (rom/interpolation/affine_model.hpp, docs/theory.md §4.4 "exact where possible"): the reduced r × r terms and
// the output operators on the basis columns, without any full-order matrix. This is what a ROM
// database stores (rom/database/database_io.hpp, /affine) and what AffineModalModel::fromReduced evaluates:
//     K_r = E (h K_m + h³ K_b),  M_r = M_rigid + ρh M_shell,  K_r y = ω² M_r y,
// and every mass-built output operator as rigid + ρh · shell (see rom/interpolation/affine_model.hpp).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace mastrom::rom {

struct AffineReducedModel {
  /// Box of validity [min, max] per parameter (min = max: fixed at that value).
  double thickness_min_m = 0.0, thickness_max_m = 0.0;
  double youngs_modulus_min_pa = 0.0, youngs_modulus_max_pa = 0.0;
  double density_min_kg_m3 = 0.0, density_max_kg_m3 = 0.0;
  int modes = 0;                     ///< modes of an evaluation, ≤ r
  double damping_s = 0.0;            ///< Kelvin–Voigt μ
  double reference_angle_rad = 0.0;  ///< θ₀ of the linearisation
  Eigen::MatrixXd k_membrane, k_bending, m_rigid, m_shell;  ///< r × r
  Eigen::VectorXd gamma_rigid, gamma_shell, gamma_c_rigid, gamma_c_shell;  ///< r
  Eigen::Matrix3Xd momentum_rigid, momentum_shell;    ///< 3 × r
  Eigen::MatrixXd coriolis_rigid, coriolis_shell;     ///< r × r
  Eigen::Matrix3Xd end_rotation, end_translation;     ///< 3 × r (geometric, fixed)
  double inertia_rigid = 0.0, inertia_shell = 0.0, mass_rigid = 0.0, mass_shell = 0.0;
  Eigen::Vector3d first_moment_rigid = Eigen::Vector3d::Zero();
  Eigen::Vector3d first_moment_shell = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_position = Eigen::Vector3d::Zero();
  /// The interfaces' linearised stress rows of the basis columns (6P × r,
  /// rom/model/modal_stress.hpp layout) per unit modulus: the membrane rows σ_m = E D̂ ε do not
  /// depend on h, the bending rows σ_b = (E h/2) D̂ κ grow with h, so σ_m rows are stored per unit E
  /// [Pa/Pa] and σ_b rows per unit E·h [Pa/(Pa·m)] — the modal stresses at (h, E) are then exact
  /// (docs/theory.md §6.5). Empty when the database was built without stresses.
  Eigen::MatrixXd stress_rows;

  int basisSize() const { return static_cast<int>(k_membrane.rows()); }
  /// Throws InputError naming the first inconsistency (sizes, non-finite values, box, modes).
  void validate() const;
};

/// One named array of the reduced model (row-major values, dims), for files and checksums.
struct NamedArray {
  std::string name;
  std::vector<std::size_t> dims;
  std::vector<double> values;
};

/// The name of the one optional array (AffineReducedModel::stress_rows), present only when
/// non-empty.
inline constexpr const char* kAffineStressRows = "stress_rows";

/// The reduced model as a fixed list of named arrays (scalars as [1]), then the optional ones, and
/// back. fromArrays throws
/// InputError naming a missing array or a wrong shape, then validates.
std::vector<NamedArray> toArrays(const AffineReducedModel& model);
AffineReducedModel fromArrays(const std::vector<NamedArray>& arrays);

}  // namespace mastrom::rom
