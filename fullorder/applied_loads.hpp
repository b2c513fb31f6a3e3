// Applied (external) loads on shell edges, integrated with the element's shape functions
// (docs/theory.md §2.2; used by the static strip tests and available to users).
//
// Every load contributes a generalized force Q(q, t) on a fixed list of global DOFs and, when Q
// depends on q, its load stiffness K_load = ∂Q/∂q (the Newton tangent is K_t − K_load). Loads are
// conservative: potential() returns V with Q = −∂V/∂q.
//
// Edges of an element are named by the side of its parameter rectangle: XMin (ξ = −1), XMax (ξ =
// +1), YMin (η = −1), YMax (η = +1). Along an XMin/XMax edge the integration runs over y (length b)
// and the slope "across" the edge is r_,x; along a Y edge it runs over x (length a) and the slope
// is r_,y.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

namespace mastrom::fullorder {

enum class ElementEdge { XMin, XMax, YMin, YMax };

class AppliedLoad {
public:
  using ConstVec = Eigen::Ref<const Eigen::VectorXd>;
  virtual ~AppliedLoad() = default;

  /// Global DOF indices, in local order.
  const std::vector<int>& dofs() const { return dofs_; }
  int localDofCount() const { return static_cast<int>(dofs_.size()); }

  /// Generalized force Q (local, overwritten).
  virtual void force(const ConstVec& q, double t, Eigen::Ref<Eigen::VectorXd> f) const = 0;
  /// True when Q depends on q (follower-type or moment loads).
  virtual bool hasStiffness() const = 0;
  /// K_load = ∂Q/∂q (local, overwritten). Default: zero.
  virtual void stiffness(const ConstVec& q, double t, Eigen::Ref<Eigen::MatrixXd> k) const {
    (void)q, (void)t;
    k.setZero();
  }
  /// Potential V(q) with Q = −∂V/∂q [J].
  virtual double potential(const ConstVec& q, double t) const = 0;

protected:
  explicit AppliedLoad(std::vector<int> dofs) : dofs_(std::move(dofs)) {}

private:
  std::vector<int> dofs_;
};

/// Constant line load p [N/m] (force per unit edge length, fixed global direction) on one element
/// edge: Q = ∫ Sᵀ p ds. A total force P spread uniformly over an edge of length b is p = P/b.
class EdgeLineLoad final : public AppliedLoad {
public:
  /// @param element_dofs  the element's 36 global DOFs (corner blocks of nine)
  EdgeLineLoad(const std::array<int, 36>& element_dofs, double a_m, double b_m, ElementEdge edge,
               const Eigen::Vector3d& force_per_length_n_m);
  void force(const ConstVec& q, double t, Eigen::Ref<Eigen::VectorXd> f) const override;
  bool hasStiffness() const override { return false; }
  double potential(const ConstVec& q, double t) const override;

private:
  Eigen::Matrix<double, 12, 1> shape_integral_;  ///< ∫ N_k ds over the edge
  Eigen::Vector3d p_;
};

/// Where the cross-edge slope of an edge moment is sampled.
enum class EdgeMomentSampling {
  /// W = ∫ m φ(g(s)) ds with the element's slope field along the edge (5-point Gauss). Note: in the
  /// incomplete bicubic the cross-edge slope inside an edge also depends on the difference of the
  /// r_y
  /// (or r_x) DOFs across the element, so this distribution also loads those DOFs.
  ElementField,
  /// W = Σ_edge corners (ℓ/2) m φ(g_corner): trapezoidal rule on the nodal slopes only (exact for a
  /// slope uniform along the edge; loads only the corner slope DOFs).
  EdgeNodes,
};

/// End moment applied through its virtual work on the slopes: a couple m [N·m/m] per unit edge
/// length that turns the cross-edge slope g (r_,x or r_,y) in the plane spanned by the unit vectors
/// (e1, e2),
///   W = ∫ m φ(g) ds,  φ = atan2(g·e2, g·e1),
///   ∂φ/∂g = (g₁ e2 − g₂ e1)/(g₁² + g₂²),  g₁ = g·e1, g₂ = g·e2,
/// smooth everywhere except g ⟂ plane (no branch cut at φ = π in the force or the stiffness).
/// Positive m turns g from e1 towards e2. The load stiffness ∂²W/∂e² is symmetric.
/// Example: a strip along x bending in the x–z plane, e1 = x, e2 = z, m = M/b for a total couple M
/// (a couple about −y in the right-hand sense).
class EdgeMomentLoad final : public AppliedLoad {
public:
  EdgeMomentLoad(const std::array<int, 36>& element_dofs, double a_m, double b_m, ElementEdge edge,
                 double moment_per_length_n, const Eigen::Vector3d& e1, const Eigen::Vector3d& e2,
                 EdgeMomentSampling sampling = EdgeMomentSampling::ElementField);
  void force(const ConstVec& q, double t, Eigen::Ref<Eigen::VectorXd> f) const override;
  bool hasStiffness() const override { return true; }
  void stiffness(const ConstVec& q, double t, Eigen::Ref<Eigen::MatrixXd> k) const override;
  /// −W with φ from atan2 ∈ (−π, π] (the potential has the branch cut the force does not).
  double potential(const ConstVec& q, double t) const override;

private:
  struct EdgePoint {
    Eigen::Matrix<double, 12, 1> dn;  ///< ∂N_k/∂(cross-edge coordinate)
    double weight = 0.0;              ///< Gauss weight × ds/dζ
  };
  std::vector<EdgePoint> points_;
  double m_;
  Eigen::Vector3d e1_, e2_;
};

}  // namespace mastrom::fullorder
