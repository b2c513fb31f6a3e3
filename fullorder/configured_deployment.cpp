#include "fullorder/configured_deployment.hpp"

#include "common/error.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/mast_model.hpp"

namespace mastrom::fullorder {

void requireRecordCoversDrive(const Config& config) {
  MASTROM_REQUIRE(config.simulation.end_time_s >= config.drive.duration_s, InputError,
                  "simulation.end_time = ", config.simulation.end_time_s,
                  " s ends before the drive does; allowed: >= drive.duration = ",
                  config.drive.duration_s, " s");
}

ConfiguredDeployment runConfiguredDeployment(const Config& config,
                                             const ConfiguredDeploymentOptions& options) {
  requireRecordCoversDrive(config);
  MASTROM_REQUIRE(options.threads >= 1, InputError, "threads = ", options.threads, " must be >= 1");
  MastModel model = buildMast(mastParametersFromConfig(config));
  model.system().setThreadCount(options.threads);
  DeploymentOptions run;
  run.integrator = integratorFromConfig(config);
  run.end_time_s = config.simulation.end_time_s;
  run.output_every = config.output.every;

  ConfiguredDeployment result;
  result.dofs = model.dofCount();
  result.constraints = model.constraintCount();
  result.shell_elements = model.system().elementCount();
  result.series = simulateDeployment(model, run, &result.statistics, options.progress);
  result.metrics = computeMetrics(result.series, config.drive.duration_s);
  return result;
}

}  // namespace mastrom::fullorder
