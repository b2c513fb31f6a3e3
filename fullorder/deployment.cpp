#include "fullorder/deployment.hpp"

#include <cmath>
#include <memory>
#include <utility>

#include "common/error.hpp"
#include "fullorder/deployment_system.hpp"
#include "fullorder/thread_tuner.hpp"

namespace mastrom::fullorder {

DeploymentSample sampleDeploymentState(const MastModel& model, const DaeState& state,
                                       int newton_iterations, double constraint_residual) {
  const MultibodySystem& sys = model.system();
  const Eigen::VectorXd& qdd =
      state.qddot_index1.size() == state.q.size() ? state.qddot_index1 : state.qddot;
  const Eigen::VectorXd& lambda =
      state.lambda_index1.size() == state.lambda.size() ? state.lambda_index1 : state.lambda;
  const int end = model.endModule();
  const int off = model.moduleDofOffset(end);
  const Vec12 q_end = state.q.segment<12>(off);
  const Vec12 qdd_end = qdd.segment<12>(off);

  DeploymentSample s;
  s.time_s = state.time_s;
  const DriveState drive = model.baseJoint().driveAt(state.time_s);
  s.drive_angle_rad = drive.angle_rad;
  s.drive_rate_rad_s = drive.rate_rad_s;
  s.drive_acceleration_rad_s2 = drive.acceleration_rad_s2;
  s.end_angular_acceleration_rad_s2 = sys.body(end).angularAcceleration(q_end, qdd_end);
  // The end point is the last module's centroid (its offset from r_i included).
  const Mat3x12 centroid = sys.body(end).centroidMap();
  s.end_position_m.noalias() = centroid * q_end;
  s.end_acceleration_m_s2.noalias() = centroid * qdd_end;
  s.joint_force_n = model.jointForce(lambda);
  s.joint_torque_nm = model.driveTorque(lambda);
  s.newton_iterations = newton_iterations;
  s.constraint_residual = constraint_residual;
  return s;
}

DeploymentSeries simulateDeployment(MastModel& model, const DeploymentOptions& options,
                                    DeploymentStatistics* statistics,
                                    const DeploymentProgress& progress,
                                    const DeploymentCheckpoint* resume) {
  MASTROM_REQUIRE(!model.baseJoint().isLocked(), InputError,
                  "simulate: the mast was built with a locked joint; a deployment needs the drive");
  MASTROM_REQUIRE(std::isfinite(options.end_time_s) && options.end_time_s > 0, InputError,
                  "simulation.end_time = ", options.end_time_s, " s must be > 0");
  MASTROM_REQUIRE(options.output_every >= 1, InputError, "output.every = ", options.output_every,
                  " must be >= 1");
  MASTROM_REQUIRE(options.checkpoint_every_steps >= 0, InputError,
                  "checkpoint interval = ", options.checkpoint_every_steps, " steps must be >= 0");
  // A checkpoint of a streamed run holds the last output only; one of a held series holds them
  // all: each continues only the same kind of run.
  MASTROM_REQUIRE(
      !resume || (resume->streamed_outputs > 0) == static_cast<bool>(options.output_sink),
      InputError, "simulate: the checkpoint (step ", resume ? resume->step : 0,
      ") was written by a run that ", resume && resume->streamed_outputs > 0 ? "streamed" : "held",
      " its outputs; this one ", options.output_sink ? "streams" : "holds", " them");
  if (options.adaptive)
    return simulateAdaptiveDeployment(model, options, statistics, progress, resume);
  const double h = options.integrator.time_step_s;
  const long steps = static_cast<long>(std::ceil(options.end_time_s / h - 1e-9));

  // Index-1 outputs are recovered only at the output instants (they do not feed back into the
  // stepping), so sparse output sampling makes them nearly free.
  const bool index1_outputs = options.integrator.recover_index1_accelerations;
  GeneralizedAlphaOptions stepping = options.integrator;
  stepping.recover_index1_accelerations = false;
  DeploymentSystem system(model, options.eliminate_linear_constraints);
  GeneralizedAlpha integrator(system.dae(), stepping);
  system.initialize(integrator, options.start_in_equilibrium && resume == nullptr);
  // The outputs need the full coordinates; expand only at output instants.
  const auto fullState = [&system](const DaeState& r) -> const DaeState& { return system.full(r); };

  DeploymentSeries series;
  DeploymentStatistics stats;
  long first_step = 1;
  if (resume) {
    MASTROM_REQUIRE(resume->step >= 0 && resume->step <= steps &&
                        resume->integrator.step_count == resume->step && !resume->series.empty(),
                    InputError, "simulate: the checkpoint (step ", resume->step,
                    ") does not fit this run of ", steps, " steps");
    integrator.restore(resume->integrator);
    series = resume->series;
    stats = resume->statistics;
    first_step = resume->step + 1;
  }
  // Streamed: the series holds the last output instant only (the sink has the others).
  const bool streamed = static_cast<bool>(options.output_sink);
  long streamed_outputs = resume ? resume->streamed_outputs : 0;
  if (!streamed) series.reserve(static_cast<std::size_t>(steps / options.output_every + 2));
  const auto keep = [&](const DeploymentSample& sample) {
    if (streamed) {
      options.output_sink(sample);
      ++streamed_outputs;
      series = DeploymentSeries{};
    }
    series.append(sample);
  };
  if (!resume) {
    const DaeState& full = fullState(integrator.state());
    if (options.state_observer)
      options.state_observer(full, system.fullVelocities(integrator.state()), true);
    keep(sampleDeploymentState(model, full, 0, 0.0));
  }

  // With a second thread the index-1 recovery of an output instant is deferred into the next step,
  // where it runs on this thread while the other evaluates the element forces
  // (GeneralizedAlpha::deferIndexOneAccelerations; ≈ 20 µs of a 130 µs step). Its sample
  // is then recorded one step late — the same values bit for bit.
  const bool overlap_recovery = index1_outputs && model.system().threadCount() > 1;
  struct PendingSample {
    bool active = false;
    int iterations = 0;
    double constraint_residual = 0.0;
  } pending;
  const auto record = [&](const DaeState& state, int iterations, double constraint_residual) {
    const DaeState& full = fullState(state);
    const DeploymentSample sample =
        sampleDeploymentState(model, full, iterations, constraint_residual);
    if (options.state_observer)
      options.state_observer(full, system.fullVelocities(state), series.empty());
    MASTROM_REQUIRE(sample.end_angular_acceleration_rad_s2.allFinite() &&
                        sample.joint_force_n.allFinite() && std::isfinite(sample.joint_torque_nm),
                    NumericalError, "simulate: non-finite output at t = ", sample.time_s, " s");
    keep(sample);
  };
  const auto recordPending = [&] {
    if (!pending.active) return;
    record(integrator.completeDeferredIndexOne(), pending.iterations, pending.constraint_residual);
    pending.active = false;
  };

  const long progress_every = std::max(1L, steps / 200);
  ThreadTuner tuner(model.system().threadCount(), options.thread_tuning);
  const ThreadCountRestorer restore_threads(model.system());
  const auto set_threads = [&model](int threads) { model.system().setThreadCount(threads); };
  for (long k = first_step; k <= steps; ++k) {
    const TunedStep timed(tuner, set_threads);
    const StepReport report = integrator.step();
    recordPending();  // the previous output instant's recovery ran inside this step
    ++stats.steps;
    stats.newton_iterations += report.iterations;
    stats.max_constraint_residual = std::max(stats.max_constraint_residual,
                                             report.constraint_residual);
    if (k % options.output_every == 0 || k == steps) {
      if (overlap_recovery && k < steps) {
        integrator.deferIndexOneAccelerations();
        pending = {true, report.iterations, report.constraint_residual};
      } else {
        if (index1_outputs) integrator.updateIndexOneAccelerations();
        record(integrator.state(), report.iterations, report.constraint_residual);
      }
    }
    if (options.stop_requested && k < steps && options.stop_requested()) {
      // Stopped from outside: the outputs end with this step, recorded now unless it was an output
      // instant (then it is pending or recorded already).
      recordPending();
      if (series.time_s.back() < integrator.state().time_s) {
        if (index1_outputs) integrator.updateIndexOneAccelerations();
        record(integrator.state(), report.iterations, report.constraint_residual);
      }
      stats.stopped_early = true;
      break;
    }
    if (progress && (k % progress_every == 0 || k == steps)) {
      stats.factorizations = integrator.factorizations();
      stats.single_thread_steps = tuner.singleThreadSteps();
      progress(integrator.state().time_s, options.end_time_s, stats);
    }
    if (options.checkpoint_sink && options.checkpoint_every_steps > 0 &&
        k % options.checkpoint_every_steps == 0 && k < steps) {
      recordPending();  // the checkpoint holds the series up to step k and no deferred work
      // Lend the series to the checkpoint instead of copying it (it may hold 10⁵ rows; streamed,
      // it holds the last output instant).
      DeploymentCheckpoint checkpoint;
      checkpoint.step = k;
      checkpoint.streamed_outputs = streamed ? streamed_outputs : 0;
      checkpoint.integrator = integrator.snapshot();
      checkpoint.statistics = stats;
      checkpoint.statistics.factorizations = integrator.factorizations();
      checkpoint.series = std::move(series);
      options.checkpoint_sink(checkpoint);
      series = std::move(checkpoint.series);
    }
  }
  recordPending();  // none is left (the last step records at once), but never drop a sample
  if (streamed) series = DeploymentSeries{};  // the sink has every output
  stats.factorizations = integrator.factorizations();
  stats.single_thread_steps = tuner.singleThreadSteps();
  if (statistics) *statistics = stats;
  return series;
}

}  // namespace mastrom::fullorder
