#include "rom/studies/rom_evaluation.hpp"

#include <chrono>
#include <optional>

#include "fullorder/drive_law.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/run_footprint.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/model/modal_stepping.hpp"
#include "rom/model/modal_stress_response.hpp"
#include "rom/studies/default_output_step.hpp"
#include "rom/studies/screen_kernel.hpp"

namespace mastrom::rom {

RomEvaluationInput romEvaluationInput(const RomDatabase& db,
                                      const std::vector<std::string>& overrides, BoxPolicy box) {
  RomEvaluationInput input;
  input.config = evaluationConfig(db, overrides);
  input.point = parameterPoint(db, input.config);
  requireInsideBox(db, input.point, box);
  input.metrics_step_s = screenStep(overrides, kDefaultScreenStepS, PeakResolution::Continuous);
  return input;
}

double romOutputBytesPerSample(const Config& config, bool stresses) {
  return fullorder::resultBytesPerSample(fullorder::mastSize(config), stresses);
}

RomEvaluation evaluateRomDeployment(const ModalInterpolator& interpolator,
                                    const RomEvaluationInput& input) {
  using clock = std::chrono::steady_clock;
  RomEvaluation result;
  const auto t0 = clock::now();
  result.model = input.stresses ? interpolator.evaluateWithStresses(input.point)
                                 : interpolator.evaluate(input.point);
  const auto t1 = clock::now();
  result.interpolation_s = std::chrono::duration<double>(t1 - t0).count();
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(input.config));
  Config config = input.config;
  result.output_step =
      resolveRomOutputStep(config, result.model, romOutputBytesPerSample(config, input.stresses));
  result.options = deploymentOptionsFromConfig(config);
  // The series on the output grid; its pass also records the stresses' modal states, so that the
  // stress peaks, their fields and the histories are those of the output samples.
  const SampledDrive sampled = sampleDrive(drive, result.options);
  const bool stresses = !result.model.stress.empty();
  std::optional<ModalStressEvaluator> evaluator;
  Eigen::MatrixXd states, eta, eta_dot;
  std::optional<ModalSampleObserver> record;
  if (stresses) {
    evaluator.emplace(result.model);
    states.resize(evaluator->inputSize(), sampled.steps + 1);
    if (stressPeaksNeedRefinement(*evaluator, result.model, sampled.step_s)) {
      eta.resize(result.model.modeCount(), sampled.steps + 1);
      eta_dot.resize(result.model.modeCount(), sampled.steps + 1);
      record = modalStressRecorder(*evaluator, states, eta, eta_dot);
    } else {
      record = modalStressRecorder(*evaluator, states);
    }
  }
  result.series = simulateModalDeployment(result.model, sampled, result.options.coriolis_coupling,
                                          record ? &*record : nullptr);
  const auto t2 = clock::now();
  result.deployment_s = std::chrono::duration<double>(t2 - t1).count();
  // The metrics are those of the continuous response, whose step sets their cost, not their
  // answer (rom/model/deployment_metrics.hpp): on the screen's grid where that is the coarser one
  // and the user did not set the output interval, so that they are a screen's numbers for this
  // design (on the main job's case, 80 times fewer steps than the output samples).
  ModalDeploymentOptions metric_options = result.options;
  if (input.metrics_step_s > result.options.step_s) metric_options.step_s = input.metrics_step_s;
  result.metrics_step_s = metric_options.step_s;
  result.metrics =
      modalDeploymentMetrics(result.model, sampleDrive(drive, metric_options),
                             result.options.coriolis_coupling, input.config.drive.duration_s,
                             fullorder::kDefaultSettlingBandRadS2, PeakResolution::Continuous);
  const auto t3 = clock::now();
  result.metrics_s = std::chrono::duration<double>(t3 - t2).count();
  if (stresses) {
    result.stresses = modalInterfaceStresses(result.model, *evaluator, sampled, states, eta,
                                             eta_dot, /*history=*/false);
    const auto t4 = clock::now();
    result.stress_s = std::chrono::duration<double>(t4 - t3).count();
    if (input.stress_history) {
      for (int i = 0; i < evaluator->interfaceCount(); ++i)
        evaluator->largestHistory(
            i, states, result.stresses->history[static_cast<std::size_t>(i)].max_von_mises_pa);
      result.stress_history_s = std::chrono::duration<double>(clock::now() - t4).count();
    }
    result.stresses->elements_axial = input.config.interface.elements_axial;
    result.stresses->elements_circumferential = input.config.interface.elements_circumferential;
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
