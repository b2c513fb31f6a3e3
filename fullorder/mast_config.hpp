// Mapping of the validated run configuration (common/config.hpp) onto the full-order model's inputs:
// the mast parameters, the drive law and the integrator options. Kept apart from mast_model so the
// model itself never depends on how a user spelled the input.
#pragma once

#include "common/config.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/drive_law.hpp"
#include "fullorder/generalized_alpha.hpp"
#include "fullorder/mast_model.hpp"

namespace mastrom::fullorder {

DriveLawParameters driveFromConfig(const Config& config);

/// The mast of the configuration with the driven joint (no lock).
MastParameters mastParametersFromConfig(const Config& config);

GeneralizedAlphaOptions integratorFromConfig(const Config& config);

/// The deployment of the configuration: integrator, end time, fixed or adaptive steps and their
/// bounds, output instants. Checkpoints and progress are the caller's.
DeploymentOptions deploymentFromConfig(const Config& config);

}  // namespace mastrom::fullorder
