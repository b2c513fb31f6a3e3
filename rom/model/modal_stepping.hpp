// The exact modal stepping shared by simulateModalDeployment (rom/model/modal_deployment.hpp) and the
// streaming metrics (rom/model/deployment_metrics.hpp), organised for speed (docs/theory.md §4.2: the
// online stage must cost O(modes × samples) with a small constant):
//  * the drive law is sampled once per (law, output step, end time) into a SampledDrive — θ, θ̇, θ̈,
//    sin θ, cos θ per sample, the one-sided limits where a breakpoint sits on the grid, and the
//    pieces of the steps a breakpoint splits — and shared by every model deployed on it (a screen
//    deploys thousands of models on a handful of drives);
//  * per model, the Δ-step maps of every mode are computed once (one 4 × 4 exponential per mode,
//    rom/model/modal_oscillator.hpp) and stored flat; split pieces get their own maps;
//  * a step is a few vectorised whole-array passes over the modes: the forcing
//    −θ̈Γ − θ̇²Γ_c (+ gravity, Coriolis) — evaluated once per step away from breakpoints, where the
//    one-sided limits equal the sample values —, the 2 × 2 maps, then η̈ = f − 2ζω η̇ − ω² η;
//    no allocation inside the loop;
//  * each output set contracts (η, η̇, η̈) with a few fixed rows in one pass over the modes
//    (modal_deployment.cpp, output_contraction.hpp).
// The rotation R(θ − θ₀) is formed from the sampled sin θ, cos θ and the model's sin θ₀, cos θ₀.
// θ is continuous for every drive law (only θ̈ jumps), so a one-sided limit shares the angle of its
// instant: only θ̇ and θ̈ are evaluated on each side.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <utility>
#include <vector>

#include "common/flush_denormals.hpp"
#include "fullorder/drive_law.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/model/modal_model.hpp"

namespace mastrom::rom {

/// The drive state one forcing evaluation needs.
struct DriveInstant {
  double rate_rad_s = 0.0;
  double acceleration_rad_s2 = 0.0;
  double sin_angle = 0.0;  ///< sin θ (global angle)
  double cos_angle = 1.0;
};

/// A drive law on the output grid t_n = nΔ, n = 0 … steps.
struct SampledDrive {
  struct Sample {
    double angle_rad = 0.0, rate_rad_s = 0.0, acceleration_rad_s2 = 0.0;  ///< at t_n (outputs)
    double sin_angle = 0.0, cos_angle = 1.0;
    /// Right limit at t_n: the forcing at the start of step n → n+1.
    double start_rate_rad_s = 0.0, start_acceleration_rad_s2 = 0.0;
    /// Left limit at t_n: the forcing at the end of step n−1 → n.
    double end_rate_rad_s = 0.0, end_acceleration_rad_s2 = 0.0;
  };
  /// A step with drive-law breakpoints strictly inside: integrated piece by piece.
  struct Piece {
    double duration_s = 0.0;
    DriveInstant start, end;  ///< right limit at its start, left limit at its end
  };
  struct Split {
    long step = 0;  ///< the step n → n+1 it replaces
    std::vector<Piece> pieces;
  };
  /// What the quiet blocks' bounds need of the drive over steps b·kBlockSteps … (b+1)·kBlockSteps −
  /// 1 (rom/model/quiet_blocks.hpp): maxima over its samples t_first … t_last, and the changes of
  /// the first-order hold's slopes between its steps.
  static constexpr long kBlockSteps = 16;
  struct Block {
    bool breakpoint = false;       ///< a split step or one-sided limits on the grid: no bound
    double acc_max = 0.0;          ///< max |θ̈| [rad/s²]
    double rate_max = 0.0;         ///< max |θ̇| [rad/s]
    double jerk_max = 0.0;         ///< max |Δθ̈|/Δ of a step [rad/s³]
    double rate2_slope_max = 0.0;  ///< max |Δ(θ̇²)|/Δ of a step [rad²/s³]
    double acc_slope_changes = 0.0, rate2_slope_changes = 0.0;  ///< Σ |change of those slopes|
    double angle_min = 0.0, angle_max = 0.0;                    ///< of θ [rad]
  };
  double step_s = 0.0;
  long steps = 0;
  std::vector<Sample> samples;  ///< steps + 1 entries
  std::vector<Block> blocks;    ///< ⌈steps / kBlockSteps⌉ entries
  std::vector<Split> splits;    ///< ascending step
  /// max |θ̇| and max |θ̈| over the samples and their one-sided limits (bounds between samples:
  /// rom/model/deployment_metrics.cpp).
  double max_abs_rate_rad_s = 0.0, max_abs_acceleration_rad_s2 = 0.0;

