// Local error control of variable generalized-α steps (docs/theory.md §5.3).
//
// Estimate. The position update of generalized-α has the local truncation error
//     e_q = c h³ q⃛ + O(h⁴),   c = β + Δα/2 − 1/6,   Δα = α_m − α_f,
// (for Newmark, Δα = 0, this is the estimate of Zienkiewicz & Xie 1991; for generalized-α it
// follows from a_n ≈ q̈(t_n + Δα h), Arnold & Brüls 2007). The outputs are accelerations, and for
// the vibration that dominates their error the acceleration error of a mode of circular frequency ω
// is ω² e_q = c h³ ω² q⃛ = −c h³ q⁽⁵⁾: the same relative error, now weighted as the outputs weight
// the modes. q⁽⁵⁾ = d³q̈/dt³ is taken from the third divided difference of the monitored
// accelerations y = q̈ of the rigid modules over the last five step points of the current smooth
// piece, averaged in neighbouring pairs first (ȳ_k = (y_k + y_{k+1})/2 at the midpoints m_k):
//     e_y = 6 c h³ ȳ[m_{n−3}, m_{n−2}, m_{n−1}, m_n].
// The averaging removes exactly what alternates in sign from step to step — round-off and the
// scheme's parasitic oscillation, which a third difference would amplify eightfold at any step
// size — and moves a smooth y only by h²y″/8.
// The error of a step is ‖W e_y‖∞ / (tol · Y), W converting the modules' direction-vector
// accelerations to the acceleration of a point one module side away [m/s²], Y the largest ‖W y‖∞
// met so far (so the tolerance is relative to the record's own peak acceleration). A step is
// accepted when that ratio is ≤ 1.
//
// Second criterion: the vibration's velocities (docs/theory.md (5.2), (5.3)). Part of what the
// accelerations carry is beyond any step: stiff shell modes rung by a jump of θ̈ or θ⃛ leave
// module accelerations of ~10⁻⁶ m/s² that the estimate reads as a local error at every step size
// (the noise floor below). When the vibration itself is small — a smooth drive, r ~10⁻³ of the
// rigid accelerations — that content exceeds tol · Y, the estimate stops at its noise floor, and
// the control of the ringing that matters is lost (Scheme 2, cycloidal law: steps 3× too long, r
// 4–40 % off). The same phase error read one derivative lower,
//     e_v = c h³ q⁽⁴⁾ = c h³ ÿ     (ÿ = 2 ȳ[m_{n−2}, m_{n−1}, m_n], the last three midpoints),
// has for a mode of frequency ω the same relative size, |e_v|/|v| = |e_y|/|y| = c (ωh)³, but
// weighs a mode ω times less: the stiff modes' content drops out by their frequency ratio. It is
// scaled by V, the largest ‖W (v − v_rig)‖∞ met so far, v_rig = θ̇ Z × x the velocities of the
// mast turning rigidly with the drive (docs/theory.md §2.4): the vibration's own velocity, so a
// small vibration is held to the tolerance relative to itself — to a share of the tolerance
// (StepControlOptions::velocity_tolerance_share). A step must meet both criteria; each has its own
// noise floor.
//
// Controller. PI control of the step (Gustafsson 1991; Hairer & Wanner, Solving ODEs II, §IV.8):
//     h_new = h · s · err_n^(−0.7/3) · (err_{n−1}/err_n)^(0.4/3),
// bounded by growth and shrink limits. The iteration matrix depends on h, and a new step size costs
// a refactorisation, so a step is only enlarged when the controller asks for at least
// grow_threshold times the current one. Right after a start or a restart at a drive breakpoint the
// difference has fewer than five points: those steps take the initial step size, held to the tolerance on the lowest
// mode the drive excites (unjudgedStepBound()).
//
// Noise floor. What the averaging leaves of the round-off can still exceed a tight tolerance; a
// step whose error does not fall when it is cut is accepted at that floor (noiseLimited()), and the
// floor is remembered, so that later steps are not held at min_step by noise.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace mastrom::fullorder {

/// A step within this factor of a breakpoint (or the end) is stretched to land on it: the step
/// that remains when the distance is less than this times min_step cannot be shortened.
constexpr double kBreakpointStretch = 1.1;

