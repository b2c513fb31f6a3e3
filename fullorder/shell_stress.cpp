// Stress recovery of the ANCF thin shell (see shell_stress.hpp; docs/theory.md §6).
#include "fullorder/shell_stress.hpp"

#include <cmath>

#include "common/error.hpp"
#include "fullorder/shell_kinematics.hpp"

namespace mastrom::fullorder {

using Map3x12 = Eigen::Map<const Mat3x12>;

double vonMisesPlaneStress(const Eigen::Vector3d& s) {
  return std::sqrt(std::max(
      0.0, s[0] * s[0] - s[0] * s[1] + s[1] * s[1] + 3.0 * s[2] * s[2]));
}

ShellStressRecovery::ShellStressRecovery(const ShellElement& element,
                                         const std::vector<std::array<double, 2>>& points)
    : e0_(element.referenceCoordinates()),
      thickness_m_(element.section().thickness_m),
      youngs_modulus_pa_(element.section().youngs_modulus_pa),
      damping_s_(element.section().damping_s),
      d_hat_(planeStressUnitModulus(element.section().poisson_ratio)) {
  const Map3x12 e0_hat(e0_.data());
  points_.reserve(points.size());
  for (const std::array<double, 2>& xe : points) {
    MASTROM_REQUIRE(std::abs(xe[0]) <= 1.0 && std::abs(xe[1]) <= 1.0, InputError,
                    "shell stress: recovery point (xi, eta) = (", xe[0], ", ", xe[1],
                    ") must lie in [-1, 1]^2");
    Point p;
    p.xi_eta = xe;
    p.shape = evaluateShellShape(xe[0], xe[1], element.sideA(), element.sideB());
    const Eigen::Vector3d gx = e0_hat * p.shape.nx, gy = e0_hat * p.shape.ny;
    const Eigen::Vector3d nrm = gx.cross(gy).normalized();
    p.metric0 << gx.squaredNorm(), gy.squaredNorm(), gx.dot(gy);
    p.curv0 << (e0_hat * p.shape.nxx).dot(nrm), (e0_hat * p.shape.nyy).dot(nrm),
        2.0 * (e0_hat * p.shape.nxy).dot(nrm);
    p.transform = voigtFrameTransform(gx, gy);
    points_.push_back(p);
  }
}

std::vector<std::array<double, 2>> ShellStressRecovery::gridPoints() {
  std::vector<std::array<double, 2>> grid;
  for (int j = -1; j <= 1; ++j)
    for (int i = -1; i <= 1; ++i) grid.push_back({double(i), double(j)});
  return grid;
}

ShellPointStress ShellStressRecovery::fromLocalStrains(const Eigen::Vector3d& eps,
                                                       const Eigen::Vector3d& kappa,
                                                       bool with_von_mises) const {
  // The element's law (shell_material.hpp) with D = D̂ (tensor shear last: D̂ maps engineering
  // strains [ε11, ε22, 2ε12] to [σ11, σ22, σ12]/E). Its moments are conjugate to k = r_,ab·n;
  // M = ∫ σ ζ dζ with ε(ζ) = ε − ζ κ is their negative (eq. 6.4).
  const double h = thickness_m_;
  const double d[6] = {d_hat_(0, 0), d_hat_(0, 1), d_hat_(0, 2),
                       d_hat_(1, 1), d_hat_(1, 2), d_hat_(2, 2)};
  const double strain[6] = {eps[0], eps[1], eps[2], kappa[0], kappa[1], kappa[2]};
  ShellSection section;  // the rate term is in eps and kappa already (stress())
  section.thickness_m = h;
  section.youngs_modulus_pa = youngs_modulus_pa_;
  const ShellSectionScales scales = shellSectionScales(section);
  double res[6];
  shellResultants<ShellStressPart::kElastic>(d, scales, strain, strain, res);
  ShellPointStress out;
  out.membrane_force_n_m << res[0], res[1], res[2];
  out.bending_moment_n << -res[3], -res[4], -res[5];
  for (int s = 0; s < kShellSurfaces; ++s) {
    const double zeta = kShellSurfaceZeta[s] * h;
    out.stress_pa[s] = out.membrane_force_n_m / h + (12.0 * zeta / (h * h * h)) * out.bending_moment_n;
    out.von_mises_pa[s] = with_von_mises ? vonMisesPlaneStress(out.stress_pa[s]) : 0.0;
  }
  return out;
}

ShellPointStress ShellStressRecovery::stress(int p, const Vec36& e, const Vec36* edot) const {
  const Point& pt = points_[static_cast<size_t>(p)];
  const Map3x12 e_hat(e.data());
  const ShellPointKinematics kin = shellKinematics(e_hat, pt.shape, pt.metric0, pt.curv0);
  Eigen::Vector3d strain = kin.membrane, curvature = kin.bending;
  if (edot != nullptr && damping_s_ != 0.0) {
    // Kelvin–Voigt: the stress is D(ε + μ ε̇), as in the internal force.
    const Eigen::Matrix<double, 6, 1> rates = shellStrainRates(kin, pt.shape, Map3x12(edot->data()));
    strain += damping_s_ * rates.head<3>();
    curvature += damping_s_ * rates.tail<3>();
  }
  return fromLocalStrains(pt.transform * strain, pt.transform * curvature, true);
}

ShellPointStress ShellStressRecovery::linearizedStress(int p, const Vec36& e, const Vec36& d) const {
  const Point& pt = points_[static_cast<size_t>(p)];
  const Map3x12 e_hat(e.data());
  const ShellPointKinematics kin = shellKinematics(e_hat, pt.shape, pt.metric0, pt.curv0);
  // (∂E/∂e·d, ∂k/∂e·d) is the strain rate for the velocity d.
  const Eigen::Matrix<double, 6, 1> variation = shellStrainRates(kin, pt.shape, Map3x12(d.data()));
  return fromLocalStrains(pt.transform * variation.head<3>(), pt.transform * variation.tail<3>(),
                          false);
}

Eigen::Vector3d ShellStressRecovery::referencePosition(int p) const {
  return Map3x12(e0_.data()) * points_[static_cast<size_t>(p)].shape.n;
}

}  // namespace mastrom::fullorder
