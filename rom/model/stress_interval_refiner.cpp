// Re-stepping one interval for its stress peak (stress_interval_refiner.hpp; docs/theory.md §6.5,
// (6.11)).
#include "rom/model/stress_interval_refiner.hpp"

#include <algorithm>
#include <cmath>

#include "rom/model/parabola_polish.hpp"

namespace mastrom::rom::stress_detail {
namespace {

/// The refinement's target: a peak within this share of itself (the sample polish's own order).
constexpr double kStressPeakTolerance = 1e-4;
constexpr int kMaxStressSubSteps = 256;

}  // namespace

IntervalRefiner::IntervalRefiner(const ModalStressEvaluator& ev, const ModalModel& m,
                                 const ModalStepping& ms, StressRefinementStats& stats)
    : ev_(ev),
      m_(m),
      ms_(ms),
      stats_(stats),
      k_(m.modeCount()),
      w_(m.omega_rad_s.array()),
      zeta_(m.damping_ratio.array()) {
  inv_w_ = 1.0 / w_.max(1e-300);
  inv_w2_ = inv_w_.square();
  two_zeta_ = 2.0 * zeta_;
  // The closed form of stateAt() is the under-damped one: every mode with ω > 0 and 0 ≤ ζ < 1.
  closed_form_ = k_ > 0 && (w_ > 0.0).all() && (zeta_ >= 0.0).all() && (zeta_ < 1.0).all();
  zeta_w_ = zeta_ * w_;
  w_damped_ = w_ * (1.0 - zeta_.square()).max(0.0).sqrt();
  for (Eigen::ArrayXd* a : {&f0_, &f1_, &ringing_, &bound_modes_, &e0_, &v0_, &p0_, &p1_, &tmp_})
    a->resize(k_);
}

void IntervalRefiner::prepare(const Eigen::Ref<const Eigen::VectorXd>& eta,
                              const Eigen::Ref<const Eigen::VectorXd>& eta_dot,
                              const DriveInstant& d0, const DriveInstant& d1, double duration_s) {
  d0_ = d0;
  d1_ = d1;
  duration_s_ = duration_s;
  s0_ = stepping_detail::forcingScalars(ms_, d0);
  s1_ = stepping_detail::forcingScalars(ms_, d1);
  const double mu = ev_.damping(), inv_d = 1.0 / duration_s;
  // Whole-array passes over the modes into member buffers (vectorised, no allocation); the
  // forcing at the start is the previous interval's end whenever the drive is continuous there.
  if (have_end_ && sameDriveInstant(d0, last_d1_)) {
    f0_.swap(f1_);
  } else {
    modalForcing(s0_, f0_);
  }
  modalForcing(s1_, f1_);
  last_d1_ = d1;
  have_end_ = true;
  tmp_ = (f1_ - f0_) * (inv_d * inv_w2_);           // η̇_p
  p0_ = f0_ * inv_w2_ - two_zeta_ * tmp_ * inv_w_;  // η_p(t_start)
  p1_ = f1_ * inv_w2_ - two_zeta_ * tmp_ * inv_w_;  // η_p(t_end)
  // The free oscillation's amplitude a; ringing = a (1 + μω) bounds its share of η + μη̇.
  ringing_ = ((eta.array() - p0_).square() + ((eta_dot.array() - tmp_) * inv_w_).square()).sqrt() *
             (1.0 + mu * w_);
  bound_modes_ = p0_.abs().max(p1_.abs()) + mu * tmp_.abs() + ringing_;
  loads_ << std::max(std::abs(s0_.acc), std::abs(s1_.acc)), std::max(s0_.rate2, s1_.rate2),
      std::max(std::abs(s0_.gx), std::abs(s1_.gx)), std::max(std::abs(s0_.gy), std::abs(s1_.gy));
  e0_ = eta.array();
  v0_ = eta_dot.array();
}

void IntervalRefiner::refine(int i, double start_sample, double step_s,
                             ModalStressEvaluator::Peak& peak) {
  const Eigen::VectorXd& c = ev_.bound(i);
  ++stats_.intervals;
  const double upper = c.head(k_).dot(bound_modes_.matrix()) +
                       c.segment<kStressLoadCount>(k_).dot(loads_) + c[k_ + kStressLoadCount];
  if (upper <= peak.von_mises_pa) return;
  // Sub-steps: the coarsest h = duration/sub whose estimated polish error over the ringing
  // modes, Σ_j c_j r_j e(ω_j h) (parabola_polish.hpp), is at most kStressPeakTolerance of the peak.
  const auto errorAt = [&](int sub) {
    const double h = duration_s_ / sub;
    double e = 0.0;
    for (int j = 0; j < k_; ++j) {
      const double x = w_[j] * h;
      e += c[j] * ringing_[j] * polishError(x);
    }
    return e;
  };
  int sub = 1;
  while (sub < kMaxStressSubSteps && errorAt(sub) > kStressPeakTolerance * peak.von_mises_pa)
    sub *= 2;
  if (sub == 1) return;  // the samples and their polish resolve it
  ++stats_.refined;
  stats_.sub_steps += sub;
  const ModalStepping::Maps& h = maps(duration_s_, sub);
  x_.resize(ev_.inputSize(), sub + 1);
  const auto load = [this](double t) { return loadAt(t); };
  eta_ = e0_.matrix();
  eta_dot_ = v0_.matrix();
  ev_.input(eta_, eta_dot_, load(0.0), x_.col(0));
  for (int j = 1; j <= sub; ++j) {
    const double ta = static_cast<double>(j - 1) / sub, tb = static_cast<double>(j) / sub;
    fa_ = f0_ + ta * (f1_ - f0_);
    fb_ = f0_ + tb * (f1_ - f0_);
    advance(h);
    ev_.input(eta_, eta_dot_, load(tb), x_.col(j));
  }
  // The sub-samples whose bound exceeds the peak, evaluated best-first (descending bound) until
  // the bound falls to the largest value found: the same maximum as in time order (of equal
  // values the earliest), with the first evaluation usually the largest and the rest pruned.
  candidates_.clear();
  for (int j = 1; j < sub; ++j) {
    const double b = c.dot(x_.col(j).cwiseAbs());
    if (b > peak.von_mises_pa) candidates_.emplace_back(b, j);
  }
  std::sort(candidates_.begin(), candidates_.end(), [](const auto& a, const auto& b) {
    return a.first > b.first || (a.first == b.first && a.second < b.second);
  });
  stats_.candidates += static_cast<long>(candidates_.size());
  int best = -1, station = 0;
  for (const auto& [b, j] : candidates_) {
    if (b <= peak.von_mises_pa) break;
    ++stats_.evaluations;
    int where = 0;
    const double v = ev_.largestAbove(i, x_.col(j), peak.von_mises_pa, &where);
    if (v > peak.von_mises_pa || (v == peak.von_mises_pa && best >= 0 && j < best)) {
      peak.von_mises_pa = v, best = j, station = where;
      ++stats_.raised;
    }
  }
  if (best < 0) return;
  peak.station = station;
  peak.sample = start_sample + duration_s_ / step_s * best / sub;
  // The parabola through the best sub-sample and its neighbours at the same station.
  double value = 0.0, offset = 0.0;
  if (parabolaMaximum(ev_.station(i, station, x_.col(best - 1)),
                      ev_.station(i, station, x_.col(best)),
                      ev_.station(i, station, x_.col(best + 1)), value, offset)) {
    peak.von_mises_pa = std::max(peak.von_mises_pa, value);
    peak.sample += duration_s_ / step_s * offset / sub;
  }
  peak.nearest_sample = static_cast<long>(std::lround(peak.sample));
}

stepping_detail::ForcingScalars IntervalRefiner::loadAt(double t) const {
  stepping_detail::ForcingScalars f;
  f.acc = s0_.acc + t * (s1_.acc - s0_.acc);
  const double rate = d0_.rate_rad_s + t * (d1_.rate_rad_s - d0_.rate_rad_s);
  f.rate2 = rate * rate;
  f.gx = s0_.gx + t * (s1_.gx - s0_.gx);
  f.gy = s0_.gy + t * (s1_.gy - s0_.gy);
  return f;
}

double IntervalRefiner::valueAt(int i, int station, double fraction) {
  x_.resize(ev_.inputSize(), 1);
  stateAt(fraction, x_.col(0));
  return ev_.station(i, station, x_.col(0));
}

void IntervalRefiner::stateAt(double fraction, Eigen::Ref<Eigen::VectorXd> x) {
  if (fraction > 0.0 && closed_form_) {
    // Each mode as prepare() splits it: the particular solution of the interval's linear forcing,
    // η_p(τ) = η_p(0) + η̇_p τ, plus the free oscillation from y₀ = η₀ − η_p(0), ẏ₀ = η̇₀ − η̇_p,
    //   y(τ) = e^{−ζωτ} (y₀ cos ω_d τ + (ẏ₀ + ζω y₀)/ω_d sin ω_d τ),
    //   ẏ(τ) = e^{−ζωτ} (ẏ₀ cos ω_d τ − (ω² y₀ + ζω ẏ₀)/ω_d sin ω_d τ),   ω_d = ω(1 − ζ²)^½:
    // the exact state a share `fraction` in (the exact maps of that length agree to round-off),
    // without a matrix exponential per mode for a length used once (a polish's vertex).
    const double tau = fraction * duration_s_;
    eta_.resize(k_);
    eta_dot_.resize(k_);
    for (int i = 0; i < k_; ++i) {
      const double y0 = e0_[i] - p0_[i], v0 = v0_[i] - tmp_[i];
      const double decay = std::exp(-zeta_w_[i] * tau);
      const double c = std::cos(w_damped_[i] * tau), s = std::sin(w_damped_[i] * tau);
      eta_[i] =
          p0_[i] + tmp_[i] * tau + decay * (y0 * c + (v0 + zeta_w_[i] * y0) / w_damped_[i] * s);
      eta_dot_[i] =
          tmp_[i] + decay * (v0 * c - (w_[i] * w_[i] * y0 + zeta_w_[i] * v0) / w_damped_[i] * s);
    }
    ev_.input(eta_, eta_dot_, loadAt(fraction), x);
    return;
  }
  stateAtByMaps(fraction, x);
}

void IntervalRefiner::stateAtByMaps(double fraction, Eigen::Ref<Eigen::VectorXd> x) {
  eta_ = e0_.matrix();
  eta_dot_ = v0_.matrix();
  if (fraction > 0.0) {
    fa_ = f0_;
    fb_ = f0_ + fraction * (f1_ - f0_);
    advance(maps(duration_s_ * fraction, 1));
  }
  ev_.input(eta_, eta_dot_, loadAt(fraction), x);
}

void IntervalRefiner::end(Eigen::VectorXd& eta, Eigen::VectorXd& eta_dot) {
  eta_ = e0_.matrix();
  eta_dot_ = v0_.matrix();
  fa_ = f0_;
  fb_ = f1_;
  advance(maps(duration_s_, 1));
  eta = eta_;
  eta_dot = eta_dot_;
}

void IntervalRefiner::modalForcing(const stepping_detail::ForcingScalars& f,
                                   Eigen::ArrayXd& out) const {
  // The stepping's own forcing arrays (rom/model/modal_stepping.hpp), without the Coriolis term.
  out = -f.acc * ms_.gamma - f.rate2 * ms_.gamma_c;
  if (f.gx != 0.0 || f.gy != 0.0) out += f.gx * ms_.momentum_x + f.gy * ms_.momentum_y;
}

const ModalStepping::Maps& IntervalRefiner::maps(double duration_s, int sub) {
  for (const auto& [d, n, m] : cache_)
    if (d == duration_s && n == sub) return m;
  cache_.push_back({duration_s, sub, modalStepMaps(m_, duration_s / sub)});
  return std::get<2>(cache_.back());
}

void IntervalRefiner::advance(const ModalStepping::Maps& h) {
  next_ = h.a00 * eta_.array() + h.a01 * eta_dot_.array() + h.b00 * fa_ + h.b10 * fb_;
  eta_dot_.array() = h.a10 * eta_.array() + h.a11 * eta_dot_.array() + h.b01 * fa_ + h.b11 * fb_;
  eta_ = next_.matrix();
}

}  // namespace mastrom::rom::stress_detail
