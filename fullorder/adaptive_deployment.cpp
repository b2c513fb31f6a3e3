// simulateDeployment() with error-controlled variable steps (docs/theory.md §5.3, §5.4).
//
// Each step is tried to t + h (or to the next drive breakpoint or the end, whichever comes first;
// a step within 10 % of a breakpoint is stretched to land on it), its local error estimated
// (fullorder/step_control.hpp), and the step accepted or taken back. At a breakpoint the integrator
// and the estimate restart (GeneralizedAlpha::restartAtDiscontinuity), so no step or difference
// ever spans a jump of θ̈ or θ⃛ (the sample at a breakpoint has the right limits). The outputs are
// recorded at every accepted step point — the index-1 accelerations and multipliers, deferred into
// the next step on two threads as in the fixed-step loop — and interpolated onto the output grid at
// the end (fullorder/continuous_response.hpp), or, streamed, while the steps go
// (fullorder/step_point_stream.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "common/error.hpp"
#include "fullorder/continuous_response.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/deployment_system.hpp"
#include "fullorder/drive_compliance.hpp"
#include "fullorder/step_point_stream.hpp"
#include "fullorder/thread_tuner.hpp"
#include "fullorder/two_threads.hpp"
#include "fullorder/work_offer.hpp"

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

/// The extent of the modules' points (the first two 3-blocks of each module's coordinates,
/// fullorder/ncf_body.hpp) in the undeformed start state [m], from the model alone, so that a run
/// and its restart see the same values.
struct ModuleExtent {
  double radius_m = 0.0;  ///< the largest distance from the joint axis (Z through the origin)
  /// The largest magnitude a point's coordinate takes while the mast turns about Z: per point
  /// max(√(x² + y²), |z|). Its ulp is the rounding of the state (docs/theory.md §5.3b); the
  /// direction vectors' coordinates, weighted by the module side, are smaller.
  double largest_coordinate_m = 0.0;
};

