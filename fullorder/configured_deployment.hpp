// One full-order deployment of a run configuration, start to finish: the mast of the configuration,
// the integrator options of its [simulation] keys, the run, and the metrics of the record. These
// are the steps `mastrom simulate` takes between reading the configuration and writing the file,
// kept in one library function so that every caller holding a Config (the Python module) produces
// the same numbers bit for bit.
#pragma once

#include <functional>
#include <optional>

#include "common/config.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/deployment_result.hpp"
#include "fullorder/interface_stress.hpp"

namespace mastrom::fullorder {

struct ConfiguredDeploymentOptions {
  int threads = 1;  ///< threads for the shell element forces (results do not depend on it), ≥ 1
  DeploymentProgress progress;  ///< called between steps; may throw to abort the run
};

struct ConfiguredDeployment {
  DeploymentSeries series;
  DeploymentMetrics metrics;
  DeploymentStatistics statistics;
  /// The interface stresses on the output instants (docs/theory.md §6).
  std::optional<InterfaceStressResult> stresses;
  double stress_seconds = 0.0;  ///< wall time their evaluation took
  int dofs = 0, constraints = 0, shell_elements = 0;  ///< size of the model that ran
};

/// Build the driven mast of `config`, integrate it to simulation.end_time (fixed or adaptive steps,
/// fullorder/mast_config.hpp deploymentFromConfig) and compute the metrics with the drive's duration
/// as its end time (fullorder/deployment_accuracy.hpp fullOrderMetrics: continuous peaks of an
/// adaptive run). Throws InputError (threads < 1) and NumericalError (a failed step).
ConfiguredDeployment runConfiguredDeployment(const Config& config,
                                             const ConfiguredDeploymentOptions& options = {});

}  // namespace mastrom::fullorder
