// One full-order deployment of a run configuration, start to finish: the mast of the configuration,
// the integrator options of its [simulation] keys, the run, and the metrics of the record. These
// are the steps `mastrom simulate` takes between reading the configuration and writing the file,
// kept in one library function so that every caller holding a Config (the Python module) produces
// the same numbers bit for bit.
#pragma once

#include <functional>

#include "common/config.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/deployment_result.hpp"

namespace mastrom::fullorder {

struct ConfiguredDeploymentOptions {
  int threads = 1;  ///< threads for the shell element forces (results do not depend on it), ≥ 1
  DeploymentProgress progress;  ///< called between steps; may throw to abort the run
};

struct ConfiguredDeployment {
  DeploymentSeries series;
  DeploymentMetrics metrics;
  DeploymentStatistics statistics;
  int dofs = 0, constraints = 0, shell_elements = 0;  ///< size of the model that ran
};

/// Check what the run needs beyond the configuration's own validation: the record must not end
/// before the drive does (the metrics measure the vibration after it). InputError otherwise, with
/// the message `mastrom simulate` prints.
void requireRecordCoversDrive(const Config& config);

/// Build the driven mast of `config`, integrate it to simulation.end_time (recording every
/// output.every-th step) and compute the metrics with the drive's duration as its end time.
/// Throws InputError (requireRecordCoversDrive, threads < 1) and NumericalError (a failed step).
ConfiguredDeployment runConfiguredDeployment(const Config& config,
                                             const ConfiguredDeploymentOptions& options = {});

}  // namespace mastrom::fullorder
