// The default output step (see output_resolution.hpp; docs/theory.md §5.4a).
#include "rom/model/output_resolution.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "common/config.hpp"

namespace mastrom::rom {
namespace {

constexpr double kTwoPi = 6.283185307179586;

// Readable steps that divide every power of ten above them (2^a 5^b): at most 25 % finer than
// asked for.
constexpr std::array<double, 10> kMantissas{1.0, 1.25, 1.6, 2.0, 2.5, 3.2, 4.0, 5.0, 6.25, 8.0};

double seriesValueAtMost(double x) {
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  double best = decade;
  for (const double m : kMantissas)
    if (m * decade <= x * (1.0 + 1e-12)) best = m * decade;
  return best;
}

double seriesValueAtLeast(double x) {
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (const double m : kMantissas)
    if (m * decade >= x * (1.0 - 1e-12)) return m * decade;
  return 10.0 * decade;
}

}  // namespace

double modalForcingBound(const ModalModel& m, int k, double max_abs_acceleration_rad_s2,
                         double max_abs_rate_rad_s) {
  // f_k = −θ̈Γ_k − θ̇²Γ_c,k + g_x L_x,k + g_y L_y,k with |g_x|, |g_y| ≤ 2|g| (Rᵀg − g₀).
  return std::abs(m.rotation_participation[k]) * max_abs_acceleration_rad_s2 +
         std::abs(m.centrifugal_participation[k]) * (max_abs_rate_rad_s * max_abs_rate_rad_s) +
         (std::abs(m.momentum_participation(0, k)) + std::abs(m.momentum_participation(1, k))) *
             (2.0 * m.gravity_m_s2.norm());
}

ExcitedMode highestExcitedMode(const ModalModel& m, double max_abs_acceleration_rad_s2,
                               double max_abs_rate_rad_s) {
  const int n = m.modeCount();
  // The reported quantities' modal rows (docs/theory.md (4.3)): the end angular acceleration
  // (ψη̈), the end acceleration (end translation η̈), the joint force (Lη̈), the drive torque
  // (Γᵀη̈). The end position sees η = η̈/ω², a share of the same rows smaller by ω², so the
  // end translation's row already covers it.
  struct Row {
    const char* name;
    double (*at)(const ModalModel&, int);
  };
  static const std::array<Row, 4> rows{{
      {"end angular acceleration",
       [](const ModalModel& mm, int k) { return mm.end_rotation.col(k).norm(); }},
      {"end acceleration",
       [](const ModalModel& mm, int k) { return mm.end_translation.col(k).norm(); }},
      {"joint force",
       [](const ModalModel& mm, int k) { return mm.momentum_participation.col(k).norm(); }},
      {"drive torque",
       [](const ModalModel& mm, int k) { return std::abs(mm.rotation_participation[k]); }},
  }};
  ExcitedMode best;
  std::vector<double> rms(static_cast<std::size_t>(n));
  for (const Row& row : rows) {
    double largest = 0.0;
    for (int k = 0; k < n; ++k) {
      const double decay = m.damping_ratio[k] * m.omega_rad_s[k];  // ζω [1/s]
      const double amplitude =
          row.at(m, k) * modalForcingBound(m, k, max_abs_acceleration_rad_s2, max_abs_rate_rad_s);
      // The ringing's RMS over its decay, |c| F / √(4ζω); an undamped mode rings for ever.
      rms[k] =
          decay > 0.0 ? amplitude / std::sqrt(4.0 * decay) : (amplitude > 0.0 ? HUGE_VAL : 0.0);
      largest = std::max(largest, rms[k]);
    }
    if (!(largest > 0.0)) continue;
    for (int k = 0; k < n; ++k) {
      const double share =
          std::isinf(largest) ? (std::isinf(rms[k]) ? 1.0 : 0.0) : rms[k] / largest;
      const bool rings = m.damping_ratio[k] < 1.0;
      const double hz = m.omega_rad_s[k] / kTwoPi;
      if (rings && share >= kRingingShare && hz > best.frequency_hz)
        best = {k, hz, share, row.name};
    }
  }
  return best;
}

OutputStepChoice chooseOutputStep(const ExcitedMode& mode, double end_time_s,
                                  double bytes_per_sample, double cap_bytes) {
  OutputStepChoice c;
  c.mode = mode;
  const double resolving = mode.mode >= 0 && mode.frequency_hz > 0.0
                               ? 1.0 / (kSamplesPerPeriod * mode.frequency_hz)
                               : kFallbackOutputStepS;
  // Never coarser than the fixed default of earlier versions: the full order's RMS and settling
  // are computed from the output samples (docs/theory.md (1.6)).
  c.wanted_step_s = seriesValueAtMost(std::min(resolving, kFallbackOutputStepS));
  c.step_s = c.wanted_step_s;
  const auto samples = [end_time_s](double step) { return std::floor(end_time_s / step) + 2.0; };
  if (samples(c.step_s) * bytes_per_sample > cap_bytes) {
    // The finest series value whose samples fit: (end/step + 2) · bytes ≤ cap.
    const double room = cap_bytes / bytes_per_sample - 2.0;
    double step = room > 1.0 ? seriesValueAtLeast(end_time_s / room) : end_time_s;
    while (samples(step) * bytes_per_sample > cap_bytes && step < end_time_s)
      step = seriesValueAtLeast(step * 1.0001);
    c.step_s = std::min(step, end_time_s);
    c.capped = true;
  }
  c.samples = samples(c.step_s);
  c.output_bytes = c.samples * bytes_per_sample;
  return c;
}

std::string describeOutputStep(const OutputStepChoice& c) {
  char line[512];
  if (c.mode.mode < 0) {
    std::snprintf(line, sizeof line,
                  "output step %.3g s (default: no mode rings in the reported quantities; "
                  "%.3g samples)",
                  c.step_s, c.samples);
  } else if (!c.capped) {
    std::snprintf(line, sizeof line,
                  "output step %.3g s (default: %.1f samples per period of mode %d at %.1f Hz, "
                  "the highest the drive excites, in the %s; %.3g samples)",
                  c.step_s, c.samplesPerPeriod(), c.mode.mode + 1, c.mode.frequency_hz,
                  c.mode.quantity.c_str(), c.samples);
  } else {
    std::snprintf(line, sizeof line,
                  "output step %.3g s (default, CAPPED by the %.0f MB bound on the output: "
                  "%.1f samples per period of mode %d at %.1f Hz, the highest the drive excites, "
                  "in the %s, where %.0f were wanted at %.3g s; set output.step to override)",
                  c.step_s, kDefaultOutputBytes / 1e6, c.samplesPerPeriod(), c.mode.mode + 1,
                  c.mode.frequency_hz, c.mode.quantity.c_str(), kSamplesPerPeriod, c.wanted_step_s);
  }
  return line;
}

}  // namespace mastrom::rom
