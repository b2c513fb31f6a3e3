// Static benchmarks of a clamped flat strip (fullorder/static_solver.hpp with the shell element,
// the grounded bonded edge and the edge loads of fullorder/applied_loads.hpp).
//
// Strip: L = 0.1 m, b = 0.01 m, h = 1 mm, E = 70 GPa, ν = 0 (no anticlastic coupling, so the strip
// is an Euler–Bernoulli beam with EI = E b h³/12), one element across the width, clamped at x = 0
// by the bonded-edge equations to a fixed ground frame (docs/theory.md §2.3), loaded on the edge x
// = L.
// References:
//  * small tip force P: tip deflection P L³/(3EI), tip slope P L²/(2EI) (linear beam theory);
//  * large deflection under a conservative transverse tip force: Mattiasson (1981), "Numerical
//  results
//    from large deflection beam and frame problems analysed by means of elliptic integrals",
//    IJNME 17:145–153, table for the cantilever with a tip load: PL²/EI = 1 → w/L = 0.30172,
//    u/L = 0.05643; PL²/EI = 10 → w/L = 0.81061, u/L = 0.55500;
//  * pure end moment M = πEI/L: the elastica is a half circle of radius L/π, tip at (−L, 2L/π) from
//    its undeformed position, tip slope π.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <random>

#include "assembly_test_helpers.hpp"
#include "common/error.hpp"
#include "fullorder/applied_loads.hpp"
#include "fullorder/bonded_edge.hpp"
#include "fullorder/multibody_system.hpp"
#include "fullorder/shell_mesh.hpp"
#include "fullorder/static_solver.hpp"

