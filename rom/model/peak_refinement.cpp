// The continuous peaks of a ROM deployment (peak_refinement.hpp). "The method" below is the header
// comment of rom/model/deployment_metrics.hpp.
#include "rom/model/peak_refinement.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/error.hpp"

namespace mastrom::rom {
namespace metrics_detail {
namespace {

thread_local PeakRefinementStats last_stats;

/// The drive between two instants of a step of the given duration (the method: θ̈ linear, θ̇ and θ
/// cubic Hermite), at fraction σ ∈ [0, 1].
struct DriveBetween {
  double rate = 0.0, acc = 0.0, angle_increment = 0.0;
};
DriveBetween driveBetween(const DriveInstant& d0, const DriveInstant& d1, double duration,
                          double sigma) {
  const double s = sigma, s2 = s * s, s3 = s2 * s, s4 = s3 * s;
  const double slope0 = duration * d0.acceleration_rad_s2,
               slope1 = duration * d1.acceleration_rad_s2;
  DriveBetween d;
  d.acc = d0.acceleration_rad_s2 + (d1.acceleration_rad_s2 - d0.acceleration_rad_s2) * s;
  d.rate = (2.0 * s3 - 3.0 * s2 + 1.0) * d0.rate_rad_s + (s3 - 2.0 * s2 + s) * slope0 +
           (3.0 * s2 - 2.0 * s3) * d1.rate_rad_s + (s3 - s2) * slope1;
  // ∫₀^σ of the Hermite basis, times the duration.
  d.angle_increment =
      duration *
      ((s - s3 + 0.5 * s4) * d0.rate_rad_s + (0.5 * s2 - 2.0 * s3 / 3.0 + 0.25 * s4) * slope0 +
       (s3 - 0.5 * s4) * d1.rate_rad_s + (0.25 * s4 - s3 / 3.0) * slope1);
  return d;
}

}  // namespace

PeakRefinementStats& threadPeakRefinementStats() { return last_stats; }

PeakRefiner::PeakRefiner(const ModalModel& m, const ModalStepping& ms, const SampledDrive& drive,
                         const OutputEvaluator& eval, double drive_end_time_s, double band)
    : ms_(ms),
      drive_(drive),
      eval_(eval),
      t_d_(drive_end_time_s),
      k_(ms.modes),
      rel_floor_(band),
      rel_slack_(kUnresolvedPeakShare * band) {
  const Eigen::ArrayXd omega = m.omega_rad_s.array();
  const Eigen::ArrayXd zeta = m.damping_ratio.array();
  const double omega_max = omega.maxCoeff();
  const double dt = drive.step_s;
  always_refine_ = !(omega.minCoeff() > 0.0);  // a rigid mode: no free-vibration bound
  // Levels ℓ = 0 … L of sub-steps h = Δ/2^ℓ, down to ω_max h ≤ 0.3; the finest maps from the
  // oscillator exponentials, each coarser one composed from two of the next finer (exact for
  // forcing linear over both: A' = A², B₀' = AB₀ + ½(AB₁ + B₀), B₁' = B₁ + ½(AB₁ + B₀)).
  int levels = 0;
  while (levels < 20 && omega_max * dt / std::ldexp(1.0, levels) > kRefinedPhasePerSubStep)
    ++levels;
  level_maps_.resize(static_cast<std::size_t>(levels) + 1);
  level_maps_.back() = modalStepMaps(m, dt / std::ldexp(1.0, levels));
  for (int l = levels - 1; l >= 0; --l) {
    const ModalStepping::Maps& f = level_maps_[static_cast<std::size_t>(l) + 1];
    ModalStepping::Maps& c = level_maps_[static_cast<std::size_t>(l)];
    const Eigen::ArrayXd mid0 = f.a00 * f.b10 + f.a01 * f.b11 + f.b00;  // (AB₁ + B₀)
    const Eigen::ArrayXd mid1 = f.a10 * f.b10 + f.a11 * f.b11 + f.b01;
    c.a00 = f.a00 * f.a00 + f.a01 * f.a10;
    c.a01 = f.a00 * f.a01 + f.a01 * f.a11;
    c.a10 = f.a10 * f.a00 + f.a11 * f.a10;
    c.a11 = f.a10 * f.a01 + f.a11 * f.a11;
    c.b00 = f.a00 * f.b00 + f.a01 * f.b01 + 0.5 * mid0;
    c.b01 = f.a10 * f.b00 + f.a11 * f.b01 + 0.5 * mid1;
    c.b10 = f.b10 + 0.5 * mid0;
    c.b11 = f.b11 + 0.5 * mid1;
  }
  for (const SampledDrive::Split& split : drive.splits) {
    std::vector<PieceMaps> pieces;
    for (const SampledDrive::Piece& piece : split.pieces) {
      const int count = static_cast<int>(std::clamp(
          std::ceil(omega_max * piece.duration_s / kRefinedPhasePerSubStep), 1.0, 1e6));
      pieces.push_back({count, modalStepMaps(m, piece.duration_s / count)});
    }
    piece_maps_.push_back(std::move(pieces));
  }
  omega_ = omega;
  propagate_ = !always_refine_ && !ms.coriolis;  // Coriolis: the forcing depends on η̇
  s_ = (1.0 + 4.0 * zeta.square()).sqrt();
  if (!always_refine_) {
    two_zeta_over_omega_ = 2.0 * zeta / omega;
    inv_omega_ = omega.inverse();
  }
  // Modal weights of the three outputs (|ÿ| ≤ √(1+4ζ²) a, a = ω√E).
  w_rel_ = m.end_rotation.row(2).transpose().array().abs() * s_;
  w_force_ = m.momentum_participation.colwise().norm().transpose().array() * s_;
  w_torque_ = m.rotation_participation.array().abs() * s_;
  // Bound rows: the η̈ rows times the deviation of ÿ from its chord over the step,
  // |ÿ − chord| ≤ min(2 √(1+4ζ²) a, (Δ²/8) max|y⁗|) with |y⁗| ≤ √(1+4ζ²)(2+4ζ²) ω² a (the energy
  // bound applied to ÿ and ⃛y, which obey the same equation); the η, η̇ terms of F and τ
  // (|ẏ| ≤ a/ω, |y| ≤ a/ω², times the drive's max |θ̇|, |θ̈| and |g|) twice: once in the end
  // values, once between.
  const Eigen::ArrayXd deviation =
      ((2.0 + 4.0 * zeta.square()) * (omega * dt).square() / 8.0).min(2.0);
  const Eigen::ArrayXd l_xy =
      m.momentum_participation.topRows<2>().colwise().norm().transpose().array();
  const Eigen::ArrayXd gamma_c = m.centrifugal_participation.array().abs();
  const double rate = drive.max_abs_rate_rad_s, acc = drive.max_abs_acceleration_rad_s2;
  const double g = m.gravity_m_s2.head<2>().norm();
  bound_rows_ = Eigen::Matrix<double, 4, Eigen::Dynamic>::Zero(4, k_);
  bound_rows_.row(kRelChord) = (w_rel_ * deviation).matrix().transpose();
  bound_rows_.row(kRelPlain) = w_rel_.matrix().transpose();
  bound_rows_.row(kForce) = (w_force_ * deviation).matrix().transpose();
  bound_rows_.row(kTorque) = (w_torque_ * deviation).matrix().transpose();
  if (!always_refine_) {
    bound_rows_.row(kForce) +=
        (2.0 * (2.0 * rate * l_xy / omega + (acc + rate * rate + g) * l_xy / omega.square()))
            .matrix()
            .transpose();
    bound_rows_.row(kTorque) +=
        (2.0 * (2.0 * rate * gamma_c / omega + (2.0 * acc * gamma_c + g * l_xy) / omega.square()))
            .matrix()
            .transpose();
  }
  if (propagate_) {
    // Per drive scalar (θ̈, θ̇², g_x, g_y): |coefficient| of each mode's forcing, then the bound
    // rows' growth per unit jump of the scalar and per unit change of its slope.
    Eigen::Matrix<double, Eigen::Dynamic, 4> coefficients(k_, 4);
    coefficients.col(0) = m.rotation_participation.cwiseAbs();
    coefficients.col(1) = m.centrifugal_participation.cwiseAbs();
    coefficients.col(2) = m.momentum_participation.row(0).transpose().cwiseAbs();
    coefficients.col(3) = m.momentum_participation.row(1).transpose().cwiseAbs();
    jump_rows_ = bound_rows_ * coefficients;
    const Eigen::VectorXd slope_factor = ((1.0 + 2.0 * zeta) / omega).matrix();
    slope_rows_ = bound_rows_ * (slope_factor.asDiagonal() * coefficients);
  }
  for (Eigen::ArrayXd* a : {&amp_, &share_, &fa_, &fb_})
    a->resize(k_);
  for (Eigen::VectorXd* x : {&eta_, &eta_dot_, &eta_ddot_}) x->resize(k_);
  last_stats.sub_steps_per_step = 1 << levels;
}

void PeakRefiner::beforeStep(long n, int piece, const Eigen::VectorXd& eta,
                             const Eigen::VectorXd& eta_dot, const Eigen::ArrayXd& f_start,
                             const Eigen::ArrayXd& f_end) {
  if (piece >= 0) {  // pieces of a split step: next to a breakpoint, always refined
    const SampledDrive::Split& split = drive_.splits[next_split_];
    double t0 = static_cast<double>(n) * drive_.step_s;
    for (int j = 0; j < piece; ++j) t0 += split.pieces[static_cast<std::size_t>(j)].duration_s;
    const SampledDrive::Piece& p = split.pieces[static_cast<std::size_t>(piece)];
    const PieceMaps& maps = piece_maps_[next_split_][static_cast<std::size_t>(piece)];
    const bool continues = piece == 0 && continuesAt(n);
    refine(maps.maps, maps.count, p.duration_s, t0, eta, eta_dot, f_start, f_end, p.start, p.end,
           continues);
    if (static_cast<std::size_t>(piece) + 1 == split.pieces.size()) {
      ++next_split_;
      refined_end_ = n + 1;
    }
    return;
  }
  // A whole step: its bound now, the decision once its end sample is known (afterSample).
  pending_ = n;
  eta0_ = eta.data();
  eta_dot0_ = eta_dot.data();
  f0_ = f_start.data();
  f1_ = f_end.data();
  exact_ = false;
  bounds_valid_ = false;
  if (!propagate_) return;
  // The bound of this step from the last one's, in O(1) (the method): a_i can grow only by the
  // change of the particular solution at t_n, |Δu_i| + |Δv_i| ≤ |Δf_i| + (1+2ζ_i)/ω_i |Δḟ_i|,
  // and f_i = −Γ_i θ̈ − Γ_c,i θ̇² + L_x,i g_x + L_y,i g_y changes through four drive scalars.
  const Eigen::Vector4d start = driveScalars(drive_.startOf(n)),
                        end = driveScalars(drive_.endAt(n + 1));
  const Eigen::Vector4d slope = (end - start) / drive_.step_s;
  if (last_step_ == n - 1 && last_bounds_valid_) {
    bounds_ += jump_rows_ * (start - last_end_).cwiseAbs() +
               slope_rows_ * (slope - last_slope_).cwiseAbs();
    bounds_valid_ = true;
  }
  last_step_ = n;
  last_end_ = end;
  last_slope_ = slope;
}

void PeakRefiner::exactBounds() {
  // The free part y = η − η_p of the step (the method): u = ω²y, v = ωẏ, a = √(u² + v²) = ω√E.
  freeAmplitudes(ms_, omega_, two_zeta_over_omega_, inv_omega_, eta0_, eta_dot0_, f0_, f1_,
                 drive_.step_s, amp_);
  bounds_.setZero();
  for (int i = 0; i < k_; ++i) bounds_.noalias() += bound_rows_.col(i) * amp_[i];
  exact_ = bounds_valid_ = true;
}

Eigen::Vector4d PeakRefiner::driveScalars(const DriveInstant& d) const {
  const stepping_detail::ForcingScalars f = stepping_detail::forcingScalars(ms_, d);
  return {f.acc, f.rate2, f.gx, f.gy};
}

bool PeakRefiner::mayExceed(const Outputs& prev, const Outputs& o, const DriveInstant& d0,
                            const DriveInstant& d1, double peak_abs, double peak_rel,
                            double peak_force, double peak_torque, double residual,
                            bool after_drive) const {
  const double acc_max =
      std::max(std::abs(d0.acceleration_rad_s2), std::abs(d1.acceleration_rad_s2));
  const double rel =
      std::min(std::max(std::abs(prev.rel_acc), std::abs(o.rel_acc)) + bounds_[kRelChord],
               bounds_[kRelPlain]);
  const double abs = std::min(std::max(prev.abs_acc, o.abs_acc) + bounds_[kRelChord],
                              acc_max + bounds_[kRelPlain]);
  return rel > peak_rel + rel_slack_ || abs > peak_abs + rel_slack_ ||
         std::max(prev.force, o.force) + bounds_[kForce] > peak_force ||
         std::max(prev.torque, o.torque) + bounds_[kTorque] > peak_torque ||
         (after_drive && rel > residual + rel_slack_);
}

void PeakRefiner::afterSample(long n, const Outputs& o,
                              const fullorder::DeploymentMetrics& sampled) {
  const Outputs prev = last_;
  last_ = o;
  ++last_stats.steps;
  if (n == 0 || pending_ != n - 1) return;
  pending_ = -1;
  const DriveInstant d0 = drive_.startOf(n - 1), d1 = drive_.endAt(n);
  const double dt = drive_.step_s;
  const double t0 = static_cast<double>(n - 1) * dt, t1 = static_cast<double>(n) * dt;
  // Breakpoints on the grid at either end: the one-sided limits differ from the samples.
  const bool at_breakpoint =
      !sameLimits(d0, drive_.valueAt(n - 1)) || !sameLimits(d1, drive_.valueAt(n));
  const double peak_abs = std::max(sampled.peak_abs_end_angular_acceleration, abs_.max());
  const double peak_rel = std::max(sampled.peak_rel_end_angular_acceleration, rel_.max());
  const double peak_force = std::max(sampled.peak_joint_force, force_.max());
  const double peak_torque = std::max(sampled.peak_drive_torque, torque_.max());
  const double residual =
      std::max(sampled.residual_rel_end_angular_acceleration, residual_.max());
  const bool after_drive = t1 > t_d_;
  if (!always_refine_ && !at_breakpoint) {
    if (!bounds_valid_) exactBounds();
    bool may_exceed = mayExceed(prev, o, d0, d1, peak_abs, peak_rel, peak_force, peak_torque,
                                residual, after_drive);
    if (may_exceed && !exact_) {  // the propagated bound is not enough: the exact one
      exactBounds();
      may_exceed = mayExceed(prev, o, d0, d1, peak_abs, peak_rel, peak_force, peak_torque,
                             residual, after_drive);
    }
    last_bounds_valid_ = true;
    if (!may_exceed) return;
  }
  if (!always_refine_ && !exact_) exactBounds();  // the level needs the modal amplitudes
  last_bounds_valid_ = !always_refine_;
  // The level: the coarsest whose estimated polish error, Σ_i ρ_i e(ω_i h) with ρ_i the share of
  // mode i in the running peaks and e(x) = min(2, 0.0234 x⁴) (the method; parabola_polish.hpp), is
  // at most kUnresolvedPeakShare; the finest otherwise.
  int level = static_cast<int>(level_maps_.size()) - 1;
  if (!always_refine_) {
    const double rel_ref =
        std::max(rel_floor_, after_drive ? std::min(peak_rel, residual) : peak_rel);
    for (int i = 0; i < k_; ++i)
      share_[i] = amp_[i] * std::max({w_rel_[i] / rel_ref, w_force_[i] / peak_force,
                                      w_torque_[i] / peak_torque});
    for (int l = 0; l < level; ++l) {
      const double h = dt / std::ldexp(1.0, l);
      double error = 0.0;
      for (int i = 0; i < k_; ++i) {
        error += share_[i] * polishError(omega_[i] * h);
      }
      if (error <= kUnresolvedPeakShare) {  // false for a NaN or ∞ from a zero peak
        level = l;
        break;
      }
    }
  }
  const bool continues = continuesAt(n - 1);
  if (level == 0 && !at_breakpoint) {
    // The samples resolve every mode that matters: polish them (no re-stepping).
    ++last_stats.refined_steps;
    if (!continues) {
      restartAll();
      pushNode(prev, t0 >= t_d_, dt);
    }
    pushNode(o, t1 >= t_d_, dt);
  } else {
    refine(level_maps_[static_cast<std::size_t>(level)], 1 << level, dt, t0,
           Eigen::Map<const Eigen::VectorXd>(eta0_, k_),
           Eigen::Map<const Eigen::VectorXd>(eta_dot0_, k_), ConstMap(f0_, k_), ConstMap(f1_, k_),
           d0, d1, continues);
  }
  refined_end_ = n;
}

void PeakRefiner::finish(fullorder::DeploymentMetrics& out) const {
  out.peak_abs_end_angular_acceleration =
      std::max(out.peak_abs_end_angular_acceleration, abs_.max());
  out.peak_rel_end_angular_acceleration =
      std::max(out.peak_rel_end_angular_acceleration, rel_.max());
  out.peak_joint_force = std::max(out.peak_joint_force, force_.max());
  out.peak_drive_torque = std::max(out.peak_drive_torque, torque_.max());
  out.residual_rel_end_angular_acceleration =
      std::max(out.residual_rel_end_angular_acceleration, residual_.max());
}

PeakRefiner::RunningPeaks PeakRefiner::running(const fullorder::DeploymentMetrics& sampled) const {
  RunningPeaks p;
  p.abs_acc = std::max(sampled.peak_abs_end_angular_acceleration, abs_.max());
  p.rel_acc = std::max(sampled.peak_rel_end_angular_acceleration, rel_.max());
  p.force = std::max(sampled.peak_joint_force, force_.max());
  p.torque = std::max(sampled.peak_drive_torque, torque_.max());
  p.residual = std::max(sampled.residual_rel_end_angular_acceleration, residual_.max());
  return p;
}

bool PeakRefiner::sameLimits(const DriveInstant& a, const DriveInstant& b) {
  return a.rate_rad_s == b.rate_rad_s && a.acceleration_rad_s2 == b.acceleration_rad_s2;
}

bool PeakRefiner::continuesAt(long n) const {
  return refined_end_ == n && sameLimits(drive_.startOf(n), drive_.endAt(n));
}

void PeakRefiner::restartAll() {
  for (PolishedMax* p : {&abs_, &rel_, &force_, &torque_, &residual_}) p->restart();
}

void PeakRefiner::pushNode(const Outputs& o, bool residual, double spacing) {
  abs_.push(o.abs_acc, spacing);
  rel_.push(std::abs(o.rel_acc), spacing);
  force_.push(o.force, spacing);
  torque_.push(o.torque, spacing);
  if (residual) {
    residual_.push(std::abs(o.rel_acc), spacing);
  } else {
    residual_.restart();
  }
}

void PeakRefiner::refine(const ModalStepping::Maps& maps, int count, double duration, double t0,
                         const Eigen::Ref<const Eigen::VectorXd>& eta,
                         const Eigen::Ref<const Eigen::VectorXd>& eta_dot,
                         const Eigen::Ref<const Eigen::ArrayXd>& f0,
                         const Eigen::Ref<const Eigen::ArrayXd>& f1, const DriveInstant& d0,
                         const DriveInstant& d1, bool continues) {
  ++last_stats.refined_steps;
  last_stats.sub_steps += count;
  eta_ = eta;
  eta_dot_ = eta_dot;
  double c0 = 1.0, s0 = 0.0;
  if (ms_.gravity) ms_.rotation(d0.sin_angle, d0.cos_angle, c0, s0);
  // Residual: nodes strictly after t_d (a left limit at t_d is still under the drive), or a
  // start node at t_d or later (a sample, or a piece's right limit).
  const double after_drive = t_d_ + 1e-9 * drive_.step_s;
  const auto node = [&](int j) {  // (η, η̇, η̈) of sub-node j in eta_, eta_dot_, eta_ddot_
    const double sigma = static_cast<double>(j) / count;
    const DriveBetween d = driveBetween(d0, d1, duration, sigma);
    double c = 1.0, s = 0.0;
    if (ms_.gravity) {
      const double cd = std::cos(d.angle_increment), sd = std::sin(d.angle_increment);
      c = c0 * cd - s0 * sd;
      s = s0 * cd + c0 * sd;
    }
    const Outputs o = eval_.at(eta_, eta_dot_, eta_ddot_, d.rate, d.acc, c, s);
    MASTROM_REQUIRE(std::isfinite(o.rel_acc) && std::isfinite(o.force) && std::isfinite(o.torque),
                    NumericalError,
                    "rom deployment metrics: non-finite output at t = ", t0 + sigma * duration,
                    " s (between samples)");
    const double t = j == count ? t0 + duration : t0 + sigma * duration;
    pushNode(o, t > after_drive || (j == 0 && t0 >= t_d_), duration / count);
  };
  if (!continues) {
    restartAll();
    stepping_detail::modalAccelerations(ms_, f0.data(), eta_.data(), eta_dot_.data(),
                                        eta_ddot_.data());
    node(0);
  }
  subStep(ms_, maps, count, eta_.data(), eta_dot_.data(), f0.data(), f1.data(), fa_, fb_,
          eta_ddot_.data(), node);
}

}  // namespace metrics_detail

PeakRefinementStats lastPeakRefinementStats() {
  return metrics_detail::threadPeakRefinementStats();
}

}  // namespace mastrom::rom
