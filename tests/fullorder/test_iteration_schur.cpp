// The Schur-complement route for the generalized-α iteration matrix
// (GeneralizedAlphaOptions::schur_iteration_solver, fullorder/schur_complement.hpp):
//  * SchurComplement solves [A Gᵀ; G 0] like a dense LU and refuses redundant constraints;
//  * the integrator takes it when the (1,1) block is symmetric and positive definite, and the LU
//    when the block is markedly unsymmetric (a circulatory force) — with the same answer as the LU;
//  * on a turning mast it gives the LU's states to within the Newton tolerance.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "coarse_mast.hpp"
#include "fullorder/eliminated_system.hpp"
#include "fullorder/generalized_alpha.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/mast_model.hpp"
#include "fullorder/schur_complement.hpp"
#include "fullorder/supernodal_cholesky.hpp"
#include "spd_test_matrices.hpp"

namespace mastrom::fullorder {
namespace {

using Sparse = Eigen::SparseMatrix<double>;
constexpr double kEps = std::numeric_limits<double>::epsilon();

TEST(SchurComplement, SolvesTheSaddleMatrixLikeADenseLu) {
  std::mt19937 gen(5);
  const int nodes = 20, n = 3 * nodes, m = 7;
  const Sparse a = testing::tripleChainSpd(nodes, 2, 12.0, gen);
  Eigen::MatrixXd g_dense = Eigen::MatrixXd::Zero(m, n);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int r = 0; r < m; ++r)  // each constraint touches a few coordinates, like joint rows
    for (int k = 0; k < 5; ++k) g_dense(r, (7 * r + 3 * k) % n) = u(gen);
  const Sparse g = g_dense.sparseView();
  SupernodalCholesky chol;
  ASSERT_TRUE(chol.compute(a));
  SchurComplement schur;
  ASSERT_TRUE(schur.setup([&chol](double* x) { chol.solveInPlace(x); }, n, g));

