// Scalar results of a ROM deployment computed while stepping, without storing the time series: the
// fast path of screening (10⁴ deployments) and of the leave-one-out estimate
// (rom/offline/leave_one_out.hpp).
//
// Both step the modal oscillators exactly as simulateModalDeployment does
// (rom/model/modal_deployment.hpp: first-order hold of the forcing −Γθ̈ − Γ_cθ̇² + Lᵀ(Rᵀg − g₀), left
// limit at the end of a step) and evaluate its output formulas at the same instants, but only the
// outputs the metrics need:
//   relative end angular acceleration  r = α_z − θ̈ = (ψη̈)_z   (R rotates about Z: z unchanged,
//                                                               and (Z × v)_z = 0)
//   joint force   F = R[Lη̈ + θ̈ Z×s + θ̇² Z×(Z×s) + 2θ̇ Z×(Lη̇)] − m g,   s = m c̄ + Lη
//   drive torque  τ = θ̈(J − 2Γ_cᵀη) − 2θ̇ Γ_cᵀη̇ + Γᵀη̈ − (R s × g)_z
// and reduce them on the fly with the definitions of fullorder::computeMetrics (time-weighted RMS
// by the trapezoidal rule and settling by linear re-entry into the band, both on the output
// samples) — except that with PeakResolution::Continuous the RMS is the exact integral of r² over
// the continuous response (rom/model/square_integral.hpp, docs/theory.md §4.2a) wherever every
// mode is damped and the Coriolis coupling is off, and the settling time is the last exit from
// the band of the continuous response (rom/model/settling_refinement.hpp, §4.2b).
//
// Peaks (PeakResolution). The peaks of r sit within a few periods of the highest modes after the
// drive law's breakpoints (jumps of θ̈): the samples t_n = nΔ miss them when Δ is not small against
// those periods (Scheme 3, trapezoidal: 203 °/s² at Δ = 1 ms, 296 at 0.1 ms, 312 at 10 µs).
//  * Samples: every max (the peaks of |α_z|, |r|, ‖F‖, |τ| and the residual max |r| over t ≥ t_d)
//    is over the output samples, exactly computeMetrics' definition: the results agree with
//    simulateModalDeployment + computeMetrics to round-off (tests/rom/test_screening.cpp), as both
//    run the same stepping kernel (rom/model/modal_stepping.hpp), with or without the Coriolis
//    coupling.
//  * Continuous (default): every max is over the continuous ROM response on [0, t_end] (one-sided
//    limits at the jumps of θ̈ included; the residual over (t_d, t_end] and the sample at t_d), to
//    the tolerance below. The response between samples is known exactly — each mode a damped
//    oscillator under the step's linear forcing f0 → f1 — so a step is refined only where a peak
//    can hide. With the particular solution η_p = f/ω² − 2ζḟ/ω³ of the step (η̈_p = 0), the free
//    part y = η − η_p has E = ẏ² + ω²y² non-increasing (dE/dt = −4ζωẏ² ≤ 0), so over the step
//        |η̈| = |ÿ| ≤ √(1+4ζ²) a,  |ẏ| ≤ a/ω,  |y| ≤ a/ω²,   a = ω√E(t_n),
//    and, as ÿ and ⃛y obey the same equation, |ÿ − chord| ≤ min(2, (2+4ζ²)(ωΔ)²/8) √(1+4ζ²) a. A
//    step's bound on |r| is the smaller of Σ|ψ_z,i|√(1+4ζ_i²)a_i and max(|r(t_n)|, |r(t_n+1)|) +
//    Σ|ψ_z,i| (chord deviation)_i — rigorous; for ‖F‖ and |τ| the chord form with the η̈ rows, plus
//    the η, η̇ rows times the drive's max θ̇, θ̈ and |g| (twice), the rigid and quasi-static rest
//    being taken as linear between the ends (drive time scales ≥ 0.1 s: O(Δ²), negligible). The
//    bounds are propagated from step to step in O(1) (a_i grows only by the change of η_p at t_n,
//    which four drive scalars θ̈, θ̇², g_x, g_y carry) and recomputed exactly, O(modes), only when
//    the propagated one allows a new max; with the Coriolis coupling they are exact every step.
//    A step whose bound stays below the running max cannot raise it and is skipped. The others
//    are re-stepped from their start state with the exact maps of h = Δ/2^ℓ (composed from the
//    finest, ω_max h ≤ 0.3), ℓ the coarsest level whose estimated polish error Σ_i ρ_i e(ω_i h),
//    e(x) = min(2, 0.0234 x⁴), ρ_i mode i's share of the running peaks, is ≤ 1e-4 (ℓ = 0: the
//    samples themselves); the outputs are evaluated at every sub-node and each local max of a
//    node sequence is polished by the parabola through it and its neighbours. Tolerance: the
//    parabola's error on a sinusoid of frequency ω is ≤ 0.0234 (ωh)⁴ of its amplitude (the plain
//    sample max: (ωh)²/8), so a peak is within kContinuousPeakTolerance (3.9e-4) of the true max,
//    for the peaks of r relative to max(peak, settling band) — an r far below the band (a smooth
//    law's quasi-static r) is resolved to 1e-4 band absolutely. Steps next to a breakpoint and
//    the pieces of split steps are always refined. The drive between samples: θ̈ linear between
//    the step's one-sided limits (the first-order hold of the forcing; exact for the trapezoidal
//    and cubic laws), θ̇ and θ the matching cubic Hermite interpolants. The coarse samples are
//    untouched and every refined peak is a max over a superset of the samples: never below the
//    sample max. The RMS and the settling time are the continuous ones (above). Where the exact
//    RMS applies, blocks of 16 steps whose bounds from their start state and the drive alone stay
//    below the running maxima are stepped without evaluating their outputs (quiet blocks,
//    rom/model/quiet_blocks.hpp, docs/theory.md §4.2c): they cannot raise a peak.
//  `rom eval` reports the metrics of this function too (Continuous), so a screen and an eval of
//  the same design at the same step print the same numbers (a screen's default step is 2 ms,
//  rom/studies/screen_kernel.hpp: within the tolerances above of an eval at 0.1 ms); its time
//  series are the samples.
#pragma once

