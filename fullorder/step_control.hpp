// Local error control of variable generalized-α steps (docs/theory.md §5.3).
//
// Estimate. The position update of generalized-α has the local truncation error
//     e_q = c h³ q⃛ + O(h⁴),   c = β + Δα/2 − 1/6,   Δα = α_m − α_f,
// (for Newmark, Δα = 0, this is the estimate of Zienkiewicz & Xie 1991; for generalized-α it follows
// from a_n ≈ q̈(t_n + Δα h), Arnold & Brüls 2007). The outputs are accelerations, and for the
// vibration that dominates their error the acceleration error of a mode of circular frequency ω is
// ω² e_q = c h³ ω² q⃛ = −c h³ q⁽⁵⁾: the same relative error, now weighted as the outputs weight the
// modes. q⁽⁵⁾ = d³q̈/dt³ is taken from the third divided difference of the monitored accelerations
// y = q̈ of the rigid modules over the last four step points of the current smooth piece:
//     e_y = 6 c h³ y[t_{n−2}, t_{n−1}, t_n, t_{n+1}].
// The error of a step is ‖W e_y‖∞ / (tol · Y), W converting the modules' direction-vector
// accelerations to the acceleration of a point one module side away [m/s²], Y the largest ‖W y‖∞
// met so far (so the tolerance is relative to the record's own peak acceleration). A step is
// accepted when that ratio is ≤ 1.
//
// Controller. PI control of the step (Gustafsson 1991; Hairer & Wanner, Solving ODEs II, §IV.8):
//     h_new = h · s · err_n^(−0.7/3) · (err_{n−1}/err_n)^(0.4/3),
// bounded by growth and shrink limits. The iteration matrix depends on h, and a new step size costs
// a refactorisation, so a step is only enlarged when the controller asks for at least
// grow_threshold times the current one. Right after a start or a restart at a drive breakpoint the
// difference has fewer than four points: those steps take the initial step size.
#pragma once

#include <vector>

#include <Eigen/Core>

namespace mastrom::fullorder {

struct StepControlOptions {
  double tolerance = 1e-5;       ///< relative local error per step of the monitored accelerations
  double initial_step_s = 1e-5;  ///< first step, and the first steps after every restart
  /// Below ~1 µs the index-3 scheme's accelerations are dominated by amplified round-off (errors
  /// of the positions appear divided by h²), so a shorter step buys nothing (docs/theory.md §5.3).
  double min_step_s = 1e-6;
  double max_step_s = 1e-3;
  double safety = 0.9;
  double max_growth = 2.0;        ///< per accepted step
  double max_shrink = 0.1;        ///< smallest factor after a rejection
  double grow_threshold = 2.0;    ///< enlarge only by at least this factor (one ladder level)
  /// Shrink an accepted step only when asked for less than this factor of it (a new step costs a
  /// refactorisation; a step that turns out too long is rejected and shortened anyway).
  double shrink_threshold = 0.8;
  /// c = β + Δα/2 − 1/6 of the integrator (generalizedAlphaErrorConstant()).
  double error_constant = 1.0 / 12.0;
};

/// c of the estimate above for a spectral radius ρ∞ (1/12 for ρ∞ = 1, the trapezoidal rule).
double generalizedAlphaErrorConstant(double rho_inf);

/// The controller's state, for checkpoints: continuing from it repeats the uninterrupted run.
struct StepControlState {
  std::vector<double> times;           ///< step points of the current smooth piece (≤ 3)
  std::vector<Eigen::VectorXd> values; ///< W y at those points
  double peak = 0.0;                   ///< Y
  double previous_error = 1.0;         ///< err_{n−1} of the PI term
  double step_s = 0.0;                 ///< the step the controller asks for next
  long rejected = 0;                   ///< steps rejected so far
  long noise_limited = 0;              ///< steps accepted at the estimate's noise floor
  /// The last rejection: from t, with step h and scaled error err (t < 0: none pending).
  double rejected_from_s = -1.0, rejected_step_s = 0.0, rejected_error = 0.0;
};

class StepController {
public:
  /// weights: W as a vector over y (its size is the size of y).
  StepController(const StepControlOptions& options, Eigen::VectorXd weights);

  /// A new smooth piece starts at t with accelerations y (the start, or a restart at a breakpoint).
  void restart(double t_s, const Eigen::VectorXd& y);
  /// The scaled error of a candidate step to t1 with accelerations y1 (≤ 1: acceptable), and the
  /// estimate of the local error itself in `local_error` (W e_y, m/s²; zero when the piece has too
  /// few points for an estimate, then the error is 0).
  double estimate(double t1_s, const Eigen::VectorXd& y1, Eigen::VectorXd& local_error) const;
  /// The candidate was accepted with scaled error err: it joins the history; proposes the next step
  /// (h_taken: the step just taken; a step shortened to land on a breakpoint does not shrink the
  /// controller's step).
  void accept(double t1_s, const Eigen::VectorXd& y1, double err, double h_taken_s);
  /// The candidate step of size h_taken was rejected with scaled error err (or Newton failed:
  /// err = +inf): proposes a shorter step, never below min_step; NumericalError when the rejected
  /// step already was min_step.
  void reject(double err, double h_taken_s, double t_s);
  /// True when a candidate step from t_s of size h_s with scaled error err > 1 retries a step just
  /// rejected from the same instant with a step at least 1.5× longer, and its error fell by less
  /// than (h/h_rejected)^1.5 — a local error falls like h³: what does not is the round-off and
  /// Newton noise of the accelerations (≈ 10⁻⁴ of their peak, amplified 8-fold by a third
  /// difference). Such a step is as accurate as the solver can make it: accept it.
  bool noiseLimited(double t_s, double h_s, double err) const;
  /// The step to take next (before clipping to breakpoints).
  double step() const { return state_.step_s; }
  /// Whether the current piece has enough points for an estimate of the next step.
  bool canEstimate() const { return state_.times.size() >= 3; }
  const StepControlState& state() const { return state_; }
  void restore(const StepControlState& state) { state_ = state; }
  const StepControlOptions& options() const { return options_; }

private:
  /// Steps live on the ladder max_step · 2^(−k): every change of step costs a refactorisation of
  /// the iteration matrix, and a ladder makes the changes few and lets the integrator keep the
  /// factorisation of the level it left (GeneralizedAlpha keeps two).
  double onLadder(double h_s) const;

  StepControlOptions options_;
  Eigen::VectorXd weights_;
  StepControlState state_;
};

}  // namespace mastrom::fullorder
