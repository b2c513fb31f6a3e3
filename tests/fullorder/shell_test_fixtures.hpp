// Reference geometries for shell-element tests: a flat rectangle and a cylindrical panel, built
// here directly from their definitions (docs/theory.md §2.2) so the tests do not depend on the mesh
// code.
#pragma once

#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "fullorder/shell_element.hpp"

namespace mastrom::fullorder::testing {

inline void setNode(Vec36& e, int corner, const Eigen::Vector3d& r, const Eigen::Vector3d& rx,
                    const Eigen::Vector3d& ry) {
  e.segment<3>(9 * corner) = r;
  e.segment<3>(9 * corner + 3) = rx;
  e.segment<3>(9 * corner + 6) = ry;
}

/// Flat a × b rectangle in the x–y plane with its corner 1 at the origin.
inline Vec36 flatReference(double a, double b) {
  Vec36 e;
  const Eigen::Vector3d ex(1, 0, 0), ey(0, 1, 0);
  setNode(e, 0, Eigen::Vector3d(0, 0, 0), ex, ey);
  setNode(e, 1, Eigen::Vector3d(a, 0, 0), ex, ey);
  setNode(e, 2, Eigen::Vector3d(a, b, 0), ex, ey);
  setNode(e, 3, Eigen::Vector3d(0, b, 0), ex, ey);
  return e;
}

/// Cylindrical panel of radius R, axial length a, spanning angle b/R from φ0; x along the axis.
inline Vec36 cylinderReference(double radius, double a, double b, double phi0 = 0.3) {
  Vec36 e;
  const double phi1 = phi0 + b / radius;
  auto pos = [&](double x, double phi) {
    return Eigen::Vector3d(x, radius * std::cos(phi), radius * std::sin(phi));
  };
  auto tangent = [](double phi) { return Eigen::Vector3d(0, -std::sin(phi), std::cos(phi)); };
  const Eigen::Vector3d ex(1, 0, 0);
  setNode(e, 0, pos(0, phi0), ex, tangent(phi0));
  setNode(e, 1, pos(a, phi0), ex, tangent(phi0));
  setNode(e, 2, pos(a, phi1), ex, tangent(phi1));
  setNode(e, 3, pos(0, phi1), ex, tangent(phi1));
  return e;
}

/// Apply r ↦ R r + t to positions and r_x, r_y ↦ R r_x, R r_y (a rigid motion of the element).
inline Vec36 rigidlyMoved(const Vec36& e, const Eigen::Matrix3d& rot, const Eigen::Vector3d& t) {
  Vec36 out;
  for (int k = 0; k < 12; ++k) {
    out.segment<3>(3 * k) = rot * e.segment<3>(3 * k);
    if (k % 3 == 0) out.segment<3>(3 * k) += t;
  }
  return out;
}

inline Eigen::Matrix3d randomRotation(std::mt19937& gen) {
  std::normal_distribution<double> nd;
  Eigen::Quaterniond q(nd(gen), nd(gen), nd(gen), nd(gen));
  q.normalize();
  return q.toRotationMatrix();
}

/// A random large deformation: positions perturbed by `scale_m`, slopes by `slope_scale`.
inline Vec36 randomlyDeformed(const Vec36& e0, std::mt19937& gen, double scale_m,
                              double slope_scale) {
  std::uniform_real_distribution<double> ud(-1.0, 1.0);
  Vec36 e = e0;
  for (int k = 0; k < 12; ++k)
    for (int c = 0; c < 3; ++c) e[3 * k + c] += ud(gen) * (k % 3 == 0 ? scale_m : slope_scale);
  return e;
}

inline ShellSection aluminium(double thickness_m, double damping_s = 0.0) {
  ShellSection s;
  s.thickness_m = thickness_m;
  s.youngs_modulus_pa = 70e9;
  s.poisson_ratio = 0.33;
  s.density_kg_m3 = 2700.0;
  s.damping_s = damping_s;
  return s;
}

}  // namespace mastrom::fullorder::testing
