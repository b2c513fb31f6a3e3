// The continuous peaks of a ROM deployment (PeakResolution::Continuous; the method — the bound of
// each step, the refinement where a peak can hide, the polished node maxima — is the header comment
// of rom/model/deployment_metrics.hpp): PeakRefiner follows the stepping of modalDeploymentMetrics
// (deployment_metrics.cpp), decides after each sample whether the step before it can hold a new
// max, and re-steps and polishes the steps that can. Not part of the library's interface.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "fullorder/deployment_result.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/model/deployment_outputs.hpp"
#include "rom/model/modal_model.hpp"
#include "rom/model/modal_stepping.hpp"
#include "rom/model/parabola_polish.hpp"

namespace mastrom::rom::metrics_detail {

/// The refinement statistics of the calling thread (what lastPeakRefinementStats returns); the
/// metrics reset them at the start of a deployment.
PeakRefinementStats& threadPeakRefinementStats();

/// Each mode's free amplitude a = ω√(ẏ² + ω²y²) at the start of a step of `duration` with forcing
/// f0 → f1, y = η − η_p the free part (the bound of the header comment of
/// rom/model/deployment_metrics.hpp; every ω > 0): what the peaks' and the settling time's
/// refinements bound a step with. two_zeta_over_omega = 2ζ/ω, inv_omega = 1/ω.
inline void freeAmplitudes(const ModalStepping& ms, const Eigen::ArrayXd& omega,
                           const Eigen::ArrayXd& two_zeta_over_omega,
                           const Eigen::ArrayXd& inv_omega, const double* eta,
                           const double* eta_dot, const double* f0, const double* f1,
                           double duration, Eigen::ArrayXd& amp) {
  const Eigen::Index k = omega.size();
  const Eigen::Map<const Eigen::ArrayXd> e(eta, k), v(eta_dot, k), a(f0, k), b(f1, k);
  const auto fdot = (b - a) * (1.0 / duration);
  amp = ((ms.stiffness * e - a + two_zeta_over_omega * fdot).square() +
         (omega * v - inv_omega * fdot).square())
            .sqrt();
}

/// Running max of a non-negative output over a sequence of nodes; each local max of three
/// consecutive nodes is replaced by the vertex of the parabola through them (≥ the node), with
/// the nodes' true spacings (a sequence refined at different levels is not evenly spaced).
class PolishedMax {
public:
  void restart() { count_ = 0; }
  /// The next node, `spacing` after the previous one (ignored for the first after a restart).
  void push(double v, double spacing) {
    if (count_ == 2 && b_ >= a_ && b_ >= v) {
      double vertex = 0.0, offset = 0.0;
      if (parabolaMaximum(a_, b_, v, spacing_ab_, spacing, vertex, offset))
        max_ = std::max(max_, vertex);
    }
    a_ = b_;
    b_ = v;
    spacing_ab_ = spacing;
    count_ = std::min(count_ + 1, 2);
    max_ = std::max(max_, v);
  }
  double max() const { return max_; }

private:
  double a_ = 0.0, b_ = 0.0, max_ = 0.0, spacing_ab_ = 1.0;
  int count_ = 0;
};

/// The continuous peaks (PeakResolution::Continuous, deployment_metrics.hpp's header comment): the
/// bound of each step, the decision after the step's end sample, and the refined evaluation.
class PeakRefiner {
public:
  PeakRefiner(const ModalModel& m, const ModalStepping& ms, const SampledDrive& drive,
              const OutputEvaluator& eval, double drive_end_time_s, double band);

  /// Before the state steps over step n (piece < 0) or piece `piece` of its split.
  void beforeStep(long n, int piece, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
                  const Eigen::ArrayXd& f_start, const Eigen::ArrayXd& f_end);

  /// After sample n (outputs o): decide on (and refine) the pending step n − 1 → n.
  void afterSample(long n, const Outputs& o, const fullorder::DeploymentMetrics& sampled);

  /// The refined maxima into the sample ones.
  void finish(fullorder::DeploymentMetrics& out) const;

  /// The running maxima so far (the sample ones in `sampled` and the refined ones): what a step
  /// must be able to exceed to matter (quiet blocks, rom/model/quiet_blocks.hpp).
  struct RunningPeaks {
    double abs_acc = 0.0, rel_acc = 0.0, force = 0.0, torque = 0.0, residual = 0.0;
  };
  RunningPeaks running(const fullorder::DeploymentMetrics& sampled) const;
  /// The slack of the r-based peaks (kUnresolvedPeakShare of the settling band) [rad/s²].
  double relSlack() const { return rel_slack_; }

private:
  enum Row { kRelChord, kRelPlain, kForce, kTorque };
  struct PieceMaps {
    int count = 1;
    ModalStepping::Maps maps;
  };

