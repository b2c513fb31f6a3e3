// The default output step (docs/theory.md §5.4a): the spacing of the output instants that resolves
// what the outputs show — at least kSamplesPerPeriod samples per period of the highest mode that
// the drive excites in the reported quantities — capped so that the output series stays within a
// stated size. Both the full order (its modes at the start configuration, rom/studies/
// default_output_step.hpp) and the ROM (its own interpolated modes) choose it here.
//
// "Excited in a reported quantity": mode k rings after a jump of the drive's forcing with η̈_k of
// amplitude up to its forcing bound F_k (modalForcingBound), seen in a quantity y through y's modal
// row c_y,k (ψ for the end rotation, the end translation, L for the joint force, Γ for the drive
// torque). The ringing's RMS over its decay is |c_y,k| F_k / √(4 ζ_k ω_k). A mode counts when it
// oscillates (ζ_k < 1) and that RMS is at least kRingingShare of the largest mode's in the same
// quantity: a mode below it adds, even unresolved, no more interpolation error than 20 samples per
// period leave in the resolved ones.
#pragma once

#include <string>

#include "rom/model/modal_model.hpp"

namespace mastrom::rom {

/// Samples per period of the highest excited mode: linear interpolation then reads a sinusoid's
/// peak at worst 1 − cos(π/20) = 1.2 % low, and its RMS error is (π/10)²/(2√30) = 0.90 %.
inline constexpr double kSamplesPerPeriod = 20.0;
/// The RMS error of linear interpolation of a sinusoid at kSamplesPerPeriod samples per period,
/// relative to its RMS, (2π/20)²/(2√30): the share of the ringing below which a mode is not
/// counted as excited (docs/theory.md (5.8)).
inline constexpr double kRingingShare = 0.0090122;
/// The stated bound on a default output: the series a chosen step makes is at most this many
/// bytes in the result file (samples × bytes per sample); above it the step is coarsened.
inline constexpr double kDefaultOutputBytes = 256e6;

/// Mode k's forcing bound |Γ_k| max|θ̈| + |Γ_c,k| max θ̇² + 2|g| (|L_x,k| + |L_y,k|) (docs/theory.md
/// (4.2): the largest f_k the drive and gravity can apply).
double modalForcingBound(const ModalModel& model, int k, double max_abs_acceleration_rad_s2,
                         double max_abs_rate_rad_s);

/// The highest mode the drive excites in a reported quantity.
struct ExcitedMode {
  int mode = -1;              ///< index into the model's modes; −1 when none rings
  double frequency_hz = 0.0;  ///< its natural frequency ω/2π
  double share = 0.0;         ///< its ringing RMS relative to the quantity's largest mode's
  std::string quantity;       ///< the reported quantity it was found in
};
ExcitedMode highestExcitedMode(const ModalModel& model, double max_abs_acceleration_rad_s2,
                               double max_abs_rate_rad_s);

/// The step chosen for a run of end_time_s.
struct OutputStepChoice {
  double step_s = 0.0;
  double wanted_step_s = 0.0;  ///< what the response alone asks for (before the cap)
  bool capped = false;         ///< the size bound made the step coarser than wanted
  double samples = 0.0;        ///< output instants of the run
  double output_bytes = 0.0;   ///< samples × bytes per sample
  ExcitedMode mode;
  /// Samples per period of the resolved mode at step_s (0 when no mode rings).
  double samplesPerPeriod() const {
    return mode.mode >= 0 ? 1.0 / (mode.frequency_hz * step_s) : 0.0;
  }
};

/// The largest step of the series 1, 1.25, 1.6, 2, 2.5, 3.2, 4, 5, 6.25, 8 × 10ⁿ that is at most
/// 1/(kSamplesPerPeriod f) of the excited mode (kFallbackOutputStepS at most, and when no mode
/// rings), then coarsened to the smallest such step whose series fits cap_bytes (samples ×
/// bytes_per_sample). These values divide the drive's round breakpoints (0.1 s, 6.1 s), so the
/// instants stay round numbers.
OutputStepChoice chooseOutputStep(const ExcitedMode& mode, double end_time_s,
                                  double bytes_per_sample, double cap_bytes = kDefaultOutputBytes);

/// One line for a run's first lines: the step, what it resolves, and the cap when it applied.
std::string describeOutputStep(const OutputStepChoice& choice);

}  // namespace mastrom::rom
