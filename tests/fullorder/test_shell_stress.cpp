// Stress recovery of the shell element (fullorder/shell_stress.hpp, docs/theory.md §6): zero under
// rigid motion, the same definition as the element's energy, the linearised stress against central
// differences, and the closed forms of a uniform membrane state and a pure bending state.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "common/error.hpp"
#include "fullorder/shell_stress.hpp"
#include "shell_test_fixtures.hpp"

namespace mastrom::fullorder {
namespace {

using testing::aluminium;
using testing::cylinderReference;
using testing::flatReference;
using testing::randomlyDeformed;
using testing::randomRotation;
using testing::rigidlyMoved;

TEST(ShellStress, VonMisesOfElementaryStates) {
  EXPECT_DOUBLE_EQ(vonMisesPlaneStress(Eigen::Vector3d(100.0, 0.0, 0.0)), 100.0);
  EXPECT_DOUBLE_EQ(vonMisesPlaneStress(Eigen::Vector3d(100.0, 100.0, 0.0)), 100.0);
  EXPECT_NEAR(vonMisesPlaneStress(Eigen::Vector3d(0.0, 0.0, 100.0)), 100.0 * std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(vonMisesPlaneStress(Eigen::Vector3d(100.0, -100.0, 0.0)), 100.0 * std::sqrt(3.0),
              1e-12);
}

TEST(ShellStress, RigidMotionGivesZeroStress) {
  std::mt19937 gen(7);
  const double radius = 0.041, a = 0.025, b = 0.032;
  const Vec36 e0 = cylinderReference(radius, a, b);
  const ShellElement element(a, b, e0, aluminium(0.002, 1e-5));
  const ShellStressRecovery recovery(element, ShellStressRecovery::gridPoints());
  const Eigen::Matrix3d rot = randomRotation(gen);
  const Vec36 e = rigidlyMoved(e0, rot, Eigen::Vector3d(0.3, -0.2, 0.1));
  // Velocity of a rigid rotation ω × (every 3-block) plus a translation: zero strain rate.
  const Eigen::Vector3d omega(1.5, -2.0, 0.7);
  Vec36 edot;
  for (int k = 0; k < 12; ++k) edot.segment<3>(3 * k) = omega.cross(e.segment<3>(3 * k));
  for (int k = 0; k < 12; k += 3) edot.segment<3>(3 * k) += Eigen::Vector3d(1.0, 2.0, 3.0);
  // Scale: a unit strain gives E = 7e10 Pa; round-off of the strains is ~1e-16 · |g|².
  for (int p = 0; p < recovery.pointCount(); ++p) {
    const ShellPointStress s = recovery.stress(p, e, &edot);
    for (int z = 0; z < kShellSurfaces; ++z) EXPECT_LT(s.von_mises_pa[z], 1e-3) << p << " " << z;
  }
}

/// ½∫σ:ε over the thickness, summed with the element's own quadrature, equals strainEnergy(e): the
/// stresses come from the strains and the material of the energy (one definition).
TEST(ShellStress, StressesReproduceTheElementEnergy) {
  std::mt19937 gen(11);
  const double radius = 0.041, a = 0.025, b = 0.032, h = 0.0015;
  const Vec36 e0 = cylinderReference(radius, a, b);
  const ShellElement element(a, b, e0, aluminium(h));
  const auto& table = *element.shapeTable();
  std::vector<std::array<double, 2>> points(table.points.begin(), table.points.end());
  const ShellStressRecovery recovery(element, points);
  const Vec36 e = randomlyDeformed(e0, gen, 2e-4, 5e-3);
  // Plane-stress compliance [ε11, ε22, 2ε12] = C [σ11, σ22, σ12].
  const double nu = 0.33;
  Eigen::Matrix3d compliance;
  compliance << 1.0, -nu, 0.0, -nu, 1.0, 0.0, 0.0, 0.0, 2.0 * (1.0 + nu);
  compliance /= 70e9;
  double energy = 0.0;
  for (int p = 0; p < recovery.pointCount(); ++p) {
    const ShellPointStress s = recovery.stress(p, e);
    const Eigen::Vector3d& n = s.membrane_force_n_m;
    const Eigen::Vector3d& m = s.bending_moment_n;
    const double density = 0.5 * n.dot(compliance * n) / h + 6.0 * m.dot(compliance * m) / (h * h * h);
    energy += element.quadPoint(static_cast<size_t>(p)).mass_weight * density;
  }
  const double expected = element.strainEnergy(e);
  EXPECT_GT(expected, 0.0);
  EXPECT_NEAR(energy, expected, 1e-11 * expected);
}

/// ∂σ/∂e·d by central differences with step ∛ε·scale: truncation O(δ²σ''') and round-off
/// O(ε σ/δ) are both ~1e-11 relative, so 1e-7 leaves a wide margin and still catches any missing
/// term (those are O(1)).
TEST(ShellStress, LinearizedStressMatchesCentralDifferences) {
  std::mt19937 gen(3);
  const double radius = 0.041, a = 0.025, b = 0.032;
  const Vec36 e0 = cylinderReference(radius, a, b);
  const ShellElement element(a, b, e0, aluminium(0.002));
  const ShellStressRecovery recovery(element, ShellStressRecovery::gridPoints());
  const Vec36 e = randomlyDeformed(e0, gen, 5e-4, 2e-2);
  Vec36 d = randomlyDeformed(Vec36::Zero(), gen, 1e-3, 3e-2);
  const double step = std::cbrt(std::numeric_limits<double>::epsilon());
  for (int p = 0; p < recovery.pointCount(); ++p) {
    const ShellPointStress lin = recovery.linearizedStress(p, e, d);
    const Vec36 ep = e + step * d, em = e - step * d;
    const ShellPointStress sp = recovery.stress(p, ep), sm = recovery.stress(p, em);
    double scale = 0.0;
    for (int z = 0; z < kShellSurfaces; ++z) scale = std::max(scale, lin.stress_pa[z].norm());
    for (int z = 0; z < kShellSurfaces; ++z) {
      const Eigen::Vector3d fd = (sp.stress_pa[z] - sm.stress_pa[z]) / (2.0 * step);
      EXPECT_LT((fd - lin.stress_pa[z]).norm(), 1e-7 * scale) << "point " << p << " ζ " << z;
    }
  }
}

/// A flat plate in uniform biaxial stretch and in pure cylindrical bending: the exact plane-stress
/// values (the element represents both states exactly).
TEST(ShellStress, UniformStretchAndPureBendingOfAFlatElement) {
  const double a = 0.02, b = 0.01, h = 0.001, young = 70e9, nu = 0.33;
  const Vec36 e0 = flatReference(a, b);
  const ShellElement element(a, b, e0, aluminium(h));
  const ShellStressRecovery recovery(element, ShellStressRecovery::gridPoints());
  // Small stretch λ along x: E_xx = ½(λ² − 1), ε local = E (unit reference metric).
  const double stretch = 1.0 + 1e-4;
  Vec36 e = e0;
  for (int c = 0; c < 4; ++c) {
    e[9 * c] *= stretch;
    e[9 * c + 3] *= stretch;
  }
  const double exx = 0.5 * (stretch * stretch - 1.0);
  const double s11 = young / (1 - nu * nu) * exx, s22 = nu * s11;
  for (int p = 0; p < recovery.pointCount(); ++p) {
    const ShellPointStress s = recovery.stress(p, e);
    for (int z = 0; z < kShellSurfaces; ++z) {
      EXPECT_NEAR(s.stress_pa[z][0], s11, 1e-9 * s11);
      EXPECT_NEAR(s.stress_pa[z][1], s22, 1e-9 * s11);
      EXPECT_NEAR(s.stress_pa[z][2], 0.0, 1e-9 * s11);
    }
  }
  // Bending: w = ½ c x² (r_xx·n = c to first order in c): surface stresses ∓E c h/2/(1−ν²) at
  // ζ = ±h/2 along n = +z, zero at the mid-surface to O(c²).
  const double curv = 1e-3;  // 1/m
  Vec36 w = e0;
  for (int c = 0; c < 4; ++c) {
    const double x = w[9 * c];
    w[9 * c + 2] = 0.5 * curv * x * x;
    w[9 * c + 5] = curv * x;
  }
  const double sb = young / (1 - nu * nu) * curv * h / 2;
  for (int p = 0; p < recovery.pointCount(); ++p) {
    const ShellPointStress s = recovery.stress(p, w);
    EXPECT_NEAR(s.stress_pa[0][0], sb, 2e-3 * sb) << p;  // ζ = −h/2
    EXPECT_NEAR(s.stress_pa[2][0], -sb, 2e-3 * sb) << p;
    EXPECT_NEAR(s.stress_pa[0][1], nu * sb, 2e-3 * sb) << p;
    EXPECT_NEAR(s.bending_moment_n[0], -young * h * h * h / 12 / (1 - nu * nu) * curv,
                2e-3 * sb * h * h / 6) << p;
  }
}

TEST(ShellStress, RejectsRecoveryPointsOutsideTheElement) {
  const ShellElement element(0.02, 0.01, flatReference(0.02, 0.01), aluminium(0.001));
  const std::vector<std::array<double, 2>> outside{{1.5, 0.0}};
  EXPECT_THROW(ShellStressRecovery(element, outside), InputError);
}

}  // namespace
}  // namespace mastrom::fullorder
