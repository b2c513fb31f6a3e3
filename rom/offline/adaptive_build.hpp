// The adaptive offline stage (docs/theory.md §4.3, adaptive sampling): a database of scattered
// samples, grown where the radial-basis method's estimated error is largest until the estimate
// over the box meets a tolerance — the greedy sampling of the reduced-basis method [BCDDPW11;
// QMN16, §7.1] with the cheap error estimate of rom/offline/rbf_leave_one_out.hpp in place of the
// residual-based one.
//
//  1. Initial design: the box centre (the tracking reference) and the Halton points 1 … 2p in the
//     box coordinates of rom/interpolation/rbf_weights.hpp — 2p + 1 samples for p parameters, more
//     than the p + 2 the leave-one-out of a linear tail needs.
//  2. Each round: the estimate at every candidate (the box corners and the next
//     kCandidatesPerParameter × p Halton points); stop when its largest value is ≤ the tolerance
//     or the sample budget is spent; else add the candidate of largest estimate, then — up to
//     kAdaptiveRoundSize points a round — the next one with the power function updated for the
//     points already chosen this round (so that one round does not pile its points into one spot).
//  3. The round's modal solves are shared round-robin over the ranks, tracked
//     against the reference every rank solved first (rom/offline/build_phases.hpp), gathered to
//     every rank; the samples' leave-one-out deployments are shared out alike (sample s on rank
//     s mod P, which keeps its own responses between rounds); rank 0 estimates and chooses, and
//     sends the next round's points to all.
// The round size is a constant, not the number of ranks, so that the design — hence the database,
// bit for bit — is the same on any number of ranks (1 or 2 of them use a round fully).
#pragma once

#include <functional>

#include "common/config.hpp"
#include "rom/database/build_report.hpp"
#include "rom/database/rom_database.hpp"
#include "rom/offline/database_build.hpp"

namespace mastrom::rom {

/// Samples added per round of an adaptive build, whatever the number of ranks: two keep both
/// cores of a workstation busy with modal solves and re-estimate often enough that a round rarely
/// adds a point the previous one's estimate would not have chosen.
constexpr int kAdaptiveRoundSize = 2;

struct AdaptiveBuildOptions {
  /// Target of the estimated NRMSE of the relative end angular acceleration over the box
  /// (relative, in (0, 1)).
  double tolerance = 0.03;
  /// Sample budget (≥ 2p + 1, the initial design; ≤ 10000).
  int max_samples = 100;
};

/// InputError (one line naming the option, its value and the allowed range) unless `adaptive`
/// suits a box of `parameter_count` parameters: 0 < tolerance < 1, 2p + 1 ≤ max_samples ≤ 10000.
/// buildAdaptiveDatabase checks the same; a caller checks first to refuse before printing anything.
void checkAdaptiveBuildOptions(const AdaptiveBuildOptions& adaptive, int parameter_count);

/// One round's outcome, as the build reports it.
struct AdaptiveRound {
  int round = 0;
  int samples = 0;                   ///< samples in the database after the round
  double response_estimate = -1.0;   ///< largest estimate over the candidates
  double frequency_estimate = -1.0;  ///< of ω₁ likewise
  double largest_left_out = -1.0;    ///< largest leave-one-out NRMSE at a sample
  int deployed = 0;                  ///< left-out models deployed for the estimate
  int reused = 0;                    ///< left-out response errors carried over
  double estimate_s = 0.0;           ///< time of the round's estimate [s]
  double wall_s = 0.0;               ///< wall time since the build started [s]
};

/// Build a scattered database over the box of `options.axes` (each holding the range {lo, hi},
/// parseParameterAxis with AxisForm::Range); `options.method` must be empty or rbf (the method of
/// scattered samples). Collective over options.communicator; the database on rank 0 (empty on the
/// others). `on_round` is called on rank 0 after every round. Throws InputError for bad options
/// (naming the argument, its value and the allowed range) before any solve, NumericalError naming
/// the sample when a modal solve fails.
RomDatabase buildAdaptiveDatabase(const Config& base, const DatabaseBuildOptions& options,
                                  const AdaptiveBuildOptions& adaptive,
                                  BuildReport* report = nullptr,
                                  const std::function<void(const AdaptiveRound&)>& on_round = {});

}  // namespace mastrom::rom
