// `mastrom simulate CONFIG [--set k=v]… [-o FILE.h5] [--checkpoint-every N [--checkpoint CKPT.h5]]
// [--restart CKPT.h5] [--estimate-error]`: one nonlinear full-order deployment (docs/theory.md §5).
// Prints the model size, the steps taken and the metrics; writes the result file (README "Files")
// atomically. The output path is checked before
// the run starts, so a bad path fails in milliseconds, not after minutes of integration.
//
// Crash safety: --checkpoint-every N writes a checkpoint (fullorder/checkpoint.hpp) every
// N time steps (or "Ts": every T simulated seconds, rounded to whole steps so the checkpoint
// instants are exact step boundaries), atomically over the previous one; --restart continues from
// one and produces datasets bit-for-bit equal to the uninterrupted run's. A finished run deletes
// the checkpoint it wrote. The outputs are streamed to the result file as in a run without
// checkpoints (fixed and adaptive steps): a checkpoint then names the file holding the outputs
// before it (the result under its temporary name), and --restart rebuilds the result from that file
// a block at a time (fullorder/streamed_result_file.hpp rebuildStreamedSeries), so memory stays
// bounded.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/cli_common.hpp"
#include "cli/interrupt.hpp"
#include "cli/output_step_note.hpp"
#include "cli/progress.hpp"
#include "cli/resource_estimates.hpp"
#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "fullorder/checkpoint.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/deployment_accuracy.hpp"
#include "fullorder/interface_stress.hpp"
#include "fullorder/interface_stress_io.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/results_io.hpp"
#include "fullorder/run_footprint.hpp"
#include "fullorder/streamed_result_file.hpp"
#include "modes/slepc_session.hpp"
#include "modes/xdmf_writer.hpp"
#include "rom/studies/default_output_step.hpp"
#include "rom/studies/full_order_check.hpp"

