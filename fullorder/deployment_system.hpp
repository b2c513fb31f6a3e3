// The system a deployment integrates — the mast with its linear bonded-edge equations eliminated
// (fullorder/eliminated_system.hpp) or whole — and the expansion of the integrator's states to the
// full coordinates the outputs read. Shared by the fixed-step and the adaptive deployment loops.
#pragma once

#include <memory>
#include <vector>

#include "fullorder/eliminated_system.hpp"
#include "fullorder/generalized_alpha.hpp"
#include "fullorder/mast_model.hpp"

namespace mastrom::fullorder {

class DeploymentSystem {
public:
  DeploymentSystem(MastModel& model, bool eliminate_linear_constraints);

  DaeSystem& dae() { return reduced_ ? static_cast<DaeSystem&>(*reduced_) : model_.system(); }
  /// Start `integrator` (built on dae()) from the model's stowed state at t = 0 — with gravity, a
  /// drive at rest and `equilibrium`, deflected into its static equilibrium there (solveStatic).
  void initialize(GeneralizedAlpha& integrator, bool equilibrium) const;
  /// The full-coordinate view of an integrator state: q, λ and the accelerations the outputs read
  /// (the index-1 ones when the state has them, else q̈). Valid until the next call.
  const DaeState& full(const DaeState& state);
  /// The full velocities of an integrator state.
  Eigen::VectorXd fullVelocities(const DaeState& state) const;
  /// The integrator-coordinate index of each of the modules' 12 NCF coordinates, module by module
  /// (the modules are never eliminated), and the weight that turns each into an acceleration of a
  /// point [m/s²] (1 for the points r_i, r_j; the module side for the unit vectors u, v).
  void moduleCoordinates(std::vector<int>& index, Eigen::VectorXd& weight) const;

private:
  MastModel& model_;
  std::unique_ptr<EliminatedSystem> reduced_;
  DaeState full_state_;
};

}  // namespace mastrom::fullorder
