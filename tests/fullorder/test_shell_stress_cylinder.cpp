// Stresses of a clamped cylinder under end loads against the closed forms of thin-walled tubes
// (Timoshenko & Gere, Mechanics of Materials; Saint-Venant's principle for the stresses away from
// the clamp and the loaded end): an axial force F gives σ₁₁ = F/(2πRh), a transverse force P at
// the free end the bending stress M R/(πR³h) with M = P(L − x), a torque T the shear stress
// T/(2πR²h). Static solves of the nonlinear model at loads small enough (≈ 1–3 MPa) that the
// geometric nonlinearity stays below 1e-4 relative. The stresses are read at the ring x = L/2,
// ≥ 6.5 decay lengths √(Rh) from both ends. Each case runs the mesh sequence 2×8 (the mast's
// default), 4×16, 8×32 and prints the errors (docs/user_guide.md §7 lists them).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "fullorder/applied_loads.hpp"
#include "fullorder/bonded_edge.hpp"
#include "fullorder/multibody_system.hpp"
#include "fullorder/shell_mesh.hpp"
#include "fullorder/shell_stress.hpp"
#include "fullorder/static_solver.hpp"

namespace mastrom::fullorder {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadius = 0.041, kLength = 0.3, kThickness = 0.002, kNu = 0.33;

enum class EndLoad { Axial, Transverse, Torque };

/// The stresses at the nodes of ring `ring` (x = ring · L/N_axial), one per node j
/// (φ_j = 2πj/N_circ), of a cylinder of length `length` under the end load of magnitude `load`
/// (N or N·m).
std::vector<ShellPointStress> ringStresses(int n_axial, int n_circ, EndLoad kind, double load,
                                           double length, int ring) {
  MultibodySystem sys;
  ShellSection section;
  section.thickness_m = kThickness;
  section.poisson_ratio = kNu;
  const ShellMesh mesh = makeCylinderMesh(kRadius, length, n_axial, n_circ);
  const int first = sys.addShellMesh(mesh, section);
  for (int node : mesh.nodes_x0)
    sys.addConstraint(std::make_unique<BondedEdgeNode>(
        GroundFrame{}, sys.nodeDofOffset(first + node), mesh.nodes[static_cast<size_t>(node)],
        mesh.normals[static_cast<size_t>(node)]));
  const double dphi = 2 * kPi / n_circ;
  for (int k = 0; k < n_circ; ++k) {
    const int e = mesh.elements_x1[static_cast<size_t>(k)];
    const double p0 = k * dphi, p1 = p0 + dphi;
    // Per element, the mean over its arc of the traction of each case (resultant exact).
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    if (kind == EndLoad::Axial) {
      p.x() = load / (2 * kPi * kRadius);
    } else if (kind == EndLoad::Transverse) {
      // Saint-Venant shear flow of a tube: q = −P sin φ/(πR) along t = (0, −sin φ, cos φ).
      const double s2 = (0.5 * (p1 - p0) - 0.25 * (std::sin(2 * p1) - std::sin(2 * p0))) / dphi;
      const double sc = 0.5 * (std::pow(std::sin(p1), 2) - std::pow(std::sin(p0), 2)) / dphi;
      p = load / (kPi * kRadius) * Eigen::Vector3d(0.0, s2, -sc);
    } else {
      // A uniform traction c·t_mid along the element's arc (t_mid the tangent at its middle)
      // has the moment c R² 2 sin(Δφ/2) about the axis and no resultant over the ring: c gives
      // each element its share T/N_circ exactly (the mean of q·t(φ) would give T·sinc²(Δφ/2),
      // 5 % low on 8 elements).
      const double c = load / (n_circ * kRadius * kRadius * 2 * std::sin(0.5 * dphi));
      const double mid = p0 + 0.5 * dphi;
      p = c * Eigen::Vector3d(0.0, -std::sin(mid), std::cos(mid));
    }
    sys.addLoad(std::make_unique<EdgeLineLoad>(sys.elementDofs(e), mesh.side_a_m, mesh.side_b_m,
                                               ElementEdge::XMax, p));
  }
  sys.finalize();
  const StaticResult solution = solveStatic(sys, sys.referenceCoordinates());
  std::vector<ShellPointStress> out;
  for (int j = 0; j < n_circ; ++j) {
    const int e = ring * n_circ + j;  // the row starting at the ring; corner 1 = node (ring, φ_j)
    const ShellStressRecovery recovery(sys.element(e), {{-1.0, -1.0}});
    Vec36 ee;
    for (int c = 0; c < 36; ++c) ee[c] = solution.q[sys.elementDofs(e)[static_cast<size_t>(c)]];
    out.push_back(recovery.stress(0, ee));
  }
  return out;
}

/// Mid-surface stresses [σ11, σ22, σ12] at the nodes of the ring x = L/2 of the 0.3 m cylinder.
std::vector<Eigen::Vector3d> midRingStresses(int n_axial, int n_circ, EndLoad kind, double load) {
  std::vector<Eigen::Vector3d> out;
  for (const ShellPointStress& s : ringStresses(n_axial, n_circ, kind, load, kLength, n_axial / 2))
    out.push_back(s.stress_pa[1]);
  return out;
}

struct Mesh {
  int axial, circ;
};
constexpr Mesh kMeshes[] = {{2, 8}, {4, 16}, {8, 32}};

/// Largest error of the stress vector against `expected(j)` over the ring, relative to `scale`.
template <class Expected>
double ringError(const std::vector<Eigen::Vector3d>& s, const Expected& expected, double scale) {
  double worst = 0.0;
  for (std::size_t j = 0; j < s.size(); ++j)
    worst = std::max(worst, (s[j] - expected(static_cast<int>(j))).cwiseAbs().maxCoeff() / scale);
  return worst;
}

// The clamp holds the hoop strain at zero (a rigid flange), so Poisson's contraction is restrained
// in a boundary layer of width ~2.4√(Rh) ≈ 22 mm: meshes whose elements are longer than that
// smear it and the hoop stress at x = L/2 is off by up to 1 % of σ₁₁ (2 × 8: 1.1 %); the 8 × 32
// mesh resolves it. The tolerance is asked of that mesh; the coarser ones are printed.
TEST(ClampedCylinderStress, AxialForceGivesMembraneStress) {
  const double force = 1000.0;  // N: σ ≈ 1.9 MPa
  const double expected = force / (2 * kPi * kRadius * kThickness);
  double error = 1.0;
  for (const Mesh& m : kMeshes) {
    const std::vector<Eigen::Vector3d> s = midRingStresses(m.axial, m.circ, EndLoad::Axial, force);
    error = ringError(s, [&](int) { return Eigen::Vector3d(expected, 0.0, 0.0); }, expected);
    std::printf("[ measured ] axial force, mesh %dx%d: max error of the stress %.2e of F/(2 pi R h)\n",
                m.axial, m.circ, error);
  }
  EXPECT_LT(error, 0.01);
}

TEST(ClampedCylinderStress, TransverseForceGivesBeamBendingStress) {
  const double force = 20.0;  // N: M R/I ≈ 1.9 MPa at x = L/2
  const double moment = force * 0.5 * kLength;
  const double expected = moment * kRadius / (kPi * std::pow(kRadius, 3) * kThickness);
  double previous = 1.0;
  for (const Mesh& m : kMeshes) {
    const std::vector<Eigen::Vector3d> s =
        midRingStresses(m.axial, m.circ, EndLoad::Transverse, force);
    // φ = 0 (y = +R) is compressed, φ = π stretched: σ11(φ) = −σ_b cos φ; the shear flow of the
    // transverse force, P sin φ/(πR) = O(R/L) of σ_b h, is compared too.
    const double error = ringError(
        s,
        [&](int j) {
          const double phi = 2 * kPi * j / m.circ;
          return Eigen::Vector3d(-expected * std::cos(phi), 0.0,
                                 s[static_cast<size_t>(j)][2]);
        },
        expected);
    double shear = 0.0;
    for (int j = 0; j < m.circ; ++j) {
      const double phi = 2 * kPi * j / m.circ;
      const double flow = force * std::sin(phi) / (kPi * kRadius * kThickness);
      shear = std::max(shear, std::abs(std::abs(s[static_cast<size_t>(j)][2]) - std::abs(flow)) /
                                  expected);
    }
    std::printf("[ measured ] transverse force, mesh %dx%d: max error of sigma11 %.2e of M R/I, "
                "of the shear %.2e of M R/I\n", m.axial, m.circ, error, shear);
    EXPECT_LT(error, previous) << "no convergence at " << m.axial << "x" << m.circ;
    previous = error;
    if (m.circ == 32) {
      EXPECT_LT(shear, 0.01);
    }
  }
  EXPECT_LT(previous, 0.01);
}

TEST(ClampedCylinderStress, TorqueGivesShearStress) {
  const double torque = 20.0;  // N·m: τ ≈ 0.95 MPa
  const double expected = torque / (2 * kPi * kRadius * kRadius * kThickness);
  double error = 1.0;
  for (const Mesh& m : kMeshes) {
    const std::vector<Eigen::Vector3d> s = midRingStresses(m.axial, m.circ, EndLoad::Torque, torque);
    const double sign = s[0][2] > 0 ? 1.0 : -1.0;
    error = ringError(s, [&](int) { return Eigen::Vector3d(0.0, 0.0, sign * expected); }, expected);
    std::printf("[ measured ] torque, mesh %dx%d: max error of the stress %.2e of T/(2 pi R^2 h)\n",
                m.axial, m.circ, error);
  }
  EXPECT_LT(error, 0.01);
}

/// At the clamp the flange holds the wall's radius: the Poisson contraction of the axial stress
/// σ = F/(2πRh) is restrained, which bends the wall in an axisymmetric boundary layer of length
/// ~1/β, β⁴ = 3(1 − ν²)/(R²h²). An imposed radial displacement δ = νσR/E with zero slope needs the
/// edge moment M₀ = 2β²Dδ (Timoshenko & Woinowsky-Krieger, Theory of Plates and Shells, §114), a
/// surface stress 6M₀/h² = νσ√(3/(1 − ν²)); with the hoop stress ν times the axial one (zero hoop
/// strain), the wall's von Mises stress at the clamp is k σ, k = (1 + ν√(3/(1 − ν²)))·√(1 − ν + ν²)
/// = 1.417 for ν = 0.33 (docs/theory.md eq. 6.8). The layer (1/β = 7 mm) needs elements well below
/// it: the printed sequence shows the edge stress converging with the axial mesh only once a ≪ 1/β.
TEST(ClampedCylinderStress, ClampedEdgeStressConcentration) {
  const double length = 0.1, force = 1000.0;
  const double sigma = force / (2 * kPi * kRadius * kThickness);
  const double k = (1 + kNu * std::sqrt(3 / (1 - kNu * kNu))) * std::sqrt(1 - kNu + kNu * kNu);
  double error = 1.0;
  for (const Mesh& m : {Mesh{2, 8}, Mesh{8, 8}, Mesh{32, 8}, Mesh{128, 8}}) {
    double peak = 0.0;
    for (const ShellPointStress& s : ringStresses(m.axial, m.circ, EndLoad::Axial, force, length, 0))
      peak = std::max({peak, s.von_mises_pa[0], s.von_mises_pa[2]});
    error = (peak - k * sigma) / (k * sigma);
    std::printf("[ measured ] clamped edge, mesh %dx%d (a = %.2g mm): wall von Mises %.4g MPa, "
                "thin-shell %.4g MPa (k = %.3f), error %+.2e\n", m.axial, m.circ,
                length / m.axial * 1e3, peak * 1e-6, k * sigma * 1e-6, k, error);
  }
  EXPECT_LT(std::abs(error), 0.03);
}

}  // namespace
}  // namespace mastrom::fullorder
