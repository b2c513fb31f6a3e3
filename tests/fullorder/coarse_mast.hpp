// The small mast the deployment tests run on: Scheme 1 (2 modules, 1 interface) on a 1 × 6 ring.
// Short horizons and this coarse ring keep each case to a fraction of a second; what the tests
// check (rigid-body mechanics, energy, solver paths) does not depend on the mesh.
#pragma once

#include <Eigen/Core>

#include "common/config.hpp"
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
