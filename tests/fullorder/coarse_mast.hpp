// The small mast the deployment tests run on: Scheme 1 (2 modules, 1 interface) on a 1 × 6 ring.
// Short horizons and this coarse ring keep each case to a fraction of a second; what the tests
// check (rigid-body mechanics, energy, solver paths) does not depend on the mesh.
#pragma once

#include <Eigen/Core>

#include "common/config.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/eliminated_system.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/mast_model.hpp"

namespace mastrom::fullorder::testing {

inline Config coarseScheme1() {
  Config c;
  c.mast.modules = 2;
  c.interface.elements_axial = 1;
  c.interface.elements_circumferential = 6;
  // The fixed step these tests were written for (the integrator tests build their options from
  // it; the adaptive tests set their own first step).
  c.simulation.time_step_s = 1e-4;
  return c;
}

/// The same mast turned 10° in 0.5 s with 20 ms ramps: after 0.02 s it cruises, the regime of
/// most of a deployment's steps (Newton and solver tests).
inline Config turningScheme1() {
  Config c = coarseScheme1();
  c.drive.angle_deg = 10.0;
  c.drive.duration_s = 0.5;
  c.drive.ramp_s = 0.02;
  return c;
}

/// Fixed steps of 0.2 ms for a mast with stiffened ("rigid") shells, to `end_time_s`.
/// The stiffened shells have MHz modes, 10³ beyond the step's resolution. A jump of θ̈ (or of the
/// jerk) excites them, and generalized-α rings such an unresolved mode algorithmically with
/// amplitude ~ the jump, decaying only like ρ∞ⁿ (measured: ±190 rad/s² around θ̈ = 218 rad/s² still
/// after 4 steps at ρ∞ = 0.9). ρ∞ = 0 (asymptotic annihilation) is the setting for such stiff
/// systems and removes it within four steps (measured at the start, where the consistent initial
/// state has the end module still at rest: errors 2 %, 44 %, 4 %, 0.6 % of θ̈ in steps 1–4); the
/// samples in those four steps after each discontinuity of the drive law are the only ones a test
/// may compare with rigid-body mechanics. For the same reason the integrator's (filtered) q̈ and λ
/// are reported: the index-1 recovery would report the true accelerations of the unresolved MHz
/// content of each state.
inline DeploymentOptions rigidMastOptions(double end_time_s) {
  DeploymentOptions o;
  o.integrator.time_step_s = 2e-4;
  o.integrator.rho_inf = 0.0;
  o.integrator.recover_index1_accelerations = false;
  o.end_time_s = end_time_s;
  return o;
}

/// turningScheme1() built, its linear constraints eliminated, and its initial state restricted to
/// the kept coordinates — what the integrator tests start from. Not movable: `reduced` refers to
/// `model`'s system.
struct EliminatedTurningMast {
  explicit EliminatedTurningMast(int threads = 1)
      : config(turningScheme1()),
        model(buildMast(mastParametersFromConfig(config))),
        reduced(model.system()) {
    model.system().setThreadCount(threads);
    Eigen::VectorXd q, v;
    model.initialState(q, v);
    q0 = reduced.restrict(q);
    v0 = reduced.restrict(v);
  }
  EliminatedTurningMast(const EliminatedTurningMast&) = delete;
  EliminatedTurningMast& operator=(const EliminatedTurningMast&) = delete;

  Config config;
  MastModel model;
  EliminatedSystem reduced;
  Eigen::VectorXd q0, v0;  ///< reduced initial positions and velocities
};

}  // namespace mastrom::fullorder::testing