/// Once a step has been accepted at the noise floor of the estimate (StepController::errorIsNoise),
/// later estimates are measured
/// against this multiple of that floor when it exceeds the tolerance's share (docs/theory.md §5.3):
/// noise alone then reads err ≤ 1/2 and the step may grow again.
constexpr double kNoiseFloorMargin = 2.0;
/// The floor decays by this factor per accepted step: half in 64 steps.
constexpr double kNoiseFloorDecayPerStep = 0.98923;

/// Where both criteria are measured against their noise floors alone (StepController::atNoiseScale)
/// a step grows by a ladder level whenever its error is at most this.
constexpr double kNoiseGrowthError = 0.5;

/// The velocity criterion's round-off floor, in ulps of the largest position coordinate turned
/// into velocity by the lowest frequency the drive excites (StepControlOptions::
/// velocity_roundoff_m_s, docs/theory.md §5.3b). The estimate e_v of a vibration at round-off was
/// measured at 0.4–8 such ulps (Scheme 3, the cycloidal start);
/// with kNoiseFloorMargin a floor of 2 lets it read ≤ 1 and grow, where 1 held the steps at 1 µs.
constexpr double kVelocityRoundoffUlps = 2.0;

/// The acceleration criterion's round-off floor, in ulps of the largest position coordinate read
/// as the scheme's acceleration at the current step h, κ_a ε ρ_q / (β h²) (StepControlOptions::
/// acceleration_roundoff_m, docs/theory.md §5.3c): positions known to within their rounding carry
/// no acceleration finer than that over a step.
constexpr double kAccelerationRoundoffUlps = 1.0;
/// The same for the velocity criterion, read as the scheme's velocity at the step h,
/// κ_v γ ε ρ_q / (β h) (StepControlOptions::velocity_step_roundoff_m, docs/theory.md §5.3c).
constexpr double kVelocityStepRoundoffUlps = 1.0 / 32.0;

/// Newton's iterates may keep an error of at most this share of the smallest scale the velocity
/// criterion can have (GeneralizedAlpha::setIterateTolerance, docs/theory.md §5.1): the κ of
/// Hairer & Wanner (Solving ODEs II, §IV.8), who stop Newton when its error estimate is below
/// κ · Tol with κ between 10⁻² and 10⁻¹.
constexpr double kIterateErrorShare = 0.1;

/// Accepted steps to wait before retrying a grown step size that was rejected, at the first
/// failure; every further failure at that size doubles the wait, up to the maximum.
constexpr long kGrowthWaitSteps = 8;
constexpr long kMaxGrowthWaitSteps = 1024;

/// Step points kept for the estimate (the candidate makes the fifth).
constexpr std::size_t kHistoryPoints = 4;

