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
}  // namespace

double StepController::onLadder(double h_s) const {
  // The largest step max_step · 2^(−k) not above h (and not below min_step).
  const StepControlOptions& o = options_;
  if (h_s >= o.max_step_s) return o.max_step_s;
  const double k = std::ceil(std::log2(o.max_step_s / h_s) - 1e-12);
  return std::max(o.max_step_s * std::exp2(-k), o.min_step_s);
}

double generalizedAlphaErrorConstant(double rho_inf) {
  const double alpha_m = (2.0 * rho_inf - 1.0) / (rho_inf + 1.0);
  const double alpha_f = rho_inf / (rho_inf + 1.0);
  const double gamma = 0.5 + alpha_f - alpha_m;
  const double beta = 0.25 * (gamma + 0.5) * (gamma + 0.5);
  return beta + 0.5 * (alpha_m - alpha_f) - 1.0 / 6.0;
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
  state_.step_s = onLadder(o.initial_step_s);
}

void StepController::restart(double t_s, const Eigen::VectorXd& y) {
  const Eigen::VectorXd wy = weights_.cwiseProduct(y);
  state_.times.assign(1, t_s);
  state_.values.assign(1, wy);
  state_.peak = std::max(state_.peak, wy.cwiseAbs().maxCoeff());
  // The jump excites what the last piece's step may not resolve; nothing yet says how fast the new
  // piece varies: begin again from the initial step.
  state_.step_s = std::min(state_.step_s, onLadder(options_.initial_step_s));
  state_.previous_error = 1.0;
}

double StepController::estimate(double t1_s, const Eigen::VectorXd& y1,
                                Eigen::VectorXd& local_error) const {
  local_error.setZero(y1.size());
  if (state_.times.size() < 3) return 0.0;
  const std::vector<double>& t = state_.times;
  const std::vector<Eigen::VectorXd>& f = state_.values;
  const double t0 = t[0], ta = t[1], tb = t[2], tc = t1_s;
  const Eigen::VectorXd f3 = weights_.cwiseProduct(y1);
  // Third divided difference f[t0, ta, tb, tc] (Newton's scheme).
  const Eigen::VectorXd d01 = (f[1] - f[0]) / (ta - t0);
  const Eigen::VectorXd d12 = (f[2] - f[1]) / (tb - ta);
  const Eigen::VectorXd d23 = (f3 - f[2]) / (tc - tb);
  const Eigen::VectorXd d012 = (d12 - d01) / (tb - t0);
  const Eigen::VectorXd d123 = (d23 - d12) / (tc - ta);
  const double h = tc - tb;
  local_error = (6.0 * options_.error_constant * h * h * h / (tc - t0)) * (d123 - d012);
  const double scale =
      options_.tolerance * std::max({state_.peak, f3.cwiseAbs().maxCoeff(), kAccelerationFloor});
  const double err = local_error.cwiseAbs().maxCoeff() / scale;
  return std::isfinite(err) ? err : std::numeric_limits<double>::infinity();
}

void StepController::accept(double t1_s, const Eigen::VectorXd& y1, double err,
                            double h_taken_s) {
  Eigen::VectorXd wy = weights_.cwiseProduct(y1);
  state_.peak = std::max(state_.peak, wy.cwiseAbs().maxCoeff());
  state_.times.push_back(t1_s);
  state_.values.push_back(std::move(wy));
  if (state_.times.size() > 3) {
    state_.times.erase(state_.times.begin());
    state_.values.erase(state_.values.begin());
  }
  const StepControlOptions& o = options_;
  const double nominal = state_.step_s;
  // A step shortened to land on a breakpoint or the end says little about the nominal one, and a
  // step without an estimate nothing: keep the nominal step (the initial one after a restart).
  state_.rejected_from_s = -1.0;
  if (h_taken_s < 0.999 * nominal || err <= 0.0) return;
  // The third difference of an oscillation depends on where in its cycle it is taken: grow from
  // the larger of this error and the last (PI memory), never from a lucky small one.
  const double e = std::max({err, state_.previous_error, 1e-10});
  double factor = o.safety * std::pow(e, -0.7 / 3.0) *
                  std::pow(std::max(state_.previous_error, 1e-10) / std::max(err, 1e-10),
                           0.4 / 3.0);
  factor = std::min(factor, o.max_growth);
  state_.previous_error = std::max(err, 1e-10);
  double next = nominal;
  if (factor < o.shrink_threshold) {
    next = nominal * std::max(factor, o.max_shrink);  // near the tolerance: avoid a rejection
  } else if (factor >= o.grow_threshold) {
    next = nominal * factor;
  }
  state_.step_s = onLadder(std::clamp(next, o.min_step_s, o.max_step_s));
}

bool StepController::noiseLimited(double t_s, double h_s, double err) const {
  const StepControlState& s = state_;
  if (h_s <= options_.min_step_s * (1.0 + 1e-9)) return true;  // as short as allowed
  return s.rejected_from_s == t_s && std::isfinite(s.rejected_error) &&
         h_s * 1.5 <= s.rejected_step_s &&
         err > s.rejected_error * std::pow(h_s / s.rejected_step_s, 1.5);
}

void StepController::reject(double err, double h_taken_s, double t_s) {
  ++state_.rejected;
  state_.rejected_from_s = t_s;
  state_.rejected_step_s = h_taken_s;
  state_.rejected_error = err;
  const StepControlOptions& o = options_;
  double factor = std::isfinite(err) ? o.safety * std::pow(err, -1.0 / 3.0) : 0.25;
  factor = std::clamp(factor, o.max_shrink, 0.9);
  // A step already at the smallest allowed cannot be shortened: a Newton failure there is an
  // error; a too large estimate is accepted at that step by the caller (atMinimum()).
  MASTROM_REQUIRE(h_taken_s > o.min_step_s * (1.0 + 1e-9), NumericalError,
                  "step control: the step at t = ", t_s, " s fails at simulation.min_time_step = ",
                  o.min_step_s, " s (scaled local error ", err, ")");
  state_.step_s = std::min(onLadder(std::max(h_taken_s * factor, o.min_step_s)),
                          onLadder(h_taken_s * 0.999));
}

}  // namespace mastrom::fullorder
