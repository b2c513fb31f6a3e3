#include "rom/model/modal_stepping.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "rom/model/modal_oscillator.hpp"

namespace mastrom::rom {
namespace {

DriveInstant instant(const fullorder::DriveState& d) {
  return {d.rate_rad_s, d.acceleration_rad_s2, std::sin(d.angle_rad), std::cos(d.angle_rad)};
}

}  // namespace

ModalStepping::Maps modalStepMaps(const ModalModel& m, double step_s) {
  const int k = m.modeCount();
  ModalStepping::Maps maps;
  for (Eigen::ArrayXd* c :
       {&maps.a00, &maps.a01, &maps.a10, &maps.a11, &maps.b00, &maps.b01, &maps.b10, &maps.b11})
    c->resize(k);
  for (int i = 0; i < k; ++i) {
    const OscillatorStep s = discretizeOscillator(m.omega_rad_s[i], m.damping_ratio[i], step_s);
    maps.a00[i] = s.a(0, 0);
    maps.a01[i] = s.a(0, 1);
    maps.a10[i] = s.a(1, 0);
    maps.a11[i] = s.a(1, 1);
    maps.b00[i] = s.b0[0];
    maps.b01[i] = s.b0[1];
    maps.b10[i] = s.b1[0];
    maps.b11[i] = s.b1[1];
  }
  return maps;
}

SampledDrive sampleDrive(const fullorder::DriveLaw& drive, const ModalDeploymentOptions& options) {
  MASTROM_REQUIRE(std::isfinite(options.step_s) && options.step_s > 0, InputError,
                  "rom: step = ", options.step_s, " s must be > 0");
  MASTROM_REQUIRE(std::isfinite(options.end_time_s) && options.end_time_s > 0, InputError,
                  "rom: end_time = ", options.end_time_s, " s must be > 0");
  const double dt = options.step_s;
  SampledDrive out;
  out.step_s = dt;
  out.steps = static_cast<long>(std::ceil(options.end_time_s / dt - 1e-9));
  MASTROM_REQUIRE(out.steps >= 1 && out.steps <= 1000000000L, InputError,
                  "rom: end_time / step = ", options.end_time_s / dt,
                  " samples; allowed: 1 to 1e9");
  // One-sided limits: the drive laws are right-continuous in θ̈, so the value at a sample is also
  // the forcing at the start of the next step; the end of a step needs the left limit, which
  // differs only at a breakpoint. A breakpoint within ±1e-9 Δ of a sample counts as on the grid.
  const double left = 1e-9 * dt;
  out.samples.resize(static_cast<std::size_t>(out.steps + 1));
  for (long n = 0; n <= out.steps; ++n) {
    const fullorder::DriveState d = drive.at(static_cast<double>(n) * dt);
    SampledDrive::Sample& s = out.samples[static_cast<std::size_t>(n)];
    s.angle_rad = d.angle_rad;
    s.rate_rad_s = s.start_rate_rad_s = s.end_rate_rad_s = d.rate_rad_s;
    s.acceleration_rad_s2 = s.start_acceleration_rad_s2 = s.end_acceleration_rad_s2 =
        d.acceleration_rad_s2;
    s.sin_angle = std::sin(d.angle_rad);
    s.cos_angle = std::cos(d.angle_rad);
  }
  const std::vector<double> breaks = drive.breakpoints();  // ascending
  for (const double tb : breaks) {
    const long nearest = std::lround(tb / dt);
    if (nearest < 0 || nearest > out.steps) continue;
    const double tn = static_cast<double>(nearest) * dt;
    if (std::abs(tb - tn) > left) continue;
    SampledDrive::Sample& s = out.samples[static_cast<std::size_t>(nearest)];
    const fullorder::DriveState after = drive.at(tn + left), before = drive.at(tn - left);
    s.start_rate_rad_s = after.rate_rad_s;
    s.start_acceleration_rad_s2 = after.acceleration_rad_s2;
    s.end_rate_rad_s = before.rate_rad_s;
    s.end_acceleration_rad_s2 = before.acceleration_rad_s2;
  }
  for (const SampledDrive::Sample& s : out.samples) {
    out.max_abs_rate_rad_s = std::max({out.max_abs_rate_rad_s, std::abs(s.rate_rad_s),
                                       std::abs(s.start_rate_rad_s), std::abs(s.end_rate_rad_s)});
    out.max_abs_acceleration_rad_s2 =
        std::max({out.max_abs_acceleration_rad_s2, std::abs(s.acceleration_rad_s2),
                  std::abs(s.start_acceleration_rad_s2), std::abs(s.end_acceleration_rad_s2)});
  }
  // Breakpoints strictly inside a step split it into pieces.
  for (std::size_t b = 0; b < breaks.size(); ++b) {
    const long n = static_cast<long>(std::floor(breaks[b] / dt));
    if (n < 0 || n >= out.steps) continue;
    const double t0 = static_cast<double>(n) * dt, t1 = static_cast<double>(n + 1) * dt;
    if (breaks[b] <= t0 + left || breaks[b] >= t1 - left) continue;
    if (!out.splits.empty() && out.splits.back().step == n) continue;  // already split there
    std::vector<double> times{t0};
    for (const double tb : breaks)
      if (tb > times.back() + left && tb < t1 - left) times.push_back(tb);
    times.push_back(t1);
    SampledDrive::Split split;
    split.step = n;
    for (std::size_t j = 0; j + 1 < times.size(); ++j) {
      split.pieces.push_back({times[j + 1] - times[j], instant(drive.at(times[j] + left)),
                              instant(drive.at(times[j + 1] - left))});
    }
    out.splits.push_back(std::move(split));
  }
  // Block summaries for the quiet blocks of the metrics (rom/model/quiet_blocks.hpp).
  std::size_t split = 0;
  for (long first = 0; first < out.steps; first += SampledDrive::kBlockSteps) {
    const long last = std::min(first + SampledDrive::kBlockSteps, out.steps);
    SampledDrive::Block b;
    while (split < out.splits.size() && out.splits[split].step < first) ++split;
    b.breakpoint = split < out.splits.size() && out.splits[split].step < last;
    b.angle_min = b.angle_max = out.samples[static_cast<std::size_t>(first)].angle_rad;
    double acc_slope_prev = 0.0, rate2_slope_prev = 0.0;
    for (long j = first; j <= last; ++j) {
      const SampledDrive::Sample& d = out.samples[static_cast<std::size_t>(j)];
      b.breakpoint = b.breakpoint || d.start_rate_rad_s != d.rate_rad_s ||
                     d.end_rate_rad_s != d.rate_rad_s ||
                     d.start_acceleration_rad_s2 != d.acceleration_rad_s2 ||
                     d.end_acceleration_rad_s2 != d.acceleration_rad_s2;
      b.acc_max = std::max(b.acc_max, std::abs(d.acceleration_rad_s2));
      b.rate_max = std::max(b.rate_max, std::abs(d.rate_rad_s));
      b.angle_min = std::min(b.angle_min, d.angle_rad);
      b.angle_max = std::max(b.angle_max, d.angle_rad);
      if (j == first) continue;
      const SampledDrive::Sample& p = out.samples[static_cast<std::size_t>(j - 1)];
      const double acc_slope = (d.acceleration_rad_s2 - p.acceleration_rad_s2) / dt;
      const double rate2_slope = (d.rate_rad_s * d.rate_rad_s - p.rate_rad_s * p.rate_rad_s) / dt;
      b.jerk_max = std::max(b.jerk_max, std::abs(acc_slope));
      b.rate2_slope_max = std::max(b.rate2_slope_max, std::abs(rate2_slope));
      if (j > first + 1) {
        b.acc_slope_changes += std::abs(acc_slope - acc_slope_prev);
        b.rate2_slope_changes += std::abs(rate2_slope - rate2_slope_prev);
      }
      acc_slope_prev = acc_slope;
      rate2_slope_prev = rate2_slope;
    }
    out.blocks.push_back(b);
  }
  return out;
}

const SampledDrive::Split& SampledDrive::splitAt(long n) const {
  const auto it = std::lower_bound(splits.begin(), splits.end(), n,
                                   [](const Split& split, long step) { return split.step < step; });
  MASTROM_REQUIRE(it != splits.end() && it->step == n, NumericalError,
                  "rom stepping: no split for step ", n);
  return *it;
}

ModalStepping prepareModalStepping(const ModalModel& m, const SampledDrive& drive,
                                   bool coriolis_coupling) {
  m.validate();
  ModalStepping ms;
  ms.modes = m.modeCount();
  ms.step_maps = modalStepMaps(m, drive.step_s);
  for (const SampledDrive::Split& split : drive.splits) {
    std::vector<ModalStepping::Maps> pieces;
    for (const SampledDrive::Piece& piece : split.pieces)
      pieces.push_back(modalStepMaps(m, piece.duration_s));
    ms.piece_maps.push_back(std::move(pieces));
  }
  ms.gamma = m.rotation_participation.array();
  ms.gamma_c = m.centrifugal_participation.array();
  ms.damping = 2.0 * m.damping_ratio.array() * m.omega_rad_s.array();
  ms.stiffness = m.omega_rad_s.array().square();
  ms.momentum_x = m.momentum_participation.row(0).transpose().array();
  ms.momentum_y = m.momentum_participation.row(1).transpose().array();
  ms.gravity_m_s2 = m.gravity_m_s2;
  ms.gravity = !m.gravity_m_s2.isZero();
  ms.coriolis = coriolis_coupling;
  MASTROM_REQUIRE(!coriolis_coupling || m.coriolis.rows() == m.modeCount(), InputError,
                  "rom: coriolis_coupling needs the model's Coriolis matrix (", m.modeCount(),
                  " x ", m.modeCount(), "), it has none");
  ms.sin_ref = std::sin(m.reference_angle_rad);
  ms.cos_ref = std::cos(m.reference_angle_rad);
  return ms;
}

}  // namespace mastrom::rom
