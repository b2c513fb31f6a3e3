// Quiet blocks of a ROM deployment's metrics (PeakResolution::Continuous; docs/theory.md §4.2c):
// upper bounds of the outputs the peak metrics take the max of — |α_z|, |r|, ‖F‖, |τ| — over a
// block of output steps, from the modal state at the block's start and the drive alone, without
// evaluating an output. A block whose bounds stay below the running maxima cannot raise any peak
// (nor the residual after the drive), so the metrics step its states without evaluating or
// refining its outputs (rom/model/deployment_metrics.cpp): at a screen's 2 ms most of a
// deployment is such blocks, and its outputs at every sample were most of the metrics' cost.
//
// The method. Over a step each mode's free part y = η − η_p (η_p = f/ω² − 2ζḟ/ω³ the particular
// solution of the step's linear forcing) keeps a = ω√(ẏ² + ω²y²) non-increasing, and from step to
// step a grows by at most |Δf| + (1 + 2ζ)/ω |Δḟ| (the bounds of rom/model/deployment_metrics.hpp).
// With the forcing f = Σ_s c_s K_s over the four drive scalars c = (θ̈, θ̇², g_x, g_y), a block with
// no breakpoint has, for every t in it,
//     a_i ≤ A_i = a_i(t_n) + (1 + 2ζ_i)/ω_i Σ_s |K_s,i| Σ_steps |Δċ_s|,
//     |η̈_i| ≤ √(1+4ζ_i²) A_i,   |η̇_i| ≤ Σ_s max|ċ_s| |K_s,i|/ω_i² + A_i/ω_i,
//     |η_i| ≤ (Σ_s max|c_s| |K_s,i| + A_i)/ω_i² + 2ζ_i Σ_s max|ċ_s| |K_s,i|/ω_i³,
// and each output is its rigid part (η = 0; a function of the drive, taken as linear between
// samples like the chord bound of the peaks: drive time scales ≥ 0.1 s) plus modal terms bounded
// by those maxima through the output formulas (deployment_outputs.hpp) and the triangle
// inequality. Blocks that hold a breakpoint (a split step or one-sided limits on the grid) get no
// bound: the peaks always refine next to them.
#pragma once

#include <Eigen/Core>

#include "rom/model/modal_model.hpp"
#include "rom/model/modal_stepping.hpp"

namespace mastrom::rom {

/// Bounds of the modal state over a block of steps, for every t in it (docs/theory.md §4.2c):
/// |η_i| ≤ eta[i], |η̇_i| ≤ rate[i] (the model's modes), |θ̈| ≤ acc, θ̇² ≤ rate2 and |g_x|, |g_y| ≤
/// gravity (the load scalars of the forcing and of the stresses' static correction). What the
/// stress peaks bound a block's stress with (rom/model/stress_blocks.hpp).
struct ModalStateBounds {
  const double* eta = nullptr;
  const double* rate = nullptr;
  double acc = 0.0, rate2 = 0.0, gravity = 0.0;
};

}  // namespace mastrom::rom

namespace mastrom::rom::metrics_detail {

/// Steps per block (SampledDrive::kBlockSteps): the bound's growth and the drive's maxima are
/// taken over a block, so shorter blocks are tighter and longer ones cheaper (O(modes) a block).
inline constexpr long kQuietBlockSteps = SampledDrive::kBlockSteps;

/// Upper bounds of the peak metrics' outputs over a block.
struct OutputBounds {
  double abs_acc = 0.0;  ///< |α_z| [rad/s²]
  double rel_acc = 0.0;  ///< |r| [rad/s²]
  double force = 0.0;    ///< ‖F‖ [N]
  double torque = 0.0;   ///< |τ| [N·m]
};

/// Whether the metrics skip quiet blocks on the calling thread (default true). False evaluates the
/// outputs at every sample, as before the blocks: the brute-force path the tests compare with.
bool& quietBlocksEnabled();

class QuietBlockBound {
public:
  /// Whether the bound exists: every mode with ω > 0 (a free amplitude) and no Coriolis coupling
  /// (whose forcing is not a combination of the four drive scalars).
  static bool supported(const ModalModel& m, const ModalStepping& ms);

  /// Per-model constants; requires supported(m, ms).
  QuietBlockBound(const ModalModel& m, const ModalStepping& ms, const SampledDrive& drive);

  /// The bounds over block `block` of the drive (SampledDrive::blocks: steps first … last − 1,
  /// t_first to t_last) from the state (η, η̇) at t_first; false (no bound) when a breakpoint
  /// lies in the block.
  bool bound(long block, const double* eta, const double* eta_dot, OutputBounds& out);

  /// From now on bound() also keeps its bounds of the modal state (stateBounds()).
  void keepStateBounds();
  /// The modal state's bounds over the block of the last bound() that returned true, after
  /// keepStateBounds() (valid until the next bound()).
  ModalStateBounds stateBounds() const;

private:
  /// ‖F‖ and |τ| of the rigid motion (η = 0) at sample j.
  void rigidOutputs(long j, double& force, double& torque) const;
  /// The modes' weighted amplitude sums of bound() (its per-mode loop); with kKeepState also
  /// each mode's state bounds.
  struct ModeSums {
    double rel, force_acc, torque_acc, l_eta, l_rate, gc_eta, gc_rate;
  };
  template <bool kKeepState>
  void modeSums(const Eigen::Array4d& c_max, const Eigen::Array4d& slope_max,
                const Eigen::Array4d& slope_changes, ModeSums& out);

  const ModalStepping& ms_;
  const SampledDrive& drive_;
  Eigen::ArrayXd omega_, two_zeta_over_omega_, inv_omega_, inv_omega2_, two_zeta_over_omega3_,
      growth_, s_;
  Eigen::Array<double, Eigen::Dynamic, 4> k_abs_;  ///< |K_s,i|: |Γ|, |Γ_c|, |L_x|, |L_y|
  Eigen::ArrayXd w_rel_, w_force_acc_, l_xy_, w_torque_acc_, gamma_c_abs_;
  double moment_x_ = 0.0, moment_y_ = 0.0, inertia_z_ = 0.0, g_xy_ = 0.0, reference_angle_ = 0.0;
  Eigen::Vector3d weight_ = Eigen::Vector3d::Zero();
  // Work arrays (sized once).
  Eigen::ArrayXd f0_, f1_, amp_;
  // The state's bounds of the last block (keepStateBounds()).
  bool keep_state_ = false;
  Eigen::ArrayXd eta_max_, rate_max_;
  double acc_max_ = 0.0, rate2_max_ = 0.0, gravity_max_ = 0.0;
};

}  // namespace mastrom::rom::metrics_detail