  /// The exact bound of the pending step (from its start state) into bounds_ and amp_.
  void exactBounds();

  Eigen::Vector4d driveScalars(const DriveInstant& d) const;

  /// Whether the pending step's bound (bounds_) lets any output exceed its running max:
  /// |z(t)| ≤ max(|z(t_{n−1})|, |z(t_n)|) + (deviation of the modal part from its chord), and
  /// for r also |r(t)| ≤ Σ w_i a_i (the plain bound, better during a transient).
  bool mayExceed(const Outputs& prev, const Outputs& o, const DriveInstant& d0,
                 const DriveInstant& d1, double peak_abs, double peak_rel, double peak_force,
                 double peak_torque, double residual, bool after_drive) const;

  static bool sameLimits(const DriveInstant& a, const DriveInstant& b);

  /// The refined node sequence may go on through t_n: the previous step was refined and the
  /// drive has no jump at t_n.
  bool continuesAt(long n) const;

  void restartAll();

  /// The next node of every polished max, `spacing` [s] after the previous one.
  void pushNode(const Outputs& o, bool residual, double spacing);

  /// Re-step [t0, t0 + duration] from (η, η̇) with `count` sub-steps of `maps`, forcing linear
  /// f0 → f1, and push the outputs at every sub-node into the polished maxima.
  void refine(const ModalStepping::Maps& maps, int count, double duration, double t0,
              const Eigen::Ref<const Eigen::VectorXd>& eta,
              const Eigen::Ref<const Eigen::VectorXd>& eta_dot,
              const Eigen::Ref<const Eigen::ArrayXd>& f0,
              const Eigen::Ref<const Eigen::ArrayXd>& f1, const DriveInstant& d0,
              const DriveInstant& d1, bool continues);

  const ModalStepping& ms_;
  const SampledDrive& drive_;
  const OutputEvaluator& eval_;
  double t_d_;
  int k_;
  /// The r-based peaks are resolved to kUnresolvedPeakShare of max(peak, settling band): peaks
  /// far below the band (a smooth law's quasi-static r) need no more than that absolutely.
  double rel_floor_, rel_slack_;
  bool always_refine_ = false;
  std::vector<ModalStepping::Maps> level_maps_;  ///< [ℓ]: sub-step Δ/2^ℓ
  std::vector<std::vector<PieceMaps>> piece_maps_;
  std::size_t next_split_ = 0;
  Eigen::ArrayXd omega_, s_, two_zeta_over_omega_, inv_omega_, w_rel_, w_force_, w_torque_;
  Eigen::Matrix<double, 4, Eigen::Dynamic> bound_rows_;
  Eigen::Vector4d bounds_ = Eigen::Vector4d::Zero();
  // The O(1) propagation of bounds_ from step to step (no Coriolis coupling, no rigid mode).
  bool propagate_ = false;
  bool exact_ = false;              ///< bounds_ is the exact bound of the pending step
  bool bounds_valid_ = false;       ///< bounds_ bounds the pending step (exact or propagated)
  bool last_bounds_valid_ = false;  ///< bounds_ bounded the previous whole step
  long last_step_ = -1;
  Eigen::Matrix4d jump_rows_ = Eigen::Matrix4d::Zero(), slope_rows_ = Eigen::Matrix4d::Zero();
  Eigen::Vector4d last_end_ = Eigen::Vector4d::Zero(), last_slope_ = Eigen::Vector4d::Zero();
  // Work arrays (sized once: no allocation per step).
  Eigen::ArrayXd amp_, share_, fa_, fb_;
  Eigen::VectorXd eta_, eta_dot_, eta_ddot_;
  // The pending step's start state and forcing: the stepping's own arrays, which keep their
  // contents until the step's end sample has been visited (runModalStepping): not copied.
  const double *eta0_ = nullptr, *eta_dot0_ = nullptr, *f0_ = nullptr, *f1_ = nullptr;
  using ConstMap = Eigen::Map<const Eigen::ArrayXd>;
  long pending_ = -1;      ///< the whole step whose decision waits for its end sample
  long refined_end_ = -1;  ///< the sample at which the last refined step ended
  Outputs last_;           ///< of the last sample
  PolishedMax abs_, rel_, force_, torque_, residual_;
};

}  // namespace mastrom::rom::metrics_detail