  /// The split that replaces step n (InputError-free: the caller knows step n has one).
  const Split& splitAt(long n) const;

  DriveInstant startOf(long n) const {
    const Sample& s = samples[static_cast<std::size_t>(n)];
    return {s.start_rate_rad_s, s.start_acceleration_rad_s2, s.sin_angle, s.cos_angle};
  }
  DriveInstant endAt(long n) const {
    const Sample& s = samples[static_cast<std::size_t>(n)];
    return {s.end_rate_rad_s, s.end_acceleration_rad_s2, s.sin_angle, s.cos_angle};
  }
  DriveInstant valueAt(long n) const {
    const Sample& s = samples[static_cast<std::size_t>(n)];
    return {s.rate_rad_s, s.acceleration_rad_s2, s.sin_angle, s.cos_angle};
  }
};

/// Sample a drive law for a deployment (validates options.step_s and options.end_time_s:
/// InputError). A breakpoint within ±1e-9 Δ of a sample counts as on the grid; one strictly inside
/// a step splits it, so a jump of θ̈ acts at its true instant.
SampledDrive sampleDrive(const fullorder::DriveLaw& drive, const ModalDeploymentOptions& options);

/// Per-model constants of the stepping on one sampled drive, stored mode-contiguous (one array per
/// coefficient) so that the per-step loops over the modes vectorise.
struct ModalStepping {
  /// Every mode's exact map x ← A x + b0 f_start + b1 f_end (x = [η, η̇]) for one step length.
  struct Maps {
    Eigen::ArrayXd a00, a01, a10, a11, b00, b01, b10, b11;
  };
  int modes = 0;
  Maps step_maps;                                     ///< Δ
  std::vector<std::vector<Maps>> piece_maps;          ///< [split][piece]
  Eigen::ArrayXd gamma, gamma_c, damping, stiffness;  ///< Γ, Γ_c, 2ζω, ω²
  Eigen::ArrayXd momentum_x, momentum_y;              ///< rows x, y of L (gravity forcing)
  Eigen::Vector3d gravity_m_s2 = Eigen::Vector3d::Zero();
  bool gravity = false;
  bool coriolis = false;
  double sin_ref = 0.0, cos_ref = 1.0;  ///< of θ₀

  /// c = cos(θ − θ₀), s = sin(θ − θ₀) at a sampled instant.
  void rotation(double sin_angle, double cos_angle, double& c, double& s) const {
    c = cos_angle * cos_ref + sin_angle * sin_ref;
    s = sin_angle * cos_ref - cos_angle * sin_ref;
  }
};

/// Every mode's exact map for one step of length step_s > 0 (rom/model/modal_oscillator.hpp).
ModalStepping::Maps modalStepMaps(const ModalModel& model, double step_s);

/// Validates the model (InputError) and computes its maps for the drive's step and pieces.
ModalStepping prepareModalStepping(const ModalModel& model, const SampledDrive& drive,
                                   bool coriolis_coupling);

/// R v for the rotation about Z with cos c, sin s.
inline Eigen::Vector3d rotateZ(double c, double s, const Eigen::Vector3d& v) {
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y(), v.z()};
}

/// Z × v.
inline Eigen::Vector3d crossZ(const Eigen::Vector3d& v) { return {-v.y(), v.x(), 0.0}; }