  const Eigen::MatrixXd h = testing::denseSaddle(Eigen::MatrixXd(a), g_dense);
  Eigen::VectorXd b(n + m);
  for (Eigen::Index i = 0; i < b.size(); ++i) b[i] = u(gen);
  Eigen::VectorXd x;
  schur.solve(b, x);
  const Eigen::VectorXd reference = h.partialPivLu().solve(b);
  EXPECT_LT(testing::backwardError(h, x, b), 64 * kEps);
  EXPECT_LT((x - reference).cwiseAbs().maxCoeff(), 1e-12 * reference.cwiseAbs().maxCoeff());
}

TEST(SchurComplement, RefusesRedundantConstraints) {
  std::mt19937 gen(6);
  const int n = 30;
  const Sparse a = testing::tripleChainSpd(n / 3, 2, 12.0, gen);
  Eigen::MatrixXd g_dense = Eigen::MatrixXd::Zero(3, n);
  g_dense(0, 1) = 1.0;
  g_dense(1, 4) = 2.0;
  g_dense.row(2) = 0.5 * g_dense.row(0) - g_dense.row(1);  // dependent
  SupernodalCholesky chol;
  ASSERT_TRUE(chol.compute(a));
  SchurComplement schur;
  EXPECT_FALSE(schur.setup([&chol](double* x) { chol.solveInPlace(x); }, n, g_dense.sparseView()));
  EXPECT_FALSE(schur.ready());
}

/// A point mass on the circle x² + y² = R² with a spring k along z and a circulatory ("swirl")
/// force κ(−y, x, 0), whose stiffness ∂(−Q)/∂q = κ[ẑ×] is antisymmetric: κ sets how unsymmetric the
/// iteration matrix's (1,1) block is.
class SwirlRing : public DaeSystem {
public:
  explicit SwirlRing(double kappa) : kappa_(kappa) {
    mass_.resize(3, 3);
    mass_.setIdentity();
    mass_ *= kMass;
  }
  int dofCount() const override { return 3; }
  int constraintCount() const override { return 1; }
  const SparseMatrix& massMatrix() const override { return mass_; }
  void forces(const Eigen::VectorXd& q, const Eigen::VectorXd&, double,
              Eigen::VectorXd& f) override {
    f = Eigen::Vector3d(-kappa_ * q[1], kappa_ * q[0], -kSpring * q[2]);
  }
  void constraints(const Eigen::VectorXd& q, double, Eigen::VectorXd& phi) override {
    phi = Eigen::VectorXd::Constant(1, 0.5 * (q[0] * q[0] + q[1] * q[1] - kRadius * kRadius));
  }
  void constraintJacobian(const Eigen::VectorXd& q, double, SparseMatrix& jac) override {
    jac.resize(1, 3);
    std::vector<Eigen::Triplet<double>> t{{0, 0, q[0]}, {0, 1, q[1]}, {0, 2, 0.0}};
    jac.setFromTriplets(t.begin(), t.end());
  }
  void velocityConstraintRhs(const Eigen::VectorXd&, double, Eigen::VectorXd& rhs) override {
    rhs = Eigen::VectorXd::Zero(1);
  }
  void accelerationConstraintRhs(const Eigen::VectorXd&, const Eigen::VectorXd& qd, double,
                                 Eigen::VectorXd& rhs) override {
    rhs = Eigen::VectorXd::Constant(1, -(qd[0] * qd[0] + qd[1] * qd[1]));
  }
  void iterationMatrix(const Eigen::VectorXd& q, const Eigen::VectorXd&,
                       const Eigen::VectorXd& lambda, double, const IterationCoefficients& c,
                       SparseMatrix& h) override {
    // K_t = ∂(Φ_qᵀλ − Q)/∂q: λ on the x, y diagonal, the spring on z, and −κ[ẑ×] from −Q.
    std::vector<Eigen::Triplet<double>> t{{0, 0, c.mass * kMass + c.stiffness * lambda[0]},
                                          {1, 1, c.mass * kMass + c.stiffness * lambda[0]},
                                          {2, 2, c.mass * kMass + c.stiffness * kSpring},
                                          {0, 1, c.stiffness * kappa_},
                                          {1, 0, -c.stiffness * kappa_},
                                          {0, 3, c.constraint_scale * q[0]},
                                          {1, 3, c.constraint_scale * q[1]},
                                          {3, 0, c.constraint_scale * q[0]},
                                          {3, 1, c.constraint_scale * q[1]},
                                          {2, 3, 0.0},
                                          {3, 2, 0.0},
                                          {3, 3, 0.0}};
    h.resize(4, 4);
    h.setFromTriplets(t.begin(), t.end());
  }

