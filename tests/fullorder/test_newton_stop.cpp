// When Newton stops (docs/theory.md §5.1, "When Newton stops"), on a system whose rows' round-off
// floors differ by eight orders of magnitude, as the mast's module and shell rows do: a soft mass
// on a hardening spring, driven, beside a stiff mass and a coordinate held by a constraint (which
// sets ‖q‖∞). The largest row's floor, taken for every row, accepts the soft row's residual far
// above its own floor; each row within its own must not. An IterateTolerance may accept such an
// iterate, but only with its velocity error — against the step solved to convergence here, by
// Newton with the exact Jacobian — within the tolerance.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "fullorder/generalized_alpha.hpp"

namespace mastrom::fullorder {
namespace {

constexpr double kSoftLinear = 1e3;   // N/m
constexpr double kSoftCubic = 1e5;    // N/m³: the soft row's tangent changes as it swings
constexpr double kStiff = 1e12;       // N/m: its row's floor is ~10⁵ times the soft row's
constexpr double kDrive = 50.0;       // N
constexpr double kDriveOmega = 60.0;  // rad/s
constexpr double kHeld = 0.5;         // m: the held coordinate, ‖q‖∞

/// q = (x_soft, x_stiff, x_held), unit masses; Φ = x_held − kHeld.
class SoftBesideStiff : public DaeSystem {
public:
  SoftBesideStiff() {
    mass_.resize(3, 3);
    mass_.setIdentity();
  }
  int dofCount() const override { return 3; }
  int constraintCount() const override { return 1; }
  const SparseMatrix& massMatrix() const override { return mass_; }
  void forces(const Eigen::VectorXd& q, const Eigen::VectorXd&, double t,
              Eigen::VectorXd& f) override {
    f.resize(3);
    f[0] =
        -kSoftLinear * q[0] - kSoftCubic * q[0] * q[0] * q[0] + kDrive * std::sin(kDriveOmega * t);
    f[1] = -kStiff * q[1] + kDrive * std::cos(kDriveOmega * t);
    f[2] = 0.0;
  }
  void constraints(const Eigen::VectorXd& q, double, Eigen::VectorXd& phi) override {
    phi = Eigen::VectorXd::Constant(1, q[2] - kHeld);
  }
  void constraintJacobian(const Eigen::VectorXd&, double, SparseMatrix& jac) override {
    jac.resize(1, 3);
    jac.setZero();
    jac.coeffRef(0, 2) = 1.0;
  }
  void velocityConstraintRhs(const Eigen::VectorXd&, double, Eigen::VectorXd& rhs) override {
    rhs = Eigen::VectorXd::Zero(1);
  }
  void accelerationConstraintRhs(const Eigen::VectorXd&, const Eigen::VectorXd&, double,
                                 Eigen::VectorXd& rhs) override {
    rhs = Eigen::VectorXd::Zero(1);
  }
  void iterationMatrix(const Eigen::VectorXd& q, const Eigen::VectorXd&, const Eigen::VectorXd&,
                       double, const IterationCoefficients& c, SparseMatrix& h) override {
    std::vector<Eigen::Triplet<double>> t{{0, 0, c.mass + c.stiffness * softTangent(q[0])},
                                          {1, 1, c.mass + c.stiffness * kStiff},
                                          {2, 2, c.mass},
                                          {2, 3, c.constraint_scale},
                                          {3, 2, c.constraint_scale},
                                          {3, 3, 0.0}};
    h.resize(4, 4);
    h.setFromTriplets(t.begin(), t.end());
  }
  static double softTangent(double x) { return kSoftLinear + 3.0 * kSoftCubic * x * x; }

private:
  SparseMatrix mass_;
};

struct Coefficients {
  double alpha_m, alpha_f, gamma, beta;
  explicit Coefficients(double rho) {
    alpha_m = (2 * rho - 1) / (rho + 1);
    alpha_f = rho / (rho + 1);
    gamma = 0.5 + alpha_f - alpha_m;
    beta = 0.25 * (gamma + 0.5) * (gamma + 0.5);
  }
};

/// The step from `before` to t_{n+1} = before.time_s + h solved to convergence: Newton in q̈_{n+1}
/// and λ_{n+1} with the exact Jacobian (docs/theory.md §5.1's updates), from the accepted iterate.
DaeState convergedStep(const DaeState& before, const DaeState& accepted, double h, double rho) {
  const Coefficients c(rho);
  SoftBesideStiff sys;
  DaeState s = accepted;
  const double t = before.time_s + h;
  const double dq_dqdd = h * h * c.beta * (1 - c.alpha_f) / (1 - c.alpha_m);
  for (int it = 0; it < 8; ++it) {
    const Eigen::VectorXd a = (c.alpha_f * before.qddot + (1 - c.alpha_f) * s.qddot -
                               c.alpha_m * before.pseudo_acceleration) /
                              (1 - c.alpha_m);
    s.q = before.q + h * before.qdot +
          h * h * ((0.5 - c.beta) * before.pseudo_acceleration + c.beta * a);
    s.qdot = before.qdot + h * ((1 - c.gamma) * before.pseudo_acceleration + c.gamma * a);
    Eigen::VectorXd f, phi;
    sys.forces(s.q, s.qdot, t, f);
    sys.constraints(s.q, t, phi);
    Eigen::Vector4d r;
    r.head(3) = s.qddot - f;
    r[2] += s.lambda[0];
    r[3] = phi[0];
    Eigen::Matrix4d j = Eigen::Matrix4d::Zero();
    j(0, 0) = 1 + SoftBesideStiff::softTangent(s.q[0]) * dq_dqdd;
    j(1, 1) = 1 + kStiff * dq_dqdd;
    j(2, 2) = 1;
    j(2, 3) = 1;
    j(3, 2) = dq_dqdd;
    const Eigen::Vector4d d = j.fullPivLu().solve(-r);
    s.qddot += d.head(3);
    s.lambda[0] += d[3];
  }
  return s;
}

/// The largest row residual of the accepted state over the larger of the force tolerance and
/// that row's own round-off floor, ε‖q‖∞ ‖∂r_i/∂q‖₂.
double worstRowOverItsFloor(SoftBesideStiff& sys, const GeneralizedAlpha& ga, double force_tol) {
  const DaeState& s = ga.state();
  Eigen::VectorXd f;
  sys.forces(s.q, s.qdot, s.time_s, f);
  Eigen::VectorXd r = s.qddot - f;
  r[2] += s.lambda[0];
  const double scale =
      std::max({s.qddot.cwiseAbs().maxCoeff(), std::abs(s.lambda[0]), f.cwiseAbs().maxCoeff()});
  const double ulp_q = std::numeric_limits<double>::epsilon() * s.q.cwiseAbs().maxCoeff();
  const Eigen::VectorXd& rows = ga.rowResidualPerPosition();
  double worst = 0.0;
  for (Eigen::Index i = 0; i < r.size(); ++i)
    worst = std::max(worst, std::abs(r[i]) / std::max(force_tol * scale, ulp_q * rows[i]));
  return worst;
}

GeneralizedAlphaOptions stopOptions() {
  GeneralizedAlphaOptions o;
  o.time_step_s = 1e-3;
  o.force_tolerance = 1e-14;  // below every floor: the floors stop Newton
  return o;
}

TEST(NewtonRoundOffFloor, SoftRowStopsAtItsOwnFloorBesideAStiffRow) {
  SoftBesideStiff sys;
  const GeneralizedAlphaOptions o = stopOptions();
  GeneralizedAlpha ga(sys, o);
  ga.initialize(Eigen::Vector3d(0.05, 0.0, kHeld), Eigen::Vector3d::Zero(), 0.0);
  double worst = 0.0;
  for (int k = 0; k < 300; ++k) {
    ga.step();
    worst = std::max(worst, worstRowOverItsFloor(sys, ga, o.force_tolerance));
  }
  std::printf("[ measured ] largest row residual / its own floor over 300 steps: %.3g\n", worst);
  // Recomputing the residual here rounds once more, by up to about the floor itself.
  EXPECT_LE(worst, 2.0);
}

TEST(NewtonIterateTolerance, AcceptedIterateKeepsItsVelocityErrorWithinTheTolerance) {
  const GeneralizedAlphaOptions o = stopOptions();
  const double velocity_tolerance_m_s = 1e-11;
  long iterations[2] = {0, 0};
  double worst_error = 0.0;
  long long by_tolerance = 0;
  for (int with_tolerance = 0; with_tolerance < 2; ++with_tolerance) {
    SoftBesideStiff sys;
    GeneralizedAlpha ga(sys, o);
    if (with_tolerance)
      ga.setIterateTolerance({{0}, Eigen::VectorXd::Ones(1), velocity_tolerance_m_s});
    ga.initialize(Eigen::Vector3d(0.05, 0.0, kHeld), Eigen::Vector3d::Zero(), 0.0);
    for (int k = 0; k < 300; ++k) {
      const DaeState before = ga.state();
      iterations[with_tolerance] += ga.step().iterations;
      const DaeState converged = convergedStep(before, ga.state(), o.time_step_s, o.rho_inf);
      if (with_tolerance)
        worst_error = std::max(worst_error, std::abs(ga.state().qdot[0] - converged.qdot[0]));
    }
    if (with_tolerance) by_tolerance = ga.iteratesAcceptedByTolerance();
  }
  std::printf(
      "[ measured ] Newton iterations %ld (rows at their floors) / %ld (tolerance), %lld "
      "iterates accepted by it; largest velocity error %.3g m/s\n",
      iterations[0], iterations[1], by_tolerance, worst_error);
  EXPECT_GT(by_tolerance, 0);  // the tolerance decided some steps
  EXPECT_LT(iterations[1], iterations[0]);
  EXPECT_LE(worst_error, velocity_tolerance_m_s);
}

}  // namespace
}  // namespace mastrom::fullorder