namespace stepping_detail {

/// The scalars of the generalized forcing at one instant (docs/theory.md §4.1):
///   f_k = −θ̈ Γ_k − θ̇² Γ_c,k + L_k · (Rᵀg − g₀) − 2θ̇ (ΦᵀMΩΦ η̇)_k,
/// with Rᵀg − g₀ = (g_x, g_y, 0) for R about Z and the Coriolis term lagged to the step start.
struct ForcingScalars {
  double acc = 0.0, rate2 = 0.0, gx = 0.0, gy = 0.0, two_rate = 0.0;
};

inline ForcingScalars forcingScalars(const ModalStepping& ms, const DriveInstant& d) {
  ForcingScalars f;
  f.acc = d.acceleration_rad_s2;
  f.rate2 = d.rate_rad_s * d.rate_rad_s;
  if (ms.gravity) {
    double c = 1.0, s = 0.0;
    ms.rotation(d.sin_angle, d.cos_angle, c, s);
    const Eigen::Vector3d& g = ms.gravity_m_s2;
    f.gx = c * g.x() + s * g.y() - g.x();
    f.gy = -s * g.x() + c * g.y() - g.y();
  }
  if (ms.coriolis) f.two_rate = 2.0 * d.rate_rad_s;
  return f;
}

// The per-mode passes, compiled for the baseline ISA and AVX2 + FMA (modal_step_kernels.cpp).
// Arrays of k = ms.modes doubles; an output may be the same array as an input.

/// One step of every mode's exact map: (e_out, v_out) = A (e, v) + B₀ f0 + B₁ f1.
void stepModes(const ModalStepping::Maps& maps, long k, const double* e, const double* v,
               const double* f0, const double* f1, double* e_out, double* v_out);
/// stepModes for the model's k modes, then η̈ = f1 − 2ζω η̇ − ω² η at the new state into accel
/// (one pass: the new state is still in registers).
void stepModesWithAccelerations(const ModalStepping& ms, const ModalStepping::Maps& maps,
                                const double* e, const double* v, const double* f0,
                                const double* f1, double* e_out, double* v_out, double* accel);
/// η̈ = f − 2ζω η̇ − ω² η.
void modalAccelerations(const ModalStepping& ms, const double* f, const double* e, const double* v,
                        double* a);
/// f = −θ̈ Γ − θ̇² Γ_c (+ g_x L_x + g_y L_y with gravity; the Coriolis term is the caller's).
void modalForcing(const ModalStepping& ms, const ForcingScalars& p, double* f);
/// f = f0 + (f1 − f0) σ: the forcing at fraction σ of a step (first-order hold).
void modalForcingBetween(long k, const double* f0, const double* f1, double sigma, double* f);

}  // namespace stepping_detail

/// Re-step an interval in `count` sub-steps of `maps` from the state (e, v) = (η, η̇) (the model's
/// modes, updated in place), the forcing linear from f0 at its start to f1 at its end; calls
/// node(j) after sub-step j = 1 … count with (e, v) the state there and `accel` its η̈. fa, fb:
/// work arrays of the mode count (no allocation). What the refinements between samples share
/// (rom/model/peak_refinement, settling_refinement). The state stays in place and the forcing is
/// read where it is, not copied: Eigen's copies store 16 bytes at a time, which the AVX2 kernels'
/// 32-byte loads cannot take from the store buffer (a stall per sub-step).
template <typename Node>
void subStep(const ModalStepping& ms, const ModalStepping::Maps& maps, int count, double* e,
             double* v, const double* f0, const double* f1, Eigen::ArrayXd& fa, Eigen::ArrayXd& fb,
             double* accel, Node&& node) {
  const FlushDenormalsScope flush;  // decayed modes are subnormal: common/flush_denormals.hpp
  const double* start = f0;
  for (int j = 1; j <= count; ++j) {
    const double* end = f1;
    if (j < count) {
      double* out = start == fa.data() ? fb.data() : fa.data();
      stepping_detail::modalForcingBetween(ms.modes, f0, f1, static_cast<double>(j) / count, out);
      end = out;
    }
    stepping_detail::stepModesWithAccelerations(ms, maps, e, v, start, end, e, v, accel);
    node(j);
    start = end;
  }
}

