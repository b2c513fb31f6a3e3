#include "rom/studies/rom_evaluation.hpp"

#include <chrono>

#include "fullorder/drive_law.hpp"
#include "fullorder/mast_config.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/model/modal_stress_response.hpp"

namespace mastrom::rom {

RomEvaluationInput romEvaluationInput(const RomDatabase& db,
                                      const std::vector<std::string>& overrides, BoxPolicy box) {
  RomEvaluationInput input;
  input.config = evaluationConfig(db, overrides);
  input.point = parameterPoint(db, input.config);
  requireInsideBox(db, input.point, box);
  return input;
}

RomEvaluation evaluateRomDeployment(const ModalInterpolator& interpolator,
                                    const RomEvaluationInput& input) {
  using clock = std::chrono::steady_clock;
  RomEvaluation result;
  const auto t0 = clock::now();
  result.model = input.stresses ? interpolator.evaluateWithStresses(input.point)
                                 : interpolator.evaluate(input.point);
  const auto t1 = clock::now();
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(input.config));
  result.options = deploymentOptionsFromConfig(input.config);
  result.series = simulateModalDeployment(result.model, drive, result.options);
  result.deployment_s = std::chrono::duration<double>(clock::now() - t1).count();
  result.interpolation_s = std::chrono::duration<double>(t1 - t0).count();
  result.metrics =
      modalDeploymentMetrics(result.model, drive, result.options, input.config.drive.duration_s);
  if (!result.model.stress.empty()) {
    const auto t2 = clock::now();
    result.stresses = modalInterfaceStresses(result.model, drive, result.options);
    result.stresses->elements_axial = input.config.interface.elements_axial;
    result.stresses->elements_circumferential = input.config.interface.elements_circumferential;
    result.stress_s = std::chrono::duration<double>(clock::now() - t2).count();
  }
  return result;
}

EvaluationDescription describeEvaluation(const RomDatabase& db,
                                         const ModalInterpolator& interpolator,
                                         const RomEvaluationInput& input, const ModalModel& model,
                                         const FrequencyRequest& request, BoxPolicy box) {
  const DesignDescriber describer(db, input.config, request, {input.config.drive.angle_deg}, box);
  EvaluationDescription d;
  d.columns = describer.columns(0, false);
  describer.describe(interpolator, model, input.point, 0, d.values);
  return d;
}

}  // namespace mastrom::rom
