// The adaptive offline stage (docs/theory.md §4.3, adaptive sampling): a database of scattered
// samples, grown where the radial-basis method's estimated error is largest until the error
// measured at held-out probes meets a tolerance — the greedy sampling of the reduced-basis method
// [BCDDPW11; QMN16, §7.1] with the cheap error estimate of rom/offline/rbf_leave_one_out.hpp in
// place of the residual-based one to choose, and a held-out validation set to stop.
//
//  1. Initial design: the box centre (the tracking reference) and the Halton points 1 … 2p in the
//     box coordinates of rom/interpolation/rbf_weights.hpp — 2p + 1 samples for p parameters, more
//     than the p + 2 the leave-one-out of a linear tail needs.
//  2. Each round: the error measured at the stopping probes (rom/offline/scattered_probes.hpp,
//     solved once after the initial design); when its largest value is ≤ the tolerance or the
//     sample budget is spent, a fresh probe set confirms the stop (or, above the tolerance with
//     budget left, joins the stopping set, and the build goes on). Else the leave-one-out
//     estimate at every candidate (the box corners
//     and the next kCandidatesPerParameter × p Halton points) says where: add the candidate of
//     largest estimate, then — up to
//     adaptiveRoundSize(N) points a round — the next one with the power function updated for the
//     points already chosen this round (so that one round does not pile its points into one spot).
//  3. The round's modal solves are shared round-robin over the ranks, tracked
//     against the reference every rank solved first (rom/offline/build_phases.hpp), gathered to
//     every rank; the samples' leave-one-out deployments are shared out alike (sample s on rank
//     s mod P, which keeps its own responses between rounds); rank 0 estimates and chooses, and
//     sends the next round's points to all.
// The round size depends on the number of samples, not of ranks, so that the design — hence the database,
// bit for bit — is the same on any number of ranks (1 or 2 of them use a round fully).
#pragma once

#include <functional>

#include "common/config.hpp"
#include "rom/database/build_report.hpp"
#include "rom/database/rom_database.hpp"
#include "rom/offline/database_build.hpp"

namespace mastrom::rom {

/// Samples added per round of an adaptive build while the database is small, whatever the number
/// of ranks: two keep both cores of a workstation busy with modal solves and re-estimate often
/// enough that a round rarely adds a point the previous one's estimate would not have chosen.
constexpr int kAdaptiveRoundSize = 2;

/// Beyond 24 samples a round adds about one in kAdaptiveRoundGrowth of the database's samples
/// (an even count), so that the number of rounds — each one leave-one-out and one probe pass —
/// grows like log N instead of N. On the five-parameter box: 17 rounds and 9.9 s to the tolerance
/// 3 % instead of 35 rounds and 13.1 s (2 ranks), 75 against 79 samples (benchmarks/README.md
/// "Held-out probes of a scattered database").
constexpr int kAdaptiveRoundGrowth = 16;

/// The samples the next round adds to a database of `samples` (before the budget's cut).
int adaptiveRoundSize(int samples);

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
  double response_estimate = -1.0;   ///< largest NRMSE measured at the held-out probes
  double frequency_estimate = -1.0;  ///< of ω₁ likewise
  int probes = 0;                    ///< held-out probes measured
  /// When the stopping probes were within the tolerance (or the budget spent): the fresh set
  /// measured to confirm it — its probes, its largest errors, and whether it failed (above the
  /// tolerance with budget left: it joined the stopping set and the build went on). 0 / −1 else.
  int fresh_probes = 0;
  double fresh_response_estimate = -1.0;
  double fresh_frequency_estimate = -1.0;
  bool fresh_joined = false;
  /// Largest leave-one-out estimate over the candidates (what picks the next samples).
  double inferred_response_estimate = -1.0;
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
