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
#include "rom/model/stress_peak_stream.hpp"
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
  const SampledDrive sampled = sampleDrive(drive, result.options);
  const bool stresses = !result.model.stress.empty();
  std::optional<ModalStressEvaluator> evaluator;
  if (stresses) evaluator.emplace(result.model);
  // The stress peaks of the output samples: on a grid fine enough for their polish, found while
  // the series steps (rom/model/stress_peak_stream.hpp: one block of states at a time, not the
  // states of every sample); on a coarse one refined between the samples from every sample's
  // recorded state, η and η̇ (modal_stress_response.hpp).
  const bool refine =
      stresses && stressPeaksNeedRefinement(*evaluator, result.model, sampled.step_s);
  // The metrics are those of the continuous response, whose step sets their cost, not their
  // answer (rom/model/deployment_metrics.hpp): on the screen's grid where that is the coarser one
  // and the user did not set the output interval, so that they are a screen's numbers for this
  // design (on the main job's case, 80 times fewer steps than the output samples). That pass also
  // records the stresses' states on its grid: their largest sample, less a margin for the
  // coarser grid's first-order hold, is the floor that lets the stream skip every block of output
  // samples that cannot reach the peak.
  ModalDeploymentOptions metric_options = result.options;
  if (input.metrics_step_s > result.options.step_s) metric_options.step_s = input.metrics_step_s;
  result.metrics_step_s = metric_options.step_s;
  const SampledDrive metric_drive = sampleDrive(drive, metric_options);
  const bool floors = stresses && !refine && metric_options.step_s > result.options.step_s;
  Eigen::MatrixXd coarse_states;
  std::optional<ModalSampleObserver> coarse_record;
  if (floors) {
    coarse_states.resize(evaluator->inputSize(), metric_drive.steps + 1);
    coarse_record = modalStressRecorder(*evaluator, coarse_states);
  }
  const auto t_metrics = clock::now();
  result.metrics =
      modalDeploymentMetrics(result.model, metric_drive, result.options.coriolis_coupling,
                             input.config.drive.duration_s, fullorder::kDefaultSettlingBandRadS2,
                             PeakResolution::Continuous, coarse_record ? &*coarse_record : nullptr);
  const auto t_series = clock::now();
  result.metrics_s = std::chrono::duration<double>(t_series - t_metrics).count();

  std::vector<double> floor_pa;
  if (floors) {
    const std::vector<char> no_polish;  // the samples' values, unpolished
    for (const ModalStressEvaluator::Peak& pk :
         findStressPeaks(*evaluator, coarse_states, no_polish, result.model, metric_drive, {}, {}))
      floor_pa.push_back((1.0 - kStressFloorMargin) * pk.sample_von_mises_pa);
  }
  const auto t_floor = clock::now();
  Eigen::MatrixXd states, eta, eta_dot;
  std::optional<StressPeakStream> stream;
  std::optional<ModalSampleObserver> observe;
  if (refine) {
    states.resize(evaluator->inputSize(), sampled.steps + 1);
    eta.resize(result.model.modeCount(), sampled.steps + 1);
    eta_dot.resize(result.model.modeCount(), sampled.steps + 1);
    observe = modalStressRecorder(*evaluator, states, eta, eta_dot);
  } else if (stresses) {
    stream.emplace(*evaluator, sampled, floor_pa);
    observe = stream->observer();
  }
  result.series = simulateModalDeployment(result.model, sampled, result.options.coriolis_coupling,
                                          observe ? &*observe : nullptr);
  const auto t_peaks = clock::now();
  // The series' time: the drive's sampling and the stepping, with the blocks the stream searched
  // while it stepped; the stress peaks' time: the floor's search, the stream's end and the result.
  result.deployment_s =
      std::chrono::duration<double>((t_metrics - t1) + (t_peaks - t_floor)).count();
  if (stresses) {
    std::vector<ModalStressEvaluator::Peak> peaks;
    std::vector<Eigen::VectorXd> peak_states;
    if (refine) {
      result.stresses = modalInterfaceStresses(result.model, *evaluator, sampled, states, eta,
                                               eta_dot, /*history=*/false);
    } else if (stream->finish(peaks, peak_states)) {
      result.stresses =
          interfaceStressResult(result.model, *evaluator, sampled, peaks, peak_states);
    } else {  // a floor above the peak (not expected): the search over every sample's state
      states =
          modalStressStates(result.model, *evaluator, sampled, result.options.coriolis_coupling);
      result.stresses = modalInterfaceStresses(result.model, *evaluator, sampled, states, eta,
                                               eta_dot, /*history=*/false);
    }
    const auto t4 = clock::now();
    result.stress_s = std::chrono::duration<double>((t4 - t_peaks) + (t_floor - t_series)).count();
    if (input.stress_history) {
      modalStressHistories(result.model, *evaluator, sampled, result.options.coriolis_coupling,
                           *result.stresses);
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