namespace mastrom::cli {
namespace {

struct CheckpointArguments {
  std::string every;           ///< as given: "N" steps or "Ts" simulated seconds
  long every_steps = 0;        ///< resolved once the time step is known
  double every_seconds = 0.0;  ///< adaptive steps with "Ts": every T simulated seconds
  bool active() const { return every_steps > 0 || every_seconds > 0.0; }
  std::string path;
  std::string restart;
};

/// --checkpoint-every: "N" (time steps, N >= 1) or "Ts" (simulated seconds, rounded to whole steps,
/// at least one). Seconds are what a user plans with; steps keep the instants exact either way.
long checkpointIntervalSteps(const std::string& text, double time_step_s) {
  const bool seconds = !text.empty() && text.back() == 's';
  const std::string number = seconds ? text.substr(0, text.size() - 1) : text;
  std::size_t used = 0;
  double value = 0.0;
  bool parsed = !number.empty();
  try {
    value = parsed ? std::stod(number, &used) : 0.0;
  } catch (const std::exception&) {
    parsed = false;
  }
  MASTROM_REQUIRE(parsed && used == number.size() && std::isfinite(value), InputError,
                  "--checkpoint-every = '", text,
                  "' is not a number; allowed: N time steps "
                  "(e.g. 5000) or simulated seconds with the unit s (e.g. 0.5s)");
  if (!seconds) {
    MASTROM_REQUIRE(value >= 1.0 && value == std::floor(value) && value < 1e15, InputError,
                    "--checkpoint-every = ", text, " must be >= 1 (time steps, a whole number)");
    return static_cast<long>(value);
  }
  const double steps = std::round(value / time_step_s);
  MASTROM_REQUIRE(steps >= 1.0 && steps < 1e15, InputError, "--checkpoint-every = ", text,
                  " must be >= one time step (", time_step_s, " s)");
  return static_cast<long>(steps);
}

/// --stress-fields-at: comma-separated instants in [0, end time] [s].
std::vector<double> stressFieldTimes(const std::string& text, double end_time_s) {
  std::vector<double> times;
  std::size_t start = 0;
  while (!text.empty() && start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    const std::string item = text.substr(start, comma - start);
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    MASTROM_REQUIRE(used > 0 && used == item.size() && std::isfinite(value) && value >= 0.0 &&
                        value <= end_time_s,
                    InputError, "--stress-fields-at: '", item,
                    "' is out of range (allowed: times "
                    "in [0, ",
                    end_time_s, "] s, comma-separated)");
    times.push_back(value);
    start = comma + 1;
  }
  return times;
}

/// Where a restarted streamed run finds the outputs before its checkpoint: the file the
/// checkpointed run was writing under its temporary name (a killed run leaves it), else the result
/// that file was renamed to (an interrupted run's, marked incomplete).
std::string streamedSeriesSource(const std::string& series_file) {
  if (std::filesystem::exists(series_file)) return series_file;
  const std::size_t tmp = series_file.rfind(".tmp.");
  return tmp == std::string::npos ? series_file : series_file.substr(0, tmp);
}

/// "run.h5" → "run.checkpoint.h5" (next to the result).
std::string defaultCheckpointPath(const std::string& output) {
  const std::string stem = output.size() > 3 && output.compare(output.size() - 3, 3, ".h5") == 0
                               ? output.substr(0, output.size() - 3)
                               : output;
  return stem + ".checkpoint.h5";
}

}  // namespace

void registerSimulateCommand(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "simulate", "Run one nonlinear full-order deployment (generalized-alpha, index-3 DAE)");
  auto args = std::make_shared<ConfigArguments>();
  auto output = std::make_shared<std::string>();
  auto quiet = std::make_shared<bool>(false);
  addConfigArguments(*command, *args);
  command->add_option(
      "-o,--output", *output,
      "Result file (HDF5; layout in docs/user_guide.md §5); default: [output] file of the config");
  command->add_flag("-q,--quiet", *quiet, "No progress lines on stderr");
  auto estimate = std::make_shared<bool>(false);
  command->add_flag("--estimate-error", *estimate,
                    "Also estimate the discretisation error of the result (NRMSE of the relative "
                    "end angular acceleration, errors of the peaks) from a second run at 8x the "
                    "tolerance (about +50 % time); stored in /metrics");
  auto threads = std::make_shared<int>(0);
  command
      ->add_option("--threads", *threads,
                   "Threads for the shell element forces, at most (results are bit-identical for "
                   "any count; steps run on one thread where that is measured faster, on cores "
                   "shared with other work); default: 2 where the machine has them, 1 under mpirun")
      ->type_name("N");
  auto field_times = std::make_shared<std::string>();
  command
      ->add_option(
          "--stress-fields-at", *field_times,
          "Also store the interfaces' stress fields at these instants [s], comma-separated "
          "(each at the first output instant at or after it); the peaks' fields always")
      ->type_name("T1,T2,...");
  auto no_stresses = std::make_shared<bool>(false);
  command->add_flag("--no-stresses", *no_stresses,
                    "Skip the interface stresses (/interfaces): their evaluation at every output "
                    "instant and their histories in the file (21 doubles per interface and output "
                    "instant)");
  auto allow_large = std::make_shared<bool>(false);
  addAllowLargeFlag(*command, *allow_large);
  auto ckpt = std::make_shared<CheckpointArguments>();
  command
      ->add_option("--checkpoint-every", ckpt->every,
                   "Write a checkpoint every N time steps, or every T seconds of simulated time "
                   "with the unit s (e.g. 0.5s), atomically over the previous one")
      ->type_name("N|Ts");
  command->add_option("--checkpoint", ckpt->path,
                      "Checkpoint file; default: the output name with .h5 -> .checkpoint.h5");
  command->add_option("--restart", ckpt->restart,
                      "Continue from a checkpoint of a run with the same configuration; the result "
                      "equals the uninterrupted run's bit for bit");
  command->callback([args, output, quiet, ckpt, threads, estimate, field_times, no_stresses,
                     allow_large]() {
    Config config = loadConfig(*args);
    const std::string path = output->empty() ? config.output.file : *output;
    h5::checkWritable(path);  // before minutes of work
    // Before anything is built: a typo of 10⁵ modules or a horizon of 10⁹ s is refused here.
    // Every run streams its series (with checkpoints too), so none holds it in memory.
    std::optional<rom::OutputStepChoice> output_step;
    std::optional<modes::SlepcSession> session;
    if (!config.output.step_s && config.simulation.adaptive) {
      // Unset output.step: chosen from the modes at the start configuration (docs/theory.md
      // §5.4a). First the mast alone is checked (one output instant), so that an impossible mast
      // is refused before its modes are solved; the chosen step's series is bounded by the cap.
      ResourceEstimate mast_only = fullorder::simulateEstimate(config, false, false);
      mast_only.result_bytes = 0.0;
      (void)checkResources(mast_only, machineLimits(path), *allow_large);
      if (config.modes.backend == EigenBackendKind::Slepc) session.emplace();
      output_step = rom::resolveFullOrderOutputStep(
          config, fullorder::resultBytesPerSample(fullorder::mastSize(config), !*no_stresses));
    }
    // The first step after each breakpoint, which no error estimate judges, resolves the ringing
    // the drive excites (the same modes; docs/theory.md §5.3); the file's config records it.
    std::string first_step_note;
    if (output_step)
      config.simulation.time_step_s = rom::resolvedFirstStep(config, *output_step, first_step_note);
    const ResourceEstimate footprint =
        fullorder::simulateEstimate(config, false, !*no_stresses, *estimate);
    requireResources(footprint, path, *allow_large);
    if (!ckpt->every.empty() && ckpt->every.back() == 's' && config.simulation.adaptive) {
      // Adaptive steps have no fixed length: checkpoint at the first step on or after each
      // multiple of T (still the same instants in every run of this configuration).
      ckpt->every_seconds = 1e-9 * static_cast<double>(checkpointIntervalSteps(ckpt->every, 1e-9));
    } else {
      ckpt->every_steps = ckpt->every.empty()
                              ? 0
                              : checkpointIntervalSteps(ckpt->every, config.simulation.time_step_s);
    }
    MASTROM_REQUIRE(ckpt->path.empty() || ckpt->active(), InputError, "--checkpoint '", ckpt->path,
                    "' needs --checkpoint-every N");
    const std::string checkpoint_path =
        ckpt->path.empty() ? defaultCheckpointPath(path) : ckpt->path;
    if (ckpt->active()) {
      MASTROM_REQUIRE(std::filesystem::absolute(checkpoint_path).lexically_normal() !=
                          std::filesystem::absolute(path).lexically_normal(),
                      InputError, "--checkpoint '", checkpoint_path,
                      "' is the result file; choose another name");
      h5::checkWritable(checkpoint_path);
    }
    const std::string config_toml = toToml(config);
    std::optional<fullorder::CheckpointFile> resume;
    if (!ckpt->restart.empty()) {
      resume = fullorder::readCheckpointFile(ckpt->restart);
      fullorder::requireSameConfiguration(ckpt->restart, resume->config_toml, config_toml);
    }

    MASTROM_REQUIRE(*threads >= 0, InputError, "--threads = ", *threads,
                    " must be >= 1 (0 or absent: automatic)");
    using namespace fullorder;
    MastModel model = buildMast(mastParametersFromConfig(config));
    model.system().setThreadCount(*threads > 0 ? *threads : defaultThreadCount());
    DeploymentOptions options = deploymentFromConfig(config);
    std::printf(
        "mastrom simulate: %d modules, %d DOFs, %d constraints, %d shell elements, "
        "mass %.4f kg, %d thread%s\n",
        model.moduleCount(), model.dofCount(), model.constraintCount(),
        model.system().elementCount(), model.totalMass(), model.system().threadCount(),
        model.system().threadCount() == 1 ? "" : "s");
    std::printf("  estimated up front: memory %s, result %s\n",
                formatBytes(footprint.memory_bytes).c_str(),
                formatBytes(footprint.result_bytes).c_str());
    std::printf("  %s\n", outputStepNote(output_step, config).c_str());
    if (!first_step_note.empty()) std::printf("  %s\n", first_step_note.c_str());
    if (options.adaptive) {
      std::printf(
          "  drive %s, %.1f deg in %.3f s; %.3f s simulated with adaptive steps "
          "(tolerance %.3g, first step %.3g s, steps in [%.3g, %.3g] s), outputs every "
          "%.3g s\n",
          toString(config.drive.law).c_str(), config.drive.angle_deg, config.drive.duration_s,
          options.end_time_s, options.step_control.tolerance, options.step_control.initial_step_s,
          options.step_control.min_step_s, options.step_control.max_step_s, options.output_step_s);
    } else {
      std::printf(
          "  drive %s, %.1f deg in %.3f s; %.3f s simulated with fixed dt = %.3g s (%ld "
          "steps)\n",
          toString(config.drive.law).c_str(), config.drive.angle_deg, config.drive.duration_s,
          options.end_time_s, options.integrator.time_step_s,
          static_cast<long>(std::ceil(options.end_time_s / options.integrator.time_step_s - 1e-9)));
    }
    if (resume) {
      std::printf("  restarting from %s at step %ld (t = %.6g s)\n", ckpt->restart.c_str(),
                  resume->checkpoint.step, resume->checkpoint.integrator.state.time_s);
    }
    if (ckpt->every_seconds > 0.0) {
      std::printf("  checkpoint every %.4g s simulated to %s\n", ckpt->every_seconds,
                  checkpoint_path.c_str());
    } else if (ckpt->every_steps > 0) {
      std::printf("  checkpoint every %ld steps to %s\n", ckpt->every_steps,
                  checkpoint_path.c_str());
    }
    std::fflush(stdout);

    ProgressReporter reporter("simulate", 2.0, !*quiet);
    std::optional<StreamedResultFile> stream;
    std::vector<double> streamed_r;  // r for the error estimate (8 bytes per instant)
    // Wall time of the earlier legs of a restarted run, so the file reports the total.
    const double earlier_wall = resume ? resume->wall_time_s : 0.0;
    options.checkpoint_every_steps = ckpt->every_steps;
    options.checkpoint_every_s = ckpt->every_seconds;
    std::string rebuilt_from;  // a restarted streamed run: the file its earlier outputs came from
    if (ckpt->active()) {
      // Streamed, the file holds every output before the checkpoint once it is flushed; its
      // absolute name, so that a restart from another directory finds it.
      options.checkpoint_sink = [&](const DeploymentCheckpoint& c) {
        if (stream) stream->flushSeries();
        writeCheckpointFile(
            checkpoint_path, c, config_toml, earlier_wall + reporter.elapsedSeconds(),
            stream ? std::filesystem::absolute(stream->temporaryPath()).string() : std::string());
        // A restarted run's source was an earlier leg's temporary file: this checkpoint names
        // the file this leg writes, so no later restart reads that one again (a run restarted
        // twice would leave it behind otherwise).
        if (!rebuilt_from.empty() && resume && rebuilt_from == resume->series_file && stream &&
            rebuilt_from != std::filesystem::absolute(stream->temporaryPath()).string()) {
          std::error_code ignored;
          std::filesystem::remove(rebuilt_from, ignored);
          rebuilt_from.clear();
        }
      };
    }
    // Interface stresses (docs/theory.md §6): evaluated at the output instants (fixed steps) or
    // at the first step point after each (adaptive), never at every step. A restarted run has
    // no record of the stresses before its checkpoint, so it writes none.
    std::optional<InterfaceStressMonitor> stress_monitor;
    if (resume) {
      std::printf("  note: a restarted run writes no interface stresses (/interfaces)\n");
    } else if (!*no_stresses) {
      stress_monitor.emplace(stressMonitorFor(model, options));
      stress_monitor->requestFields(stressFieldTimes(*field_times, options.end_time_s));
    }
    // The outputs go to the file as they are computed (fullorder/result_stream.hpp), with
    // checkpoints too (they name the file and the count written). The stress histories go beside
    // them, resampled onto the output instants as the run goes
    // (InterfaceStressMonitor::streamHistories). The error estimate needs only the relative end
    // angular acceleration of the run (8 bytes per instant, kept beside the stream).
    const auto keep_r = [&](const DeploymentSeries& rows) {
      if (*estimate)
        streamed_r.insert(streamed_r.end(), rows.end_relative_angular_acceleration_rad_s2.begin(),
                          rows.end_relative_angular_acceleration_rad_s2.end());
    };
    {
      const std::size_t interfaces =
          stress_monitor ? static_cast<std::size_t>(model.interfaceCount()) : 0;
      stream.emplace(path, config.drive.duration_s,
                     StreamedResultFile::Histories{interfaces, true});
      if (resume) {
        rebuilt_from = streamedSeriesSource(resume->series_file);
        rebuildStreamedSeries(*stream, rebuilt_from,
                              static_cast<std::size_t>(resume->checkpoint.streamed_outputs),
                              resume->checkpoint.series, keep_r);
      }
      if (stress_monitor) stress_monitor->streamHistories(stream->stressRowSink());
      options.output_sink = [&](const DeploymentSample& sample) {
        stream->addSample(sample);
        if (stress_monitor) stress_monitor->outputInstant(sample.time_s);
        if (*estimate)
          streamed_r.push_back(sample.end_angular_acceleration_rad_s2.z() -
                               sample.drive_acceleration_rad_s2);
      };
    }
    // SIGINT / SIGTERM end the integration after the current step; what was computed is then
    // written below, marked incomplete (cli/interrupt.hpp). With the stresses the run stops only
    // at a state the monitor has evaluated (every state offered once the signal is seen), so that
    // the stress histories reach the last output instant too.
    std::atomic<bool> stopping{false};
    options.stop_requested = [&stopping, &stress_monitor, &options] {
      if (stress_monitor && options.adaptive) return stopping.load();
      return interruptRequested();
    };
    if (stress_monitor) {
      options.state_observer = [&stopping, monitor = &*stress_monitor,
                                observe = observeInterfaceStresses(*stress_monitor)](
                                   const DaeState& s, const Eigen::VectorXd& qdot, bool start) {
        observe(s, qdot, start);
        if (!stopping && interruptRequested()) stopping = true;
        if (stopping)
          monitor->evaluate(s.time_s, s.q, qdot,
                            s.qddot_index1.size() == s.q.size() ? s.qddot_index1 : s.qddot);
      };
    }
    DeploymentStatistics stats;
    (void)simulateDeployment(
        model, options, &stats,
        [&reporter](double t, double end, const DeploymentStatistics& s) {
          if (interruptRequested()) return;  // the run stops at once (stop_requested)
          char detail[160];
          std::snprintf(detail, sizeof detail, "t = %.4f / %.4f s, %.2f Newton it/step", t, end,
                        s.steps ? double(s.newton_iterations) / double(s.steps) : 0.0);
          reporter.update(t, end, detail);
        },
        resume ? &resume->checkpoint : nullptr);
    const double wall = earlier_wall + reporter.elapsedSeconds();
    const std::size_t samples = stream->rows();
    const double last_time_s = stream->lastTime();
    DeploymentMetrics metrics = fullOrderMetrics(stream->sampleMetrics(), stats);
    if (*estimate && !stats.stopped_early) {
      ProgressReporter second("simulate (error estimate: 8x tolerance)", 2.0, !*quiet);
      DeploymentOptions second_run = options;
      second_run.state_observer = nullptr;  // the stresses are those of the result itself
      // No monitor to latch the signal in this run: it stops on the signal itself.
      second_run.stop_requested = [] { return interruptRequested(); };
      estimateDiscretisationError(model, second_run, streamed_r, metrics,
                                  [&second](double t, double end, const DeploymentStatistics&) {
                                    second.update(t, end, "");
                                  });
    }
    // An interrupted run stopped at an evaluated state (above), so its stresses reach its last
    // output instant too.
    std::optional<InterfaceStressResult> stresses;
    if (stress_monitor) {
      stress_monitor->finishHistories();
      stresses = stress_monitor->result();  // peaks and fields; the histories are in the file
    }
    const std::optional<double> stopped_at =
        stats.stopped_early ? std::optional<double>(last_time_s) : std::nullopt;
    stream->finish(metrics, config_toml, wall, ResultSource::FullOrder, stopped_at, stresses,
                   config.material.yield_strength_pa,
                   [&](h5::File& file) { writeOutputStepAttributes(file, output_step, config); });
    if (stresses) {
      // The peak fields for ParaView, next to the result ("run.h5" → "run.xdmf").
      writeInterfaceStressXdmf(modes::xdmfPathFor(path),
                               std::filesystem::path(path).filename().string(), *stresses);
    }
    if (stopped_at) {
      // One line, exit code 130 (cli/main.cpp); a checkpoint of the run is kept for --restart.
      throw Interrupted(detail::concat("simulate: interrupted at t = ", *stopped_at,
                                       " s; wrote the ", samples, " output samples computed to ",
                                       path, ", marked incomplete (root attribute complete = 0)"));
    }
    if (ckpt->active()) {
      // The result is complete: a checkpoint of this run can only mislead a later --restart.
      std::error_code ignored;
      std::filesystem::remove(checkpoint_path, ignored);
    }
    if (!rebuilt_from.empty() && resume && rebuilt_from == resume->series_file) {
      // The killed run's temporary file: its outputs are in the result now.
      std::error_code ignored;
      std::filesystem::remove(rebuilt_from, ignored);
    }

    std::printf(
        "  wall time %.2f s = %.3f x simulated time; %ld steps, %.2f Newton "
        "iterations/step, %ld factorisations, max |Phi| %.2e\n",
        wall, wall / options.end_time_s, stats.steps,
        double(stats.newton_iterations) / double(std::max(1L, stats.steps)), stats.factorizations,
        stats.max_constraint_residual);
    if (stats.single_thread_steps > 0)
      std::printf(
          "  %ld of %ld steps (rejected ones included) ran on one thread instead of %d: "
          "one was measured faster (cores shared with other work; the results do not "
          "depend on it)\n",
          stats.single_thread_steps, stats.steps + stats.rejected_steps,
          model.system().threadCount());
    if (stats.speculative_steps > 0)
      std::printf(
          "  %ld steps taken on one thread while the other judged the step before "
          "(docs/theory.md §5.6; the results do not depend on it)\n",
          stats.speculative_steps);
    if (options.adaptive) {
      std::printf("  adaptive steps: %ld rejected, step %.3g ... %.3g s (mean %.3g s)\n",
                  stats.rejected_steps, stats.min_step_s, stats.max_step_s,
                  options.end_time_s / double(std::max(1L, stats.steps)));
      if (stats.first_step_s > 0.0 && stats.first_step_s < options.step_control.initial_step_s)
        std::printf("  first steps of each piece at most %.3g s, not %.3g s: the tolerance on the lowest "
                    "mode the drive excites (docs/theory.md §5.3, \"The first steps of a piece\")\n",
                    stats.first_step_s, options.step_control.initial_step_s);
      if (stats.noise_limited_steps > 0)
        std::printf(
            "  %ld steps accepted above the tolerance, at the round-off floor of the error "
            "estimate or at simulation.min_time_step\n",
            stats.noise_limited_steps);
      // Steps held near the shortest allowed mean a vibration at the round-off of the outputs
      // (docs/theory.md §5.3a): there the result's error is not the tolerance's, and at rho_inf
      // near 1 round-off content of the stiff shell modes survives such steps into r.
      const double mean_step_s = options.end_time_s / double(std::max(1L, stats.steps));
      if (mean_step_s < 2.0 * options.step_control.min_step_s)
        std::printf(
            "  warning: the mean step %.3g s is within 2x simulation.min_time_step: the vibration "
            "is at the round-off of the outputs, and the relative end angular acceleration may be "
            "off by more than the tolerance says (on the camera mast's first 0.05 s with its "
            "motor profile, rho_inf = %.2g: about 50 %%); compare with --set simulation.rho_inf=0 "
            "(docs/theory.md §5.3a)\n",
            mean_step_s, options.integrator.rho_inf);
    }
    std::printf("metrics (the file stores SI units):\n");
    printDeploymentMetrics(metrics);
    if (stresses) {
      std::printf(
          "interface stresses (docs/theory.md §6; %zu evaluations, %.2f s = %.1f %% of the "
          "run):\n",
          stress_monitor->evaluationCount(), stress_monitor->evaluationSeconds(),
          100.0 * stress_monitor->evaluationSeconds() / std::max(1e-9, wall));
      printInterfaceStressSummary(*stresses, config.material.yield_strength_pa);
      printStressMeshWarning(config.interface.elements_axial);
    }
    std::printf("wrote %s\n", path.c_str());
    if (stresses)
      std::printf("wrote %s (interface stress fields at their peaks, for ParaView)\n",
                  modes::xdmfPathFor(path).c_str());
  });
}

}  // namespace mastrom::cli
