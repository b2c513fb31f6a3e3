// Rigid module in natural coordinates (docs/theory.md §2.1; [LW24] eqs. 1–7, [LW24] eq. 39).
//
// q = [r_i; r_j; u; v] ∈ R¹²: r_i the centroid, r_j = r_i + d·x̂ a point on the local x axis,
// u = ŷ, v = ẑ. A material point with local coordinates (X, Y, Z) [m] relative to the centroid sits at
//   r = (1 − X/d) r_i + (X/d) r_j + Y u + Z v = A(X, Y, Z) q,
// so the mass matrix M = ∫ρ AᵀA dV is constant and follows from m and the centroidal inertia alone.
// Six internal constraints, squared so they are polynomial (quadratic) in q:
//   (r_j − r_i)·(r_j − r_i) − d² ,  u·u − 1 ,  v·v − 1 ,  u·(r_j − r_i) ,  v·(r_j − r_i) ,  u·v
// Because they are quadratic, the Hessian term (Φ_qᵀλ)_q depends on λ only.
#pragma once

#include <Eigen/Core>

namespace mastrom::fullorder {

using Vec12 = Eigen::Matrix<double, 12, 1>;
using Mat12 = Eigen::Matrix<double, 12, 12>;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6x12 = Eigen::Matrix<double, 6, 12>;
using Mat3x12 = Eigen::Matrix<double, 3, 12>;

class RigidModule {
public:
  static constexpr int kDofs = 12;
  static constexpr int kConstraints = 6;

  /// @param axis_length_m  d: distance from r_i to r_j (the module side for a cube)
  /// @param mass_kg        m > 0
  /// @param inertia_kg_m2  centroidal inertia tensor in the module's local (x, y, z) frame, SPD
  RigidModule(double axis_length_m, double mass_kg, const Eigen::Matrix3d& inertia_kg_m2);

  /// Solid-box inertia about the centroid for side lengths (sx, sy, sz) [m].
  static Eigen::Matrix3d boxInertia(double mass_kg, double sx_m, double sy_m, double sz_m);

  double axisLength() const { return d_; }
  double mass() const { return m_; }
  const Eigen::Matrix3d& inertia() const { return inertia_; }

  /// Constant 12×12 mass matrix.
  const Mat12& massMatrix() const { return mass_matrix_; }

  /// Coordinates of the body with centroid c and orientation R (columns = local x, y, z in global).
  Vec12 coordinates(const Eigen::Vector3d& centroid_m, const Eigen::Matrix3d& rotation) const;

  /// A(X, Y, Z): r = A q for the material point at local (X, Y, Z) [m] from the centroid.
  Mat3x12 pointMap(const Eigen::Vector3d& local_m) const;
  /// Map of a body-fixed direction: t = t_x x̂ + t_y u + t_z v = A_dir q, with x̂ = (r_j − r_i)/d.
  Mat3x12 directionMap(const Eigen::Vector3d& local_direction) const;

  /// Φ(q) ∈ R⁶ (order as in the header comment).
  Vec6 constraints(const Vec12& q) const;
  /// Φ_q (6×12).
  Mat6x12 constraintJacobian(const Vec12& q) const;
  /// (Φ_qᵀ λ)_q (12×12, symmetric, independent of q).
  Mat12 constraintHessianTerm(const Vec6& lambda) const;
  /// Φ_q q̇ differentiated once more in time: (Φ_q q̇)_q q̇ (the γ term of the index-1 system).
  Vec6 constraintQuadraticVelocityTerm(const Vec12& qdot) const;

  /// Rotation matrix [x̂, u, v] (exact only on the constraint manifold).
  Eigen::Matrix3d rotation(const Vec12& q) const;
  /// Angular velocity ω [rad/s] (global frame): ω = ½ Σ_k c_k × ċ_k over the frame columns.
  Eigen::Vector3d angularVelocity(const Vec12& q, const Vec12& qdot) const;
  /// Angular acceleration α [rad/s²] (global): α = ½ Σ_k c_k × c̈_k.
  Eigen::Vector3d angularAcceleration(const Vec12& q, const Vec12& qddot) const;

private:
  double d_;
  double m_;
  Eigen::Matrix3d inertia_;
  Mat12 mass_matrix_;
};

}  // namespace mastrom::fullorder
