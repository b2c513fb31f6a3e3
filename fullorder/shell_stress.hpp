// Stresses of the ANCF thin-shell element at recovery points (docs/theory.md §6): the membrane
// forces, bending moments and plane stresses at the mid-surface and the two faces, with their von
// Mises equivalent, computed from the very strain measures the internal force uses
// (fullorder/shell_kinematics.hpp: Green–Lagrange membrane strain E and curvature change k, mapped
// to the local orthonormal frame by the element's T). With ζ the distance from the mid-surface
// along the unit normal n = g_x × g_y / |g_x × g_y| (Kirchhoff–Love), ε(ζ) = ε − ζ κ, so
//   N = E h D̂ (ε + μ ε̇)            membrane forces  [N/m]   (theory eq. 6.3)
//   M = −E h³/12 D̂ (κ + μ κ̇)       bending moments M = ∫ σ ζ dζ  [N·m/m]   (eq. 6.4)
//   σ(ζ) = N/h + 12 ζ M / h³        plane stress [Pa], ζ ∈ {−h/2, 0, +h/2}   (eq. 6.5)
// in the local frame (t₁ along the reference G_x, t₂ = N × t₁), Voigt [11, 22, 12] (tensor shear).
// The Kelvin–Voigt rate term is the same one the internal force carries (stress = D(ε + μ ε̇)).
//
// The map is evaluated at any point of the element (not only quadrature points); the default set
// is the 3 × 3 grid ξ, η ∈ {−1, 0, 1}, which includes the corners and edge midpoints where the
// bonded edges put the peak stresses. linearizedStress() gives ∂σ/∂e · d (a stress per unit of a
// direction d in coordinate space, e.g. a mode shape) for modal stress recovery.
#pragma once

#include <array>
#include <vector>

#include <Eigen/Core>

#include "fullorder/shell_element.hpp"

namespace mastrom::fullorder {

/// Number of through-thickness stations: ζ = −h/2, 0, +h/2 along n.
inline constexpr int kShellSurfaces = 3;
/// ζ/h of station s.
inline constexpr double kShellSurfaceZeta[kShellSurfaces] = {-0.5, 0.0, 0.5};

/// Plane-stress von Mises equivalent of [σ11, σ22, σ12] [Pa].
double vonMisesPlaneStress(const Eigen::Vector3d& sigma_pa);

/// The stress state of one point of the shell.
struct ShellPointStress {
  Eigen::Vector3d membrane_force_n_m = Eigen::Vector3d::Zero();  ///< [N11, N22, N12]
  Eigen::Vector3d bending_moment_n = Eigen::Vector3d::Zero();    ///< [M11, M22, M12] (N·m/m)
  std::array<Eigen::Vector3d, kShellSurfaces> stress_pa{};       ///< σ at each ζ station
  std::array<double, kShellSurfaces> von_mises_pa{};
};

/// Recovery of one element's stresses at a fixed set of points.
class ShellStressRecovery {
public:
  /// @param points  (ξ, η) ∈ [−1, 1]² of each recovery point (InputError outside)
  ShellStressRecovery(const ShellElement& element, const std::vector<std::array<double, 2>>& points);

  /// The default points: the 3 × 3 grid ξ, η ∈ {−1, 0, 1}, ξ fastest.
  static std::vector<std::array<double, 2>> gridPoints();

  int pointCount() const { return static_cast<int>(points_.size()); }
  const std::array<double, 2>& point(int p) const { return points_[static_cast<size_t>(p)].xi_eta; }

  /// The stresses at point p for element coordinates e and velocities ė (ė may be null: the
  /// elastic part only; it is not read when μ = 0). Throws NumericalError on a degenerate surface.
  ShellPointStress stress(int p, const Vec36& e, const Vec36* edot = nullptr) const;

  /// The directional derivative ∂σ/∂e · d at e (elastic part; the same formula with (ε, κ)
  /// replaced by their first variations (∂ε/∂e·d, ∂κ/∂e·d), fullorder/shell_kinematics.hpp
  /// shellStrainRates). von_mises_pa is left zero (it is not linear).
  ShellPointStress linearizedStress(int p, const Vec36& e, const Vec36& d) const;

  /// Reference position of point p (interpolated reference surface) [m].
  Eigen::Vector3d referencePosition(int p) const;

private:
  struct Point {
    std::array<double, 2> xi_eta{};
    ShellShapeValues shape;
    Eigen::Vector3d metric0, curv0;
    Eigen::Matrix3d transform;  ///< T of the point (strain to local frame)
  };
  ShellPointStress fromLocalStrains(const Eigen::Vector3d& eps, const Eigen::Vector3d& kappa,
                                    bool with_von_mises) const;

  Vec36 e0_;
  double thickness_m_ = 0.0, youngs_modulus_pa_ = 0.0, damping_s_ = 0.0;
  Eigen::Matrix3d d_hat_;
  std::vector<Point> points_;
};

}  // namespace mastrom::fullorder
