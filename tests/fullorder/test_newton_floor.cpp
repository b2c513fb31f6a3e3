// Newton's round-off floor (GeneralizedAlpha, GeneralizedAlphaOptions::force_tolerance): a residual
// below ε‖q‖∞ · residualPerPosition() is accepted because rounding the positions alone moves the
// residual that far. Checked on a turning mast: the floor must bound the residual change that
// roundings of the positions cause, without exceeding it by orders of magnitude; and in the cruise
// of a deployment Newton then needs one iteration per step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

#include "coarse_mast.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/eliminated_system.hpp"
#include "fullorder/generalized_alpha.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/mast_model.hpp"

namespace mastrom::fullorder {
namespace {

/// Momentum residual M q̈ + Φ_qᵀλ − Q(q, q̇).
Eigen::VectorXd residual(DaeSystem& sys, const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                         const Eigen::VectorXd& qddot, const Eigen::VectorXd& lambda, double t) {
  Eigen::VectorXd force;
  SparseMatrix g;
  sys.forces(q, qdot, t, force);
  sys.constraintJacobian(q, t, g);
  return sys.massMatrix() * qddot + g.transpose() * lambda - force;
}

TEST(NewtonRoundOffFloor, BoundsTheResidualChangeOfRoundedPositions) {
  testing::EliminatedTurningMast mast;
  EliminatedSystem& reduced = mast.reduced;
  const GeneralizedAlphaOptions o = integratorFromConfig(mast.config);
  GeneralizedAlpha integrator(reduced, o);
  integrator.initialize(mast.q0, mast.v0, 0.0);
  for (int k = 0; k < 400; ++k) integrator.step();  // into the cruise, 0.04 s
  const double per_position = integrator.residualPerPosition();
  ASSERT_GT(per_position, 0.0);

  // A Newton iterate ties q̈ and q̇ to q: Δq̈ = β′Δq, Δq̇ = γ′Δq (docs/theory.md §5 coefficients).
  const double r = o.rho_inf, h = o.time_step_s;
  const double am = (2 * r - 1) / (r + 1), af = r / (r + 1), gamma = 0.5 + af - am;
  const double beta = 0.25 * (gamma + 0.5) * (gamma + 0.5);
  const double beta_prime = (1 - am) / (h * h * beta * (1 - af)), gamma_prime = gamma / (h * beta);
  const DaeState& s = integrator.state();
  const Eigen::VectorXd r0 = residual(reduced, s.q, s.qdot, s.qddot, s.lambda, s.time_s);
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  std::mt19937 gen(3);
  std::uniform_int_distribution<int> sign(0, 1);
  double worst = 0.0;
  for (int draw = 0; draw < 20; ++draw) {
    // Every position rounded by one ulp, with random signs.
    Eigen::VectorXd dq(s.q.size());
    for (Eigen::Index j = 0; j < dq.size(); ++j)
      dq[j] = (sign(gen) ? 1.0 : -1.0) * kEps * std::abs(s.q[j]);
    const Eigen::VectorXd r1 = residual(reduced, s.q + dq, s.qdot + gamma_prime * dq,
                                        s.qddot + beta_prime * dq, s.lambda, s.time_s);
    worst = std::max(worst, (r1 - r0).cwiseAbs().maxCoeff());
  }
  const double floor = kEps * s.q.cwiseAbs().maxCoeff() * per_position;
  std::printf(
      "[ measured ] residual change of one-ulp positions %.2e N, floor %.2e N (ratio %.1f)\n",
      worst, floor, floor / worst);
  EXPECT_LE(worst, floor);
  // A bound, not a loose guess: within two orders of magnitude of what rounding really does.
  EXPECT_GE(worst, 1e-2 * floor);
}

TEST(NewtonRoundOffFloor, OneIterationPerStepInTheCruise) {
  Config c = testing::turningScheme1();
  MastModel model = buildMast(mastParametersFromConfig(c));
  DeploymentOptions o;
  o.integrator = integratorFromConfig(c);
  o.end_time_s = 0.1;
  DeploymentStatistics stats;
  const DeploymentSeries series = simulateDeployment(model, o, &stats);
  // After the ramp (0.02 s) the drive turns at a constant rate: forces are small and a second
  // iteration could only chase round-off.
  long after_ramp = 0, iterations = 0;
  for (std::size_t i = 0; i < series.size(); ++i)
    if (series.time_s[i] > 0.03) {
      ++after_ramp;
      iterations += series.newton_iterations[i];
    }
  ASSERT_GT(after_ramp, 500);
  std::printf("[ measured ] cruise: %.3f Newton iterations per step\n",
              double(iterations) / double(after_ramp));
  EXPECT_LT(double(iterations) / double(after_ramp), 1.1);
}

}  // namespace
}  // namespace mastrom::fullorder
