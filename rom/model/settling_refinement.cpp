// The settling time of the continuous ROM response (settling_refinement.hpp; docs/theory.md §4.2b).
#include "rom/model/settling_refinement.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rom/model/deployment_metrics.hpp"
#include "rom/model/parabola_polish.hpp"
#include "rom/model/peak_refinement.hpp"

namespace mastrom::rom::metrics_detail {

SettlingRefiner::SettlingRefiner(const ModalModel& m, const ModalStepping& ms,
                                 const SampledDrive& drive, double drive_end_time_s, double band)
    : m_(m), ms_(ms), drive_(drive), t_d_(drive_end_time_s), band_(band), k_(ms.modes) {
  omega_ = m.omega_rad_s.array();
  const Eigen::ArrayXd zeta = m.damping_ratio.array();
  omega_max_ = omega_.maxCoeff();
  resolvable_ = omega_.minCoeff() > 0.0;
  psi_ = m.end_rotation.row(2).transpose().array();
  weight_ = psi_.abs() * (1.0 + 4.0 * zeta.square()).sqrt();
  chord_ = weight_ * ((2.0 + 4.0 * zeta.square()) * (omega_ * drive.step_s).square() / 8.0).min(2.0);
  if (resolvable_) {
    two_zeta_over_omega_ = 2.0 * zeta / omega_;
    inv_omega_ = omega_.inverse();
  }
  amp_.resize(k_);
}

void SettlingRefiner::keep(double t0, double duration, bool piece, const double* eta,
                           const double* eta_dot, const double* f0, const double* f1) {
  Candidate c;
  c.t0 = t0;
  c.duration = duration;
  c.piece = piece;
  c.offset = store_.size();
  for (const double* source : {eta, eta_dot, f0, f1})
    store_.insert(store_.end(), source, source + k_);
  candidates_.push_back(c);
}

void SettlingRefiner::amplitudes(const double* eta, const double* eta_dot, const double* f0,
                                 const double* f1, double duration) {
  freeAmplitudes(ms_, omega_, two_zeta_over_omega_, inv_omega_, eta, eta_dot, f0, f1, duration,
                 amp_);
}

void SettlingRefiner::beforeStep(long n, int piece, const Eigen::VectorXd& eta,
                                 const Eigen::VectorXd& eta_dot, const Eigen::ArrayXd& f_start,
                                 const Eigen::ArrayXd& f_end) {
  const double dt = drive_.step_s;
  if (piece >= 0) {  // a piece of a split step (next to a breakpoint): kept when after t_d
    const SampledDrive::Split& split = drive_.splitAt(n);
    double t0 = static_cast<double>(n) * dt;
    for (int j = 0; j < piece; ++j) t0 += split.pieces[static_cast<std::size_t>(j)].duration_s;
    const double duration = split.pieces[static_cast<std::size_t>(piece)].duration_s;
    if (t0 + duration > t_d_)
      keep(t0, duration, true, eta.data(), eta_dot.data(), f_start.data(), f_end.data());
    return;
  }
  pending_ = !quiet_ && static_cast<double>(n + 1) * dt > t_d_;
  if (!pending_) return;
  pending_step_ = n;
  eta0_ = eta.data();
  eta_dot0_ = eta_dot.data();
  f0_ = f_start.data();
  f1_ = f_end.data();
}

void SettlingRefiner::afterSample(long n, double r_n) {
  const double dt = drive_.step_s;
  if (pending_ && pending_step_ == n - 1) {
    pending_ = false;
    const double t0 = static_cast<double>(n - 1) * dt;
    bool candidate = !resolvable_ || t0 < t_d_ || std::abs(last_r_) > band_ ||
                     std::abs(r_n) > band_;
    if (!candidate) {
      amplitudes(eta0_, eta_dot0_, f0_, f1_, dt);
      const double plain = (weight_ * amp_).sum();
      if (plain <= band_) {
        // After the drive the forcing is constant: the amplitudes only decay from here on.
        const DriveInstant d0 = drive_.startOf(n - 1), d1 = drive_.endAt(n);
        quiet_ = d0.rate_rad_s == 0.0 && d0.acceleration_rad_s2 == 0.0 && d1.rate_rad_s == 0.0 &&
                 d1.acceleration_rad_s2 == 0.0;
      } else {
        candidate =
            std::max(std::abs(last_r_), std::abs(r_n)) + (chord_ * amp_).sum() > band_;
      }
    }
    if (candidate) keep(t0, dt, false, eta0_, eta_dot0_, f0_, f1_);
  }
  // A sample outside the band after t_d: the settling time is later than every candidate so far.
  if (static_cast<double>(n) * dt >= t_d_ && std::abs(r_n) > band_) {
    candidates_.clear();
    store_.clear();
  }
  last_r_ = r_n;
}

double SettlingRefiner::lastCrossing(const Candidate& c) {
  const double* eta = store_.data() + c.offset;
  const double* eta_dot = eta + k_;
  const double* f0 = eta_dot + k_;
  const double* f1 = f0 + k_;
  // Sub-steps: pieces and unresolvable models at the finest (ω_max h ≤ 0.3); a whole step at the
  // coarsest level whose estimated polish error, relative to the band, is ≤ kUnresolvedPeakShare.
  int count = static_cast<int>(
      std::clamp(std::ceil(omega_max_ * c.duration / kRefinedPhasePerSubStep), 1.0, 1e6));
  if (!c.piece && resolvable_) {
    amplitudes(eta, eta_dot, f0, f1, c.duration);
    const Eigen::ArrayXd share = weight_ * amp_ / band_;
    int level = 0;
    while ((1 << level) < count && level < 20) {
      const double h = c.duration / std::ldexp(1.0, level);
      double error = 0.0;
      for (int i = 0; i < k_; ++i) error += share[i] * polishError(omega_[i] * h);
      if (error <= kUnresolvedPeakShare) break;
      ++level;
    }
    count = 1 << level;
  }
  PeakRefinementStats& stats = threadPeakRefinementStats();
  ++stats.settling_steps;
  stats.settling_sub_steps += count;
  const double h = c.duration / count;
  const ModalStepping::Maps maps = modalStepMaps(m_, h);
  Eigen::ArrayXd e = Eigen::Map<const Eigen::ArrayXd>(eta, k_);
  Eigen::ArrayXd v = Eigen::Map<const Eigen::ArrayXd>(eta_dot, k_);
  const Eigen::ArrayXd f_start = Eigen::Map<const Eigen::ArrayXd>(f0, k_);
  const Eigen::ArrayXd f_end = Eigen::Map<const Eigen::ArrayXd>(f1, k_);
  const Eigen::ArrayXd fdot = (f_end - f_start) / c.duration;
  Eigen::ArrayXd fa(k_), fb(k_), acc(k_);
  // r and ṙ at every node: η̈ = f − 2ζωη̇ − ω²η, and η⃛ = ḟ − 2ζωη̈ − ω²η̇ (ḟ constant here).
  std::vector<double> r(static_cast<std::size_t>(count) + 1), rate(r.size());
  const auto node = [&](int j) {  // (η, η̇, η̈) of sub-node j in e, v, acc
    r[static_cast<std::size_t>(j)] = (psi_ * acc).sum();
    rate[static_cast<std::size_t>(j)] =
        (psi_ * (fdot - ms_.damping * acc - ms_.stiffness * v)).sum();
  };
  stepping_detail::modalAccelerations(ms_, f_start.data(), e.data(), v.data(), acc.data());
  node(0);
  subStep(ms_, maps, count, e.data(), v.data(), f_start.data(), f_end.data(), fa, fb, acc.data(),
          node);
  // Between two nodes r is the cubic Hermite interpolant of their values and slopes (error
  // ≈ (ωh)⁴/384 of a mode's amplitude). The sub-intervals from the last backwards, each sampled
  // at kProbes points, until one leaves the band at or after t_d; the crossing after its last
  // point outside is then bisected on the cubic, with the samples' sign rule (the level ±b on the
  // side of that point).
  constexpr int kProbes = 32;
  const double from = t_d_ - 1e-9 * drive_.step_s;
  for (int j = count; j >= 1; --j) {
    const double t_a = c.t0 + (j - 1) * h;
    if (t_a + h < from) break;
    const std::size_t a = static_cast<std::size_t>(j) - 1, b = static_cast<std::size_t>(j);
    const auto cubic = [&](double s) {  // s ∈ [0, 1]
      const double s2 = s * s, s3 = s2 * s;
      return (2.0 * s3 - 3.0 * s2 + 1.0) * r[a] + (s3 - 2.0 * s2 + s) * h * rate[a] +
             (3.0 * s2 - 2.0 * s3) * r[b] + (s3 - s2) * h * rate[b];
    };
    for (int p = kProbes; p >= 0; --p) {
      const double s_out = static_cast<double>(p) / kProbes;
      const double value = cubic(s_out);
      if (!(std::abs(value) > band_) || t_a + s_out * h < from) continue;
      if (p == kProbes) return t_a + h;  // only at the candidate's last node (see finish)
      const double level = value > 0.0 ? band_ : -band_, side = value > 0.0 ? 1.0 : -1.0;
      double lo = s_out, hi = static_cast<double>(p + 1) / kProbes;  // outside, inside
      for (int it = 0; it < 50; ++it) {
        const double mid = 0.5 * (lo + hi);
        (side * (cubic(mid) - level) > 0.0 ? lo : hi) = mid;
      }
      return t_a + 0.5 * (lo + hi) * h;
    }
  }
  return -std::numeric_limits<double>::infinity();
}

void SettlingRefiner::finish(fullorder::DeploymentMetrics& out) {
  if (!out.settled) return;  // the record ends outside the band: the samples' verdict stands
  for (auto it = candidates_.rbegin(); it != candidates_.rend(); ++it) {
    const double t = lastCrossing(*it);
    if (t > -std::numeric_limits<double>::infinity()) {
      out.settling_time = std::max(t_d_, t);
      return;
    }
  }
  out.settling_time = t_d_;
}

}  // namespace mastrom::rom::metrics_detail
