#include "fullorder/step_control.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "common/error.hpp"

namespace mastrom::fullorder {

namespace {
/// The scale Y never drops below this [m/s²] (a start from rest under a drive whose θ̈(0) = 0, the
/// quintic law, has y = 0 at first): 10⁻⁷ g, far below any acceleration an output resolves.
constexpr double kAccelerationFloor = 1e-6;
/// The same for V [m/s]: a start from rest has no vibration at first.
constexpr double kVelocityFloor = 1e-9;
}  // namespace

double StepController::onLadder(double h_s) const {
  // The largest step max_step · 2^(−k) not above h (and not below min_step).
  const StepControlOptions& o = options_;
  if (h_s >= o.max_step_s) return o.max_step_s;
  const double k = std::ceil(std::log2(o.max_step_s / h_s) - 1e-12);
  return std::max(o.max_step_s * std::exp2(-k), o.min_step_s);
}

double generalizedAlphaGamma(double rho_inf) {
  const double alpha_m = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
  const double alpha_f = rho_inf / (rho_inf + 1.0);
  return 0.5 + alpha_f - alpha_m;
}

double generalizedAlphaBeta(double rho_inf) {
  const double gamma = generalizedAlphaGamma(rho_inf);
  return 0.25 * (gamma + 0.5) * (gamma + 0.5);
}

double generalizedAlphaErrorConstant(double rho_inf) {
  const double alpha_m = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
  const double alpha_f = rho_inf / (rho_inf + 1.0);
  return generalizedAlphaBeta(rho_inf) + 0.5 * (alpha_m - alpha_f) - 1.0 / 6.0;
}

double unjudgedStepBound(const StepControlOptions& options, double omega_rad_s) {
  if (!(omega_rad_s > 0.0) || !(options.error_constant > 0.0)) return options.initial_step_s;
  const double h = std::cbrt(options.tolerance / options.error_constant) / omega_rad_s;
  return std::max(options.min_step_s, std::min(options.initial_step_s, h));
}

StepController::StepController(const StepControlOptions& options, Eigen::VectorXd weights)
    : options_(options), weights_(std::move(weights)) {
  const StepControlOptions& o = options_;
  MASTROM_REQUIRE(std::isfinite(o.tolerance) && o.tolerance > 0.0, InputError,
                  "simulation.tolerance = ", o.tolerance, " must be > 0");
  MASTROM_REQUIRE(o.min_step_s > 0.0 && o.min_step_s <= o.initial_step_s &&
                      o.initial_step_s <= o.max_step_s && std::isfinite(o.max_step_s),
                  InputError, "step bounds must satisfy 0 < simulation.min_time_step (",
                  o.min_step_s, " s) <= simulation.time_step (", o.initial_step_s,
                  " s) <= simulation.max_time_step (", o.max_step_s, " s)");
  MASTROM_REQUIRE(std::isfinite(o.velocity_tolerance_share) && o.velocity_tolerance_share >= 0.0,
                  InputError,
                  "step control: velocity_tolerance_share = ", o.velocity_tolerance_share,
                  " must be >= 0 (0 switches the criterion off)");
  MASTROM_REQUIRE(std::isfinite(o.acceleration_scale_floor) && o.acceleration_scale_floor >= 0.0 &&
                      std::isfinite(o.velocity_scale_floor) && o.velocity_scale_floor >= 0.0,
                  InputError, "step control: scale floors ", o.acceleration_scale_floor,
                  " m/s^2 and ", o.velocity_scale_floor, " m/s must be finite and >= 0");
  MASTROM_REQUIRE(std::isfinite(o.velocity_roundoff_m_s) && o.velocity_roundoff_m_s >= 0.0,
                  InputError, "step control: velocity round-off ", o.velocity_roundoff_m_s,
                  " m/s must be finite and >= 0");
  MASTROM_REQUIRE(
      std::isfinite(o.acceleration_roundoff_m) && o.acceleration_roundoff_m >= 0.0 &&
          std::isfinite(o.velocity_step_roundoff_m) && o.velocity_step_roundoff_m >= 0.0,
      InputError, "step control: acceleration and velocity round-off ", o.acceleration_roundoff_m,
      " m and ", o.velocity_step_roundoff_m, " m must be finite and >= 0");
  state_.step_s = onLadder(o.initial_step_s);
}

void StepController::updateVelocityPeak(const Eigen::VectorXd& v) {
  if (v.size() == 0) return;
  state_.peak_velocity =
      std::max(state_.peak_velocity, weights_.cwiseProduct(v).cwiseAbs().maxCoeff());
}

void StepController::restart(double t_s, const Eigen::VectorXd& y, const Eigen::VectorXd& v) {
  updateVelocityPeak(v);
  const Eigen::VectorXd wy = weights_.cwiseProduct(y);
  state_.times.assign(1, t_s);
  state_.values.assign(1, wy);
  state_.peak = std::max(state_.peak, wy.cwiseAbs().maxCoeff());
  // The jump excites what the last piece's step may not resolve; nothing yet says how fast the new
  // piece varies: begin again from the initial step.
  state_.step_s = std::min(state_.step_s, onLadder(options_.initial_step_s));
  state_.previous_error = 1.0;
}

double StepController::estimate(double t1_s, const Eigen::VectorXd& y1, const Eigen::VectorXd& v1,
                                Eigen::VectorXd& local_error, double& velocity_error,
                                Eigen::Vector2d* error_parts) const {
  local_error.setZero(y1.size());
  velocity_error = 0.0;
  if (error_parts) error_parts->setZero();
  if (!canEstimate()) return 0.0;
  const std::vector<double>& t = state_.times;
  const std::vector<Eigen::VectorXd>& f = state_.values;
  const Eigen::VectorXd f4 = weights_.cwiseProduct(y1);
  // Averages of neighbouring step points at the steps' midpoints (docs/theory.md §5.3): a component
  // that alternates in sign from step to step — the round-off and parasitic oscillation of the
  // accelerations at the step's own Nyquist frequency — cancels exactly, a smooth one is moved by
  // h²y″/8, whose third difference is of higher order.
  const double m[4] = {0.5 * (t[0] + t[1]), 0.5 * (t[1] + t[2]), 0.5 * (t[2] + t[3]),
                       0.5 * (t[3] + t1_s)};
  const Eigen::VectorXd g0 = 0.5 * (f[0] + f[1]), g1 = 0.5 * (f[1] + f[2]),
                        g2 = 0.5 * (f[2] + f[3]), g3 = 0.5 * (f[3] + f4);
  // Third divided difference g[m0, m1, m2, m3] (Newton's scheme).
  const Eigen::VectorXd d01 = (g1 - g0) / (m[1] - m[0]);
  const Eigen::VectorXd d12 = (g2 - g1) / (m[2] - m[1]);
  const Eigen::VectorXd d23 = (g3 - g2) / (m[3] - m[2]);
  const Eigen::VectorXd d012 = (d12 - d01) / (m[2] - m[0]);
  const Eigen::VectorXd d123 = (d23 - d12) / (m[3] - m[1]);
  const double h = t1_s - t[3];
  local_error = (6.0 * options_.error_constant * h * h * h / (m[3] - m[0])) * (d123 - d012);
  // The floors read through this stencil on its actual spacings (docs/theory.md §5.3c, (5.11)).
  const Eigen::Vector2d scale = scales(h, y1, v1, noiseGains(t1_s));
  double err = local_error.cwiseAbs().maxCoeff() / scale[0];
  double err_v = 0.0;
  if (v1.size() > 0 && options_.velocity_tolerance_share > 0.0) {
    // The velocity criterion: e_v = c h³ ÿ, ÿ = 2 ȳ[m1, m2, m3] (see the header).
    velocity_error = 2.0 * options_.error_constant * h * h * h * d123.cwiseAbs().maxCoeff();
    err_v = velocity_error / scale[1];
  }
  if (error_parts) *error_parts = Eigen::Vector2d(err, err_v);
  err = std::max(err, err_v);
  return std::isfinite(err) ? err : std::numeric_limits<double>::infinity();
}

Eigen::Vector2d StepController::scales(double h_s, const Eigen::VectorXd& y1,
                                       const Eigen::VectorXd& v1,
                                       const Eigen::Vector2d& gains) const {
  const double acceleration =
      std::max(accelerationTolerance(weights_.cwiseProduct(y1).cwiseAbs().maxCoeff()),
               kNoiseFloorMargin * gains[0] * accelerationNoiseFloor(h_s));
  const double velocity_now = v1.size() > 0 ? weights_.cwiseProduct(v1).cwiseAbs().maxCoeff() : 0.0;
  const double velocity = std::max(velocityTolerance(velocity_now),
                                   kNoiseFloorMargin * gains[1] * velocityNoiseFloor(h_s));
  return Eigen::Vector2d(acceleration, velocity);
}

Eigen::Vector2d StepController::noiseGains(double t1_s) const {
  if (!canEstimate()) return Eigen::Vector2d::Ones();
  // The five step points t_0 … t_4 (t_4 = t1) and the step that ended at each (the first one's is
  // not kept: taken as its successor's). A point reached by a step h_i carries round-off ∝ 1/h_i²
  // ((5.10)); relative to the candidate's, (h / h_i)².
  const std::vector<double>& t = state_.times;
  const double p[5] = {t[0], t[1], t[2], t[3], t1_s};
  const double h = p[4] - p[3];
  double noise[5];
  for (int i = 0; i < 5; ++i) {
    const double h_i = i == 0 ? p[1] - p[0] : p[i] - p[i - 1];
    noise[i] = (h / h_i) * (h / h_i);
  }
  double m[4];
  for (int k = 0; k < 4; ++k) m[k] = 0.5 * (p[k] + p[k + 1]);
  // Weights of a divided difference over the midpoints m[first … first + n − 1] on the values
  // there: 1 / Π_{j ≠ k} (m_k − m_j); each midpoint value is the average of its two step points.
  const auto gain = [&](int first, int n) {
    double w[5] = {0.0, 0.0, 0.0, 0.0, 0.0};
    for (int k = first; k < first + n; ++k) {
      double denominator = 1.0;
      for (int j = first; j < first + n; ++j)
        if (j != k) denominator *= m[k] - m[j];
      w[k] += 0.5 / denominator;
      w[k + 1] += 0.5 / denominator;
    }
    double sum = 0.0;
    for (int i = 0; i < 5; ++i) sum += std::abs(w[i]) * noise[i];
    return sum * std::pow(h, n - 1);  // the difference's own scale on uniform steps h
  };
  // On uniform steps h the gains are 1/2 (third difference, h³ Σ|w| = 1/2, e_y's 6 c h³ times
  // that is 3 c) and 1 (second difference, h² Σ|w|): the floors of (5.9), (5.10) are stated there.
  return Eigen::Vector2d(std::max(1.0, 2.0 * gain(0, 4)), std::max(1.0, gain(1, 3)));
}

void StepController::accept(double t1_s, const Eigen::VectorXd& y1, const Eigen::VectorXd& v1,
                            double err, double h_taken_s, const Eigen::Vector2d* error_parts) {
  // The next step is proposed from the error as uniform steps of this size would read it
  // (docs/theory.md §5.3c, (5.11)): a step judged on a stencil of unequal spacings, against floors
  // its gain raised, says only that its error is below round-off so amplified — not that this
  // size, or a longer one, is accurate. Measured before the candidate joins the history.
  double control_error = err;
  if (error_parts && canEstimate() && err > 0.0) {
    const Eigen::Vector2d raised = scales(h_taken_s, y1, v1, noiseGains(t1_s));
    const Eigen::Vector2d uniform = scales(h_taken_s, y1, v1, Eigen::Vector2d::Ones());
    const int set_by = (*error_parts)[0] >= (*error_parts)[1] ? 0 : 1;
    control_error = err * raised[set_by] / uniform[set_by];
  }
  const bool at_noise_scale = error_parts && atNoiseScale(*error_parts, h_taken_s);
  updateVelocityPeak(v1);
  Eigen::VectorXd wy = weights_.cwiseProduct(y1);
  state_.peak = std::max(state_.peak, wy.cwiseAbs().maxCoeff());
  state_.times.push_back(t1_s);
  state_.values.push_back(std::move(wy));
  if (state_.times.size() > kHistoryPoints) {
    state_.times.erase(state_.times.begin());
    state_.values.erase(state_.values.begin());
  }
  const StepControlOptions& o = options_;
  const double nominal = state_.step_s;
  // A step shortened to land on a breakpoint or the end says little about the nominal one, and a
  // step without an estimate nothing: keep the nominal step (the initial one after a restart).
  state_.rejected_from_s = -1.0;
  if (state_.growth_wait > 0) --state_.growth_wait;
  state_.noise_floor *= kNoiseFloorDecayPerStep;
  state_.noise_floor_velocity *= kNoiseFloorDecayPerStep;
  if (state_.growth_barrier_s > 0.0 && h_taken_s >= 0.999 * state_.growth_barrier_s) {
    state_.growth_barrier_s = 0.0;  // the step that failed once now holds: forget the failure
    state_.growth_backoff = 0;
  }
  if (h_taken_s < 0.999 * nominal || err <= 0.0) return;
  // The size a grown step came from: it returns no lower (its error there was known).
  const double grown_from =
      control_error > err && state_.accepted_step_s < h_taken_s ? state_.accepted_step_s : 0.0;
  err = control_error;
  state_.accepted_step_s = h_taken_s;
  // The third difference of an oscillation depends on where in its cycle it is taken: grow from
  // the larger of this error and the last (PI memory), never from a lucky small one.
  const double e = std::max({err, state_.previous_error, 1e-10});
  double factor =
      o.safety * std::pow(e, -0.7 / 3.0) *
      std::pow(std::max(state_.previous_error, 1e-10) / std::max(err, 1e-10), 0.4 / 3.0);
  factor = std::min(factor, o.max_growth);
  state_.previous_error = std::max(err, 1e-10);
  double next = nominal;
  if (factor < o.shrink_threshold) {
    next = std::max(nominal * std::max(factor, o.max_shrink), grown_from);  // avoid a rejection
  } else if (factor >= o.grow_threshold || (err <= kNoiseGrowthError && at_noise_scale)) {
    // Measured against the round-off floors alone, the error is round-off, which does not grow
    // like h³ (docs/theory.md §5.3): the step may grow by a ladder level whenever it leaves half the
    // tolerance, and a grown step whose true error shows is rejected and waits as any other.
    factor = std::max(factor, o.grow_threshold);
    next = nominal * factor;
    // A growth to a step that was just rejected waits (see StepControlState::growth_wait).
    if (state_.growth_barrier_s > 0.0 && next >= 0.999 * state_.growth_barrier_s &&
        state_.growth_wait > 0)
      next = std::min(nominal, next);
  }
  state_.step_s = onLadder(std::clamp(next, o.min_step_s, o.max_step_s));
}

double StepController::accelerationTolerance(double current) const {
  return options_.tolerance * std::max({state_.peak, current, kAccelerationFloor,
                                        options_.acceleration_scale_floor});
}

double StepController::velocityTolerance(double current) const {
  return options_.velocity_tolerance_share * options_.tolerance *
         std::max({state_.peak_velocity, current, kVelocityFloor, options_.velocity_scale_floor});
}

bool StepController::atNoiseScale(const Eigen::Vector2d& error_parts, double h_s) const {
  // The criterion that set err (the larger part) decides.
  if (error_parts[0] >= error_parts[1])
    return kNoiseFloorMargin * accelerationNoiseFloor(h_s) >= accelerationTolerance(0.0);
  return kNoiseFloorMargin * velocityNoiseFloor(h_s) >= velocityTolerance(0.0);
}

double StepController::velocityNoiseFloor(double h_s) const {
  return std::max({state_.noise_floor_velocity, options_.velocity_roundoff_m_s,
                   options_.velocity_step_roundoff_m / h_s});
}

double StepController::accelerationNoiseFloor(double h_s) const {
  // A rounding δ of the positions is the acceleration δ / (β h²) of the scheme's update over a
  // step h (docs/theory.md §5.3c): the round-off rises as the step shortens.
  return std::max(state_.noise_floor, options_.acceleration_roundoff_m / (h_s * h_s));
}

bool StepController::atShortestStep(double h_s, bool lands_on_stop) const {
  const double limit = (lands_on_stop ? 2.0 : kBreakpointStretch) * options_.min_step_s;
  return h_s <= limit * (1.0 + 1e-9);
}

bool StepController::errorIsNoise(double t_s, double h_s, double err) const {
  const StepControlState& s = state_;
  return s.rejected_from_s == t_s && std::isfinite(s.rejected_error) &&
         h_s * 1.5 <= s.rejected_step_s &&
         err > s.rejected_error * std::pow(h_s / s.rejected_step_s, 1.5);
}

bool StepController::noiseLimited(double t_s, double h_s, double err, bool lands_on_stop) const {
  return atShortestStep(h_s, lands_on_stop) || errorIsNoise(t_s, h_s, err);
}

void StepController::acceptAtNoiseFloor(const Eigen::VectorXd& local_error) {
  ++state_.noise_limited;
  if (local_error.size() > 0 && local_error.allFinite())
    state_.noise_floor = std::max(state_.noise_floor, local_error.cwiseAbs().maxCoeff());
}

void StepController::acceptAtNoiseFloor(const Eigen::VectorXd& local_error, double velocity_error,
                                        const Eigen::Vector2d& error_parts) {
  const bool velocity_failed = error_parts[1] > 1.0;
  // The acceleration floor rises when that criterion failed, or when nothing says which did.
  if (error_parts[0] > 1.0 || !velocity_failed)
    acceptAtNoiseFloor(local_error);
  else
    ++state_.noise_limited;
  if (velocity_failed && std::isfinite(velocity_error))
    state_.noise_floor_velocity = std::max(state_.noise_floor_velocity, velocity_error);
}

double StepController::relativeNoiseFloor() const {
  return state_.noise_floor / std::max(state_.peak, kAccelerationFloor);
}

void StepController::reject(double err, double h_taken_s, double t_s, bool lands_on_stop) {
  ++state_.rejected;
  state_.rejected_from_s = t_s;
  state_.rejected_step_s = h_taken_s;
  state_.rejected_error = err;
  const StepControlOptions& o = options_;
  if (std::isfinite(err) && state_.accepted_step_s > 0.0 &&
      h_taken_s > 1.5 * state_.accepted_step_s) {
    // A step just grown failed: its error did not scale like h³ from the last one (a vibration
    // near the step's resolution limit). Try that size again only after a wait that doubles with
    // every repeated failure (a cycle grow → reject → shrink wastes a third of the steps).
    state_.growth_barrier_s = h_taken_s;
    state_.growth_backoff =
        std::min(state_.growth_backoff == 0 ? kGrowthWaitSteps : 2 * state_.growth_backoff,
                 kMaxGrowthWaitSteps);
    state_.growth_wait = state_.growth_backoff;
  }
  double factor = std::isfinite(err) ? o.safety * std::pow(err, -1.0 / 3.0) : 0.25;
  factor = std::clamp(factor, o.max_shrink, 0.9);
  // A step already at the smallest allowed cannot be shortened: a Newton failure there is an
  // error; a too large estimate is accepted at that step by the caller (atShortestStep()).
  MASTROM_REQUIRE(!atShortestStep(h_taken_s, lands_on_stop), NumericalError, "step control: the step at t = ", t_s,
                  " s fails at simulation.min_time_step = ", o.min_step_s,
                  " s (scaled local error ", err, ")");
  state_.step_s =
      std::min(onLadder(std::max(h_taken_s * factor, o.min_step_s)), onLadder(h_taken_s * 0.999));
}

}  // namespace mastrom::fullorder
