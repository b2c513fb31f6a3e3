#include "fullorder/configured_deployment.hpp"

#include "common/error.hpp"
#include "fullorder/deployment_accuracy.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/mast_model.hpp"

namespace mastrom::fullorder {

ConfiguredDeployment runConfiguredDeployment(const Config& config,
                                             const ConfiguredDeploymentOptions& options) {
  MASTROM_REQUIRE(options.threads >= 1, InputError, "threads = ", options.threads, " must be >= 1");
  MastModel model = buildMast(mastParametersFromConfig(config));
  model.system().setThreadCount(options.threads);
  DeploymentOptions run = deploymentFromConfig(config);
  InterfaceStressMonitor monitor = stressMonitorFor(model, run);
  run.state_observer = observeInterfaceStresses(monitor);

  ConfiguredDeployment result;
  result.dofs = model.dofCount();
  result.constraints = model.constraintCount();
  result.shell_elements = model.system().elementCount();
  result.series = simulateDeployment(model, run, &result.statistics, options.progress);
  result.metrics = fullOrderMetrics(result.series, result.statistics, config.drive.duration_s);
  result.stresses = monitor.resample(result.series.time_s);
  result.stress_seconds = monitor.evaluationSeconds();
  return result;
}

}  // namespace mastrom::fullorder
