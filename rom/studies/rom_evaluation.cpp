#include "rom/studies/rom_evaluation.hpp"

#include <chrono>
#include <cmath>
#include <optional>

#include "common/error.hpp"
#include "fullorder/drive_law.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/run_footprint.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/model/modal_stepping.hpp"
#include "rom/model/modal_stress_response.hpp"
#include "rom/model/stress_blocks.hpp"
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

namespace {

using clock = std::chrono::steady_clock;

/// Everything but the outputs (the series and the stress histories); `evaluator` is set when the
/// model carries stress modes.
RomEvaluation evaluateOutcome(const ModalInterpolator& interpolator,
                              const RomEvaluationInput& input,
                              std::optional<ModalStressEvaluator>& evaluator) {
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
  const bool stresses = !result.model.stress.empty();
  if (stresses) evaluator.emplace(result.model);
  // What the evaluation reports — the metrics and the stress peaks — are those of the continuous
  // response, whose step sets their cost, not their answer (rom/model/deployment_metrics.hpp,
  // docs/theory.md §4.2, §6.5): one pass on the screen's grid where that is the coarser one and
  // the user did not set the output interval, so that they are a screen's numbers for this design
  // (on the main job's case, 80 times fewer steps than the output samples). On a grid coarse for
  // the peaks' polish that pass records η, η̇ and the stresses' state of its samples, and the peaks
  // are refined between them (modal_stress_response.hpp); on a fine one the stream searches its
  // samples while it steps (stress_peak_stream.hpp: one block of states at a time).
  ModalDeploymentOptions metric_options = result.options;
  if (input.metrics_step_s > result.options.step_s) metric_options.step_s = input.metrics_step_s;
  result.metrics_step_s = metric_options.step_s;
  const SampledDrive metric_drive = sampleDrive(drive, metric_options);
  const bool refine =
      stresses && stressPeaksNeedRefinement(*evaluator, result.model, metric_drive.step_s);
  std::optional<StressBlockRecord> blocks;
  std::optional<ModalBlockObserver> observe_blocks;
  std::optional<StressPeakStream> stream;
  std::optional<ModalSampleObserver> observe;
  if (refine) {
    // The state at each block's start and the block's stress bounds, not every sample's state
    // (stress_blocks.hpp: the same peaks).
    blocks.emplace(*evaluator, result.model, metric_drive, result.options.coriolis_coupling);
    observe_blocks = blocks->observer();
  } else if (stresses) {
    stream.emplace(*evaluator, metric_drive, std::vector<double>{});
    observe = stream->observer();
  }
  result.metrics = modalDeploymentMetrics(
      result.model, metric_drive, result.options.coriolis_coupling, input.config.drive.duration_s,
      fullorder::kDefaultSettlingBandRadS2, PeakResolution::Continuous,
      observe ? &*observe : nullptr, observe_blocks ? &*observe_blocks : nullptr);
  const auto t_peaks = clock::now();
  // The metrics' time includes the choice of the output step and the drive's sampling on their
  // grid (both before the pass).
  result.metrics_s = std::chrono::duration<double>(t_peaks - t1).count();
  std::vector<ModalStressEvaluator::Peak> peaks;
  std::vector<Eigen::VectorXd> peak_states;
  if (stresses) {
    if (refine) {
      peaks = blocks->peaks(samplesNearBreakpoints(metric_drive));
      peak_states = stressPeakStates(*evaluator, result.model, metric_drive, *blocks, peaks);
    } else {
      // Without floors the stream's search is peak()'s on every sample: always certain.
      const bool certain = stream->finish(peaks, peak_states);
      MASTROM_REQUIRE(certain, NumericalError, "rom eval: the stress peaks' stream found no peak");
    }
    result.stresses =
        interfaceStressPeaks(result.model, *evaluator, metric_drive.step_s, peaks, peak_states);
    result.stress_s = std::chrono::duration<double>(clock::now() - t_peaks).count();
  }
  if (stresses) {
    result.stresses->elements_axial = input.config.interface.elements_axial;
    result.stresses->elements_circumferential = input.config.interface.elements_circumferential;
  }
  const long steps =
      static_cast<long>(std::ceil(result.options.end_time_s / result.options.step_s - 1e-9));
  result.output_samples = static_cast<std::size_t>(steps + 1);
  return result;
}

}  // namespace

RomEvaluation evaluateRomDeployment(const ModalInterpolator& interpolator,
                                    const RomEvaluationInput& input) {
  std::optional<ModalStressEvaluator> evaluator;
  RomEvaluation result = evaluateOutcome(interpolator, input, evaluator);
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(input.config));
  // The series at every output sample (the drive sampled on the output grid, the stepping): an
  // output, what the result file holds, no input of the numbers above.
  const auto t_series = clock::now();
  const SampledDrive sampled = sampleDrive(drive, result.options);
  result.series =
      simulateModalDeployment(result.model, sampled, result.options.coriolis_coupling, nullptr);
  if (evaluator) setStressOutputInstants(sampled, *result.stresses);  // the histories' instants
  const auto t_history = clock::now();
  result.deployment_s = std::chrono::duration<double>(t_history - t_series).count();
  if (evaluator && input.stress_history) {
    modalStressHistories(result.model, *evaluator, sampled, result.options.coriolis_coupling,
                         *result.stresses);
    result.stress_history_s = std::chrono::duration<double>(clock::now() - t_history).count();
  }
  return result;
}

RomEvaluation evaluateRomOutcome(const ModalInterpolator& interpolator,
                                 const RomEvaluationInput& input) {
  std::optional<ModalStressEvaluator> evaluator;
  return evaluateOutcome(interpolator, input, evaluator);
}

void streamRomOutputs(RomEvaluation& evaluation, const RomEvaluationInput& input,
                      std::size_t block_rows, const ModalSeriesBlockSink& series,
                      const StressHistoryBlockSink& histories) {
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(input.config));
  const auto t_series = clock::now();
  const SampledDrive sampled = sampleDrive(drive, evaluation.options);
  streamModalDeployment(evaluation.model, sampled, evaluation.options.coriolis_coupling, series,
                        block_rows);
  const auto t_history = clock::now();
  evaluation.deployment_s = std::chrono::duration<double>(t_history - t_series).count();
  if (evaluation.stresses && input.stress_history) {
    const ModalStressEvaluator evaluator(evaluation.model);
    streamModalStressHistories(evaluation.model, evaluator, sampled,
                               evaluation.options.coriolis_coupling, histories);
    evaluation.stress_history_s = std::chrono::duration<double>(clock::now() - t_history).count();
  }
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
