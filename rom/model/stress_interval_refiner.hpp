// Re-stepping one interval of a ROM deployment for its stress peak (docs/theory.md §6.5, "Between
// samples"): the bound (6.11) of the modal state over the interval from its start state, and where
// that bound lets a peak hide, the exact sub-steps, their stresses and the parabola polish of the
// largest. refineStressPeaks (stress_peak_refinement.cpp) decides which intervals to re-step. Not
// part of the library's interface.
#pragma once

#include <Eigen/Core>
#include <tuple>
#include <utility>
#include <vector>

#include "rom/model/modal_model.hpp"
#include "rom/model/modal_stepping.hpp"
#include "rom/model/modal_stress_response.hpp"

namespace mastrom::rom::stress_detail {

/// The forcing scalars are a function of the drive instant: equal instants, equal scalars (so the
/// end scalars of one interval serve as the start of the next where the drive is continuous).
inline bool sameDriveInstant(const DriveInstant& a, const DriveInstant& b) {
  return a.rate_rad_s == b.rate_rad_s && a.acceleration_rad_s2 == b.acceleration_rad_s2 &&
         a.sin_angle == b.sin_angle && a.cos_angle == b.cos_angle;
}

/// Re-steps one interval (a step or a piece of a split step) where its bound allows a higher peak.
/// prepare() bounds the modal state over the interval once; refine() then serves each interface.
/// Buffers are members: no allocation per interval.
class IntervalRefiner {
public:
  /// `stats` (borrowed) counts the intervals bounded and re-stepped.
  IntervalRefiner(const ModalStressEvaluator& ev, const ModalModel& m, const ModalStepping& ms,
                  StressRefinementStats& stats);

  /// Bound the interval from the state (η, η̇) at its start.
  void prepare(const Eigen::Ref<const Eigen::VectorXd>& eta,
               const Eigen::Ref<const Eigen::VectorXd>& eta_dot, const DriveInstant& d0,
               const DriveInstant& d1, double duration_s);

  /// Σ_j c_j r_j of interface i for the prepared interval: its ringing bound at the start.
  double ringingBound(int i) const { return ev_.bound(i).head(k_).dot(ringing_.matrix()); }

  /// Raise interface i's peak if the prepared interval holds a higher value; start_sample is the
  /// interval's start as a (fractional) sample index.
  void refine(int i, double start_sample, double step_s, ModalStressEvaluator::Peak& peak);

  /// The state at the prepared interval's end (for the next piece of a split step).
  void end(Eigen::VectorXd& eta, Eigen::VectorXd& eta_dot);

  /// The exact von Mises stress of interface i at `station` a share `fraction` ∈ [0, 1) into the
  /// prepared interval (one exact step there; the interval's start at 0): what replaces a parabola's vertex value, which
  /// can overshoot the continuous response when the samples are coarse.
  double valueAt(int i, int station, double fraction);
  /// The state x a share `fraction` ∈ [0, 1] into the prepared interval: the exact response,
  /// in closed form where every mode is under-damped, else one exact step of that length.
  void stateAt(double fraction, Eigen::Ref<Eigen::VectorXd> x);
  /// The same through the exact maps of that length (what the closed form is checked against).
  void stateAtByMaps(double fraction, Eigen::Ref<Eigen::VectorXd> x);

private:
  void modalForcing(const stepping_detail::ForcingScalars& f, Eigen::ArrayXd& out) const;
  const ModalStepping::Maps& maps(double duration_s, int sub);
  void advance(const ModalStepping::Maps& h);
  /// The load scalars a share t ∈ [0, 1] into the prepared interval (θ̈ and g linear, θ̇ linear
  /// so θ̇² quadratic).
  stepping_detail::ForcingScalars loadAt(double t) const;

  const ModalStressEvaluator& ev_;
  const ModalModel& m_;
  const ModalStepping& ms_;
  StressRefinementStats& stats_;
  int k_;
  Eigen::ArrayXd w_, zeta_, inv_w_, inv_w2_, two_zeta_, zeta_w_, w_damped_;
  bool closed_form_ = false;
  // The prepared interval.
  DriveInstant d0_, d1_;
  double duration_s_ = 0.0;
  stepping_detail::ForcingScalars s0_, s1_;
  Eigen::ArrayXd f0_, f1_, ringing_, bound_modes_, e0_, v0_, p0_, p1_, tmp_;
  DriveInstant last_d1_;
  bool have_end_ = false;
  Eigen::Matrix<double, kStressLoadCount, 1> loads_;
  // Sub-stepping.
  Eigen::VectorXd eta_, eta_dot_;
  Eigen::ArrayXd fa_, fb_, next_;
  Eigen::MatrixXd x_;
  std::vector<std::tuple<double, int, ModalStepping::Maps>> cache_;
  std::vector<std::pair<double, int>> candidates_;  ///< (bound, sub-sample) of refine()
};

}  // namespace mastrom::rom::stress_detail
