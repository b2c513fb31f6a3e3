// The error estimate of the radial-basis method (docs/theory.md §4.4 (d)), cheap enough to run
// after every round of an adaptive build.
//
// 1. Leave-one-out at the samples without leaving anything out [Rip99]: for the features of every
//    sample at once (the tracked modal quantities of rom/interpolation/tracked_interpolation.hpp), the
//    interpolant of the other samples misses sample k by e_k = c_k / (M⁻¹)_kk
//    (RadialBasisWeights::leaveOneOutErrors) — O(N² × features) for all N samples instead of N
//    interpolants.
// 2. Modal error → response error as the grid's leave-one-out does it (rom/offline/leave_one_out.hpp):
//    the left-out model f_k − e_k against the sample's own, each simulated by the ROM with the
//    base configuration's drive; the NRMSE of the relative end angular acceleration, and the
//    relative error of ω₁. Two ROM deployments per sample (the sample's own cached between calls),
//    all a call needs stepped side by side on the modes r sees (responseNrmseTogether,
//    rom/offline/leave_one_out.hpp).
// 3. From the samples to the box: the native-space bound |f − s|(x) ≤ P(x) |f|_N [Wen05, §11.1]
//    holds for the interpolant of all samples with its power function P, and for the left-out one
//    at x_k with P₋ₖ(x_k) = 1/√(M⁻¹)_kk. Each sample's error thus measures the local size of
//    |f|_N, ε_k = e_k / P₋ₖ(x_k), and the estimate at x is P(x) · max ε_k over the p + 1 samples
//    nearest x (a simplex's worth; p parameters). It is the "scaled power function" error
//    indicator of kernel greedy methods [DSW05]; like the grid's ρ-scaled leave-one-out it is an
//    estimate, not a bound (it assumes the response error linear in the modal errors, and the
//    local |f|_N of the nearest samples).
// The database's estimate is the largest value over a fixed candidate set (the box corners and
// Halton points, estimateCandidates) — the same set the adaptive build picks its samples from.
#pragma once

#include <utility>
#include <vector>

#include "fullorder/drive_law.hpp"
#include "rom/database/build_report.hpp"
#include "rom/database/rom_database.hpp"
#include "rom/interpolation/rbf_weights.hpp"
#include "rom/model/modal_deployment.hpp"

namespace mastrom::rom {

/// Indices of the `count` samples whose box coordinates are nearest `u` (all when there are fewer),
/// nearest first (ties: the lower index).
std::vector<int> nearestSamples(const std::vector<Eigen::VectorXd>& coordinates,
                                const Eigen::VectorXd& u, int count);

/// Halton candidates per database parameter (plus the 2^p corners) of the estimate.
constexpr int kCandidatesPerParameter = 200;

/// The candidate points: the box corners (p ≤ 10), then Halton points `skip`, `skip` + 1, … in box
/// coordinates (rom/offline/space_filling.hpp), `count` of them, as parameter values.
std::vector<std::vector<double>> estimateCandidates(const std::vector<ParameterAxis>& axes,
                                                    int count, long skip);

/// Steps 1 and 2 of the header: per sample, the leave-one-out errors (relative error of ω₁, NRMSE
/// of the response); −1 for the samples of other ranks' shares.
struct LeftOutErrors {
  std::vector<double> frequency, response;
};

/// What radialBasisLeaveOneOut keeps between the rounds of an adaptive build (one per rank,
/// index = sample): the samples' own response series, and per sample the left-out feature error
/// whose response was last deployed, with that response error.
struct LeaveOneOutCache {
  std::vector<std::vector<double>> exact;
  std::vector<Eigen::VectorXd> residual;
  std::vector<double> response;
  int deployed = 0, reused = 0;  ///< of the last call
};

/// Relative change of a sample's left-out feature error below which its response error is
/// carried over (scaled) instead of deployed again (see radialBasisLeaveOneOut).
constexpr double kResidualReuseTolerance = 0.2;

/// The weights the carry-over test measures feature errors with: 1/(each feature's spread over
/// the samples' `features`), 0 for a constant one (the gravity vector, θ₀ without an angle axis).
Eigen::ArrayXd featureSpreadWeights(const std::vector<Eigen::VectorXd>& features);

/// Steps 1 and 2 for the samples s ≡ first (mod stride) of `db` (rbf interpolation over its
/// samples, grid or scattered), the reference deployment given by `drive` and `options`. Between
/// calls, `cache` keeps the samples' own responses, and a sample whose left-out feature error e_k
/// moved by less than kResidualReuseTolerance since its last deployment (features scaled by their
/// spread over the samples) gets that response error scaled by the ratio of the norms instead of a
/// new deployment — the response error linear in the modal errors, as step 3 takes it too. Adding
/// a sample changes the left-out errors of the distant ones little, so most are carried over.
/// Throws InputError when the samples do not determine the radial-basis weights.
LeftOutErrors radialBasisLeaveOneOut(const RomDatabase& db, const fullorder::DriveLaw& drive,
                                     const ModalDeploymentOptions& options,
                                     LeaveOneOutCache& cache, int first = 0, int stride = 1);

class RadialBasisErrorEstimate {
public:
  /// Step 3 of the header from every sample's leave-one-out errors.
  RadialBasisErrorEstimate(const RomDatabase& db, LeftOutErrors errors);

  const std::vector<double>& frequencyErrors() const { return errors_.frequency; }
  const std::vector<double>& responseErrors() const { return errors_.response; }
  /// The estimated errors (ω₁, response NRMSE) of the interpolant at `parameters` (step 3).
  std::pair<double, double> at(const std::vector<double>& parameters) const;

  /// Step 3 at many points: per point the power function P and the local scales ε of ω₁ and of
  /// the response; the estimates are P·ε.
  struct PointEstimates {
    Eigen::VectorXd power, frequency_scale, response_scale;
    double frequency(Eigen::Index i) const { return power[i] * frequency_scale[i]; }
    double response(Eigen::Index i) const { return power[i] * response_scale[i]; }
  };
  PointEstimates atPoints(const std::vector<std::vector<double>>& points) const;

private:
  RadialBasisWeights weights_;
  LeftOutErrors errors_;
  std::vector<double> frequency_scale_, response_scale_;  ///< ε_k = e_k / P₋ₖ(x_k)
  std::vector<Eigen::VectorXd> coordinates_;              ///< samples' box coordinates
  std::vector<ParameterAxis> axes_;
};

/// The rbf method's entry of a build report: per sample the largest estimate over the candidates
/// nearest to it (−1 when none is), the estimates the maxima over all candidates, the maxima of
/// the samples' own leave-one-out errors as max_frequency_error / max_response_error.
/// `at_candidates` = estimate.atPoints(candidates).
LeaveOneOutResult summariseRadialBasis(
    const RadialBasisErrorEstimate& estimate, const RomDatabase& db,
    const std::vector<std::vector<double>>& candidates,
    const RadialBasisErrorEstimate::PointEstimates& at_candidates);

}  // namespace mastrom::rom