  static constexpr double kMass = 0.3, kRadius = 0.2, kSpring = 50.0;

private:
  double kappa_;
  SparseMatrix mass_;
};

struct SwirlRun {
  DaeState state;
  bool schur = false;  ///< the factorisation in use at the end is the Schur one
};

SwirlRun runSwirl(double kappa, bool schur_allowed, int steps) {
  SwirlRing system(kappa);
  GeneralizedAlphaOptions o;
  o.time_step_s = 1e-3;
  o.schur_iteration_solver = schur_allowed;
  GeneralizedAlpha ga(system, o);
  ga.initialize(Eigen::Vector3d(SwirlRing::kRadius, 0.0, 0.01), Eigen::Vector3d(0.0, 0.5, 0.0),
                0.0);
  for (int k = 0; k < steps; ++k) ga.step();
  return {ga.state(), ga.iterationSolveBySchur()};
}

TEST(IterationSchur, TakenForANearlySymmetricBlockWithTheLuAnswer) {
  // κ = 0.1 N/m at h = 1 ms: ‖A − Aᵀ‖ = 2√2 κ/β′ is 1.4e-7 of ‖A‖ — well within 1e-4.
  const SwirlRun schur = runSwirl(0.1, true, 200), lu = runSwirl(0.1, false, 200);
  EXPECT_TRUE(schur.schur);
  EXPECT_FALSE(lu.schur);
  // Both converge to the same Newton solution; what differs is below the force tolerance (1e-6 of
  // the force scale) propagated over 200 steps.
  const double scale = lu.state.q.cwiseAbs().maxCoeff();
  EXPECT_LT((schur.state.q - lu.state.q).cwiseAbs().maxCoeff(), 1e-9 * scale);
  EXPECT_LT(std::abs(schur.state.lambda[0] - lu.state.lambda[0]),
            1e-6 * std::abs(lu.state.lambda[0]));
}

TEST(IterationSchur, NotTakenForAnUnsymmetricBlock) {
  // κ = 3000 N/m: ‖A − Aᵀ‖ is 4e-3 of ‖A‖ — above the 1e-4 limit, so the LU, whose
  // answer is then exactly that of the run without the option. (20 steps: the swirl force speeds
  // the mass up without bound.)
  const SwirlRun allowed = runSwirl(3000.0, true, 20), lu = runSwirl(3000.0, false, 20);
  EXPECT_FALSE(allowed.schur);
  EXPECT_EQ(allowed.state.q, lu.state.q);
  EXPECT_EQ(allowed.state.lambda, lu.state.lambda);
}

struct MastRun {
  DaeState state;
  long iterations = 0;
  int lu_fallbacks = 0;  ///< steps that ended on an LU factor chosen over the Schur route
  bool schur_at_end = false;
};

MastRun runMast(int steps, bool schur, double max_contraction, double time_step_s = 1e-4) {
  testing::EliminatedTurningMast mast;
  GeneralizedAlphaOptions o = integratorFromConfig(mast.config);
  o.schur_iteration_solver = schur;
  o.max_contraction = max_contraction;
  o.time_step_s = time_step_s;
  GeneralizedAlpha integrator(mast.reduced, o);
  integrator.initialize(mast.q0, mast.v0, 0.0);
  MastRun run;
  for (int k = 0; k < steps; ++k) {
    run.iterations += integrator.step().iterations;
    run.lu_fallbacks += integrator.snapshot().iteration.general_lu ? 1 : 0;
  }
  run.state = integrator.state();
  run.schur_at_end = integrator.iterationSolveBySchur();
  return run;
}

TEST(IterationSchur, TurningMastMatchesTheLu) {
  const MastRun lu = runMast(400, false, 0.3), schur = runMast(400, true, 0.3);  // ramp + 0.02 s
  EXPECT_FALSE(lu.schur_at_end);
  EXPECT_TRUE(schur.schur_at_end);
  EXPECT_EQ(schur.lu_fallbacks, 0);
  const double dq = (schur.state.q - lu.state.q).cwiseAbs().maxCoeff();
  const double lambda_peak = lu.state.lambda_index1.cwiseAbs().maxCoeff();
  const double dlambda = (schur.state.lambda_index1 - lu.state.lambda_index1).cwiseAbs().maxCoeff();
  std::printf(
      "[ measured ] Schur vs LU after 400 steps: |dq| %.2e m, |dlambda| / |lambda| %.2e; "
      "Newton iterations %ld vs %ld\n",
      dq, dlambda / lambda_peak, schur.iterations, lu.iterations);
  // Same Newton solutions up to the force tolerance: positions to far below a nanometre, the
  // multipliers (joint force, torque) to the 1e-6 relative force criterion.
  EXPECT_LT(dq, 1e-10);
  EXPECT_LT(dlambda, 1e-5 * lambda_peak);
  // Leaving out the block's antisymmetric part costs (almost) no extra iterations.
  EXPECT_LE(schur.iterations, lu.iterations + 4);
}

TEST(IterationSchur, FallsBackToTheLuWhenAFreshFactorContractsSlowly) {
  // With max_contraction = 1e-12 every second Newton increment above round-off counts as slow: a
  // stale factor is renewed (by the Schur route again), and a fresh Schur factor that is still
  // "slow" gives way to the LU of the whole matrix — which the checkpoint records (general_lu).
  // A 1 ms step, so that ramp steps need several iterations (at 0.1 ms the second increment is
  // already at round-off, which never counts as slow).
  const MastRun strict = runMast(50, true, 1e-12, 1e-3), lu = runMast(50, false, 1e-12, 1e-3);
  std::printf("[ measured ] steps ending on a fallback LU factor: %d of 50\n", strict.lu_fallbacks);
  EXPECT_GE(strict.lu_fallbacks, 1);
  EXPECT_LT((strict.state.q - lu.state.q).cwiseAbs().maxCoeff(), 1e-10);
}

}  // namespace
}  // namespace mastrom::fullorder
