// Held-out probes of a scattered database (docs/theory.md §4.3, "Probes of a scattered database").
//
// The radial-basis estimate of rom/offline/rbf_leave_one_out.hpp infers the error between the
// samples from their leave-one-out residuals; it is good at saying *where* the error is largest
// (the adaptive build samples there), but as a number it is only as honest as that inference:
// on the five-parameter box it read 3.7 % where 20 random points measured at most 1.4 %
// (benchmarks/README.md "Held-out probes of a scattered database"). So the adaptive build also
// solves the modes at a fixed set of held-out points — Halton points of the box that are never
// candidates for a sample — and after every round measures the interpolant there: the rbf model
// deployed against the probe's own modal model (NRMSE of the relative end angular acceleration,
// relative error of ω₁), exactly as the grid's cell-centre probes (rom/offline/probe_estimate.hpp).
// The build stops when the largest measured error is ≤ the tolerance. That stop selects the
// probes' values — it happens the first time they are all small, and one round can drop their
// maximum from 8.5 to 2.2 % — so their maximum at the stop reads low: 0.59–0.79 × the largest of
// 20–40 random points' errors on the five-parameter box. So a stop is confirmed on a fresh set of
// as many probes, which took no part in it: solved and measured then; if its worst error is above
// the tolerance (and the budget allows) it joins the stopping set and the build goes on, else the
// build ends. The database's estimate is the maximum over the stopping probes and the last fresh
// set. Cost: scatteredProbeCount(p) modal solves per set, then one ROM deployment per stopping
// probe and round that the change of the interpolant does not let it carry over, shared over the
// ranks like the leave-one-out deployments and, like them, stepped side by side
// (responseNrmseTogether, rom/offline/leave_one_out.hpp).
#pragma once

#include <vector>

#include "fullorder/drive_law.hpp"
#include "rom/database/build_report.hpp"
#include "rom/database/rom_database.hpp"
#include "rom/model/modal_deployment.hpp"

namespace mastrom::rom {

/// Probes per parameter in each set, plus as many again: 4(p + 1), between 8 and kMaxProbes
/// (rom/offline/probe_estimate.hpp). On the five-parameter box (four sampled axes, 2 × 20
/// probes) the largest over both sets was 1.09 × the largest of 40 random points' errors
/// (tolerance 3 %) and 1.02 × that of 20 (tolerance 2 %).
constexpr int kScatteredProbesPerParameter = 4;

/// The number of probes of a scattered database over p sampled parameters.
int scatteredProbeCount(int p);

/// Set `set` (0, 1, 2, …) of probes of a scattered database over `axes`, scatteredProbeCount(p)
/// points: Halton points in box coordinates (rom/offline/space_filling.hpp), taken after the
/// initial design and every candidate of the adaptive build (rom/offline/rbf_leave_one_out.hpp,
/// estimateCandidates), so that no probe is ever a sample; set k follows set k − 1. Set 0 stops
/// the build; the later ones are the fresh sets that confirm a stop.
std::vector<std::vector<double>> scatteredProbePoints(const std::vector<ParameterAxis>& axes,
                                                      int set);

/// What measureProbeShare keeps between the rounds of a build (one per rank, index = probe): the
/// probes' own response series, and per probe the feature error (interpolated − own, weighted as
/// the leave-one-out's reuse test weighs it) whose response was last deployed, with that error.
struct ProbeResponseCache {
  std::vector<std::vector<double>> exact;
  std::vector<Eigen::VectorXd> difference;
  std::vector<double> response;
  std::vector<char> reused;  ///< the probe's current value was carried over, not deployed
  int deployed = 0, carried = 0;  ///< of the last call
};

/// The rbf interpolant of `db` measured at the probes j ≡ first (mod stride): `solved[j]` is the
/// probe solved at points[j] and tracked like a sample; appends (j, ω₁ relative error, response
/// NRMSE) per probe to `out`. The reference deployment is `drive` with `options`. ω₁ is always
/// exact; the response error is deployed unless — as the leave-one-out carries its errors over
/// (rom/offline/rbf_leave_one_out.hpp) — the probe's feature error moved by less than
/// kResidualReuseTolerance since its last deployment *and* the error so scaled is ≤ `carry_below`:
/// a probe that could decide the build's stop (≥ carry_below, half the tolerance) is always
/// measured. carry_below = 0 deploys every probe whose value was carried over before (the final
/// pass that makes every stored value a measured one).
void measureProbeShare(const RomDatabase& db, const std::vector<std::vector<double>>& points,
                       const std::vector<RomSample>& solved, const fullorder::DriveLaw& drive,
                       const ModalDeploymentOptions& options, double carry_below,
                       ProbeResponseCache& cache, int first, int stride, std::vector<double>& out);

/// The rbf method's entry of a build report from the measured probes: the estimates their
/// maxima, and per sample the largest error of the probes nearest to it (−1 where none is).
LeaveOneOutResult summariseScatteredProbes(const RomDatabase& db,
                                           const std::vector<ProbeError>& measured);

}  // namespace mastrom::rom
