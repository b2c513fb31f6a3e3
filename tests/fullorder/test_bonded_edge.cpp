// Bonded edge (fullorder/bonded_edge.hpp, docs/theory.md §2.3): the equations vanish on the
// reference and under any common rigid motion, allow exactly the edge motions docs/theory.md §2.3
// allows, and their Jacobian, Hessian term and velocity term agree with central differences.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "assembly_test_helpers.hpp"
#include "fullorder/bonded_edge.hpp"
#include "fullorder/shell_mesh.hpp"

namespace mastrom::fullorder {
namespace {

using testing::centralJacobian;
using testing::evaluateBlock;
using testing::hessianOf;
using testing::jacobianOf;
using testing::velocityTermOf;

constexpr double kPi = 3.14159265358979323846;

/// A module with a random pose and the interface meshed on its +x face, as in the mast.
struct Flange {
  RigidModule body{0.1, 0.5, RigidModule::boxInertia(0.5, 0.1, 0.1, 0.1)};
  Eigen::Matrix3d rotation;
  Eigen::Vector3d centroid{0.2, -0.1, 0.3};
  Vec12 q_body;
  ShellMesh mesh;
  double radius = 0.041, length = 0.05;

  explicit Flange(std::mt19937& gen) : rotation(testing::randomRotationMatrix(gen)) {
    q_body = body.coordinates(centroid, rotation);
    Placement p;
    p.origin = centroid + rotation * Eigen::Vector3d(0.05, 0.0, 0.0);
    p.rotation = rotation;
    mesh = makeCylinderMesh(radius, length, 2, 8, p);
  }
  /// Block for ring-0 node j (body DOFs at 0, node DOFs at 12 in the local vector).
  BondedEdgeNode block(int j) const {
    const int node = mesh.nodes_x0[static_cast<size_t>(j)];
    return BondedEdgeNode(body, 0, q_body, 12, mesh.nodes[static_cast<size_t>(node)],
                          mesh.normals[static_cast<size_t>(node)]);
  }
  Eigen::VectorXd localReference(int j) const {
    Eigen::VectorXd q(21);
    q << q_body, mesh.nodes[static_cast<size_t>(mesh.nodes_x0[static_cast<size_t>(j)])];
    return q;
  }
};

/// Apply the rigid motion x ↦ Q x + p to every position block and Q to every direction block.
Eigen::VectorXd moved(const Eigen::VectorXd& q, const Eigen::Matrix3d& rot,
                      const Eigen::Vector3d& p, const std::vector<bool>& is_position) {
  Eigen::VectorXd out = q;
  for (size_t k = 0; k < is_position.size(); ++k) {
    out.segment<3>(static_cast<Eigen::Index>(3 * k)) =
        rot * q.segment<3>(static_cast<Eigen::Index>(3 * k));
    if (is_position[k]) out.segment<3>(static_cast<Eigen::Index>(3 * k)) += p;
  }
  return out;
}
// Local layout [r_i, r_j, u, v, r, r_x, r_y].
const std::vector<bool> kModuleNodeBlocks = {true, true, false, false, true, false, false};

TEST(BondedEdge, LocalDataOfARingNode) {
  std::mt19937 gen(11);
  const Flange f(gen);
  for (int j = 0; j < 8; ++j) {
    const BondedEdgeNode b = f.block(j);
    const double phi = 2.0 * kPi * j / 8;
    // Round-off: the data pass through one rotation and its transpose.
    EXPECT_LT((b.localPosition() -
               Eigen::Vector3d(0.05, f.radius * std::cos(phi), f.radius * std::sin(phi)))
                  .norm(),
              1e-15);
    EXPECT_LT((b.localTangent() - Eigen::Vector3d(0.0, -std::sin(phi), std::cos(phi))).norm(),
              1e-15);
    EXPECT_LT((b.localNormal() - Eigen::Vector3d(0.0, std::cos(phi), std::sin(phi))).norm(), 1e-15);
    EXPECT_EQ(b.size(), 7);
    EXPECT_EQ(b.localDofCount(), 21);
    EXPECT_TRUE(b.hasHessianTerm());
    EXPECT_FALSE(b.isTimeDependent());
  }
}

TEST(BondedEdge, VanishesOnReferenceAndUnderRigidMotion) {
  std::mt19937 gen(12);
  const Flange f(gen);
  for (int j = 0; j < 8; ++j) {
    const BondedEdgeNode b = f.block(j);
    const Eigen::VectorXd q0 = f.localReference(j);
    // Φ entries are lengths ~0.1 m or O(1) products: round-off ~1e-16.
    EXPECT_LT(evaluateBlock(b, q0, 0.0).cwiseAbs().maxCoeff(), 1e-15) << "node " << j;
    for (int trial = 0; trial < 3; ++trial) {
      const Eigen::Matrix3d rot = testing::randomRotationMatrix(gen);
      const Eigen::Vector3d p = testing::randomVector(gen, 3, 1.0);
      const Eigen::VectorXd q = moved(q0, rot, p, kModuleNodeBlocks);
      EXPECT_LT(evaluateBlock(b, q, 0.7).cwiseAbs().maxCoeff(), 1e-14) << "node " << j;
    }
  }
}

TEST(BondedEdge, AllowsAxialStretchAndShearButNotRotationAboutTheEdge) {
  std::mt19937 gen(13);
  const Flange f(gen);
  const int j = 3;
  const BondedEdgeNode b = f.block(j);
  const Eigen::VectorXd q0 = f.localReference(j);
  const Eigen::Vector3d axis = f.rotation.col(0);
  const Eigen::Vector3d tangent = q0.segment<3>(18);
  const Eigen::Vector3d normal = f.rotation * b.localNormal();

  Eigen::VectorXd q = q0;
  q.segment<3>(15) = 1.01 * axis + 0.02 * tangent;  // stretch and in-plane shear of r_x
  EXPECT_LT(evaluateBlock(b, q, 0.0).cwiseAbs().maxCoeff(), 1e-15);

  q = q0;
  q.segment<3>(15) = std::cos(0.01) * axis + std::sin(0.01) * normal;  // wall turns about the edge
  const Eigen::VectorXd phi = evaluateBlock(b, q, 0.0);
  EXPECT_LT(phi.head<6>().cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_NEAR(phi[6], std::sin(0.01), 1e-15);

  q = q0;
  q.segment<3>(18) *= 1.001;  // hoop stretch of the edge is forbidden
  EXPECT_GT(evaluateBlock(b, q, 0.0).segment<3>(3).norm(), 0.9e-3);
}

TEST(BondedEdge, DerivativesAgreeWithCentralDifferences) {
  std::mt19937 gen(14);
  const Flange f(gen);
  for (int j : {0, 2, 5}) {
    const BondedEdgeNode b = f.block(j);
    const Eigen::VectorXd q = f.localReference(j) + testing::randomVector(gen, 21, 0.05);
    const Eigen::VectorXd lambda = testing::randomVector(gen, 7, 3.0);
    const Eigen::VectorXd qdot = testing::randomVector(gen, 21, 0.5);
    const double t = 0.3;

    // Jacobian: Φ is at most bilinear, so central differences are exact up to round-off
    // ~ε|Φ|/h ≈ 1e-16·0.1/6e-6 ≈ 2e-12 on O(1) entries.
    const Eigen::MatrixXd jac = jacobianOf(b, q, t);
    const Eigen::MatrixXd jac_fd =
        centralJacobian([&](const Eigen::VectorXd& x) { return evaluateBlock(b, x, t); }, q);
    EXPECT_LT((jac - jac_fd).cwiseAbs().maxCoeff(), 1e-9) << "node " << j;
    EXPECT_TRUE(testing::insideStructure(jac, b.jacobianStructure()));

    // Hessian term (Φ_qᵀλ)_q against differences of Φ_qᵀλ: again exact up to round-off.
    const Eigen::MatrixXd hess = hessianOf(b, q, lambda, t);
    const Eigen::MatrixXd hess_fd = centralJacobian(
        [&](const Eigen::VectorXd& x) -> Eigen::VectorXd {
          return jacobianOf(b, x, t).transpose() * lambda;
        },
        q);
    EXPECT_LT((hess - hess_fd).cwiseAbs().maxCoeff(), 1e-8) << "node " << j;
    EXPECT_EQ((hess - hess.transpose()).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_TRUE(testing::insideStructure(hess, b.hessianStructure()));

    // γ_v = d²/ds² Φ(q + s q̇) (time-independent block): second difference, step ε^¼ on a
    // quadratic function — exact up to round-off 4ε|Φ|/h² ≈ 1e-9.
    const double h = testing::kQrtEps;
    const Eigen::VectorXd second =
        (evaluateBlock(b, q + h * qdot, t) - 2.0 * evaluateBlock(b, q, t) +
         evaluateBlock(b, q - h * qdot, t)) /
        (h * h);
    EXPECT_LT((velocityTermOf(b, q, qdot, t) - second).cwiseAbs().maxCoeff(), 1e-8) << "node " << j;
  }
}

TEST(BondedEdge, GroundedNodeOfAStrip) {
  std::mt19937 gen(15);
  const ShellMesh strip = makeFlatStripMesh(0.1, 0.01, 4, 1);
  GroundFrame ground;  // the global frame
  const int node = strip.nodes_x0[1];
  const BondedEdgeNode b(ground, 0, strip.nodes[static_cast<size_t>(node)],
                         strip.normals[static_cast<size_t>(node)]);
  EXPECT_TRUE(b.isGrounded());
  EXPECT_EQ(b.localDofCount(), 9);
  EXPECT_FALSE(b.hasHessianTerm());
  Eigen::VectorXd q = strip.nodes[static_cast<size_t>(node)];
  EXPECT_LT(evaluateBlock(b, q, 0.0).cwiseAbs().maxCoeff(), 1e-16);
  // Clamped: position and r_y fixed, r_x may stretch and shear in the plane but not leave it.
  q.segment<3>(3) = Eigen::Vector3d(1.02, 0.03, 0.0);
  EXPECT_LT(evaluateBlock(b, q, 0.0).cwiseAbs().maxCoeff(), 1e-16);
  q.segment<3>(3) = Eigen::Vector3d(1.0, 0.0, 0.01);
  EXPECT_NEAR(evaluateBlock(b, q, 0.0)[6], 0.01, 1e-16);
  q.head<3>() += Eigen::Vector3d(0.0, 0.0, 1e-3);
  EXPECT_NEAR(evaluateBlock(b, q, 0.0)[2], 1e-3, 1e-16);

  // A ground frame placed elsewhere: the strip moved rigidly with it satisfies the equations.
  GroundFrame moved_ground;
  moved_ground.rotation = testing::randomRotationMatrix(gen);
  moved_ground.origin = Eigen::Vector3d(0.3, 0.2, -0.1);
  const Vec9 e0 = strip.nodes[static_cast<size_t>(node)];
  Vec9 e_moved;
  e_moved << moved_ground.origin + moved_ground.rotation * e0.head<3>(),
      moved_ground.rotation * e0.segment<3>(3), moved_ground.rotation * e0.tail<3>();
  const BondedEdgeNode bm(moved_ground, 0, e_moved,
                          moved_ground.rotation * strip.normals[static_cast<size_t>(node)]);
  // Round-off only: the equations rotate O(1) coordinates into the frame and back (two 3×3
  // products, ≈ 3 rounding errors each of ≤ ½ ulp(1) = 1.1e-16 per component, plus the origin):
  // ≤ ~10 ulps. 1e-15 (4.5 ulps) was exceeded at 1.11e-15 by the -O1 sanitizer build.
  EXPECT_LT(evaluateBlock(bm, e_moved, 0.0).cwiseAbs().maxCoeff(), 2.5e-15);

  const Eigen::VectorXd qr = e_moved + testing::randomVector(gen, 9, 0.05);
  const Eigen::MatrixXd jac = jacobianOf(bm, qr, 0.0);
  const Eigen::MatrixXd jac_fd =
      centralJacobian([&](const Eigen::VectorXd& x) { return evaluateBlock(bm, x, 0.0); }, qr);
  EXPECT_LT((jac - jac_fd).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_TRUE(testing::insideStructure(jac, bm.jacobianStructure()));
  EXPECT_EQ(velocityTermOf(bm, qr, testing::randomVector(gen, 9, 1.0), 0.0).norm(), 0.0);
}

}  // namespace
}  // namespace mastrom::fullorder
