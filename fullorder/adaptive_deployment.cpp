// simulateDeployment() with error-controlled variable steps (docs/theory.md §5.3, §5.4).
//
// Each step is tried to t + h (or to the next drive breakpoint or the end, whichever comes first;
// a step within 10 % of a breakpoint is stretched to land on it), its local error estimated
// (fullorder/step_control.hpp), and the step accepted or taken back. At a breakpoint the integrator
// and the estimate restart (GeneralizedAlpha::restartAtDiscontinuity), so no step or difference
// ever spans a jump of θ̈ or θ⃛ (the sample at a breakpoint has the right limits). The outputs are
// recorded at every accepted step point — the index-1 accelerations and multipliers, deferred into
// the next step on two threads as in the fixed-step loop — and interpolated onto the output grid at
// the end (fullorder/continuous_response.hpp).
#include <algorithm>
#include <cmath>
#include <limits>

#include "common/error.hpp"
#include "fullorder/continuous_response.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/deployment_system.hpp"
#include "fullorder/thread_tuner.hpp"

namespace mastrom::fullorder {

namespace {

/// The drive's breakpoints strictly inside (0, end), then the end itself. A breakpoint less than
/// the smallest step after the stop before it (or 0), or before the end, is dropped: no step could
/// land between the two, so its jump falls inside one step, as in a fixed-step run.
std::vector<double> stopTimes(const MastModel& model, double end_time_s, double min_step_s) {
  std::vector<double> stops;
  for (double t : model.baseJoint().driveLaw().breakpoints()) {
    const double previous = stops.empty() ? 0.0 : stops.back();
    if (t - previous >= min_step_s && t < end_time_s - min_step_s) stops.push_back(t);
  }
  stops.push_back(end_time_s);
  return stops;
}

/// The module coordinates' velocities v less those of the mast turning rigidly with the drive at
/// rate θ̇ about Z through the origin (docs/theory.md §2.4): v − θ̇ Z × x for every 3-block of
/// the coordinates x (two points and two direction vectors per module, §2.2). The step control's
/// velocity criterion is scaled by their peak (fullorder/step_control.hpp).
void vibrationVelocities(const Eigen::VectorXd& x, const Eigen::VectorXd& v, double rate_rad_s,
                         Eigen::VectorXd& out) {
  out.resize(x.size());
  for (Eigen::Index b = 0; b + 2 < x.size(); b += 3) {
    out[b] = v[b] + rate_rad_s * x[b + 1];
    out[b + 1] = v[b + 1] - rate_rad_s * x[b];
    out[b + 2] = v[b + 2];
  }
}

}  // namespace

DeploymentSeries simulateAdaptiveDeployment(MastModel& model, const DeploymentOptions& options,
                                            DeploymentStatistics* statistics,
                                            const DeploymentProgress& progress,
                                            const DeploymentCheckpoint* resume) {
  MASTROM_REQUIRE(std::isfinite(options.output_step_s) && options.output_step_s > 0.0, InputError,
                  "output.step = ", options.output_step_s, " s must be > 0");
  MASTROM_REQUIRE(std::isfinite(options.checkpoint_every_s) && options.checkpoint_every_s >= 0.0,
                  InputError, "checkpoint interval = ", options.checkpoint_every_s,
                  " s must be >= 0");
  const double end_time = options.end_time_s;
  const bool index1_outputs = options.integrator.recover_index1_accelerations;
  GeneralizedAlphaOptions stepping = options.integrator;
  stepping.recover_index1_accelerations = false;
  stepping.time_step_s = options.step_control.initial_step_s;
  DeploymentSystem system(model, options.eliminate_linear_constraints);
  GeneralizedAlpha integrator(system.dae(), stepping);
  system.initialize(integrator, options.start_in_equilibrium && resume == nullptr);

  std::vector<int> monitored;
  Eigen::VectorXd weight;
  system.moduleCoordinates(monitored, weight);
  StepControlOptions control_options = options.step_control;
  control_options.error_constant = generalizedAlphaErrorConstant(options.integrator.rho_inf);
  StepController controller(control_options, weight);
  // y: the index-1 accelerations of the module coordinates; v: their vibration velocities.
  const auto size = static_cast<Eigen::Index>(monitored.size());
  Eigen::VectorXd y(size), x(size), xdot(size), v(size), local_error;
  const auto monitor = [&](const DaeState& state) -> const Eigen::VectorXd& {
    for (Eigen::Index i = 0; i < size; ++i) {
      const int k = monitored[static_cast<std::size_t>(i)];
      y[i] = state.qddot_index1[k];
      x[i] = state.q[k];
      xdot[i] = state.qdot[k];
    }
    vibrationVelocities(x, xdot, model.baseJoint().driveAt(state.time_s).rate_rad_s, v);
    return y;
  };
  const std::vector<double> stops = stopTimes(model, end_time, control_options.min_step_s);
  DeploymentSeries steps;
  std::vector<long> piece_starts;
  DeploymentStatistics stats;
  if (resume) {
    MASTROM_REQUIRE(!resume->series.empty() && !resume->piece_starts.empty() &&
                        resume->integrator.state.time_s < end_time,
                    InputError, "simulate: the checkpoint (step ", resume->step,
                    ") does not fit this adaptive run");
    integrator.restore(resume->integrator);
    controller.restore(resume->controller);
    steps = resume->series;
    piece_starts = resume->piece_starts;
    stats = resume->statistics;
  }

  DaeState index3_view;  // simulation.accelerations = "index3": the scheme's own q̈ and λ
  const auto record = [&](const DaeState& state, int iterations, double constraint_residual,
                          bool piece_start) {
    const DaeState* source = &state;
    if (!index1_outputs) {
      index3_view = state;
      index3_view.qddot_index1.resize(0);
      index3_view.lambda_index1.resize(0);
      source = &index3_view;
    }
    const DaeState& full = system.full(*source);
    const DeploymentSample sample =
        sampleDeploymentState(model, full, iterations, constraint_residual);
    if (options.state_observer)
      options.state_observer(full, system.fullVelocities(state), piece_start);
    MASTROM_REQUIRE(sample.end_angular_acceleration_rad_s2.allFinite() &&
                        sample.joint_force_n.allFinite() && std::isfinite(sample.joint_torque_nm),
                    NumericalError, "simulate: non-finite output at t = ", sample.time_s, " s");
    steps.append(sample);
  };
  if (!resume) {
    integrator.updateIndexOneAccelerations();
    record(integrator.state(), 0, 0.0, true);
    piece_starts.push_back(0);
    controller.restart(0.0, monitor(integrator.state()), v);
  }

  double t = integrator.state().time_s;
  std::size_t next_stop = 0;
  while (next_stop < stops.size() && stops[next_stop] <= t) ++next_stop;
  double next_checkpoint = t;
  if (options.checkpoint_every_s > 0.0)
    next_checkpoint = options.checkpoint_every_s * (std::floor(t / options.checkpoint_every_s) + 1);
  ThreadTuner tuner(model.system().threadCount(), options.thread_tuning);
  const ThreadCountRestorer restore_threads(model.system());
  const auto set_threads = [&model](int threads) { model.system().setThreadCount(threads); };
  while (t < end_time) {
    const TunedStep timed(tuner, set_threads);  // this pass of the loop, rejected or not
    // The controller's step, set exactly (t1 = t + h is then the instant the pipelined evaluation
    // of the previous step predicted, whenever the step is kept).
    integrator.setStepSize(controller.step());
    const double h = integrator.stepSize();
    const double stop = stops[next_stop];
    const bool at_stop = t + kBreakpointStretch * h >= stop;
    const double t1 = at_stop ? stop : t + h;
    StepReport report;
    try {
      report = integrator.stepTo(t1);
    } catch (const NumericalError& e) {
      // Newton failed: the integrator is back at t; a shorter step usually converges.
      ++stats.rejected_steps;
      try {
        controller.reject(std::numeric_limits<double>::infinity(), t1 - t, t);
      } catch (const NumericalError&) {
        throw NumericalError(detail::concat(e.what(), " (also at the smallest step allowed, ",
                                            control_options.min_step_s, " s)"));
      }
      continue;
    }
    // The estimate reads the index-1 accelerations: the index-3 q̈ of generalized-α carries the
    // scheme's parasitic root (−α_m/(1−α_m) per step, not small as h → 0), which a third difference
    // amplifies 8-fold and no step size removes (docs/theory.md §5.3).
    integrator.updateIndexOneAccelerations();
    const Eigen::VectorXd& y1 = monitor(integrator.state());
    // A step landing on a breakpoint has the drive's right limits in its accelerations: it is not
    // estimated (it is at most 1.1 times the nominal step, whose error the steps before it had).
    const bool at_breakpoint = at_stop && next_stop + 1 < stops.size();
    double err = 0.0, velocity_error = 0.0;
    Eigen::Vector2d error_parts = Eigen::Vector2d::Zero();
    local_error.setZero(y1.size());
    if (controller.canEstimate() && !at_breakpoint)
      err = controller.estimate(t1, y1, v, local_error, velocity_error, &error_parts);
    if (err > 1.0 && controller.noiseLimited(t, t1 - t, err)) {
      // Round-off (cutting the step did not reduce the error) or a step that cannot be cut:
      // accepted, and later estimates measured against this floor (it decays; docs/theory.md §5.3).
      ++stats.noise_limited_steps;
      controller.acceptAtNoiseFloor(local_error, velocity_error, error_parts);
      err = 1.0;
    }
    if (err > 1.0) {
      integrator.rejectStep();
      ++stats.rejected_steps;
      controller.reject(err, t1 - t, t);
      continue;
    }
    const double h_taken = t1 - t;
    controller.accept(t1, y1, v, err, h_taken);
    t = t1;
    ++stats.steps;
    stats.newton_iterations += report.iterations;
    stats.max_constraint_residual =
        std::max(stats.max_constraint_residual, report.constraint_residual);
    stats.min_step_s = stats.steps == 1 ? h_taken : std::min(stats.min_step_s, h_taken);
    stats.max_step_s = std::max(stats.max_step_s, h_taken);

    if (at_stop && next_stop + 1 < stops.size()) {
      // A breakpoint of the drive: restart with its right limits; that state opens a new piece.
      integrator.restartAtDiscontinuity();
      record(integrator.state(), report.iterations, report.constraint_residual, true);
      piece_starts.push_back(static_cast<long>(steps.size()) - 1);
      controller.restart(t, monitor(integrator.state()), v);
      ++next_stop;
    } else {
      record(integrator.state(), report.iterations, report.constraint_residual, false);
    }
    // Every step: the receiver limits itself by wall time, and an interrupt (which the progress
    // callback raises) then stops the run within one step however slowly time advances.
    if (progress) {
      stats.factorizations = integrator.factorizations();
      stats.single_thread_steps = tuner.singleThreadSteps();
      progress(t, end_time, stats);
    }
    const bool checkpoint_due =
        (options.checkpoint_every_s > 0.0 && t >= next_checkpoint) ||
        (options.checkpoint_every_steps > 0 && stats.steps % options.checkpoint_every_steps == 0);
    if (options.checkpoint_sink && checkpoint_due && t < end_time) {
      DeploymentCheckpoint checkpoint;
      checkpoint.step = stats.steps;
      checkpoint.integrator = integrator.snapshot();
      checkpoint.statistics = stats;
      checkpoint.statistics.factorizations = integrator.factorizations();
      checkpoint.controller = controller.state();
      checkpoint.piece_starts = piece_starts;
      checkpoint.series = std::move(steps);
      options.checkpoint_sink(checkpoint);
      steps = std::move(checkpoint.series);
      if (options.checkpoint_every_s > 0.0)
        next_checkpoint =
            options.checkpoint_every_s * (std::floor(t / options.checkpoint_every_s) + 1);
    }
  }
  stats.factorizations = integrator.factorizations();
  stats.single_thread_steps = tuner.singleThreadSteps();

  const DriveAt drive = [&model](double time) { return model.baseJoint().driveAt(time); };
  const StepPoints points{steps, piece_starts};
  stats.continuous_peaks =
      continuousPeaks(points, model.baseJoint().driveLaw().parameters().duration_s, drive);
  stats.has_continuous_peaks = true;
  stats.step_times_s = steps.time_s;
  for (long start : piece_starts) stats.piece_start_times_s.push_back(steps.time_s[start]);
  if (statistics) *statistics = std::move(stats);
  return resampleStepPoints(points, options.output_step_s, drive);
}

}  // namespace mastrom::fullorder
