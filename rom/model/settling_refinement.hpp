// The settling time of the continuous ROM response (PeakResolution::Continuous; docs/theory.md
// §4.2b): the last instant t ≥ t_d at which |r| leaves the band b, found between the samples.
// From the samples alone it can be off by many output steps, because the last excursion above the
// band is often a ringing peak between two samples (measured on a five-parameter screen: up to
// 21 ms at a 1 ms step and 1.9 ms at 0.1 ms against 10 µs samples).
//
// The method. Each mode's free part y = η − η_p has a non-increasing amplitude a = ω√(ẏ² + ω²y²)
// over a step (the bound of rom/model/deployment_metrics.hpp), so over a step
//     |r| ≤ Σ|ψ_z,i|√(1+4ζ_i²) a_i                      (plain)
//     |r| ≤ max(|r(t_n)|, |r(t_n+1)|) + Σ|ψ_z,i| (chord deviation)_i.
// While stepping, a step after t_d whose bound exceeds b is a candidate, and its start state is
// kept; a sample above the band after t_d discards the candidates before it (the settling time
// is later). After t_d the forcing is constant, so the amplitudes never grow again: once the plain
// bound is within the band, no later step can leave it and the checks stop. At the end the
// candidates are re-stepped from the last backwards at sub-steps fine enough for the modes that
// matter (the level rule of the peaks with the band as the scale), until one leaves the band:
// the crossing is the linear re-entry after the last node (or parabola vertex) above the band,
// with the samples' sign rule. Cost: the checks of the steps between t_d and the quiet bound,
// and the few trailing candidates.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "fullorder/deployment_result.hpp"
#include "rom/model/modal_model.hpp"
#include "rom/model/modal_stepping.hpp"

namespace mastrom::rom::metrics_detail {

class SettlingRefiner {
public:
  SettlingRefiner(const ModalModel& m, const ModalStepping& ms, const SampledDrive& drive,
                  double drive_end_time_s, double band);

  /// Before the state steps over step n (piece < 0) or piece `piece` of its split.
  void beforeStep(long n, int piece, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
                  const Eigen::ArrayXd& f_start, const Eigen::ArrayXd& f_end);
  /// After sample n with relative end angular acceleration r_n.
  void afterSample(long n, double r_n);
  /// The continuous settling time into `out`, whose settling fields hold the samples' verdict: a
  /// record whose last sample is outside the band stays unsettled.
  void finish(fullorder::DeploymentMetrics& out);

private:
  struct Candidate {
    double t0 = 0.0, duration = 0.0;
    bool piece = false;
    std::size_t offset = 0;  // of η, η̇, f0, f1 in store_
  };
  void keep(double t0, double duration, bool piece, const double* eta, const double* eta_dot,
            const double* f0, const double* f1);
  /// Each mode's free amplitude a at the start of a step of `duration` into amp_.
  void amplitudes(const double* eta, const double* eta_dot, const double* f0, const double* f1,
                  double duration);
  /// The last crossing out of the band within a candidate (re-stepped), or −∞ for none.
  double lastCrossing(const Candidate& c);

  const ModalModel& m_;
  const ModalStepping& ms_;
  const SampledDrive& drive_;
  double t_d_, band_;
  int k_;
  bool resolvable_ = true;  ///< every mode has ω > 0 (the amplitude bound exists)
  double omega_max_ = 0.0;
  Eigen::ArrayXd omega_, psi_, weight_, chord_, two_zeta_over_omega_, inv_omega_, amp_;
  std::vector<Candidate> candidates_;
  std::vector<double> store_;
  // The whole step waiting for its end sample.
  bool pending_ = false, quiet_ = false;
  long pending_step_ = -1;
  // Its start state and forcing: the stepping's arrays, unchanged until its end sample has been
  // visited (runModalStepping), so pointers rather than copies.
  const double *eta0_ = nullptr, *eta_dot0_ = nullptr, *f0_ = nullptr, *f1_ = nullptr;
  double last_r_ = 0.0;
};

}  // namespace mastrom::rom::metrics_detail