struct StepControlOptions {
  double tolerance = 1e-5;       ///< relative local error per step of the monitored accelerations
  double initial_step_s = 1e-5;  ///< first step, and the first steps after every restart
  /// Below ~1 µs the index-3 scheme's accelerations are dominated by amplified round-off (errors
  /// of the positions appear divided by h²), so a shorter step buys nothing (docs/theory.md §5.3).
  double min_step_s = 1e-6;
  double max_step_s = 1e-3;
  double safety = 0.9;
  double max_growth = 2.0;      ///< per accepted step
  double max_shrink = 0.1;      ///< smallest factor after a rejection
  double grow_threshold = 2.0;  ///< enlarge only by at least this factor (one ladder level)
  /// Shrink an accepted step only when asked for less than this factor of it (a new step costs a
  /// refactorisation; a step that turns out too long is rejected and shortened anyway).
  double shrink_threshold = 0.8;
  /// c = β + Δα/2 − 1/6 of the integrator (generalizedAlphaErrorConstant()).
  double error_constant = 1.0 / 12.0;
  /// The velocity criterion is held to this share of the tolerance (0: off). Calibrated
  /// (docs/theory.md §5.3, benchmarks/README.md): at the full tolerance the ringing of a cycloidal
  /// start (Scheme 2) ends 1.5 % NRMSE off, at ½ 0.94 %, at ¼ 0.60 %, at ⅛ 0.36 % (error ∝
  /// share^(2/3)); ¼ leaves the trapezoidal Schemes 1–3 at their accuracy for ≤ 10 % more steps.
  double velocity_tolerance_share = 0.25;
  /// Floors of the scales Y [m/s²] and V [m/s] known before the first step (docs/theory.md §5.3):
  /// the run's caller derives them from the drive (simulateAdaptiveDeployment). 0: none beyond the
  /// fixed round-off floors.
  double acceleration_scale_floor = 0.0;
  double velocity_scale_floor = 0.0;
  /// The velocity criterion's round-off [m/s] (docs/theory.md §5.3b): κ ε ω_R ρ_q, the velocity
  /// κ = kVelocityRoundoffUlps ulps of the largest position coordinate ρ_q put into the lowest mode
  /// ω_R the drive excites. Every step's rounding adds about that much to the vibration, so a local
  /// error below it is not resolved: the velocity criterion's noise floor is never below it.
  /// 0: none (the run's caller derives it, simulateAdaptiveDeployment).
  double velocity_roundoff_m_s = 0.0;
  /// The acceleration criterion's round-off as a length [m] (docs/theory.md §5.3c): κ_a ε ρ_q / β,
  /// the rounding of the largest position coordinate ρ_q (κ_a = kAccelerationRoundoffUlps ulps)
  /// divided by the weight β of a_{n+1} in the position update. At a step h the scheme's
  /// accelerations are resolved by the positions only to acceleration_roundoff_m / h², so the
  /// acceleration criterion's noise floor is never below that. 0: none (the run's caller derives
  /// it, simulateAdaptiveDeployment).
  double acceleration_roundoff_m = 0.0;
  /// The same rounding read as the scheme's velocity over a step [m] (docs/theory.md §5.3c):
  /// κ_a γ ε ρ_q / β, the velocity update's weight γ / (β h) of a position change. At a step h the
  /// velocity criterion's noise floor is never below velocity_step_roundoff_m / h. 0: none.
  double velocity_step_roundoff_m = 0.0;
};

/// c of the estimate above for a spectral radius ρ∞ (1/12 for ρ∞ = 1, the trapezoidal rule).
double generalizedAlphaErrorConstant(double rho_inf);
/// γ = ½ + α_f − α_m of generalized-α for a spectral radius ρ∞ (docs/theory.md §5.1): the weight
/// of a_{n+1} in the velocity update, h γ a_{n+1}.
double generalizedAlphaGamma(double rho_inf);
/// β = ¼(γ + ½)² of generalized-α for a spectral radius ρ∞ (docs/theory.md §5.1): the weight of
/// a_{n+1} in the position update, h² β a_{n+1}.
double generalizedAlphaBeta(double rho_inf);

/// The first steps of every smooth piece, which no estimate judges (fewer than five step points),
/// held to the tolerance on a mode of circular frequency omega_rad_s: the step h with
/// c (ω h)³ = tol, where it is shorter than options.initial_step_s, never below min_step
/// (docs/theory.md §5.3, "The first steps of a piece"). omega_rad_s ≤ 0: initial_step_s unchanged.
double unjudgedStepBound(const StepControlOptions& options, double omega_rad_s);

/// The controller's state, for checkpoints: continuing from it repeats the uninterrupted run.
struct StepControlState {
  std::vector<double> times;            ///< step points of the current smooth piece (≤ 4)
  std::vector<Eigen::VectorXd> values;  ///< W y at those points
  double peak = 0.0;                    ///< Y
  double peak_velocity = 0.0;           ///< V: the largest ‖W (v − v_rig)‖∞ so far
  double previous_error = 1.0;          ///< err_{n−1} of the PI term
  double step_s = 0.0;                  ///< the step the controller asks for next
  long rejected = 0;                    ///< steps rejected so far
  long noise_limited = 0;               ///< steps accepted at the noise floor or the shortest step
  /// The largest local-error estimate ‖W e_y‖∞ [m/s²] of a step accepted at the noise floor: the
  /// round-off level of the estimate, below which it says nothing (0: none met yet).
  double noise_floor = 0.0;
  /// The same for the velocity criterion: the largest ‖W e_v‖∞ [m/s] accepted at its noise floor.
  double noise_floor_velocity = 0.0;
  /// The last accepted step that was not shortened to land on a breakpoint [s] (0: none yet).
  double accepted_step_s = 0.0;
  /// Growth barrier: a grown step of this size [s] was rejected (0: none). The controller does not
  /// ask for it again before growth_wait more steps have been accepted; growth_backoff is the wait
  /// set by the last failure (doubled by each repeated one, cleared when the size is accepted).
  double growth_barrier_s = 0.0;
  long growth_wait = 0;
  long growth_backoff = 0;
  /// The last rejection: from t, with step h and scaled error err (t < 0: none pending).
  double rejected_from_s = -1.0, rejected_step_s = 0.0, rejected_error = 0.0;
};

