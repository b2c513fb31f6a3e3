// One full-order deployment: the mast model integrated by generalized-α from the stowed state
// through the drive law, sampled into the outputs of docs/theory.md §1
// (fullorder/deployment_result.hpp).
//
// Every output comes from the integrator's state, not from finite differences of positions:
// the end module's angular acceleration α = ½ Σ c_k × c̈_k from its NCF accelerations, the end
// centroid's acceleration r̈_i, the joint force and drive torque from the multipliers
// (fullorder/base_joint.hpp signs). Accelerations and multipliers are the index-1 recovered ones at
// the converged state (fullorder/generalized_alpha.hpp explains why).
#pragma once

#include <functional>
#include <vector>

#include "fullorder/continuous_response.hpp"
#include "fullorder/deployment_result.hpp"
#include "fullorder/generalized_alpha.hpp"
#include "fullorder/mast_model.hpp"
#include "fullorder/step_control.hpp"
#include "fullorder/step_point_stream.hpp"
#include "fullorder/thread_tuner.hpp"

namespace mastrom::fullorder {

struct DeploymentCheckpoint;
/// See DeploymentOptions::state_observer.
using DeploymentStateObserver = std::function<void(
    const DaeState& full_state, const Eigen::VectorXd& full_qdot, bool piece_start)>;
/// Receives a checkpoint every DeploymentOptions::checkpoint_every_steps steps.
using DeploymentCheckpointSink = std::function<void(const DeploymentCheckpoint&)>;
/// Receives every output instant in time order (DeploymentOptions::output_sink).
using DeploymentSampleSink = std::function<void(const DeploymentSample&)>;

struct DeploymentOptions {
  GeneralizedAlphaOptions integrator;
  double end_time_s = 8.0;
  int output_every = 1;  ///< fixed steps: record every n-th step (the first and last always)
  /// Error-controlled variable steps (fullorder/step_control.hpp; integrator.time_step_s is then
  /// ignored in favour of step_control.initial_step_s). Steps land on the drive's breakpoints and
  /// restart there; outputs are interpolated onto t = k · output_step_s (and the end).
  bool adaptive = false;
  StepControlOptions step_control;
  double output_step_s = 1e-4;
  /// Adaptive: a checkpoint at the first step on or after every multiple of this [s] (0: never).
  double checkpoint_every_s = 0.0;
  /// Integrate with the linear bonded-edge equations eliminated (fullorder/eliminated_system.hpp):
  /// the same solution, a 2.2× smaller Newton system for the default mast.
  bool eliminate_linear_constraints = true;
  /// With gravity and a drive that starts at rest: start from the static equilibrium at the start
  /// angle (the mast as it stood before the swing, docs/theory.md §5.1 "Initial state"), not from
  /// the undeformed mast, which would drop and ring under its own weight.
  bool start_in_equilibrium = true;
  /// Hand a checkpoint to checkpoint_sink after every n-th step (0: never). Steps, not seconds, so
  /// that checkpoints fall at the same instants in every run; none after the last step.
  long checkpoint_every_steps = 0;
  DeploymentCheckpointSink checkpoint_sink;
  /// Called at every recorded state (fixed steps: the output instants; adaptive: every accepted
  /// step point) with the full-coordinate state (q, λ and the accelerations the outputs read), the
  /// full velocities and whether the state opens a smooth piece of the drive (the first state, a
  /// breakpoint). For recovery that needs the whole state (fullorder/interface_stress.hpp).
  /// Called in step order, never twice at once, but on two threads an adaptive run calls it from
  /// the thread that judges the steps while the next step is computed (docs/theory.md §5.6): it
  /// may read the model's data but must not evaluate its system.
  DeploymentStateObserver state_observer;
  /// Whether steps run on the system's threads or on one, whichever is measured faster
  /// (fullorder/thread_tuner.hpp); the results are the same.
  ThreadTunerOptions thread_tuning;
  /// Asked after every accepted step (before the progress report); true ends the run there, with
  /// the outputs of what was computed (the last step point is recorded) and
  /// DeploymentStatistics::stopped_early set. The CLI's SIGINT / SIGTERM (cli/interrupt.hpp), so
  /// an interrupted run still leaves its result, marked incomplete.
  std::function<bool()> stop_requested;
  /// Stream the outputs instead of returning them: each output instant goes to the sink as soon
  /// as it is known (adaptive runs through fullorder/step_point_stream.hpp, a window of four step
  /// points), and simulateDeployment returns an empty series, so memory does not grow with the
  /// horizon (fullorder/result_stream.hpp writes them to a file). Also with checkpoint_sink: a
  /// checkpoint then carries the last output instant and the count of those handed over
  /// (DeploymentCheckpoint::streamed_outputs; adaptive runs also the stream's window of step
  /// points and its peaks), and whoever writes the sink's outputs keeps them for a restart. An
  /// adaptive run's first checkpoint waits for the first output instant.
  DeploymentSampleSink output_sink;
};

/// Counters of one run, for progress reports and profiles.
struct DeploymentStatistics {
  long steps = 0;           ///< accepted steps
  long rejected_steps = 0;  ///< by the error estimate or a failed Newton iteration (adaptive)
  /// Accepted above the tolerance, at the noise floor of the error estimate or the shortest step
  /// (StepController::noiseLimited).
  long noise_limited_steps = 0;
  long newton_iterations = 0;
  long factorizations = 0;
  /// Steps run on one thread although the system allowed more, because one was measured faster
  /// (fullorder/thread_tuner.hpp: cores shared with other work). Counted from the run's start or
  /// its restart; not in checkpoints, since it describes the machine, not the result.
  long single_thread_steps = 0;
  /// Adaptive runs on two threads: steps taken speculatively beside the judgement of the step
  /// before them and kept (docs/theory.md §5.6). Like single_thread_steps, machine-dependent and
  /// not in checkpoints.
  long speculative_steps = 0;
  double max_constraint_residual = 0.0;
  double min_step_s = 0.0, max_step_s = 0.0;  ///< of the accepted steps (adaptive)
  /// Adaptive runs: the first steps of every smooth piece, which no estimate judges — the
  /// configured first step or, when shorter, the step the tolerance allows on the lowest mode the
  /// drive excites (docs/theory.md §5.3, "The first steps of a piece").
  double first_step_s = 0.0;
  /// DeploymentOptions::stop_requested ended the run before options.end_time_s.
  bool stopped_early = false;
  /// Adaptive runs: the peaks of the continuous response (fullorder/continuous_response.hpp) and
  /// the time of every step point (not with DeploymentOptions::output_sink: it would grow with the
  /// horizon).
  bool has_continuous_peaks = false;
  ContinuousPeaks continuous_peaks;
  std::vector<double> step_times_s;
  std::vector<double> piece_start_times_s;  ///< where each smooth piece (breakpoint) begins
};

/// Called after steps with (time reached [s], end time [s], statistics so far).
using DeploymentProgress = std::function<void(double, double, const DeploymentStatistics&)>;

/// A deployment between two steps: everything its remaining steps depend on, so that continuing
/// from it reproduces the uninterrupted run bit for bit (fullorder/checkpoint.hpp stores it in a
/// file).
struct DeploymentCheckpoint {
  long step = 0;                  ///< steps completed
  IntegratorSnapshot integrator;  ///< in the integrator's (eliminated) coordinates
  /// The outputs recorded so far: at the output instants (fixed steps), or at every step point
  /// (adaptive; interpolated onto the output instants at the end). A streamed run (with
  /// DeploymentOptions::output_sink, fixed or adaptive steps): the last output instant only.
  DeploymentSeries series;
  /// A streamed run: the output instants handed to the sink so far, `series` the last of them
  /// (0: not streamed, `series` holds them all). A restart hands the sink the later ones only.
  long streamed_outputs = 0;
  DeploymentStatistics statistics;  ///< counters so far
  // Adaptive runs only:
  StepControlState controller;
  std::vector<long> piece_starts;  ///< series index where each smooth piece begins (held series)
  /// A streamed adaptive run: the continuous response's window and peaks (`series` then holds the
  /// last output instant, as for fixed steps) and where each smooth piece began [s].
  StepPointStream::State stream;
  std::vector<double> piece_start_times_s;
};

/// The outputs of the current integrator state of `model` (drive values from the model's joint).
DeploymentSample sampleDeploymentState(const MastModel& model, const DaeState& state,
                                       int newton_iterations, double constraint_residual);

/// Integrate a driven mast (model built without a lock) from t = 0 to options.end_time_s, or from
/// `resume` (a checkpoint of a run with the same model and options) to the end: the result is then
/// bit-for-bit that of the uninterrupted run. Throws NumericalError (with time and residuals) when
/// a step fails, never returns NaNs; InputError when `resume` does not fit the model and options.
DeploymentSeries simulateDeployment(MastModel& model, const DeploymentOptions& options,
                                    DeploymentStatistics* statistics = nullptr,
                                    const DeploymentProgress& progress = {},
                                    const DeploymentCheckpoint* resume = nullptr);

/// simulateDeployment() with options.adaptive (fullorder/adaptive_deployment.cpp).
DeploymentSeries simulateAdaptiveDeployment(MastModel& model, const DeploymentOptions& options,
                                            DeploymentStatistics* statistics,
                                            const DeploymentProgress& progress,
                                            const DeploymentCheckpoint* resume);

}  // namespace mastrom::fullorder
