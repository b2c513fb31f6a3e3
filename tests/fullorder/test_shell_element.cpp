// ANCF thin-shell element (docs/theory.md §2.2): rigid-motion invariance, energy/force/tangent
// consistency by central differences, symmetry, damping, mass, and membrane/bending patch tests
// against closed forms.
#include <cmath>
#include <random>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "fullorder/gauss_quadrature.hpp"
#include "fullorder/shell_element.hpp"
#include "shell_test_fixtures.hpp"

namespace mastrom::fullorder {
namespace {
using namespace testing;

constexpr double kRadius = 0.041, kA = 0.025;
const double kB = 2.0 * M_PI * kRadius / 8.0;  // 8 elements around the default ring

struct Case {
  const char* name;
  Vec36 e0;
  double a, b;
};

std::vector<Case> referenceCases() {
  return {{"flat", flatReference(0.03, 0.02), 0.03, 0.02},
          {"cylinder", cylinderReference(kRadius, kA, kB), kA, kB}};
}

/// The two parts of a quantity of the section, Q(h) = h·Q_m + h³·Q_b (docs/theory.md (4.8): the
/// section factors are E h and E h³/12), from its values q1, q2 at two thicknesses h1 ≠ h2 — as the
/// ROM's affine method obtains K_m and K_b from two linearisations.
template <class T>
struct ThicknessParts {
  T membrane, bending;  ///< Q_m and Q_b: the parts at thickness h are h·Q_m and h³·Q_b
};
template <class T>
ThicknessParts<T> thicknessParts(const T& q1, double h1, const T& q2, double h2) {
  const double h1_cubed = h1 * h1 * h1, h2_cubed = h2 * h2 * h2;
  const double det = h1 * h2_cubed - h2 * h1_cubed;  // of [h1 h1³; h2 h2³]
  ThicknessParts<T> parts;
  parts.membrane = (h2_cubed * q1 - h1_cubed * q2) / det;
  parts.bending = (h1 * q2 - h2 * q1) / det;
  return parts;
}

// Central differences with step δ: truncation ~ δ²·|f'''| and round-off ~ ε|f|/δ. With coordinates
// of order 0.03 m, δ = 1e-7 m balances both at ~1e-9 relative — well inside the 1e-6 requirement.
constexpr double kStep = 1e-7;
constexpr double kRelTol = 1e-6;

TEST(ShellElement, ReferenceStateIsStressFreeAndRigidMotionsStayStressFree) {
  std::mt19937 gen(7);
  for (const Case& c : referenceCases()) {
    const ShellElement el(c.a, c.b, c.e0, aluminium(0.002));
    Vec36 f;
    el.elasticForce(c.e0, f);
    EXPECT_EQ(el.strainEnergy(c.e0), 0.0) << c.name;
    EXPECT_EQ(f.norm(), 0.0) << c.name;
    // Force scale: a unit-order strain would produce forces ~ E h a = 70e9·0.002·0.03 ≈ 4e6 N.
    const double force_scale = 70e9 * 0.002 * c.a;
    for (int trial = 0; trial < 5; ++trial) {
      const Vec36 e = rigidlyMoved(c.e0, randomRotation(gen), Eigen::Vector3d::Random());
      el.elasticForce(e, f);
      EXPECT_LT(f.norm(), 1e-13 * force_scale) << c.name;
      EXPECT_LT(el.strainEnergy(e), 1e-13 * force_scale * c.a) << c.name;
    }
  }
}

TEST(ShellElement, ForceIsGradientOfEnergy) {
  std::mt19937 gen(11);
  for (const Case& c : referenceCases()) {
    const ShellElement el(c.a, c.b, c.e0, aluminium(0.002));
    for (int trial = 0; trial < 3; ++trial) {
      const Vec36 e = randomlyDeformed(c.e0, gen, 0.05 * c.a, 0.05);
      Vec36 f, fd;
      el.elasticForce(e, f);
      for (int i = 0; i < 36; ++i) {
        Vec36 ep = e, em = e;
        ep[i] += kStep;
        em[i] -= kStep;
        fd[i] = (el.strainEnergy(ep) - el.strainEnergy(em)) / (2 * kStep);
      }
      EXPECT_LT((f - fd).norm(), kRelTol * f.norm()) << c.name << " trial " << trial;
    }
  }
}

TEST(ShellElement, TangentIsGradientOfForceAndSymmetric) {
  std::mt19937 gen(13);
  for (const Case& c : referenceCases()) {
    const ShellElement el(c.a, c.b, c.e0, aluminium(0.002));
    for (int trial = 0; trial < 3; ++trial) {
      const Vec36 e = randomlyDeformed(c.e0, gen, 0.05 * c.a, 0.05);
      Vec36 f, f2, fp, fm;
      Mat36 k, fd;
      el.elasticForceAndTangent(e, f, k);
      el.elasticForce(e, f2);
      EXPECT_EQ((f - f2).cwiseAbs().maxCoeff(), 0.0);  // the same point force (shellPointForce)
      for (int i = 0; i < 36; ++i) {
        Vec36 ep = e, em = e;
        ep[i] += kStep;
        em[i] -= kStep;
        el.elasticForce(ep, fp);
        el.elasticForce(em, fm);
        fd.col(i) = (fp - fm) / (2 * kStep);
      }
      EXPECT_LT((k - fd).norm(), kRelTol * k.norm()) << c.name << " trial " << trial;
      EXPECT_LT((k - k.transpose()).norm(), 1e-12 * k.norm()) << c.name;
    }
  }
}

TEST(ShellElement, StiffnessIsAffineInThicknessAndItsCube) {
  // docs/theory.md (4.8): at the reference state K(h) = h·K_m + h³·K_b, which the ROM's affine
  // method relies on. K_m and K_b from h = 1 and 2 mm must give K at 1.5 and 3 mm, and both parts
  // must be present: the bending part is a share of order (h/side)² of the membrane part.
  for (const Case& c : referenceCases()) {
    const auto stiffness = [&c](double h) {
      Mat36 k;
      Vec36 f;
      ShellElement(c.a, c.b, c.e0, aluminium(h)).elasticForceAndTangent(c.e0, f, k);
      return k;
    };
    const ThicknessParts<Mat36> parts =
        thicknessParts(stiffness(0.001), 0.001, stiffness(0.002), 0.002);
    for (double h : {0.0015, 0.003}) {
      const Mat36 k = stiffness(h);
      const Mat36 membrane = h * parts.membrane, bending = h * h * h * parts.bending;
      // Each entry of K is a sum of point terms with round-off ~1e-16 of ‖K‖, and so are the parts
      // (K_b is a difference of two such matrices, but only its h³ multiple enters: ~1e-16 of ‖K‖).
      EXPECT_LT((membrane + bending - k).norm(), 1e-14 * k.norm()) << c.name << ", h = " << h;
      EXPECT_GT(bending.norm(), 1e-4 * membrane.norm()) << c.name << ", h = " << h;
    }
  }
}

TEST(ShellElement, DampingVanishesUnderRigidVelocityAndTangentsMatchDifferences) {
  std::mt19937 gen(17);
  const double mu = 1e-3;  // large enough that the damping force dominates round-off
  for (const Case& c : referenceCases()) {
    const ShellElement el(c.a, c.b, c.e0, aluminium(0.002, mu));
    // Rigid velocity field at a deformed state: ṙ = v + ω × r for positions, ω × r_x, ω × r_y.
    const Vec36 e = randomlyDeformed(c.e0, gen, 0.05 * c.a, 0.05);
    const Eigen::Vector3d omega = Eigen::Vector3d::Random(), vel = Eigen::Vector3d::Random();
    Vec36 edot_rigid;
    for (int k = 0; k < 12; ++k) {
      edot_rigid.segment<3>(3 * k) = omega.cross(Eigen::Vector3d(e.segment<3>(3 * k)));
      if (k % 3 == 0) edot_rigid.segment<3>(3 * k) += vel;
    }
    Vec36 f;
    el.dampingForce(e, edot_rigid, f);
    Vec36 edot = Vec36::Random();
    Vec36 f_def;
    el.dampingForce(e, edot, f_def);
    EXPECT_LT(f.norm(), 1e-12 * f_def.norm()) << c.name;

    Mat36 cmat, kd;
    Vec36 fd_check, fp, fm;
    el.dampingForceAndTangents(e, edot, fd_check, cmat, kd);
    EXPECT_EQ((fd_check - f_def).cwiseAbs().maxCoeff(), 0.0);  // the same point force
    // C = ∂F_d/∂ė = μ × (material part of K); F_d is linear in ė, so C·ė = F_d exactly.
    EXPECT_LT((cmat * edot - f_def).norm(), 1e-12 * f_def.norm()) << c.name;
    EXPECT_LT((cmat - cmat.transpose()).norm(), 1e-12 * cmat.norm()) << c.name;
    Mat36 fd_k;
    for (int i = 0; i < 36; ++i) {
      Vec36 ep = e, em = e;
      ep[i] += kStep;
      em[i] -= kStep;
      el.dampingForce(ep, edot, fp);
      el.dampingForce(em, edot, fm);
      fd_k.col(i) = (fp - fm) / (2 * kStep);
    }
    EXPECT_LT((kd - fd_k).norm(), kRelTol * kd.norm()) << c.name;
  }
}

// The iteration-matrix block in one pass equals stiffness (K + K_d) + damping C assembled from the
// two separate tangents (each checked against differences above) to round-off: the products are
// regrouped, not approximated. With damping, without, and with either coefficient zero.
TEST(ShellElement, IterationTangentEqualsTheSeparateTangentsCombined) {
  std::mt19937 gen(23);
  for (const double mu : {0.0, 1e-3}) {
    for (const Case& c : referenceCases()) {
      const ShellElement el(c.a, c.b, c.e0, aluminium(0.002, mu));
      const Vec36 e = randomlyDeformed(c.e0, gen, 0.05 * c.a, 0.05);
      const Vec36 edot = Vec36::Random();
      Vec36 f;
      Mat36 k, cmat, kd;
      el.elasticForceAndTangent(e, f, k);
      el.dampingForceAndTangents(e, edot, f, cmat, kd);
      for (const auto& [ck, cd] : {std::pair{1.0, 0.0}, std::pair{0.0, 1.0},
                                   std::pair{2.7e-9, 3.1e-5}}) {
        const Mat36 expected = ck * (k + kd) + cd * cmat;
        Mat36 block;
        el.iterationTangent(e, edot, ck, cd, block);
        EXPECT_LE((block - expected).norm(), 1e-13 * expected.norm())
            << c.name << ", mu = " << mu << ", stiffness " << ck << ", damping " << cd;
      }
    }
  }
}

// An element with its own shape table and one with a shared table (the mesh's) compute the same
// numbers bit for bit, for both Gauss orders of the project (4 = mast default, 5 = docs/theory.md
// §2.2), with and without damping.
TEST(ShellElement, SharedAndOwnShapeTablesGiveIdenticalForcesAndMass) {
  std::mt19937 gen(23);
  for (const Case& c : referenceCases()) {
    for (int order : {4, 5}) {
      for (double mu : {0.0, 1e-4}) {
        const ShellSection sec = aluminium(0.002, mu);
        const ShellElement own(c.a, c.b, c.e0, sec, order);
        const ShellElement shared(makeShellShapeTable(c.a, c.b, order), c.e0, sec);
        EXPECT_EQ(own.sideA(), c.a);
        EXPECT_EQ(own.sideB(), c.b);
        const Vec36 e = randomlyDeformed(c.e0, gen, 0.05 * c.a, 0.05);
        const Vec36 edot = Vec36::Random();
        Vec36 f_own, f_shared, fd_own, fd_shared;
        own.elasticForce(e, f_own);
        shared.elasticForce(e, f_shared);
        own.dampingForce(e, edot, fd_own);
        shared.dampingForce(e, edot, fd_shared);
        EXPECT_EQ((f_shared - f_own).cwiseAbs().maxCoeff(), 0.0) << c.name;
        EXPECT_EQ((fd_shared - fd_own).cwiseAbs().maxCoeff(), 0.0) << c.name;
        Mat36 m_own, m_shared;
        own.mass(m_own);
        shared.mass(m_shared);
        EXPECT_EQ((m_own - m_shared).cwiseAbs().maxCoeff(), 0.0) << c.name;
      }
    }
  }
}

TEST(ShellElement, MassMatrixCarriesTheShellMassAndIsPositiveDefinite) {
  for (const Case& c : referenceCases()) {
    const ShellSection sec = aluminium(0.002);
    const ShellElement el(c.a, c.b, c.e0, sec);
    Mat36 m;
    el.mass(m);
    // Kinetic energy of a rigid translation t: ½ tᵀ(Σ blocks)t = ½ ρ h A |t|².
    Vec36 tr = Vec36::Zero();
    for (int i = 0; i < 4; ++i) tr.segment<3>(9 * i) = Eigen::Vector3d(0.3, -1.1, 0.7);
    const double mass = sec.density_kg_m3 * sec.thickness_m * el.referenceArea();
    EXPECT_NEAR(tr.dot(m * tr), mass * tr.segment<3>(0).squaredNorm(), 1e-14 * mass);
    Eigen::SelfAdjointEigenSolver<Mat36> eig(m);
    EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0) << c.name;
  }
  // Flat: area exactly a·b.
  const ShellElement flat(0.03, 0.02, flatReference(0.03, 0.02), aluminium(0.002));
  EXPECT_NEAR(flat.referenceArea(), 0.03 * 0.02, 1e-17);
  // Cylinder panel: the interpolated surface is the straight extrusion along x of the cubic Hermite
  // curve through the two edge nodes (the ACM functions summed over ξ reduce to Hermite functions in
  // η), so its area is a × (length of that curve). The reference length is integrated here
  // independently with a 20-point Gauss rule; the element's own 5×5 rule must agree to ~1e-9.
  const ShellElement cyl(kA, kB, cylinderReference(kRadius, kA, kB), aluminium(0.002));
  const Vec36 e0 = cylinderReference(kRadius, kA, kB);
  const Eigen::Vector3d p0 = e0.segment<3>(0), t0 = e0.segment<3>(6);
  const Eigen::Vector3d p1 = e0.segment<3>(27), t1 = e0.segment<3>(33);
  const GaussRule rule = gaussLegendre(20);
  double length = 0.0;
  for (std::size_t i = 0; i < rule.points.size(); ++i) {
    const double t = 0.5 * (rule.points[i] + 1.0);
    // d/dt of the Hermite basis h00, h10, h01, h11.
    const Eigen::Vector3d dp = (6 * t * t - 6 * t) * p0 + (3 * t * t - 4 * t + 1) * kB * t0 +
                               (-6 * t * t + 6 * t) * p1 + (3 * t * t - 2 * t) * kB * t1;
    length += 0.5 * rule.weights[i] * dp.norm();
  }
  EXPECT_NEAR(cyl.referenceArea(), kA * length, 1e-9 * kA * length);
  // and the interpolated arc is within the Hermite error of the true arc (~6e-4 at β = π/4).
  EXPECT_NEAR(length, kB, 1e-3 * kB);
}

TEST(ShellElement, MembranePatchUniformStretchGivesExactEnergy) {
  // Displacement u = ε x (uniaxial) is represented exactly: E₁₁ = ε + ε²/2, E₂₂ = E₁₂ = 0, and
  // U = ½ h E/(1 − ν²) E₁₁² a b (plane stress, lateral strain held at zero).
  const double a = 0.03, b = 0.02, eps = 1e-3;
  const ShellSection sec = aluminium(0.001);
  const Vec36 e0 = flatReference(a, b);
  const ShellElement el(a, b, e0, sec);
  Vec36 e = e0;
  for (int i = 0; i < 4; ++i) {
    e[9 * i] *= 1 + eps;  // x of each corner
    e[9 * i + 3] = 1 + eps;  // r_x = (1 + ε, 0, 0)
  }
  const double e11 = eps + 0.5 * eps * eps;
  const double nu = sec.poisson_ratio;
  const double exact = 0.5 * sec.thickness_m * sec.youngs_modulus_pa / (1 - nu * nu) * e11 * e11 * a * b;
  EXPECT_NEAR(el.strainEnergy(e), exact, 1e-12 * exact);
  // In-plane shear: r = (x + γ y, y): E₁₂ = γ/2, E₂₂ = γ²/2.
  const double g = 1e-3;
  Vec36 es = e0;
  for (int i = 0; i < 4; ++i) {
    es[9 * i] += g * es[9 * i + 1];
    es[9 * i + 6] = g;  // r_y = (γ, 1, 0)
  }
  Eigen::Vector3d strain(0.0, 0.5 * g * g, g);
  Eigen::Matrix3d d;
  d << 1, nu, 0, nu, 1, 0, 0, 0, 0.5 * (1 - nu);
  d *= sec.youngs_modulus_pa / (1 - nu * nu);
  const double exact_shear = 0.5 * sec.thickness_m * strain.dot(d * strain) * a * b;
  EXPECT_NEAR(el.strainEnergy(es), exact_shear, 1e-12 * exact_shear);
}

TEST(ShellElement, BendingPatchQuadraticDeflectionGivesPlateEnergy) {
  // w = ½κ_x x² + κ_xy x y + ½κ_y y² lies in the element's space. For small κ the Kirchhoff energy is
  // U = h³/24 kᵀ D k a b with k = [κ_x, κ_y, 2κ_xy]; geometric nonlinearity and the membrane
  // energy of the deflection are O((κa)²) ≈ 1e-6 relative here.
  const double a = 0.03, b = 0.02;
  const double kx = 1e-3, ky = -0.6e-3, kxy = 0.4e-3;
  const ShellSection sec = aluminium(0.001);
  const Vec36 e0 = flatReference(a, b);
  const ShellElement el(a, b, e0, sec);
  Vec36 e = e0;
  for (int i = 0; i < 4; ++i) {
    const double x = e0[9 * i], y = e0[9 * i + 1];
    e[9 * i + 2] = 0.5 * kx * x * x + kxy * x * y + 0.5 * ky * y * y;
    e[9 * i + 5] = kx * x + kxy * y;  // ∂w/∂x
    e[9 * i + 8] = kxy * x + ky * y;  // ∂w/∂y
  }
  const double nu = sec.poisson_ratio, h = sec.thickness_m;
  Eigen::Matrix3d d;
  d << 1, nu, 0, nu, 1, 0, 0, 0, 0.5 * (1 - nu);
  d *= sec.youngs_modulus_pa / (1 - nu * nu);
  const Eigen::Vector3d k(kx, ky, 2 * kxy);
  const double exact = h * h * h / 24.0 * k.dot(d * k) * a * b;
  EXPECT_NEAR(el.strainEnergy(e), exact, 1e-5 * exact);
  // The bending part (the h³ term of U(h) = h·U_m + h³·U_b, from a second thickness) must carry it:
  // the membrane part is the tiny O(w_x²) stretch.
  ShellSection thicker = sec;
  thicker.thickness_m = 2.0 * h;
  const ThicknessParts<double> parts = thicknessParts(
      el.strainEnergy(e), h, ShellElement(a, b, e0, thicker).strainEnergy(e), 2.0 * h);
  EXPECT_NEAR(h * h * h * parts.bending, exact, 1e-5 * exact);
  EXPECT_LT(std::abs(h * parts.membrane), 1e-5 * exact);
}

}  // namespace
}  // namespace mastrom::fullorder