ModuleExtent moduleExtent(const MastModel& model) {
  Eigen::VectorXd q, qdot;
  model.initialState(q, qdot);
  ModuleExtent extent;
  for (int k = 0; k < model.moduleCount(); ++k)
    for (int p = 0; p < 6; p += 3) {
      const int i = model.moduleDofOffset(k) + p;
      const double radius = std::hypot(q[i], q[i + 1]);
      extent.radius_m = std::max(extent.radius_m, radius);
      extent.largest_coordinate_m =
          std::max({extent.largest_coordinate_m, radius, std::abs(q[i + 2])});
    }
  return extent;
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
  StepControlOptions control_options = options.step_control;
  control_options.error_constant = generalizedAlphaErrorConstant(options.integrator.rho_inf);
  const DriveCompliance compliance = driveCompliance(model);
  // The first steps of each piece, unjudged, held to the tolerance on the lowest mode the drive
  // excites (docs/theory.md §5.3, "The first steps of a piece").
  control_options.initial_step_s =
      unjudgedStepBound(control_options, compliance.rayleigh_frequency_rad_s);
  GeneralizedAlphaOptions stepping = options.integrator;
  stepping.recover_index1_accelerations = false;
  stepping.time_step_s = control_options.initial_step_s;
  DeploymentSystem system(model, options.eliminate_linear_constraints);
  GeneralizedAlpha integrator(system.dae(), stepping);
  system.initialize(integrator, options.start_in_equilibrium && resume == nullptr);

  std::vector<int> monitored;
  Eigen::VectorXd weight;
  system.moduleCoordinates(monitored, weight);
  {
    // The scales' floors from the drive (docs/theory.md §5.3a): the rigid turn's largest
    // acceleration, and the velocity of the vibration the drive excites — quasi-static under its
    // jerk, ringing after a jump of θ̈.
    const DriveLaw::Excitation drive = model.baseJoint().driveLaw().excitation();
    const ModuleExtent extent = moduleExtent(model);
    control_options.acceleration_scale_floor =
        std::max(control_options.acceleration_scale_floor, extent.radius_m * drive.turn_rad_s2);
    control_options.velocity_scale_floor =
        std::max(control_options.velocity_scale_floor,
                 compliance.module_deflection_m_per_rad_s2 *
                     std::max(drive.jerk_rad_s3,
                              compliance.rayleigh_frequency_rad_s * drive.jump_rad_s2));
    // The velocity criterion's round-off (§5.3b): ulps of the largest coordinate, as a vibration
    // of the lowest mode the drive excites.
    control_options.velocity_roundoff_m_s =
        std::max(control_options.velocity_roundoff_m_s,
                 kVelocityRoundoffUlps * std::numeric_limits<double>::epsilon() *
                     compliance.rayleigh_frequency_rad_s * extent.largest_coordinate_m);
    // The acceleration criterion's round-off (§5.3c): the same rounding read as the scheme's
    // acceleration over a step, δ / (β h²); the controller divides by h².
    control_options.acceleration_roundoff_m = std::max(
        control_options.acceleration_roundoff_m,
        kAccelerationRoundoffUlps * std::numeric_limits<double>::epsilon() *
            extent.largest_coordinate_m / generalizedAlphaBeta(options.integrator.rho_inf));
    control_options.velocity_step_roundoff_m = std::max(
        control_options.velocity_step_roundoff_m,
        kVelocityStepRoundoffUlps * std::numeric_limits<double>::epsilon() *
            extent.largest_coordinate_m * generalizedAlphaGamma(options.integrator.rho_inf) /
            generalizedAlphaBeta(options.integrator.rho_inf));
  }
  StepController controller(control_options, weight);
  if (control_options.velocity_tolerance_share > 0.0) {
    // Newton's iterates (docs/theory.md §5.1, "When Newton stops"): what an iterate still lacks,
    // read as the velocities the step control judges, is accepted up to a share of the smallest
    // scale its velocity criterion can have in this run — the tolerance's share of the floor V₀
    // or twice the round-off V_r, both known before the first step (the run's V and floors only
    // grow), so a speculative or restarted step is judged as the run without them.
    IterateTolerance iterate;
    iterate.coordinates = monitored;
    iterate.weights = weight;
    iterate.velocity_m_s =
        kIterateErrorShare *
        std::max(control_options.velocity_tolerance_share * control_options.tolerance *
                     control_options.velocity_scale_floor,
                 kNoiseFloorMargin * control_options.velocity_roundoff_m_s);
    integrator.setIterateTolerance(std::move(iterate));
  }
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

  // Streamed outputs (DeploymentOptions::output_sink): the step points go through the stream as
  // they are accepted and `steps` keeps only the last one. A checkpoint then carries the stream's
  // state and the last output instant instead of the step points, so memory stays bounded with
  // checkpoints too.
  const bool streamed = static_cast<bool>(options.output_sink);
  const double drive_end_s = model.baseJoint().driveLaw().parameters().duration_s;
  const DriveAt drive = [&model](double time) { return model.baseJoint().driveAt(time); };
  long streamed_outputs = resume ? resume->streamed_outputs : 0;
  DeploymentSeries last_output = resume && streamed ? resume->series : DeploymentSeries{};
  StepPointStream stream(
      options.output_step_s, drive_end_s, drive,
      !streamed ? StepPointStream::Emit{} : [&](const DeploymentSample& sample) {
        options.output_sink(sample);
        ++streamed_outputs;
        last_output = DeploymentSeries{};
        last_output.append(sample);
      });
  std::vector<double> piece_start_times;  // streamed runs: where each piece began
  if (resume && streamed) {
    MASTROM_REQUIRE(resume->series.size() == 1 && resume->stream.points > 0, InputError,
                    "simulate: the checkpoint (step ", resume->step,
                    ") holds no stream state for this streamed adaptive run");
    stream.restore(resume->stream);
    piece_start_times = resume->piece_start_times_s;
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
    if (streamed) {
      stream.add(sample, piece_start);
      if (piece_start) piece_start_times.push_back(sample.time_s);
      steps = DeploymentSeries{};
    }
    steps.append(sample);
  };
  if (!resume) {
    integrator.updateIndexOneAccelerations();
    record(integrator.state(), 0, 0.0, true);
    piece_starts.push_back(0);
    controller.restart(0.0, monitor(integrator.state()), v);
  }

  stats.first_step_s = control_options.initial_step_s;
  double t = integrator.state().time_s;
  std::size_t next_stop = 0;
  while (next_stop < stops.size() && stops[next_stop] <= t) ++next_stop;
  double next_checkpoint = t;
  if (options.checkpoint_every_s > 0.0)
    next_checkpoint = options.checkpoint_every_s * (std::floor(t / options.checkpoint_every_s) + 1);
  ThreadTuner tuner(model.system().threadCount(), options.thread_tuning);
  const ThreadCountRestorer restore_threads(model.system());
  const auto set_threads = [&model](int threads) { model.system().setThreadCount(threads); };
  // Where a step of the controller's size h from t_from ends: at t_from + h, or at the next stop
  // when that lies within the stretch or t_from + h would leave less than min_step before it (then
  // at_stop). So no step is shorter than min_step: the last one to a stop is stretched instead,
  // by less than min_step (docs/theory.md §5.3).
  // A stretched step that was rejected would come back stretched to the same length (the shorter
  // step the controller then asks for again leaves less than min_step): from that instant the
  // rest to the stop, at least 2 min_step, is split in two equal steps instead, so every rejection
  // shortens the step and the loop ends (split_from: the instant, or −1).
  const double min_step = control_options.min_step_s;
  double split_from = -1.0;
  const auto stepEnd = [&](double t_from, double h, bool& at_stop) {
    const double stop = stops[next_stop];
    at_stop = t_from + kBreakpointStretch * h >= stop || stop - (t_from + h) < min_step;
    if (at_stop && t_from == split_from && t_from + kBreakpointStretch * h < stop &&
        stop - t_from >= 2.0 * min_step) {
      at_stop = false;
      return t_from + 0.5 * (stop - t_from);
    }
    return at_stop ? stop : t_from + h;
  };
  // Judge the step from t to t1 by its state s (index-1 accelerations recovered): accept it
  // (controller and statistics; true) or reject it (false). Touches neither the integrator nor
  // the system's evaluations, so it may run beside a speculative step.
  const auto judge = [&](const DaeState& s, double t1, bool at_stop, const StepReport& report) {
    // The estimate reads the index-1 accelerations: the index-3 q̈ of generalized-α carries the
    // scheme's parasitic root (−α_m/(1−α_m) per step, not small as h → 0), which a third
    // difference amplifies 8-fold and no step size removes (docs/theory.md §5.3).
    const Eigen::VectorXd& y1 = monitor(s);
    // A step landing on a breakpoint has the drive's right limits in its accelerations: it is not
    // estimated (it is at most 1.1 times the nominal step, whose error the steps before it had).
    const bool at_breakpoint = at_stop && next_stop + 1 < stops.size();
    double err = 0.0, velocity_error = 0.0;
    Eigen::Vector2d error_parts = Eigen::Vector2d::Zero();
    local_error.setZero(y1.size());
    if (controller.canEstimate() && !at_breakpoint)
      err = controller.estimate(t1, y1, v, local_error, velocity_error, &error_parts);
    if (err > 1.0 && controller.noiseLimited(t, t1 - t, err, at_stop)) {
      // Round-off (cutting the step did not reduce the error) or a step that cannot be cut:
      // accepted, and later estimates measured against this floor (it decays; docs/theory.md §5.3).
      ++stats.noise_limited_steps;
      controller.acceptAtNoiseFloor(local_error, velocity_error, error_parts);
      err = 1.0;
    }
    if (err > 1.0) {
      ++stats.rejected_steps;
      if (at_stop) split_from = t;
      controller.reject(err, t1 - t, t, at_stop);
      return false;
    }
    const double h_taken = t1 - t;
    controller.accept(t1, y1, v, err, h_taken, &error_parts);
    ++stats.steps;
    stats.newton_iterations += report.iterations;
    stats.max_constraint_residual =
        std::max(stats.max_constraint_residual, report.constraint_residual);
    stats.min_step_s = stats.steps == 1 ? h_taken : std::min(stats.min_step_s, h_taken);
    stats.max_step_s = std::max(stats.max_step_s, h_taken);
    return true;
  };
  // Newton failed on the step from t of size h: the integrator is back at t; a shorter step
  // usually converges.
  const auto newtonFailed = [&](const char* what, double h, bool lands_on_stop) {
    ++stats.rejected_steps;
    if (lands_on_stop) split_from = t;
    try {
      controller.reject(std::numeric_limits<double>::infinity(), h, t, lands_on_stop);
    } catch (const NumericalError&) {
      throw NumericalError(detail::concat(what, " (also at the smallest step allowed, ",
                                          control_options.min_step_s, " s)"));
    }
  };

  // Speculative steps (docs/theory.md §5.6): on two threads, each step is taken on this thread
  // while the other recovers, judges and records the one before it, on the bet that the step before
  // is accepted and the step size kept (99 % of the steps of Scheme 3); a lost bet takes the
  // speculative step back. A step that would renew its factorisation, lands on a stop or precedes
  // a checkpoint is not taken speculatively. The steps and results are those of one thread, bit
  // for bit.
  struct Speculation {
    bool taken = false, failed = false;
    StepReport report;
    double t1 = 0.0;
    bool at_stop = false;
    std::string failure;
  };
  WorkOffer offer;
  Speculation kept;  // the step taken speculatively in the last pass and kept
  bool have_kept = false;
  while (t < end_time) {
    const TunedStep timed(tuner, set_threads);  // this pass of the loop, rejected or not
    StepReport report;
    const double h_c = controller.step();
    double t1 = 0.0;
    bool at_stop = false;
    if (have_kept) {  // taken in the last pass, at this size
      have_kept = false;
      report = kept.report;
      t1 = kept.t1;
      at_stop = kept.at_stop;
    } else {
      // The controller's step, set exactly (t1 = t + h is then the instant the pipelined
      // evaluation of the previous step predicted, whenever the step is kept).
      integrator.setStepSize(h_c);
      t1 = stepEnd(t, integrator.stepSize(), at_stop);
      try {
        report = integrator.stepTo(t1);
      } catch (const NumericalError& e) {
        newtonFailed(e.what(), t1 - t, at_stop);
        continue;
      }
    }
    const bool at_breakpoint = at_stop && next_stop + 1 < stops.size();
    const bool checkpoint_may_be_due =
        options.checkpoint_sink && ((options.checkpoint_every_s > 0.0 && t1 >= next_checkpoint) ||
                                    (options.checkpoint_every_steps > 0 &&
                                     (stats.steps + 1) % options.checkpoint_every_steps == 0));
    // The step after this one as the next pass takes it if this one is accepted and the controller
    // keeps its size. Only a step that changes nothing but the state can be taken back exactly: not
    // one to a stop (a new size swaps factorisations, GeneralizedAlpha::setStepSize).
    Speculation next;
    next.t1 = stepEnd(t1, integrator.stepSize(), next.at_stop);
    const bool speculate = options.integrator.pipelined_steps && tuner.threads() > 1 && !at_stop &&
                           !next.at_stop && !checkpoint_may_be_due && integrator.keepsStepSize(h_c);
    bool accepted = false;
    if (speculate) {
      integrator.deferIndexOneAccelerations();
      integrator.beginSpeculation();
      // The speculative step evaluates on this thread alone; once the judging thread is done it
      // evaluates the predictor of the step after beside the step's last Newton evaluations.
      set_threads(1);
      offer.open();
      integrator.setPairRunner(&offer);
      runOnTwoThreads(
          [&] {
            // Closed however this ends: the judging thread serves until then.
            struct CloseOffers {
              WorkOffer& offer;
              ~CloseOffers() { offer.close(); }
            } close_offers{offer};
            try {
              next.report = integrator.stepTo(next.t1);
              next.taken = true;
            } catch (const SpeculationAbandoned&) {
            } catch (const NumericalError& e) {
              next.failed = true;
              next.failure = e.what();
            }
          },
          [&] {
            integrator.recoverDeferredIndexOne();
            const DaeState& s = integrator.deferredIndexOneState();
            accepted = judge(s, t1, at_stop, report);
            if (accepted) record(s, report.iterations, report.constraint_residual, false);
            offer.serve();
          },
          true);
      integrator.setPairRunner(nullptr);
      set_threads(tuner.threads());
      integrator.completeDeferredIndexOne();
    } else {
      integrator.updateIndexOneAccelerations();
      accepted = judge(integrator.state(), t1, at_stop, report);
    }
    if (!accepted) {
      if (speculate) integrator.endSpeculation(false);
      integrator.rejectStep();
      continue;
    }
    t = t1;
    if (speculate) {
      // The next pass takes the controller's step from here: the speculative one when the size
      // stayed (a failure of it then happens there as well).
      const bool same_step = controller.step() == h_c;
      integrator.endSpeculation(same_step);
      if (same_step && next.taken) {
        kept = std::move(next);
        have_kept = true;
        ++stats.speculative_steps;
      } else if (same_step && next.failed) {
        newtonFailed(next.failure.c_str(), next.t1 - t, next.at_stop);
      }
    } else if (at_breakpoint) {
      // A breakpoint of the drive: restart with its right limits; that state opens a new piece.
      integrator.restartAtDiscontinuity();
      record(integrator.state(), report.iterations, report.constraint_residual, true);
      piece_starts.push_back(static_cast<long>(steps.size()) - 1);
      controller.restart(t, monitor(integrator.state()), v);
      ++next_stop;
    } else {
      record(integrator.state(), report.iterations, report.constraint_residual, false);
    }
    // Stopped from outside: every accepted step point is recorded already (a speculative step
    // beyond it is dropped), so the outputs end here.
    if (options.stop_requested && t < end_time && options.stop_requested()) {
      stats.stopped_early = true;
      break;
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
    // Streamed, a checkpoint names the outputs before it by their count and the last one: it
    // waits for the first (a few step points into the run).
    if (options.checkpoint_sink && checkpoint_due && t < end_time &&
        (!streamed || streamed_outputs > 0)) {
      DeploymentCheckpoint checkpoint;
      checkpoint.step = stats.steps;
      checkpoint.integrator = integrator.snapshot();
      checkpoint.statistics = stats;
      checkpoint.statistics.factorizations = integrator.factorizations();
      checkpoint.controller = controller.state();
      checkpoint.piece_starts = piece_starts;
      if (streamed) {
        checkpoint.streamed_outputs = streamed_outputs;
        checkpoint.series = last_output;
        checkpoint.stream = stream.state();
        checkpoint.piece_start_times_s = piece_start_times;
      } else {
        checkpoint.series = std::move(steps);
      }
      options.checkpoint_sink(checkpoint);
      if (!streamed) steps = std::move(checkpoint.series);
      if (options.checkpoint_every_s > 0.0)
        next_checkpoint =
            options.checkpoint_every_s * (std::floor(t / options.checkpoint_every_s) + 1);
    }
  }
  stats.factorizations = integrator.factorizations();
  stats.single_thread_steps = tuner.singleThreadSteps();

  if (streamed) {
    stream.finish();
    stats.continuous_peaks = stream.peaks();
    stats.has_continuous_peaks = true;
    stats.piece_start_times_s = std::move(piece_start_times);
    if (statistics) *statistics = std::move(stats);
    return DeploymentSeries{};  // the sink has every output
  }
  const StepPoints points{steps, piece_starts};
  stats.continuous_peaks = continuousPeaks(points, drive_end_s, drive);
  stats.has_continuous_peaks = true;
  stats.step_times_s = steps.time_s;
  for (long start : piece_starts) stats.piece_start_times_s.push_back(steps.time_s[start]);
  if (statistics) *statistics = std::move(stats);
  return resampleStepPoints(points, options.output_step_s, drive);
}

}  // namespace mastrom::fullorder
