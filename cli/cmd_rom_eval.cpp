// `mastrom rom eval` (see cmd_rom_eval.hpp).
#include "cli/cmd_rom_eval.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>

#include "cli/cli_common.hpp"
#include "cli/interrupt.hpp"
#include "cli/output_step_note.hpp"
#include "cli/resource_estimates.hpp"
#include "cli/rom_eval_output.hpp"
#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "fullorder/interface_stress_io.hpp"
#include "fullorder/mast_mass.hpp"
#include "fullorder/results_io.hpp"
#include "rom/database/database_io.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/interpolation/point_error_estimate.hpp"
#include "rom/studies/default_output_step.hpp"
#include "rom/studies/rom_evaluation.hpp"

namespace mastrom::cli {
namespace {

/// The design's mass and natural frequencies (docs/theory.md §1.7), two lines.
void printDesignDescription(const rom::EvaluationDescription& d, double deployed_deg) {
  const fullorder::MastMass& m = d.values.mass;
  std::printf("  mass %.6g kg: modules", m.total_kg);
  for (const double x : m.module_kg) std::printf(" %.6g", x);
  std::printf(", interfaces");
  for (const double x : m.interface_kg) std::printf(" %.6g", x);
  std::printf(" kg\n");
  if (d.values.frequency_hz.empty()) {
    std::printf("  natural frequencies at the deployed angle: none (%s)\n",
                d.columns.no_frequency_reason.c_str());
    return;
  }
  std::printf(
      "  natural frequencies of the mast locked at the deployed angle %.6g deg "
      "(the database's estimate of the error, docs/theory.md (4.15)):",
      deployed_deg);
  for (std::size_t k = 0; k < d.values.frequency_hz.size(); ++k) {
    const double e = d.values.frequency_error[k];
    if (e >= 0)
      std::printf("%s %.6g Hz +- %.2g %%", k ? "," : "", d.values.frequency_hz[k], 100.0 * e);
    else
      std::printf("%s %.6g Hz (no estimate)", k ? "," : "", d.values.frequency_hz[k]);
  }
  std::printf("\n");
}

}  // namespace

void runEval(const EvalArguments& args) {
  const auto start = std::chrono::steady_clock::now();
  const rom::RomDatabase db = rom::readDatabase(args.database);
  const rom::InterpolationMethod method =
      rom::interpolationMethodOr(args.method, db.default_method, "--method");
  rom::RomEvaluationInput input = rom::romEvaluationInput(
      db, args.overrides, args.extrapolate ? rom::BoxPolicy::Extrapolate : rom::BoxPolicy::Refuse);
  input.stresses = !args.no_stresses;
  input.stress_history = args.stress_history;
  const Config& config = input.config;
  const std::vector<double>& point = input.point;
  if (!args.output.empty()) h5::checkWritable(args.output);
  const std::unique_ptr<rom::ModalInterpolator> interpolator = rom::makeInterpolator(db, method);
  // An unset output.step is chosen from the interpolated model's response (docs/theory.md §5.4a)
  // before the estimate, which then counts the chosen step's samples.
  const std::optional<rom::OutputStepChoice> step =
      rom::resolveRomOutputStep(input.config, interpolator->evaluate(point),
                                rom::romOutputBytesPerSample(config, !args.no_stresses));
  // The metrics' pass steps at the coarser of the screen's step and the output step
  // (rom/studies/rom_evaluation.cpp).
  const double metrics_step_s =
      std::max(input.metrics_step_s, rom::deploymentOptionsFromConfig(config).step_s);
  requireResources(
      romEvalEstimate(config, metrics_step_s, fileBytes(args.database), !args.no_stresses),
      args.output, args.allow_large);
  const rom::BoxPolicy box =
      args.extrapolate ? rom::BoxPolicy::Extrapolate : rom::BoxPolicy::Refuse;
  rom::FrequencyRequest frequencies;
  if (args.frequencies) frequencies = {*args.frequencies, true, "--frequencies"};
  // The screen's metrics (rom/studies/rom_evaluation.hpp): sample RMS and settling, peaks of the
  // continuous response — the same numbers as `mastrom screen` for this design. The outputs (the
  // series, the stress history) are stepped only for the file, while it is written, never held.
  rom::RomEvaluation evaluation = rom::evaluateRomOutcome(*interpolator, input);
  const rom::ModalModel& model = evaluation.model;
  const rom::ModalDeploymentOptions& options = evaluation.options;
  const fullorder::DeploymentMetrics& metrics = evaluation.metrics;
  const rom::EvaluationDescription design =
      rom::describeEvaluation(db, *interpolator, input, model, frequencies, box);
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::printf("mastrom rom eval: %s, %zu samples x %d modes, method %s\n", args.database.c_str(),
              db.samples.size(), db.modes_per_sample, rom::toString(method).c_str());
  std::printf("  %s\n", outputStepNote(step, config).c_str());
  std::printf("  point:");
  for (std::size_t a = 0; a < db.axes.size(); ++a)
    std::printf("%s %s = %.6g %s", a ? "," : "", db.axes[a].key.c_str(), point[a],
                rom::configKeyUnits(db.axes[a].key).c_str());
  std::printf("%s\n", db.contains(point) ? "" : "  (OUTSIDE the sampled box: extrapolated)");
  std::printf("  lowest frequencies:");
  for (int k = 0; k < std::min(model.modeCount(), 4); ++k)
    std::printf(" %.2f", model.omega_rad_s[k] / (2.0 * 3.14159265358979323846));
  std::printf(" Hz\n");
  printDesignDescription(design, config.drive.angle_deg);
  const auto [loo_f, loo_r] = rom::databaseErrorEstimate(db);
  if (loo_f >= 0) {
    std::printf(
        "  database error estimate (%s; %s): omega_1 %.3g %%, "
        "NRMSE of the relative end angular acceleration %.3g %% (reference deployment)\n",
        rom::toString(db.default_method).c_str(),
        !db.estimate_from_probes ? "leave-one-out between samples, or affine at the samples"
        : db.isGrid()            ? "measured at held-out cell centres"
                                 : "worst of the held-out probes",
        100.0 * loo_f, 100.0 * loo_r);
    const auto [point_f, point_r] = rom::pointErrorEstimate(db, point);
    if (point_r >= 0 && method == db.default_method && db.isGrid())
      std::printf(
          "  estimated at this point (the error measured at its cell's centre, scaled by "
          "the node polynomials, docs/theory.md (4.13)): omega_1 %.3g %%, NRMSE %.3g %%\n",
          100.0 * point_f, 100.0 * point_r);
    if (point_r >= 0 && method == db.default_method && !db.isGrid())
      std::printf(
          "  estimated at this point (the power function times the probes' scale, "
          "docs/theory.md (4.14)): NRMSE %.3g %% typical (omega_1 %.3g %%), up to "
          "%.3g %% at the least favourable scale a probe met\n",
          100.0 * point_r, 100.0 * point_f, 100.0 * rom::pointErrorUpperEstimate(db, point).second);
    if (method == rom::InterpolationMethod::Cubic &&
        db.default_method != rom::InterpolationMethod::Cubic)
      std::printf(
          "  (that estimate is the %s method's; the cubic weights are far more accurate "
          "where the data are smooth: rom build prints their own leave-one-out estimate "
          "when an axis has >= 5 samples, docs/theory.md §4.4)\n",
          rom::toString(db.default_method).c_str());
  }
  std::printf("  drive %s, %.1f deg in %.3f s; %.3f s with output step %.3g s (%zu samples)\n",
              toString(config.drive.law).c_str(), config.drive.angle_deg, config.drive.duration_s,
              options.end_time_s, options.step_s, evaluation.output_samples);
  if (evaluation.metrics_step_s != options.step_s)
    std::printf(
        "  metrics of the continuous response stepped at %.3g s, a screen's step (their "
        "accuracy: rom/model/deployment_metrics.hpp; --set output.step=... steps them at "
        "the output step)\n",
        evaluation.metrics_step_s);
  // The evaluation (what the metrics and stress peaks printed below cost); the outputs are
  // computed only to be written (their time follows the file's line).
  std::printf("  interpolation %.1f us, metrics %.1f us, stress peaks %.1f us\n",
              1e6 * evaluation.interpolation_s, 1e6 * evaluation.metrics_s,
              1e6 * evaluation.stress_s);
  std::printf("metrics (README.md \"Outputs and units\"; the file stores SI units):\n");
  printDeploymentMetrics(metrics);
  if (evaluation.stresses) {
    std::printf(
        "interface stresses (modal recovery, mode-acceleration form, docs/theory.md §6.5; "
        "%s):\n",
        input.stress_history ? "peaks and the history at every sample"
                             : "peaks; the history at every sample with --stress-history");
    fullorder::printInterfaceStressSummary(*evaluation.stresses, config.material.yield_strength_pa);
    printStressMeshWarning(config.interface.elements_axial);
  } else if (args.no_stresses) {
    std::printf("interface stresses: skipped (--no-stresses)\n");
  } else {
    std::printf("interface stresses: not available (the database carries no stress modes: %s)\n",
                (db.default_method == rom::InterpolationMethod::Affine ||
                 method == rom::InterpolationMethod::Affine) &&
                        db.affine && db.affine->stress_rows.size() == 0 && !db.samples.empty() &&
                        !db.samples.front().modal.stress.empty()
                    ? "its affine terms were written by an earlier mastrom without the basis's "
                      "stress rows; rebuild it, or choose another method with --method"
                    : "built with --no-stresses or by an earlier mastrom; rebuild it without "
                      "--no-stresses");
  }
  if (!args.output.empty()) {
    // SIGINT / SIGTERM end the series at the next block, the file marked incomplete.
    const RomEvaluationFileSummary written = writeStreamedRomEvaluationFile(
        args.output, evaluation, input, toToml(config), wall, config.material.yield_strength_pa,
        [&](h5::File& file) { writeOutputStepAttributes(file, step, config); },
        [] { return interruptRequested(); });
    if (written.stopped_at_s) {
      std::fflush(stdout);
      throw Interrupted(detail::concat("rom eval: interrupted at t = ", *written.stopped_at_s,
                                       " s; wrote the ", written.samples,
                                       " output samples up to it to ", args.output,
                                       ", marked incomplete (root attribute complete = 0)"));
    }
    std::printf("wrote %s (output series stepped and written in %.1f us", args.output.c_str(),
                1e6 * evaluation.deployment_s);
    if (input.stress_history)
      std::printf(", stress history %.1f us", 1e6 * evaluation.stress_history_s);
    std::printf(")\n");
  }
  std::fflush(stdout);
}

}  // namespace mastrom::cli