namespace mastrom::fullorder {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kLength = 0.1, kWidth = 0.01, kThickness = 0.001, kModulus = 70e9;
constexpr double kEI = kModulus * kWidth * kThickness * kThickness * kThickness / 12.0;

enum class TipLoad { TransverseForce, EndMoment };

struct TipResult {
  double deflection_over_l = 0.0;  ///< w/L (+z)
  double shortening_over_l = 0.0;  ///< (L − x_tip)/L
  double slope_rad = 0.0;          ///< atan2(r_x·z, r_x·x) at the tip, in (−π/2, 3π/2]
  StaticResult solve;
};

/// Build the clamped strip with n_x elements, apply the load (force P [N] or couple M [N·m]),
/// solve.
TipResult solveStrip(int n_x, TipLoad kind, double magnitude, int load_steps,
                     EdgeMomentSampling sampling = EdgeMomentSampling::ElementField) {
  MultibodySystem sys;
  ShellSection section;
  section.thickness_m = kThickness;
  section.youngs_modulus_pa = kModulus;
  section.poisson_ratio = 0.0;
  section.density_kg_m3 = 2700.0;
  const ShellMesh mesh = makeFlatStripMesh(kLength, kWidth, n_x, 1);
  const int first = sys.addShellMesh(mesh, section);
  for (int node : mesh.nodes_x0)
    sys.addConstraint(std::make_unique<BondedEdgeNode>(
        GroundFrame{}, sys.nodeDofOffset(first + node), mesh.nodes[static_cast<size_t>(node)],
        mesh.normals[static_cast<size_t>(node)]));
  for (int e : mesh.elements_x1) {
    if (kind == TipLoad::TransverseForce)
      sys.addLoad(std::make_unique<EdgeLineLoad>(sys.elementDofs(e), mesh.side_a_m, mesh.side_b_m,
                                                 ElementEdge::XMax,
                                                 Eigen::Vector3d(0.0, 0.0, magnitude / kWidth)));
    else
      sys.addLoad(std::make_unique<EdgeMomentLoad>(
          sys.elementDofs(e), mesh.side_a_m, mesh.side_b_m, ElementEdge::XMax, magnitude / kWidth,
          Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ(), sampling));
  }
  sys.finalize();
  StaticSolverOptions opt;
  opt.load_steps = load_steps;
  TipResult out;
  out.solve = solveStatic(sys, sys.referenceCoordinates(), opt);
  const Eigen::VectorXd& q = out.solve.q;
  for (int node : mesh.nodes_x1) {
    const int o = sys.nodeDofOffset(first + node);
    const Eigen::Vector3d r = q.segment<3>(o), rx = q.segment<3>(o + 3);
    const Eigen::Vector3d r0 = mesh.nodes[static_cast<size_t>(node)].head<3>();
    out.deflection_over_l += (r.z() - r0.z()) / kLength / mesh.nodes_x1.size();
    out.shortening_over_l += (r0.x() - r.x()) / kLength / mesh.nodes_x1.size();
    double slope = std::atan2(rx.z(), rx.x());
    if (slope < -0.5 * kPi) slope += 2.0 * kPi;  // continuous through π (the half circle)
    out.slope_rad += slope / mesh.nodes_x1.size();
  }
  return out;
}

TEST(EdgeLoads, LineLoadResultantAndMomentLoadDerivatives) {
  std::mt19937 gen(41);
  const double a = 0.02, b = 0.01;
  const Vec36 e0 = makeFlatStripMesh(a, b, 1, 1).elementReference(0);
  std::array<int, 36> dofs{};
  for (int i = 0; i < 36; ++i) dofs[static_cast<size_t>(i)] = i;

  // Line load: resultant = p × edge length; potential −p·∫r ds changes by −p·δ·ℓ under a
  // translation.
  const Eigen::Vector3d p(1.0, -2.0, 3.0);
  for (ElementEdge edge :
       {ElementEdge::XMin, ElementEdge::XMax, ElementEdge::YMin, ElementEdge::YMax}) {
    const EdgeLineLoad load(dofs, a, b, edge, p);
    Eigen::VectorXd f(36);
    load.force(e0, 0.0, f);
    Eigen::Vector3d resultant = Eigen::Vector3d::Zero();
    for (int k = 0; k < 12; k += 3) resultant += f.segment<3>(3 * k);  // position functions only
    const double ell = (edge == ElementEdge::XMin || edge == ElementEdge::XMax) ? b : a;
    EXPECT_LT((resultant - p * ell).norm(), 1e-15);
    Eigen::VectorXd shifted = e0;
    for (int k = 0; k < 12; k += 3) shifted.segment<3>(3 * k) += Eigen::Vector3d(0.1, 0.2, 0.3);
    EXPECT_NEAR(load.potential(shifted, 0.0) - load.potential(e0, 0.0),
                -p.dot(Eigen::Vector3d(0.1, 0.2, 0.3)) * ell, 1e-15);
  }

  // Moment load at a strongly bent state: Q = −∂V/∂e and K_load = ∂Q/∂e, symmetric. Smooth
  // functions: central differences with step ∛ε reach ~1e-10 relative.
  for (EdgeMomentSampling sampling :
       {EdgeMomentSampling::ElementField, EdgeMomentSampling::EdgeNodes}) {
    const EdgeMomentLoad load(dofs, a, b, ElementEdge::XMax, 7.0, Eigen::Vector3d::UnitX(),
                              Eigen::Vector3d::UnitZ(), sampling);
    Eigen::VectorXd e = e0 + testing::randomVector(gen, 36, 0.05);
    e.segment<3>(9 + 3) = Eigen::Vector3d(-0.2, 0.05, 0.9);  // tip slopes turned by ≈ 100°
    e.segment<3>(18 + 3) = Eigen::Vector3d(-0.3, -0.02, 0.8);
    Eigen::VectorXd f(36);
    load.force(e, 0.0, f);
    const Eigen::MatrixXd f_fd = testing::centralJacobian(
        [&](const Eigen::VectorXd& x) {
          return Eigen::VectorXd::Constant(1, -load.potential(x, 0.0));
        },
        e);
    EXPECT_LT((f - f_fd.row(0).transpose()).cwiseAbs().maxCoeff(), 1e-8 * f.cwiseAbs().maxCoeff());
    Eigen::MatrixXd k(36, 36);
    load.stiffness(e, 0.0, k);
    const Eigen::MatrixXd k_fd = testing::centralJacobian(
        [&](const Eigen::VectorXd& x) {
          Eigen::VectorXd g(36);
          load.force(x, 0.0, g);
          return g;
        },
        e);
    EXPECT_LT((k - k_fd).cwiseAbs().maxCoeff(), 1e-7 * k.cwiseAbs().maxCoeff());
    EXPECT_LT((k - k.transpose()).cwiseAbs().maxCoeff(), 1e-14 * k.cwiseAbs().maxCoeff());
    // The load is smooth through φ = π (r_x along −x): finite force, no branch cut.
    e.segment<3>(9 + 3) = Eigen::Vector3d(-1.0, 0.0, 0.0);
    e.segment<3>(18 + 3) = Eigen::Vector3d(-1.0, 0.0, 1e-12);
    load.force(e, 0.0, f);
    EXPECT_TRUE(f.allFinite());
  }
}

TEST(EdgeLoads, LoadStiffnessEntersTheIterationMatrix) {
  // A 3-element strip with an end moment (scaled by s = 0.7; K_load ≈ m b/a² ≈ 5e4, far above the
  // 1e-7·max|K| ≈ 10 tolerance): the K block of the iteration matrix
  // must equal ∂(Φ_qᵀλ − f)/∂q, f = s·Q_load − F_elastic, including −s·K_load.
  MultibodySystem sys;
  ShellSection section;
  section.thickness_m = kThickness;
  section.poisson_ratio = 0.0;
  const ShellMesh mesh = makeFlatStripMesh(kLength, kWidth, 3, 1);
  const int first = sys.addShellMesh(mesh, section);
  for (int node : mesh.nodes_x0)
    sys.addConstraint(std::make_unique<BondedEdgeNode>(
        GroundFrame{}, sys.nodeDofOffset(first + node), mesh.nodes[static_cast<size_t>(node)],
        mesh.normals[static_cast<size_t>(node)]));
  sys.addLoad(std::make_unique<EdgeMomentLoad>(sys.elementDofs(mesh.elements_x1[0]), mesh.side_a_m,
                                               mesh.side_b_m, ElementEdge::XMax, 5000.0,
                                               Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ()));
  sys.finalize();
  std::mt19937 gen(42);
  const int n = sys.dofCount(), m = sys.constraintCount();
  const Eigen::VectorXd q = sys.referenceCoordinates() + testing::randomVector(gen, n, 1e-3);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  const Eigen::VectorXd lambda = testing::randomVector(gen, m, 1.0);
  const double s = 0.7;
  IterationCoefficients c;
  c.mass = 0.0;
  c.damping = 0.0;
  c.stiffness = 1.0;
  SparseMatrix h;
  sys.assembleIterationMatrix(q, zero, lambda, 0.0, c, h, s);
  const Eigen::MatrixXd k_fd = testing::centralJacobian(
      [&](const Eigen::VectorXd& x) {
        Eigen::VectorXd f, r = Eigen::VectorXd::Zero(n);
        sys.forces(x, zero, 0.0, f, s);
        sys.addConstraintForces(x, lambda, 0.0, r);
        return Eigen::VectorXd(r - f);
      },
      q, 0.1);
  const Eigen::MatrixXd k = Eigen::MatrixXd(h).topLeftCorner(n, n);
  EXPECT_LT((k - k_fd).cwiseAbs().maxCoeff(), 1e-7 * k_fd.cwiseAbs().maxCoeff());
}

TEST(StaticStrip, SmallTipForceMatchesLinearBeamTheory) {
  // PL²/EI = 1e-4: geometric nonlinearity is O((w/L)²) ≈ 1e-9, far below the 0.5 % tolerance.
  const double p = 1e-4 * kEI / (kLength * kLength);
  for (int n_x : {2, 8}) {
    const TipResult r = solveStrip(n_x, TipLoad::TransverseForce, p, 1);
    const double w_ref = p * kLength * kLength * kLength / (3.0 * kEI);
    const double slope_ref = p * kLength * kLength / (2.0 * kEI);
    const double w_err = r.deflection_over_l * kLength / w_ref - 1.0;
    const double s_err = r.slope_rad / slope_ref - 1.0;
    std::cout << "[ strip linear ] N_x = " << n_x << ": deflection error " << w_err
              << ", slope error " << s_err << ", Newton iterations " << r.solve.iterations << "\n";
    EXPECT_LT(std::abs(w_err), 5e-3) << "N_x = " << n_x;
    EXPECT_LT(std::abs(s_err), 5e-3) << "N_x = " << n_x;
  }
}

struct Mattiasson {
  double load;        ///< PL²/EI
  double deflection;  ///< w/L
  double shortening;  ///< u/L
};

TEST(StaticStrip, LargeDeflectionUnderTipForceMatchesMattiasson) {
  for (const Mattiasson ref :
       {Mattiasson{1.0, 0.30172, 0.05643}, Mattiasson{10.0, 0.81061, 0.55500}}) {
    const double p = ref.load * kEI / (kLength * kLength);
    double previous = 0.0;
    for (int n_x : {4, 8, 16}) {
      const auto start = std::chrono::steady_clock::now();
      const TipResult r = solveStrip(n_x, TipLoad::TransverseForce, p, ref.load > 5 ? 5 : 1);
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const double w_err = r.deflection_over_l / ref.deflection - 1.0;
      const double u_err = r.shortening_over_l / ref.shortening - 1.0;
      const double err = std::max(std::abs(w_err), std::abs(u_err));
      std::cout << "[ strip Mattiasson ] PL²/EI = " << ref.load << ", N_x = " << n_x
                << ": w/L = " << r.deflection_over_l << " (error " << w_err
                << "), u/L = " << r.shortening_over_l << " (error " << u_err << "), "
                << r.solve.iterations << " Newton iterations in " << r.solve.load_steps
                << " load steps (" << r.solve.rejected_steps << " cut), " << seconds << " s\n";
      if (n_x >= 8) {
        EXPECT_LT(err, previous) << "error must fall with refinement, PL²/EI = " << ref.load;
      }
      if (n_x == 16) {
        EXPECT_LT(std::abs(w_err), 1e-2) << "PL²/EI = " << ref.load;
        EXPECT_LT(std::abs(u_err), 1e-2) << "PL²/EI = " << ref.load;
      }
      previous = err;
    }
  }
}

TEST(StaticStrip, PureEndMomentCurlsIntoAHalfCircle) {
  // Two distributions of the same couple (applied_loads.hpp): the element's slope field along the
  // edge (consistent; it also loads the tip nodes' r_y through the incomplete bicubic and cups the
  // tip edge — with one element across the width this local distortion does not shrink with N_x,
  // only with N_y) and the nodal slopes (trapezoidal). Both must land within 1 % of L. The discrete
  // model converges to the *extensible* Kirchhoff strip, whose tip differs from the inextensible
  // elastica by ≈ 5e-4 L here (axial strain −EI φ′²/EA ≈ −1.4e-4 and the matching extra rotation),
  // so the refinement check is made on the coarse end: N_x = 4 → 8.
  const double moment = kPi * kEI / kLength;
  struct Case {
    EdgeMomentSampling sampling;
    const char* name;
  };
  for (const Case c : {Case{EdgeMomentSampling::ElementField, "element field"},
                       Case{EdgeMomentSampling::EdgeNodes, "edge nodes"}}) {
    double previous = 0.0;
    for (int n_x : {4, 8, 16}) {
      const TipResult r = solveStrip(n_x, TipLoad::EndMoment, moment, 8, c.sampling);
      // Displacement of the tip relative to L: (−1, 2/π).
      const double ex = -r.shortening_over_l - (-1.0);
      const double ez = r.deflection_over_l - 2.0 / kPi;
      const double err = std::hypot(ex, ez);
      std::cout << "[ strip moment ] " << c.name << ", N_x = " << n_x << ": tip displacement/L = ("
                << -r.shortening_over_l << ", " << r.deflection_over_l << "), error " << err
                << ", tip slope " << r.slope_rad << " (π = " << kPi << "), " << r.solve.iterations
                << " Newton iterations, " << r.solve.load_steps << " load steps\n";
      if (n_x >= 8) {
        EXPECT_LT(err, 1e-2) << c.name << ", N_x = " << n_x;
        EXPECT_NEAR(r.slope_rad, kPi, 1e-2 * kPi) << c.name << ", N_x = " << n_x;
      }
      if (n_x == 8) {
        EXPECT_LT(err, previous) << c.name;
      }
      previous = err;
    }
  }
}

TEST(StaticStrip, SolverReportsFailureWithContext) {
  // One load step and one Newton iteration cannot reach PL²/EI = 10; with the increment floor at
  // 0.5 the solver must give up with a NumericalError naming the load factor and residuals.
  MultibodySystem sys;
  ShellSection section;
  section.thickness_m = kThickness;
  section.poisson_ratio = 0.0;
  const ShellMesh mesh = makeFlatStripMesh(kLength, kWidth, 4, 1);
  const int first = sys.addShellMesh(mesh, section);
  for (int node : mesh.nodes_x0)
    sys.addConstraint(std::make_unique<BondedEdgeNode>(
        GroundFrame{}, sys.nodeDofOffset(first + node), mesh.nodes[static_cast<size_t>(node)],
        mesh.normals[static_cast<size_t>(node)]));
  sys.addLoad(std::make_unique<EdgeLineLoad>(
      sys.elementDofs(mesh.elements_x1[0]), mesh.side_a_m, mesh.side_b_m, ElementEdge::XMax,
      Eigen::Vector3d(0, 0, 10.0 * kEI / (kLength * kLength) / kWidth)));
  sys.finalize();
  StaticSolverOptions opt;
  opt.max_iterations = 1;
  opt.min_load_increment = 0.5;
  try {
    solveStatic(sys, sys.referenceCoordinates(), opt);
    FAIL() << "expected NumericalError";
  } catch (const NumericalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("load factor"), std::string::npos) << what;
    EXPECT_NE(what.find("force residual"), std::string::npos) << what;
    EXPECT_NE(what.find("constraint residual"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace mastrom::fullorder