/// Step the model over samples first … last of the sampled drive from the state (η0, η̇0) at sample
/// `first` — the arithmetic of the whole run, so from a state the whole run reached, the states
/// are its own bit for bit (what re-stepping a block of a deployment needs); calls visit(n, η, η̇,
/// η̈) at every sample n = first … last (η̈ from the equation of motion at t_n, with the drive's
/// value there), and
/// before_step(n, piece, η, η̇, f_start, f_end) just before each exact step of the state: the whole
/// step n → n+1 (piece = −1) or piece `piece` of a split step, with the forcing at its start and
/// end (linear in between) — what an evaluation between the samples needs
/// (rom/model/deployment_metrics). For a whole step the memory of those four arrays (their data())
/// keeps its contents until visit(n + 1) has returned, so a hook may keep pointers instead of
/// copies until then; a piece's only until the next piece steps.
template <typename Visit, typename BeforeStep>
void runModalSteppingRange(const ModalModel& m, const ModalStepping& ms, const SampledDrive& drive,
                           long first, long last, const Eigen::Ref<const Eigen::VectorXd>& eta0,
                           const Eigen::Ref<const Eigen::VectorXd>& eta_dot0, Visit&& visit,
                           BeforeStep&& before_step) {
  // The decayed free vibration of the higher modes falls into the subnormal range, where every
  // operation is a slow microcode assist (common/flush_denormals.hpp): flushed to zero here.
  const FlushDenormalsScope flush;
  const int k = ms.modes;
  Eigen::VectorXd eta = eta0, eta_dot = eta_dot0;
  Eigen::VectorXd eta_ddot = Eigen::VectorXd::Zero(k);
  // C η̇ of the current sample (what the loop below leaves there after each step); stays 0
  // without the coupling.
  Eigen::VectorXd coriolis = Eigen::VectorXd::Zero(k);
  if (ms.coriolis && first > 0) coriolis.noalias() = m.coriolis * eta_dot;
  // Forcing arrays: at the start and end of a step, and at the current and next sample. Away from
  // breakpoints the one-sided limits equal the sample values, so without the Coriolis coupling
  // (which lags the end of a step to its start) one evaluation per step serves all three uses.
  Eigen::ArrayXd f_start(k), f_end(k), f_value(k), f_next(k);
  Eigen::VectorXd eta_next(k), rate_next(k);  // the other half of the state's double buffer
  const auto forcing = [&](const DriveInstant& d, Eigen::ArrayXd& f) {
    const stepping_detail::ForcingScalars p = stepping_detail::forcingScalars(ms, d);
    stepping_detail::modalForcing(ms, p, f.data());
    if (ms.coriolis) f -= p.two_rate * coriolis.array();
  };
  // One step of every mode under forcing linear between two instants (one vectorised pass,
  // stepping_detail::stepModes). The new state goes to the other buffer and the two are swapped
  // (O(1)): the start state's memory, which before_step saw, keeps its contents until the next
  // step writes it.
  const auto advance = [&](const ModalStepping::Maps& maps, const Eigen::ArrayXd& f0,
                           const Eigen::ArrayXd& f1) {
    stepping_detail::stepModes(maps, k, eta.data(), eta_dot.data(), f0.data(), f1.data(),
                               eta_next.data(), rate_next.data());
    eta.swap(eta_next);
    eta_dot.swap(rate_next);
  };
  const auto sameAsValue = [&](double rate, double acc, long n) {
    const SampledDrive::Sample& s = drive.samples[static_cast<std::size_t>(n)];
    return rate == s.rate_rad_s && acc == s.acceleration_rad_s2;
  };

  // η̈ = f − 2ζω η̇ − ω² η at each sample, f with the drive's value there (and the current η̇).
  forcing(drive.valueAt(first), f_value);
  stepping_detail::modalAccelerations(ms, f_value.data(), eta.data(), eta_dot.data(),
                                      eta_ddot.data());
  visit(first, static_cast<const Eigen::VectorXd&>(eta),
        static_cast<const Eigen::VectorXd&>(eta_dot),
        static_cast<const Eigen::VectorXd&>(eta_ddot));
  std::size_t next_split = static_cast<std::size_t>(
      std::lower_bound(drive.splits.begin(), drive.splits.end(), first,
                       [](const SampledDrive::Split& s, long n) { return s.step < n; }) -
      drive.splits.begin());
  for (long n = first; n < last; ++n) {
    bool next_done = false;  // f_next already holds the forcing at sample n + 1
    if (next_split < drive.splits.size() && drive.splits[next_split].step == n) {
      const SampledDrive::Split& split = drive.splits[next_split];
      for (std::size_t j = 0; j < split.pieces.size(); ++j) {
        // Each piece lags the Coriolis term to its own start (C η̇ of t_n is already current).
        if (ms.coriolis && j > 0) coriolis.noalias() = m.coriolis * eta_dot;
        forcing(split.pieces[j].start, f_start);
        forcing(split.pieces[j].end, f_end);
        before_step(n, static_cast<int>(j), static_cast<const Eigen::VectorXd&>(eta),
                    static_cast<const Eigen::VectorXd&>(eta_dot),
                    static_cast<const Eigen::ArrayXd&>(f_start),
                    static_cast<const Eigen::ArrayXd&>(f_end));
        advance(ms.piece_maps[next_split][j], f_start, f_end);
      }
      ++next_split;
    } else {
      // The start of the step: C η̇ of t_n is current, so the value forcing serves unless a
      // breakpoint on the grid makes the right limit differ.
      const SampledDrive::Sample& s0 = drive.samples[static_cast<std::size_t>(n)];
      const bool start_is_value = sameAsValue(s0.start_rate_rad_s, s0.start_acceleration_rad_s2, n);
      if (!start_is_value) forcing(drive.startOf(n), f_start);
      const SampledDrive::Sample& s1 = drive.samples[static_cast<std::size_t>(n + 1)];
      const bool end_is_value =
          !ms.coriolis && sameAsValue(s1.end_rate_rad_s, s1.end_acceleration_rad_s2, n + 1);
      if (end_is_value) {
        forcing(drive.valueAt(n + 1), f_next);
        next_done = true;
      } else {
        forcing(drive.endAt(n + 1), f_end);
      }
      const Eigen::ArrayXd& step_start = start_is_value ? f_value : f_start;
      const Eigen::ArrayXd& step_end = end_is_value ? f_next : f_end;
      before_step(n, -1, static_cast<const Eigen::VectorXd&>(eta),
                  static_cast<const Eigen::VectorXd&>(eta_dot), step_start, step_end);
      if (next_done) {  // η̈ at t_n+1 in the same pass (f_next is its forcing)
        stepping_detail::stepModesWithAccelerations(ms, ms.step_maps, eta.data(), eta_dot.data(),
                                                    step_start.data(), step_end.data(),
                                                    eta_next.data(), rate_next.data(),
                                                    eta_ddot.data());
        eta.swap(eta_next);
        eta_dot.swap(rate_next);
      } else {
        advance(ms.step_maps, step_start, step_end);
      }
    }
    if (!next_done) {
      if (ms.coriolis) coriolis.noalias() = m.coriolis * eta_dot;
      forcing(drive.valueAt(n + 1), f_next);
      stepping_detail::modalAccelerations(ms, f_next.data(), eta.data(), eta_dot.data(),
                                          eta_ddot.data());
    }
    f_value.swap(f_next);
    visit(n + 1, static_cast<const Eigen::VectorXd&>(eta),
          static_cast<const Eigen::VectorXd&>(eta_dot),
          static_cast<const Eigen::VectorXd&>(eta_ddot));
  }
}