class StepController {
public:
  /// weights: W as a vector over y (its size is the size of y).
  StepController(const StepControlOptions& options, Eigen::VectorXd weights);

  /// In the calls below y are the monitored accelerations at a step point and v the vibration's
  /// velocities there, v − v_rig of the header (same layout). The overloads without v leave V
  /// and the velocity criterion out.
  ///
  /// A new smooth piece starts at t with accelerations y (the start, or a restart at a breakpoint).
  void restart(double t_s, const Eigen::VectorXd& y, const Eigen::VectorXd& v);
  void restart(double t_s, const Eigen::VectorXd& y) { restart(t_s, y, Eigen::VectorXd()); }
  /// The scaled error of a candidate step to t1 (≤ 1: acceptable): the larger of the two criteria.
  /// The local error estimates themselves go to `local_error` (W e_y, m/s²; zero when the piece
  /// has too few points for an estimate, then the error is 0) and `velocity_error` (‖W e_v‖∞,
  /// m/s), the two scaled errors to `error_parts` when given.
  double estimate(double t1_s, const Eigen::VectorXd& y1, const Eigen::VectorXd& v1,
                  Eigen::VectorXd& local_error, double& velocity_error,
                  Eigen::Vector2d* error_parts = nullptr) const;
  double estimate(double t1_s, const Eigen::VectorXd& y1, Eigen::VectorXd& local_error) const {
    double velocity_error = 0.0;
    return estimate(t1_s, y1, Eigen::VectorXd(), local_error, velocity_error);
  }
  /// The candidate was accepted with scaled error err: it joins the history; proposes the next step
  /// (h_taken: the step just taken; a step shortened to land on a breakpoint does not shrink the
  /// controller's step).
  /// error_parts: estimate()'s two scaled errors, when known (they let a step measured against a
  /// noise floor grow, atNoiseScale()).
  void accept(double t1_s, const Eigen::VectorXd& y1, const Eigen::VectorXd& v1, double err,
              double h_taken_s, const Eigen::Vector2d* error_parts = nullptr);
  void accept(double t1_s, const Eigen::VectorXd& y1, double err, double h_taken_s) {
    accept(t1_s, y1, Eigen::VectorXd(), err, h_taken_s);
  }
  /// The candidate step of size h_taken was rejected with scaled error err (or Newton failed:
  /// err = +inf): proposes a shorter step, never below min_step; NumericalError when the rejected
  /// step already was min_step.
  /// lands_on_stop: the step was stretched to a breakpoint or the end (see atShortestStep()).
  void reject(double err, double h_taken_s, double t_s, bool lands_on_stop = false);
  /// True when a candidate step from t_s of size h_s with scaled error err > 1 retries a step just
  /// rejected from the same instant with a step at least 1.5× longer, and its error fell by less
  /// than (h/h_rejected)^1.5 — a local error falls like h³: what does not is the round-off of the
  /// accelerations. Such a step is as accurate as the solver can make it: accept it
  /// (acceptAtNoiseFloor()).
  bool errorIsNoise(double t_s, double h_s, double err) const;
  /// True when a step of size h_s cannot be shortened: it is min_step, or no longer than
  /// kBreakpointStretch · min_step, or it lands on a stop (lands_on_stop) from less than
  /// 2 · min_step before it — a shorter step would leave less than min_step to the stop, and the
  /// loop never leaves that (it stretches such a step to the stop: no step is shorter than
  /// min_step). Accept it (acceptAtNoiseFloor()).
  bool atShortestStep(double h_s, bool lands_on_stop = false) const;
  /// Either of the two: the caller accepts the step with err = 1 (acceptAtNoiseFloor()).
  bool noiseLimited(double t_s, double h_s, double err, bool lands_on_stop = false) const;
  /// A step is accepted at the noise floor with the local-error estimate `local_error`
  /// (estimate()'s): its size raises the floor later estimates are measured against, so round-off
  /// no longer holds the step down. The floor decays by half every 64 accepted steps
  /// (kNoiseFloorDecayPerStep): what a transient left behind does not loosen the control for good.
  /// At the shortest step the error may be real — content faster than min_step resolves, which the
  /// scheme's numerical damping removes only at longer steps — and the decay bounds how long it
  /// relaxes the control.
  void acceptAtNoiseFloor(const Eigen::VectorXd& local_error);
  /// The same with both criteria's estimates (estimate()'s): each floor is raised only by the
  /// criterion that exceeded its tolerance (its scaled error in error_parts > 1).
  void acceptAtNoiseFloor(const Eigen::VectorXd& local_error, double velocity_error,
                          const Eigen::Vector2d& error_parts);
  /// The noise floor relative to the peak acceleration Y (0 when none was met): the relative
  /// local accuracy the run could actually resolve when this exceeds the tolerance.
  double relativeNoiseFloor() const;
  /// True when the criterion that set the error (the larger of estimate()'s two parts) is measured
  /// against its noise floor (kNoiseFloorMargin times the floor at least the tolerance's share) at
  /// a step h_s: its error then is round-off, which a longer step does not raise like h³ (e_y's
  /// not at all, e_v's like h).
  bool atNoiseScale(const Eigen::Vector2d& error_parts, double h_s) const;
  /// The gains of the two estimates' stencils on round-off, for a candidate step point t1_s after
  /// the current history, relative to uniform steps of the candidate's size (docs/theory.md §5.3c,
  /// (5.11)): Σ_i |w_i| (h / h_i)² over the five step points, w_i the weights of e_y (of e_v) on
  /// them and h_i the step that reached each (round-off ∝ 1/h_i², (5.10)), divided by the same on
  /// uniform steps h. Never below 1. A step just grown from h/2 reads its neighbours' round-off
  /// 24× (e_y) and 9× (e_v) higher than uniform steps h; the floors are raised by as much.
  Eigen::Vector2d noiseGains(double t1_s) const;
  /// The step to take next (before clipping to breakpoints).
  double step() const { return state_.step_s; }
  /// Whether the current piece has enough points for an estimate of the next step.
  bool canEstimate() const { return state_.times.size() >= kHistoryPoints; }
  const StepControlState& state() const { return state_; }
  void restore(const StepControlState& state) { state_ = state; }
  const StepControlOptions& options() const { return options_; }

private:
  /// The tolerance's share of each scale (before the noise floors): tol · max(Y, the candidate's
  /// |W y|, the floors) [m/s²], and s · tol · max(V, the candidate's |W v|, the floors) [m/s].
  double accelerationTolerance(double current) const;
  /// The two criteria's scales at a candidate step h_s with accelerations y1 and velocities v1
  /// (before they join Y and V): the tolerance's share or kNoiseFloorMargin times the noise floor
  /// raised by the stencil's gains (noiseGains(); ones: uniform steps), whichever is larger.
  Eigen::Vector2d scales(double h_s, const Eigen::VectorXd& y1, const Eigen::VectorXd& v1,
                         const Eigen::Vector2d& gains) const;
  double velocityTolerance(double current) const;
  /// V updated with the vibration's velocities v at a step point (nothing when v is empty).
  void updateVelocityPeak(const Eigen::VectorXd& v);
  /// The velocity criterion's noise floor [m/s]: the largest e_v accepted at the noise floor, and
  /// never below the round-off known before the run (StepControlOptions::velocity_roundoff_m_s).
  double velocityNoiseFloor(double h_s) const;
  /// The acceleration criterion's noise floor at a step h_s [m/s²]: the largest e_y accepted at the
  /// noise floor, and never below the round-off of the accelerations at that step
  /// (StepControlOptions::acceleration_roundoff_m / h²).
  double accelerationNoiseFloor(double h_s) const;

  /// Steps live on the ladder max_step · 2^(−k): every change of step costs a refactorisation of
  /// the iteration matrix, and a ladder makes the changes few and lets the integrator keep the
  /// factorisation of the level it left (GeneralizedAlpha keeps two).
  double onLadder(double h_s) const;

  StepControlOptions options_;
  Eigen::VectorXd weights_;
  StepControlState state_;
};

}  // namespace mastrom::fullorder
