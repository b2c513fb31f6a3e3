#include "fullorder/deployment_system.hpp"

#include "common/error.hpp"
#include "fullorder/static_solver.hpp"

namespace mastrom::fullorder {

DeploymentSystem::DeploymentSystem(MastModel& model, bool eliminate_linear_constraints)
    : model_(model) {
  if (eliminate_linear_constraints) reduced_ = std::make_unique<EliminatedSystem>(model.system());
}

void DeploymentSystem::initialize(GeneralizedAlpha& integrator, bool equilibrium) const {
  Eigen::VectorXd q0, qdot0;
  model_.initialState(q0, qdot0);
  const MultibodySystem& sys = model_.system();
  // At rest is judged on the drive's rate against its round-off (docs/theory.md §1.5, §5.1): a
  // table's spline may give θ̇(0) = 10⁻¹⁹ rad/s, and an exact test then started a mast under
  // gravity undeformed, to drop and ring under its weight. Such a start is made exactly at rest.
  const bool at_rest = model_.baseJoint().driveLaw().startsAtRest();
  if (at_rest) qdot0.setZero();
  // Every law is at rest at t = 0 by construction (tables by their clamped spline); a drive that
  // were not could not start in equilibrium under gravity, and the run must not pretend it does.
  MASTROM_REQUIRE(at_rest || !equilibrium || sys.gravity().squaredNorm() == 0.0, InputError,
                  "drive: the joint rate at t = 0 is ", model_.baseJoint().driveAt(0.0).rate_rad_s,
                  " rad/s, not at rest (|rate| <= ",
                  model_.baseJoint().driveLaw().restRateTolerance(),
                  " rad/s); a deployment under gravity must start from rest");
  if (equilibrium && sys.gravity().squaredNorm() > 0.0) {  // at rest: required above
    // The drive's constraint at t = 0 holds the joint at the start angle (docs/theory.md §5.1).
    StaticSolverOptions statics;
    statics.time_s = 0.0;
    q0 = solveStatic(sys, q0, statics).q;
  }
  if (reduced_) {
    integrator.initialize(reduced_->restrict(q0), reduced_->restrict(qdot0), 0.0);
  } else {
    integrator.initialize(q0, qdot0, 0.0);
  }
}

const DaeState& DeploymentSystem::full(const DaeState& r) {
  if (!reduced_) return r;
  DaeState& f = full_state_;
  f.time_s = r.time_s;
  f.q = reduced_->expandPositions(r.q);
  f.lambda = reduced_->expandMultipliers(r.lambda);
  // sampleDeploymentState reads the index-1 values when there are any, else q̈ and λ: expand only
  // what it reads (every output instant counts when outputs are taken every step).
  if (r.qddot_index1.size() == r.q.size()) {
    f.qddot.resize(0);
    f.qddot_index1 = reduced_->expandRates(r.qddot_index1);
    f.lambda_index1 = reduced_->expandMultipliers(r.lambda_index1);
  } else {
    f.qddot = reduced_->expandRates(r.qddot);
    f.qddot_index1.resize(0);
    f.lambda_index1.resize(0);
  }
  return f;
}

Eigen::VectorXd DeploymentSystem::fullVelocities(const DaeState& r) const {
  return reduced_ ? reduced_->expandRates(r.qdot) : r.qdot;
}

void DeploymentSystem::moduleCoordinates(std::vector<int>& index, Eigen::VectorXd& weight) const {
  const int modules = model_.moduleCount();
  std::vector<int> to_reduced;
  if (reduced_) {
    to_reduced.assign(static_cast<std::size_t>(model_.dofCount()), -1);
    const std::vector<int>& kept = reduced_->keptDofs();
    for (std::size_t j = 0; j < kept.size(); ++j)
      to_reduced[static_cast<std::size_t>(kept[j])] = static_cast<int>(j);
  }
  index.clear();
  weight.resize(12 * modules);
  for (int k = 0; k < modules; ++k) {
    const int offset = model_.moduleDofOffset(k);
    for (int c = 0; c < 12; ++c) {
      const int full = offset + c;
      const int i = reduced_ ? to_reduced[static_cast<std::size_t>(full)] : full;
      MASTROM_REQUIRE(i >= 0, Error, "deployment: module ", k + 1, " coordinate ", c,
                      " was eliminated");
      index.push_back(i);
      // NCF layout [r_i, r_j, u, v] (fullorder/ncf_body.hpp): points, then unit vectors.
      weight[12 * k + c] = c < 6 ? 1.0 : model_.system().body(k).axisLength();
    }
  }
}

}  // namespace mastrom::fullorder