/// Step the model over the whole sampled drive from rest (with gravity: from the static deflection
/// under it at the start angle, when the drive starts at rest): runModalSteppingRange over samples
/// 0 … steps.
template <typename Visit, typename BeforeStep>
void runModalStepping(const ModalModel& m, const ModalStepping& ms, const SampledDrive& drive,
                      Visit&& visit, BeforeStep&& before_step) {
  Eigen::VectorXd eta = Eigen::VectorXd::Zero(ms.modes);
  // With gravity and a drive that starts at rest, the mast stands in its static equilibrium before
  // the swing, as the full order starts (docs/theory.md §4.1): each mode at its static deflection
  // under the gravity forcing at the start angle; θ̈ and θ̇² act from t = 0 on.
  if (ms.gravity) {
    const DriveInstant d0 = drive.valueAt(0);
    if (d0.rate_rad_s == 0.0) {
      const stepping_detail::ForcingScalars p = stepping_detail::forcingScalars(ms, d0);
      eta.array() = (p.gx * ms.momentum_x + p.gy * ms.momentum_y) / ms.stiffness.max(1e-300);
    }
  }
  runModalSteppingRange(m, ms, drive, 0, drive.steps, eta, Eigen::VectorXd::Zero(ms.modes),
                        std::forward<Visit>(visit), std::forward<BeforeStep>(before_step));
}

/// The same without a step hook.
template <typename Visit>
void runModalStepping(const ModalModel& m, const ModalStepping& ms, const SampledDrive& drive,
                      Visit&& visit) {
  runModalStepping(m, ms, drive, std::forward<Visit>(visit),
                   [](long, int, const Eigen::VectorXd&, const Eigen::VectorXd&,
                      const Eigen::ArrayXd&, const Eigen::ArrayXd&) {});
}

}  // namespace mastrom::rom
