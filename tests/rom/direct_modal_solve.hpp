// Test support for the parametric ROM tests (test_spd_interpolation.cpp, test_affine_model.cpp):
// a coarse Scheme 1 configuration with a compressed drive, the "truth" modal model at a
// configuration by a direct dense modal solve, and the comparison of two ROM deployments.
#pragma once

#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "common/config.hpp"
#include "fullorder/deployment_result.hpp"
#include "fullorder/drive_law.hpp"
#include "fullorder/mast_config.hpp"
#include "modes/eigen_solver.hpp"
#include "modes/linearize.hpp"
#include "rom/model/comparison.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/model/modal_extraction.hpp"

namespace mastrom::rom::testing {

/// Scheme 1 (2 modules, 1 interface), mesh 2 × 8, dense modal solves, and the drive of
/// test_modal_deployment.cpp compressed to 10° in 40 ms (ramps of 10 ms), so that one deployment
/// covers tens of periods of every mode and the ROM runs in milliseconds.
inline Config scheme1Config(int modes) {
  Config c;
  c.mast.modules = 2;
  c.interface.elements_axial = 2;
  c.interface.elements_circumferential = 8;
  c.drive.angle_deg = 10.0;
  c.drive.duration_s = 0.04;
  c.drive.ramp_s = 0.01;
  c.simulation.end_time_s = 0.05;
  c.modes.count = modes;
  c.modes.backend = EigenBackendKind::Dense;
  return c;
}

/// The modal model of `config` by a direct dense modal solve (locked at modes.angle_deg).
struct DirectSolve {
  fullorder::MastModel model;
  modes::Linearization lin;
  modes::EigenResult eig;
  ModalModel modal;
};

inline DirectSolve directModalSolve(const Config& config, int modes) {
  fullorder::MastModel model = modes::buildLockedMast(fullorder::mastParametersFromConfig(config),
                                                      config.modes.angleRad());
  modes::Linearization lin = modes::linearizeMast(model);
  modes::EigenSolverOptions eo;
  eo.count = modes;
  eo.backend = EigenBackendKind::Dense;
  modes::EigenResult eig = modes::solveConstrainedEigenproblem(lin.problem, eo);
  EXPECT_TRUE(eig.ok()) << eig.message;
  LinearizedModes lm;
  lm.q_reference = lin.q;
  lm.reference_angle_rad = config.modes.angleRad();
  lm.mass = lin.problem.mass;
  lm.damping = lin.damping;
  lm.omega_squared = eig.eigenvalues_rad2_s2;
  lm.modes = eig.modes;
  ModalModel modal = extractModalModel(model, lm);
  return {std::move(model), std::move(lin), std::move(eig), std::move(modal)};
}

/// Scheme 3 (4 modules, the default drive: 90° in 6.1 s, ramps 0.1 s, record 8 s) on a coarse
/// interface mesh (1 × 8), 10 modes by a dense solve: the model of the tests of the continuous
/// metrics (peaks, RMS, settling), solved once per binary; coarseScheme3Config() its configuration.
inline Config coarseScheme3Config() {
  Config c;
  c.interface.elements_axial = 1;
  c.interface.elements_circumferential = 8;
  c.modes.count = 10;
  c.modes.backend = EigenBackendKind::Dense;
  return c;
}
inline const ModalModel& coarseScheme3Model() {
  static const ModalModel m = directModalSolve(coarseScheme3Config(), 10).modal;
  return m;
}

/// A compressed swing (90° in 0.4003 s, ramps 0.0502 s): its breakpoints fall inside the steps
/// of a 1 ms or 0.1 ms grid, which are then split.
inline fullorder::DriveLawParameters compressedDrive(DriveLawKind law) {
  fullorder::DriveLawParameters p;
  p.kind = law;
  p.duration_s = 0.4003;
  p.ramp_s = 0.0502;
  return p;
}

/// One ROM deployment of `config`'s drive up to simulation.end_time, outputs every 5 µs (≥ 20 per
/// period of every mode below 10 kHz).
inline fullorder::DeploymentSeries deploy(const ModalModel& modal, const Config& config) {
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(config));
  ModalDeploymentOptions o;
  o.end_time_s = config.simulation.end_time_s;
  o.step_s = 5e-6;
  return simulateModalDeployment(modal, drive, o);
}

/// A ROM deployment against the one of the direct modal solve (the reference), same instants.
inline DeploymentComparison compareRoms(const ModalModel& reference, const ModalModel& candidate,
                                        const Config& config) {
  const fullorder::DeploymentSeries a = deploy(reference, config), b = deploy(candidate, config);
  const double t_drive = config.drive.duration_s;
  return compareDeployments(a, fullorder::computeMetrics(a, t_drive), b,
                            fullorder::computeMetrics(b, t_drive));
}

/// max_k |ω_k/ω_k,ref − 1| over the first `count` modes.
inline double frequencyError(const ModalModel& reference, const ModalModel& candidate, int count) {
  double e = 0.0;
  for (int k = 0; k < count; ++k)
    e = std::max(e, std::abs(candidate.omega_rad_s[k] / reference.omega_rad_s[k] - 1.0));
  return e;
}

}  // namespace mastrom::rom::testing