#include <functional>

#include "fullorder/deployment_result.hpp"
#include "fullorder/drive_law.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/model/modal_model.hpp"
#include "rom/model/modal_stepping.hpp"
#include "rom/model/quiet_blocks.hpp"

namespace mastrom::rom {

/// What the peak metrics are the max of (see the header comment).
enum class PeakResolution {
  Samples,     ///< the output samples: computeMetrics of the series, to round-off
  Continuous,  ///< the continuous ROM response (refined between samples where a peak can hide)
};

/// Peak resolution: the finest sub-step h of a refined step resolves every mode (ω_max h ≤ 0.3) ...
inline constexpr double kRefinedPhasePerSubStep = 0.3;
/// ... and a coarser one is taken when its estimated polish error is at most this share of the
/// running peaks (header comment).
inline constexpr double kUnresolvedPeakShare = 1e-4;

/// The tolerance of a continuous peak, relative to it (header comment).
inline constexpr double kContinuousPeakTolerance =
    0.0234 * kRefinedPhasePerSubStep * kRefinedPhasePerSubStep * kRefinedPhasePerSubStep *
        kRefinedPhasePerSubStep +
    2.0 * kUnresolvedPeakShare;

/// The metrics of simulateModalDeployment(model, drive, options) without the series: with
/// PeakResolution::Samples, computeMetrics(series, drive_end_time_s, band); with Continuous, the
/// same except that the peaks and the residual are maxima over the continuous response, the RMS
/// is its exact integral and the settling time its last exit from the band (header). Same
/// errors: InputError when the record ends before drive_end_time_s or the band is not > 0;
/// NumericalError on a non-finite output.
fullorder::DeploymentMetrics modalDeploymentMetrics(
    const ModalModel& model, const fullorder::DriveLaw& drive,
    const ModalDeploymentOptions& options, double drive_end_time_s,
    double settling_band_rad_s2 = fullorder::kDefaultSettlingBandRadS2,
    PeakResolution peaks = PeakResolution::Continuous);

/// Sees the state at the first sample of every block of SampledDrive::kBlockSteps steps (block =
/// sample / kBlockSteps, in order), with the quiet blocks' bounds of the modal state over the block
/// (docs/theory.md §4.2c) where they exist — null for a block with a breakpoint or where the
/// metrics have no quiet blocks (PeakResolution::Samples, the Coriolis coupling, an undamped
/// mode). What the stress peaks keep of a pass instead of every sample's state
/// (rom/model/stress_blocks.hpp).
using ModalBlockObserver =
    std::function<void(long block, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
                       const ModalStateBounds* bounds)>;

/// The same on a drive sampled once (sampleDrive): what a screen runs per design, sharing the
/// sampling of each drive law over all its designs. `observer` (may be null) sees every sample,
/// `block_observer` (may be null) the start of every block.
fullorder::DeploymentMetrics modalDeploymentMetrics(
    const ModalModel& model, const SampledDrive& drive, bool coriolis_coupling,
    double drive_end_time_s, double settling_band_rad_s2 = fullorder::kDefaultSettlingBandRadS2,
    PeakResolution peaks = PeakResolution::Continuous,
    const ModalSampleObserver* observer = nullptr,
    const ModalBlockObserver* block_observer = nullptr);

/// How much of the last deployment was refined (diagnostics for tests and benchmarks): refined
/// steps / pieces and sub-steps, on the calling thread.
struct PeakRefinementStats {
  long steps = 0, refined_steps = 0, sub_steps = 0;
  int sub_steps_per_step = 0;
  /// Steps (or pieces) re-stepped for the continuous settling time, and their sub-steps.
  long settling_steps = 0, settling_sub_steps = 0;
  /// Steps in quiet blocks (stepped without evaluating their outputs, docs/theory.md §4.2c).
  long quiet_steps = 0;
};
PeakRefinementStats lastPeakRefinementStats();

/// max |relative end angular acceleration| over the output samples of a ROM deployment (no
/// end-time requirement).
double peakRelativeEndAcceleration(const ModalModel& model, const fullorder::DriveLaw& drive,
                                   const ModalDeploymentOptions& options);

}  // namespace mastrom::rom
