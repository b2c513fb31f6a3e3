// Bounds of the outputs over a block of steps (quiet_blocks.hpp; docs/theory.md §4.2c).
#include "rom/model/quiet_blocks.hpp"

#include <algorithm>
#include <cmath>

#include "rom/model/peak_refinement.hpp"

namespace mastrom::rom::metrics_detail {

bool& quietBlocksEnabled() {
  thread_local bool enabled = true;
  return enabled;
}

bool QuietBlockBound::supported(const ModalModel& m, const ModalStepping& ms) {
  return !ms.coriolis && m.modeCount() > 0 && m.omega_rad_s.minCoeff() > 0.0 &&
         (m.damping_ratio.array() >= 0.0).all();
}

QuietBlockBound::QuietBlockBound(const ModalModel& m, const ModalStepping& ms,
                                 const SampledDrive& drive)
    : ms_(ms), drive_(drive) {
  const Eigen::ArrayXd zeta = m.damping_ratio.array();
  omega_ = m.omega_rad_s.array();
  two_zeta_over_omega_ = 2.0 * zeta / omega_;
  inv_omega_ = omega_.inverse();
  inv_omega2_ = inv_omega_.square();
  two_zeta_over_omega3_ = two_zeta_over_omega_ * inv_omega2_;
  growth_ = (1.0 + 2.0 * zeta) * inv_omega_;  // a's growth per unit change of ḟ
  s_ = (1.0 + 4.0 * zeta.square()).sqrt();    // |ÿ| ≤ s a
  const int k = m.modeCount();
  k_abs_.resize(k, 4);
  k_abs_.col(0) = m.rotation_participation.array().abs();
  k_abs_.col(1) = m.centrifugal_participation.array().abs();
  k_abs_.col(2) = m.momentum_participation.row(0).transpose().array().abs();
  k_abs_.col(3) = m.momentum_participation.row(1).transpose().array().abs();
  w_rel_ = m.end_rotation.row(2).transpose().array().abs() * s_;
  w_force_acc_ = m.momentum_participation.colwise().norm().transpose().array() * s_;
  l_xy_ = m.momentum_participation.topRows<2>().colwise().norm().transpose().array();
  w_torque_acc_ = m.rotation_participation.array().abs() * s_;
  gamma_c_abs_ = m.centrifugal_participation.array().abs();
  const Eigen::Vector3d moment = m.total_mass_kg * m.centroid_m;
  moment_x_ = moment.x();
  moment_y_ = moment.y();
  inertia_z_ = m.inertia_z_kg_m2;
  weight_ = m.total_mass_kg * m.gravity_m_s2;
  reference_angle_ = m.reference_angle_rad;
  g_xy_ = ms.gravity ? m.gravity_m_s2.head<2>().norm() : 0.0;
  for (Eigen::ArrayXd* a : {&f0_, &f1_, &amp_}) a->resize(k);
}

void QuietBlockBound::rigidOutputs(long j, double& force, double& torque) const {
  // deployment_outputs.hpp with η = η̇ = η̈ = 0.
  const SampledDrive::Sample& d = drive_.samples[static_cast<std::size_t>(j)];
  const double th_d = d.rate_rad_s, th_dd = d.acceleration_rad_s2, th_d2 = th_d * th_d;
  const double px = th_dd * -moment_y_ - th_d2 * moment_x_;
  const double py = th_dd * moment_x_ - th_d2 * moment_y_;
  double tau_gravity = 0.0;
  if (ms_.gravity) {
    double cr = 1.0, sr = 0.0;
    ms_.rotation(d.sin_angle, d.cos_angle, cr, sr);
    force = Eigen::Vector3d(cr * px - sr * py - weight_.x(), sr * px + cr * py - weight_.y(),
                            -weight_.z())
                .norm();
    const double gx = cr * moment_x_ - sr * moment_y_, gy = sr * moment_x_ + cr * moment_y_;
    tau_gravity = gx * ms_.gravity_m_s2.y() - gy * ms_.gravity_m_s2.x();
  } else {
    force = std::hypot(px, py);
  }
  torque = std::abs(th_dd * inertia_z_ - tau_gravity);
}

template <bool kKeepState>
void QuietBlockBound::modeSums(const Eigen::Array4d& c_max, const Eigen::Array4d& slope_max,
                               const Eigen::Array4d& slope_changes, ModeSums& out) {
  // One pass over the modes: A_i, then |η̈_i| ≤ s A, |η̇_i| ≤ ḟ/ω² + A/ω,
  // |η_i| ≤ (f + A)/ω² + 2ζḟ/ω³, weighted by each output's modal rows. (A template, so that the
  // metrics' own pass, which keeps no state bounds, runs the loop it always ran.)
  double rel = 0.0, force_acc = 0.0, torque_acc = 0.0, l_eta = 0.0, l_rate = 0.0, gc_eta = 0.0,
         gc_rate = 0.0;
  for (Eigen::Index i = 0; i < amp_.size(); ++i) {
    double f_max = 0.0, f_dot_max = 0.0, changes = 0.0;
    for (int j = 0; j < 4; ++j) {
      const double k = k_abs_(i, j);
      f_max += k * c_max[j];
      f_dot_max += k * slope_max[j];
      changes += k * slope_changes[j];
    }
    const double a = amp_[i] + growth_[i] * changes;
    const double eta_max = (f_max + a) * inv_omega2_[i] + two_zeta_over_omega3_[i] * f_dot_max;
    const double rate_i = f_dot_max * inv_omega2_[i] + a * inv_omega_[i];
    if constexpr (kKeepState) eta_max_[i] = eta_max, rate_max_[i] = rate_i;
    rel += w_rel_[i] * a;
    force_acc += w_force_acc_[i] * a;
    torque_acc += w_torque_acc_[i] * a;
    l_eta += l_xy_[i] * eta_max;
    l_rate += l_xy_[i] * rate_i;
    gc_eta += gamma_c_abs_[i] * eta_max;
    gc_rate += gamma_c_abs_[i] * rate_i;
  }
  out = {rel, force_acc, torque_acc, l_eta, l_rate, gc_eta, gc_rate};
}

bool QuietBlockBound::bound(long block, const double* eta, const double* eta_dot,
                            OutputBounds& out) {
  if (static_cast<std::size_t>(block) >= drive_.blocks.size()) return false;
  const SampledDrive::Block& b = drive_.blocks[static_cast<std::size_t>(block)];
  if (b.breakpoint) return false;
  const double dt = drive_.step_s;
  const long first = block * SampledDrive::kBlockSteps;
  const long last = std::min(first + SampledDrive::kBlockSteps, drive_.steps);
  const double duration = static_cast<double>(last - first) * dt;
  // The drive scalars (θ̈, θ̇², g_x, g_y): maxima, maxima of the hold's slopes, and the sums of the
  // slopes' changes. θ̇ between samples (the cubic Hermite) within |θ̈|Δ of the samples'; the
  // gravity scalars |(Rᵀ − I)g|_xy = 2|sin((θ − θ₀)/2)| |g_xy|, their first and second time
  // derivatives within |θ̇| |g_xy| and (|θ̈| + θ̇²)|g_xy| (a slope change between neighbouring
  // steps is at most 2Δ times the second derivative).
  const double rate = b.rate_max + b.acc_max * dt, acc = b.acc_max;
  const double turn = std::min(2.0, std::max(std::abs(b.angle_max - reference_angle_),
                                             std::abs(b.angle_min - reference_angle_)));
  const double g_scalar = g_xy_ * turn, g_slope = g_xy_ * rate;
  const double g_changes =
      g_xy_ * (acc + rate * rate) * 2.0 * dt * static_cast<double>(last - first - 1);
  const Eigen::Array4d c_max(acc, rate * rate, g_scalar, g_scalar);
  const Eigen::Array4d slope_max(b.jerk_max, b.rate2_slope_max, g_slope, g_slope);
  const Eigen::Array4d slope_changes(b.acc_slope_changes, b.rate2_slope_changes, g_changes,
                                     g_changes);
  // The rigid outputs: their values at the block's ends plus their Lipschitz constants over half
  // of it (d/dt of R(θ̈ Z×m − θ̇² m) and of θ̈J − τ_g(θ)).
  double force_first = 0.0, torque_first = 0.0, force_last = 0.0, torque_last = 0.0;
  rigidOutputs(first, force_first, torque_first);
  rigidOutputs(last, force_last, torque_last);
  const double moment = std::hypot(moment_x_, moment_y_);
  const double force_rigid =
      std::max(force_first, force_last) +
      0.5 * duration * moment * (b.jerk_max + 3.0 * rate * acc + rate * rate * rate);
  const double torque_rigid =
      std::max(torque_first, torque_last) +
      0.5 * duration * (b.jerk_max * std::abs(inertia_z_) + rate * moment * g_xy_);
  // Every mode's free amplitude at t_first (its step's particular solution), then its growth
  // over the block.
  stepping_detail::modalForcing(ms_, stepping_detail::forcingScalars(ms_, drive_.valueAt(first)),
                                f0_.data());
  stepping_detail::modalForcing(
      ms_, stepping_detail::forcingScalars(ms_, drive_.valueAt(first + 1)), f1_.data());
  freeAmplitudes(ms_, omega_, two_zeta_over_omega_, inv_omega_, eta, eta_dot, f0_.data(),
                 f1_.data(), dt, amp_);
  const double rate_max = rate, acc_max = acc;
  ModeSums m;
  if (keep_state_) {
    modeSums<true>(c_max, slope_max, slope_changes, m);
    acc_max_ = acc_max, rate2_max_ = rate_max * rate_max, gravity_max_ = g_scalar;
  } else {
    modeSums<false>(c_max, slope_max, slope_changes, m);
  }
  const double rel = m.rel, force_acc = m.force_acc, torque_acc = m.torque_acc, l_eta = m.l_eta,
               l_rate = m.l_rate, gc_eta = m.gc_eta, gc_rate = m.gc_rate;
  out.rel_acc = rel;
  out.abs_acc = acc_max + rel;
  // ‖F‖: rigid part, ‖Lη̈‖, |θ̈ Z×u − θ̇² u| ≤ (|θ̈| + θ̇²)|u| for u = (Lη)_xy, 2|θ̇| ‖(Lη̇)_xy‖.
  out.force =
      force_rigid + force_acc + (acc_max + rate_max * rate_max) * l_eta + 2.0 * rate_max * l_rate;
  // |τ|: rigid part, |Γᵀη̈|, 2|θ̈||Γ_cᵀη|, 2|θ̇||Γ_cᵀη̇|, the gravity torque of (Lη)_xy.
  out.torque =
      torque_rigid + torque_acc + 2.0 * acc_max * gc_eta + 2.0 * rate_max * gc_rate + g_xy_ * l_eta;
  return std::isfinite(out.force) && std::isfinite(out.torque) && std::isfinite(out.abs_acc);
}

}  // namespace mastrom::rom::metrics_detail

namespace mastrom::rom::metrics_detail {

void QuietBlockBound::keepStateBounds() {
  keep_state_ = true;
  eta_max_.resize(amp_.size());
  rate_max_.resize(amp_.size());
}

ModalStateBounds QuietBlockBound::stateBounds() const {
  return {eta_max_.data(), rate_max_.data(), acc_max_, rate2_max_, gravity_max_};
}

}  // namespace mastrom::rom::metrics_detail
