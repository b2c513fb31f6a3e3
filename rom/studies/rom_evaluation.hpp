// One deployment from a ROM database, start to finish: the configuration of the evaluation (the
// database's base configuration with `--set`-style overrides), its point in the parameter box, the
// interpolated modal model, the deployment's time series and its metrics. `mastrom rom eval` and
// the Python module's RomDatabase.evaluate both run these two functions, so they agree bit for bit.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "common/config.hpp"
#include "fullorder/deployment_result.hpp"
#include "fullorder/interface_stress.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/database/rom_database.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/model/modal_model.hpp"
#include "rom/model/modal_stress_response.hpp"
#include "rom/model/output_resolution.hpp"
#include "rom/studies/design_description.hpp"
#include "rom/studies/design_metrics.hpp"

namespace mastrom::rom {

/// What one evaluation asks for.
struct RomEvaluationInput {
  Config config;              ///< database base configuration + overrides, validated
  std::vector<double> point;  ///< one value per database axis
  /// Recover the interfaces' stresses too (when the database carries stress modes): their peaks,
  /// where and when, and the margins.
  bool stresses = true;
  /// ... and the largest von Mises of every interface at every output sample (most of the
  /// stresses' cost; rom/model/modal_stress_response.hpp).
  bool stress_history = false;
  /// The step [s] of the metrics' pass (their continuous peaks, RMS and settling), a screen's
  /// (screenStep) unless the overrides set the output interval; ≤ 0: the output step.
  double metrics_step_s = 0.0;
};

/// evaluationConfig + parameterPoint + requireInsideBox: every input error of an evaluation
/// (InputError, one line) before any work.
RomEvaluationInput romEvaluationInput(const RomDatabase& db,
                                      const std::vector<std::string>& overrides, BoxPolicy box);

struct RomEvaluation {
  ModalModel model;                    ///< interpolated at the point
  ModalDeploymentOptions options;      ///< end time and output step of the deployment
  /// The output step chosen from the model's response (docs/theory.md §5.4a) when the input's
  /// output.step was unset; empty when it was set.
  std::optional<OutputStepChoice> output_step;
  fullorder::DeploymentSeries series;  ///< the samples (empty from evaluateRomOutcome)
  std::size_t output_samples = 0;      ///< how many: t = 0, step, …, end time
  /// Peaks and residual of the continuous response, its exact RMS and continuous settling
  /// (rom/model/deployment_metrics.hpp), stepped at metrics_step_s: the same numbers a screen
  /// gives for this design.
  fullorder::DeploymentMetrics metrics;
  /// The interfaces' stresses (rom/model/modal_stress_response.hpp), when asked and the database
  /// carries stress modes: the peaks of the continuous response found on the metrics' grid (each
  /// with its field at the peak's instant), and the histories on the series' instants when
  /// RomEvaluationInput::stress_history.
  std::optional<fullorder::InterfaceStressResult> stresses;
  double metrics_step_s = 0.0;  ///< the step of the metrics' pass [s]
  /// Wall times. The evaluation, what the metrics and the stress peaks cost: the interpolation;
  /// the metrics' pass (with the choice of the output step and the drive's sampling on its grid,
  /// and the recording or streaming of the stresses' states); the stress peaks (their search,
  /// refinement and fields). Outputs apart: the series at every output sample (`deployment_s`: the
  /// drive sampled on the output grid and the stepping) and the stress histories (a stepping pass
  /// of their own).
  double interpolation_s = 0.0, deployment_s = 0.0, metrics_s = 0.0, stress_s = 0.0,
         stress_history_s = 0.0;
};

/// Bytes per output instant of an evaluation's result file, for the cap of a default output step.
double romOutputBytesPerSample(const Config& config, bool stresses);

/// The deployment of `input` with `interpolator` (made from the same database). An unset
/// output.step is chosen from the interpolated model's response
/// (rom/studies/default_output_step.hpp).
RomEvaluation evaluateRomDeployment(const ModalInterpolator& interpolator,
                                    const RomEvaluationInput& input);

/// evaluateRomDeployment without its outputs: the interpolated model, the options, the metrics and
/// the stress peaks — what is printed — with `series` and the stress histories left empty (and
/// their times 0). streamRomOutputs then produces them without holding them.
RomEvaluation evaluateRomOutcome(const ModalInterpolator& interpolator,
                                 const RomEvaluationInput& input);

/// The outputs of `evaluation` (evaluateRomOutcome of `input`) as they are stepped: the series to
/// `series` in blocks of at most `block_rows` rows, then, with input.stress_history and stresses,
/// the histories to `histories` (a block of samples at a time). Bit for bit the series and
/// histories evaluateRomDeployment holds; memory does not grow with the samples. Sets
/// evaluation.deployment_s and stress_history_s. An exception a sink throws ends the stepping.
void streamRomOutputs(RomEvaluation& evaluation, const RomEvaluationInput& input,
                      std::size_t block_rows, const ModalSeriesBlockSink& series,
                      const StressHistoryBlockSink& histories);

/// The mass and natural frequencies of an evaluated design (rom/studies/design_description.hpp):
/// `values` holds them (its other fields unset), `columns` says which frequencies there are or why
/// there are none.
struct EvaluationDescription {
  MetricColumns columns;
  DesignValues values;
};

/// The description of the design of `input` whose interpolated model is `model` (an evaluation's),
/// deployed to the configuration's drive.angle_deg. InputError for a frequency request the
/// database cannot meet (explicit requests only; see FrequencyRequest).
EvaluationDescription describeEvaluation(const RomDatabase& db,
                                         const ModalInterpolator& interpolator,
                                         const RomEvaluationInput& input, const ModalModel& model,
                                         const FrequencyRequest& request, BoxPolicy box);

}  // namespace mastrom::rom
