// Edge line loads and edge moments (see applied_loads.hpp).
#include "fullorder/applied_loads.hpp"

#include <cmath>

#include "common/error.hpp"
#include "fullorder/gauss_quadrature.hpp"
#include "fullorder/shell_shape.hpp"

namespace mastrom::fullorder {
namespace {

/// (ξ, η) of the edge point at edge coordinate ζ ∈ [−1, 1], and ds/dζ.
void edgePoint(ElementEdge edge, double zeta, double a, double b, double& xi, double& eta,
               double& jac) {
  xi = eta = jac = 0.0;
  switch (edge) {
    case ElementEdge::XMin:
      xi = -1.0;
      eta = zeta;
      jac = 0.5 * b;
      break;
    case ElementEdge::XMax:
      xi = 1.0;
      eta = zeta;
      jac = 0.5 * b;
      break;
    case ElementEdge::YMin:
      xi = zeta;
      eta = -1.0;
      jac = 0.5 * a;
      break;
    case ElementEdge::YMax:
      xi = zeta;
      eta = 1.0;
      jac = 0.5 * a;
      break;
  }
}

bool isXEdge(ElementEdge edge) { return edge == ElementEdge::XMin || edge == ElementEdge::XMax; }

std::vector<int> toVector(const std::array<int, 36>& a) {
  return std::vector<int>(a.begin(), a.end());
}

/// r (or a slope) of the element field: Σ_k n_k e_k.
Eigen::Vector3d combine(const Eigen::Matrix<double, 12, 1>& n,
                        const Eigen::Ref<const Eigen::VectorXd>& e) {
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  for (int k = 0; k < 12; ++k) r += n[k] * e.segment<3>(3 * k);
  return r;
}

}  // namespace

EdgeLineLoad::EdgeLineLoad(const std::array<int, 36>& element_dofs, double a_m, double b_m,
                           ElementEdge edge, const Eigen::Vector3d& force_per_length_n_m)
    : AppliedLoad(toVector(element_dofs)), p_(force_per_length_n_m) {
  MASTROM_REQUIRE(a_m > 0.0 && b_m > 0.0, InputError, "edge line load: element sides (", a_m, ", ",
                  b_m, ") must be > 0");
  // N_k is cubic along the edge: 3 Gauss points integrate it exactly.
  const GaussRule rule = gaussLegendre(3);
  const std::vector<double>& x = rule.points;
  const std::vector<double>& w = rule.weights;
  shape_integral_.setZero();
  for (size_t i = 0; i < x.size(); ++i) {
    double xi = 0.0, eta = 0.0, jac = 0.0;
    edgePoint(edge, x[i], a_m, b_m, xi, eta, jac);
    shape_integral_ += w[i] * jac * evaluateShellShape(xi, eta, a_m, b_m).n;
  }
}

void EdgeLineLoad::force(const ConstVec&, double, Eigen::Ref<Eigen::VectorXd> f) const {
  for (int k = 0; k < 12; ++k) f.segment<3>(3 * k) = shape_integral_[k] * p_;
}

double EdgeLineLoad::potential(const ConstVec& q, double) const {
  return -p_.dot(combine(shape_integral_, q));
}

EdgeMomentLoad::EdgeMomentLoad(const std::array<int, 36>& element_dofs, double a_m, double b_m,
                               ElementEdge edge, double moment_per_length_n,
                               const Eigen::Vector3d& e1, const Eigen::Vector3d& e2,
                               EdgeMomentSampling sampling)
    : AppliedLoad(toVector(element_dofs)),
      m_(moment_per_length_n),
      e1_(e1.normalized()),
      e2_(e2.normalized()) {
  MASTROM_REQUIRE(a_m > 0.0 && b_m > 0.0, InputError, "edge moment load: element sides (", a_m,
                  ", ", b_m, ") must be > 0");
  MASTROM_REQUIRE(
      std::abs(e1_.dot(e2_)) < 1e-12, InputError,
      "edge moment load: the plane vectors e1, e2 must be orthogonal (e1·e2 = ", e1_.dot(e2_), ")");
  // The element field: 5 Gauss points (the slope is cubic along the edge, φ is smooth). The edge
  // nodes: the trapezoidal rule, whose points are the corners, where the slope field equals the
  // nodal slope exactly (interpolation property).
  GaussRule rule;
  if (sampling == EdgeMomentSampling::ElementField) {
    rule = gaussLegendre(5);
  } else {
    rule.points = {-1.0, 1.0};
    rule.weights = {1.0, 1.0};
  }
  const std::vector<double>& x = rule.points;
  const std::vector<double>& w = rule.weights;
  for (size_t i = 0; i < x.size(); ++i) {
    double xi = 0.0, eta = 0.0, jac = 0.0;
    edgePoint(edge, x[i], a_m, b_m, xi, eta, jac);
    const ShellShapeValues s = evaluateShellShape(xi, eta, a_m, b_m);
    points_.push_back(EdgePoint{isXEdge(edge) ? s.nx : s.ny, w[i] * jac});
  }
}

void EdgeMomentLoad::force(const ConstVec& q, double, Eigen::Ref<Eigen::VectorXd> f) const {
  f.setZero();
  for (const EdgePoint& p : points_) {
    const Eigen::Vector3d g = combine(p.dn, q);
    const double g1 = g.dot(e1_), g2 = g.dot(e2_);
    const Eigen::Vector3d dphi = (g1 * e2_ - g2 * e1_) / (g1 * g1 + g2 * g2);
    for (int k = 0; k < 12; ++k) f.segment<3>(3 * k) += (p.weight * m_ * p.dn[k]) * dphi;
  }
}

void EdgeMomentLoad::stiffness(const ConstVec& q, double, Eigen::Ref<Eigen::MatrixXd> k) const {
  k.setZero();
  Eigen::Matrix<double, 3, 2> basis;
  basis << e1_, e2_;
  for (const EdgePoint& p : points_) {
    const Eigen::Vector3d g = combine(p.dn, q);
    const double g1 = g.dot(e1_), g2 = g.dot(e2_);
    const double rho4 = (g1 * g1 + g2 * g2) * (g1 * g1 + g2 * g2);
    // ∂²φ/∂(g1, g2)² of φ = atan2(g2, g1).
    Eigen::Matrix2d h2;
    h2 << 2.0 * g1 * g2, g2 * g2 - g1 * g1, g2 * g2 - g1 * g1, -2.0 * g1 * g2;
    h2 /= rho4;
    const Eigen::Matrix3d h = basis * h2 * basis.transpose();
    for (int a = 0; a < 12; ++a)
      for (int b = 0; b < 12; ++b)
        k.block<3, 3>(3 * a, 3 * b) += (p.weight * m_ * p.dn[a] * p.dn[b]) * h;
  }
}

double EdgeMomentLoad::potential(const ConstVec& q, double) const {
  double work = 0.0;
  for (const EdgePoint& p : points_) {
    const Eigen::Vector3d g = combine(p.dn, q);
    work += p.weight * m_ * std::atan2(g.dot(e2_), g.dot(e1_));
  }
  return -work;
}

}  // namespace mastrom::fullorder
