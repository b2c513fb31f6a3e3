// Greedy adaptive sampling of a scattered ROM database (see adaptive_build.hpp).
#include "rom/offline/adaptive_build.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "common/error.hpp"
#include "common/option_names.hpp"
#include "common/text_parsing.hpp"
#include "common/version.hpp"
#include "fullorder/mast_config.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/interpolation/rbf_weights.hpp"
#include "rom/offline/build_phases.hpp"
#include "rom/offline/modulus_reduction.hpp"
#include "rom/offline/mpi_gather.hpp"
#include "rom/offline/rbf_leave_one_out.hpp"
#include "rom/offline/scattered_probes.hpp"
#include "rom/offline/space_filling.hpp"

namespace mastrom::rom {
namespace {

constexpr int kMaxSamples = 10000;

}  // namespace

void checkAdaptiveBuildOptions(const AdaptiveBuildOptions& adaptive, int parameter_count) {
  const int p = parameter_count;
  MASTROM_REQUIRE(
      std::isfinite(adaptive.tolerance) && adaptive.tolerance > 0.0 && adaptive.tolerance < 1.0,
      InputError, optionName(Option::Tolerance), " = ", shortestText(adaptive.tolerance),
      " is out of range (a relative NRMSE: 0 < T < 1, e.g. 0.03 for 3 %)");
  MASTROM_REQUIRE(adaptive.max_samples >= 2 * p + 1 && adaptive.max_samples <= kMaxSamples,
                  InputError, optionName(Option::MaxSamples), " = ", adaptive.max_samples,
                  " is out of range (", 2 * p + 1, " to ", kMaxSamples, ": the initial design of ",
                  p, " parameters has 2p + 1 = ", 2 * p + 1, " samples)");
}

int adaptiveRoundSize(int samples) {
  const int grown = 2 * ((samples + kAdaptiveRoundGrowth / 2) / kAdaptiveRoundGrowth);
  return std::max(kAdaptiveRoundSize, grown);
}

namespace {

/// The options checked before anything is solved; the settings every sample is solved with.
SampleSettings planAdaptiveBuild(const Config& base, const DatabaseBuildOptions& options,
                                 const AdaptiveBuildOptions& adaptive) {
  MASTROM_REQUIRE(!options.axes.empty(), InputError,
                  "rom build: no parameter axis (give at least one with ",
                  optionName(Option::Param), " KEY=LO:HI)");
  for (const ParameterAxis& a : options.axes)
    MASTROM_REQUIRE(a.values.size() == 2 && a.values[0] < a.values[1], InputError,
                    optionName(Option::Param), " ", a.key,
                    ": an adaptive build takes the range KEY=LO:HI");
  checkAdaptiveBuildOptions(adaptive, static_cast<int>(options.axes.size()));
  MASTROM_REQUIRE(!options.method || *options.method == InterpolationMethod::Rbf, InputError,
                  "rom build: the ", toString(options.method.value_or(InterpolationMethod::Rbf)),
                  " method needs a tensor grid; an adaptive database is interpolated by rbf");
  MASTROM_REQUIRE(options.modes >= 0, InputError, "rom build: ", optionName(Option::Modes), " ",
                  options.modes,
                  " is out of range (>= 1, or 0 for modes.count of the configuration)");
  SampleSettings s;
  s.base = databaseBaseConfig(base, options.axes);
  s.axes = options.axes;
  s.modes = options.modes > 0 ? options.modes : s.base.modes.count;
  s.backend = options.backend.value_or(s.base.modes.backend);
  s.stresses = options.stresses;
  return s;
}

RomDatabase describeAdaptiveDatabase(const SampleSettings& s) {
  RomDatabase db;
  Config stored = s.base;
  stored.modes.count = s.modes;
  stored.modes.backend = s.backend;
  db.base_config_toml = toToml(stored);
  db.axes = s.axes;
  db.layout = SampleLayout::Scattered;
  db.modes_per_sample = s.modes;
  db.mastrom_version = std::string(kVersion);
  db.default_method = InterpolationMethod::Rbf;
  db.reference_sample = 0;  // the box centre, the first point of the initial design
  return db;
}

/// Step 1 of the header: the centre, then Halton points 1 … 2p — skipping one that is the centre
/// (in one dimension the first, 1/2: the rbf needs distinct samples).
std::vector<std::vector<double>> initialDesign(const std::vector<ParameterAxis>& axes) {
  const int p = static_cast<int>(axes.size());
  const Eigen::VectorXd centre = Eigen::VectorXd::Constant(p, 0.5);
  std::vector<std::vector<double>> points{boxPoint(axes, centre)};
  for (int i = 1; static_cast<int>(points.size()) < 2 * p + 1; ++i) {
    const Eigen::VectorXd u = haltonPoint(i, p);
    if (u != centre) points.push_back(boxPoint(axes, u));
  }
  return points;
}

/// Step 2 of the header: up to `count` candidates, largest estimate first, each later one with the
/// power function of the samples plus the points already chosen. `at` = the estimate at the
/// candidates; `used` marks the candidates chosen (before and now).
std::vector<std::vector<double>> chooseCandidates(
    const RomDatabase& db, const std::vector<std::vector<double>>& candidates,
    const RadialBasisErrorEstimate::PointEstimates& at, std::vector<char>& used, int count) {
  std::vector<std::vector<double>> points;
  for (const RomSample& s : db.samples) points.push_back(s.parameters);
  // estimate = P(x) · ε(x): ε stays, P follows the points chosen.
  Eigen::VectorXd power = at.power;
  std::vector<std::vector<double>> chosen;
  for (int n = 0; n < count; ++n) {
    if (n > 0) power = RadialBasisWeights(db.axes, points).powerFunctions(candidates);
    std::size_t best = candidates.size();
    double largest = 0.0;
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      const double e =
          power[static_cast<Eigen::Index>(c)] * at.response_scale[static_cast<Eigen::Index>(c)];
      if (!used[c] && e > largest) {
        largest = e;
        best = c;
      }
    }
    if (best == candidates.size()) break;  // every candidate used or at a sample
    used[best] = 1;
    chosen.push_back(candidates[best]);
    points.push_back(candidates[best]);
  }
  return chosen;
}

/// The probes on every rank: solved round-robin over the ranks (tracked against
/// the reference, without stresses: the estimate deploys the end acceleration only) and gathered.
std::vector<RomSample> solveProbes(const SampleSettings& settings,
                                    const std::vector<std::vector<double>>& points,
                                    const SampleSolution& reference, int rank, int size,
                                    MPI_Comm comm, SolveTimes& times) {
  SampleSettings probe_settings = settings;
  probe_settings.stresses = false;
  RankOutcome share;
  runCatching(share, "rom build: probe: ", [&] {
    solveShare(probe_settings, points, 0, reference, -1, rank, size, times, share);
  });
  throwIfAnyRankFailed(comm, share.error, share.numerical);
  RomDatabase solved;  // the probes as samples, only to unpack them
  solved.axes = settings.axes;
  solved.samples.assign(points.size(), RomSample{});
  BuildReport unused;
  collectSamples(gatherToAll(comm, share.values), points, 0, solved, unused);
  return std::move(solved.samples);
}

/// The triples (probe, ω₁ error, response error) every rank measured, in probe order.
std::vector<ProbeError> unpackProbeErrors(const std::vector<double>& gathered,
                                          const std::vector<std::vector<double>>& points) {
  std::vector<ProbeError> out(points.size());
  std::vector<char> seen(points.size(), 0);
  for (std::size_t i = 0; i + 2 < gathered.size(); i += 3) {
    const auto j = static_cast<std::size_t>(gathered[i]);
    MASTROM_REQUIRE(j < points.size() && !seen[j], NumericalError,
                    "rom build: probe ", j, " measured twice or out of range");
    seen[j] = 1;
    out[j] = ProbeError{points[j], gathered[i + 1], gathered[i + 2]};
  }
  MASTROM_REQUIRE(std::all_of(seen.begin(), seen.end(), [](char c) { return c != 0; }),
                  NumericalError, "rom build: a probe's error did not arrive");
  return out;
}

/// A fresh probe set: its points and, once solved, the probes.
struct FreshProbes {
  std::vector<std::vector<double>> points;
  std::vector<RomSample> samples;
};

/// The measurements that confirm a stop (collective): the fresh set solved, then this rank's share
/// of the stopping probes whose value was carried over deployed (so that every value is a measured
/// one) and of the fresh set measured; both gathered to rank 0 as measureProbeShare's triples.
/// Returns this rank's time in the fresh set's modal solves [s].
double measureForConfirmation(const SampleSettings& settings, const SampleSolution& reference,
                            const RomDatabase& db, const fullorder::DriveLaw& drive,
                            const ModalDeploymentOptions& deploy,
                            const std::vector<std::vector<double>>& stop_points,
                            const std::vector<RomSample>& stop_samples, ProbeResponseCache& cache,
                            FreshProbes& fresh, int rank, int size, MPI_Comm comm,
                            std::vector<double>& stop_gathered,
                            std::vector<double>& fresh_gathered) {
  const auto solves_start = BuildClock::now();
  SolveTimes fresh_times;
  fresh.samples = solveProbes(settings, fresh.points, reference, rank, size, comm, fresh_times);
  const double solves_s = secondsSince(solves_start);
  RankOutcome stop;
  std::vector<double> fresh_values;
  ProbeResponseCache fresh_cache;
  runCatching(stop, "rom build: error estimate: ", [&] {
    measureProbeShare(db, stop_points, stop_samples, drive, deploy, 0.0, cache, rank, size,
                      stop.values);
    measureProbeShare(db, fresh.points, fresh.samples, drive, deploy, 0.0, fresh_cache, rank, size,
                      fresh_values);
  });
  throwIfAnyRankFailed(comm, stop.error, stop.numerical);
  stop_gathered = gatherToRoot(comm, stop.values);
  fresh_gathered = gatherToRoot(comm, fresh_values);
  return solves_s;
}

/// Rank 0's points sent to every rank (a gather with only rank 0 contributing), with a leading
/// count; an empty list ends the build.
std::vector<std::vector<double>> shareFromRoot(MPI_Comm comm, int rank, std::size_t p,
                                               const std::vector<std::vector<double>>& points) {
  std::vector<double> flat;
  if (rank == 0) {
    flat.push_back(static_cast<double>(points.size()));
    for (const std::vector<double>& x : points) flat.insert(flat.end(), x.begin(), x.end());
  }
  const std::vector<double> all = gatherToAll(comm, flat);
  const auto count = static_cast<std::size_t>(all.at(0));
  MASTROM_REQUIRE(all.size() == 1 + count * p, NumericalError,
                  "rom build: the next round's points arrived truncated");
  std::vector<std::vector<double>> out(count);
  for (std::size_t i = 0; i < count; ++i)
    out[i].assign(all.begin() + static_cast<long>(1 + i * p),
                  all.begin() + static_cast<long>(1 + (i + 1) * p));
  return out;
}

}  // namespace

RomDatabase buildAdaptiveDatabase(const Config& base, const DatabaseBuildOptions& options,
                                  const AdaptiveBuildOptions& adaptive, BuildReport* report,
                                  const std::function<void(const AdaptiveRound&)>& on_round) {
  // Young's modulus handled exactly (rom/offline/modulus_reduction.hpp): the same build over the
  // other axes at E₀, the E axis restored afterwards.
  const ModulusReduction plan = planModulusReduction(base, options.axes);
  if (plan.applies()) {
    DatabaseBuildOptions reduced = options;
    reduced.axes = reducedBuildAxes(options.axes, plan);
    RomDatabase db = buildAdaptiveDatabase(reducedBuildBase(base, plan), reduced, adaptive, report,
                                           on_round);
    restoreModulusAxis(db, base, options.axes[static_cast<std::size_t>(plan.axis)], plan);
    return db;
  }
  const auto wall_start = BuildClock::now();
  const SampleSettings settings = planAdaptiveBuild(base, options, adaptive);
  RomDatabase db = describeAdaptiveDatabase(settings);
  const std::size_t p = settings.axes.size();
  const MPI_Comm comm = options.communicator;
  int rank = 0, size = 1;
  communicatorRankSize(comm, rank, size);

  const fullorder::DriveLaw drive(fullorder::driveFromConfig(settings.base));
  const ModalDeploymentOptions deploy = deploymentOptionsFromConfig(settings.base);
  const std::vector<std::vector<double>> candidates = estimateCandidates(
      settings.axes, kCandidatesPerParameter * static_cast<int>(p), 2 * static_cast<long>(p) + 1);
  std::vector<char> used(candidates.size(), 0);
  LeaveOneOutCache loo_cache;  // this rank's samples' responses between rounds

  BuildReport rep;
  BuildTiming timing;
  timing.ranks = size;
  SolveTimes solve_times;
  double estimate_s = 0.0;      // this rank's time in the estimate, probe solves apart
  double probe_solves_s = 0.0;  // this rank's time in the probes' modal solves
  std::vector<std::vector<double>> round_points = initialDesign(settings.axes);
  std::optional<SampleSolution> reference;
  LeaveOneOutResult last;
  // The held-out probes that decide the stop (rom/offline/scattered_probes.hpp): solved after the
  // first round's samples, measured every round, this rank's share of their responses kept in
  // probe_cache. A fresh set that fails to confirm a stop joins them.
  std::vector<std::vector<double>> probe_points = scatteredProbePoints(settings.axes, 0);
  std::vector<RomSample> probe_samples;
  ProbeResponseCache probe_cache;
  std::vector<double> probe_share;
  std::vector<ProbeError> measured, fresh_measured;  // rank 0
  int fresh_sets = 0;
  // Rank 0: the round's estimate (4.11) at the candidates, which a failed confirmation chooses from.
  RadialBasisErrorEstimate::PointEstimates at_candidates;
  for (int round = 0; !round_points.empty(); ++round) {
    // The round's modal solves (the reference first, on every rank, once).
    const int first = static_cast<int>(db.samples.size());
    RankOutcome solved;
    runCatching(solved, "rom build: ", [&] {
      if (!reference) reference = solveReference(settings, round_points.front(), 0, solve_times);
      solveShare(settings, round_points, first, *reference, 0, rank, size, solve_times, solved,
                 options.progress);
    });
    const auto comm_start = BuildClock::now();
    throwIfAnyRankFailed(comm, solved.error, solved.numerical);
    const std::vector<double> all = gatherToAll(comm, solved.values);
    timing.communication_s += secondsSince(comm_start);
    db.samples.resize(static_cast<std::size_t>(first) + round_points.size());
    collectSamples(all, round_points, first, db, rep);
    if (probe_samples.empty()) {  // timed with the estimate, as the grid's probes are
      const auto probes_start = BuildClock::now();
      SolveTimes probe_times;
      probe_samples = solveProbes(settings, probe_points, *reference, rank, size, comm, probe_times);
      probe_solves_s += secondsSince(probes_start);
    }

    // The samples' leave-one-out errors, shared out like the solves (each rank keeps the exact
    // responses of its own samples between rounds), and the stopping probes likewise; rank 0:
    // the estimate and the next round's points.
    const auto estimate_start = BuildClock::now();
    RankOutcome share;
    runCatching(share, "rom build: error estimate: ", [&] {
      const LeftOutErrors own = radialBasisLeaveOneOut(db, drive, deploy, loo_cache, rank, size);
      for (std::size_t s = static_cast<std::size_t>(rank); s < db.samples.size();
           s += static_cast<std::size_t>(size)) {
        share.values.push_back(static_cast<double>(s));
        share.values.push_back(own.frequency[s]);
        share.values.push_back(own.response[s]);
      }
      // A probe that could decide the stop (≥ half the tolerance) is always deployed.
      measureProbeShare(db, probe_points, probe_samples, drive, deploy, 0.5 * adaptive.tolerance,
                        probe_cache, rank, size, probe_share);
      share.values.push_back(-1.0);  // this rank's counts
      share.values.push_back(loo_cache.deployed + probe_cache.deployed);
      share.values.push_back(loo_cache.reused + probe_cache.carried);
    });
    estimate_s += secondsSince(estimate_start);  // this rank's share (waits excluded)
    throwIfAnyRankFailed(comm, share.error, share.numerical);
    const std::vector<double> gathered = gatherToRoot(comm, share.values);
    const std::vector<double> probe_gathered = gatherToRoot(comm, probe_share);
    probe_share.clear();
    RankOutcome next;
    std::vector<std::vector<double>> chosen;
    AdaptiveRound r;  // rank 0
    const auto choose = [&] {
      const int budget = adaptive.max_samples - static_cast<int>(db.samples.size());
      if (budget > 0)
        chosen = chooseCandidates(
            db, candidates, at_candidates, used,
            std::min(adaptiveRoundSize(static_cast<int>(db.samples.size())), budget));
    };
    if (rank == 0) {
      const auto choice_start = BuildClock::now();
      runCatching(next, "rom build: error estimate: ", [&] {
        LeftOutErrors errors;
        errors.frequency.assign(db.samples.size(), -1.0);
        errors.response.assign(db.samples.size(), -1.0);
        int deployed = 0, reused = 0;
        for (std::size_t i = 0; i + 2 < gathered.size(); i += 3) {
          if (gathered[i] < 0) {
            deployed += static_cast<int>(gathered[i + 1]);
            reused += static_cast<int>(gathered[i + 2]);
            continue;
          }
          const auto s = static_cast<std::size_t>(gathered[i]);
          errors.frequency.at(s) = gathered[i + 1];
          errors.response.at(s) = gathered[i + 2];
        }
        const RadialBasisErrorEstimate estimate(db, std::move(errors));
        at_candidates = estimate.atPoints(candidates);
        const LeaveOneOutResult inferred =
            summariseRadialBasis(estimate, db, candidates, at_candidates);
        measured = unpackProbeErrors(probe_gathered, probe_points);
        last = summariseScatteredProbes(db, measured);
        if (last.response_estimate > adaptive.tolerance) choose();
        r.round = round;
        r.samples = static_cast<int>(db.samples.size());
        r.response_estimate = last.response_estimate;
        r.frequency_estimate = last.frequency_estimate;
        r.probes = static_cast<int>(measured.size());
        r.inferred_response_estimate = inferred.response_estimate;
        r.largest_left_out = inferred.max_response_error;
        r.deployed = deployed;
        r.reused = reused;
      });
      estimate_s += secondsSince(choice_start);
    }
    throwIfAnyRankFailed(comm, next.error, next.numerical);
    round_points = shareFromRoot(comm, rank, p, chosen);

    if (round_points.empty()) {
      // The stopping probes are within the tolerance (or the budget is spent). They were selected
      // by that stop, so it is confirmed on a fresh set that took no part in it
      // (rom/offline/scattered_probes.hpp); every stopping probe whose value was carried over is
      // deployed first (a measured value for each in the file). A fresh set above the tolerance
      // joins the stopping set, and the build goes on while the budget lasts.
      const auto confirm_start = BuildClock::now();
      FreshProbes fresh{scatteredProbePoints(settings.axes, ++fresh_sets), {}};
      std::vector<double> stop_gathered, fresh_gathered;
      const double fresh_solves_s =
          measureForConfirmation(settings, *reference, db, drive, deploy, probe_points,
                                 probe_samples, probe_cache, fresh, rank, size, comm, stop_gathered,
                                 fresh_gathered);
      probe_solves_s += fresh_solves_s;
      estimate_s += secondsSince(confirm_start) - fresh_solves_s;
      RankOutcome decision;
      if (rank == 0) {
        runCatching(decision, "rom build: error estimate: ", [&] {
          measured = unpackProbeErrors(stop_gathered, probe_points);
          fresh_measured = unpackProbeErrors(fresh_gathered, fresh.points);
          double worst = 0.0, worst_frequency = 0.0;
          for (const ProbeError& e : fresh_measured) {
            worst = std::max(worst, e.response_error);
            worst_frequency = std::max(worst_frequency, e.frequency_error);
          }
          r.fresh_probes = static_cast<int>(fresh_measured.size());
          r.fresh_response_estimate = worst;
          r.fresh_frequency_estimate = worst_frequency;
          if (worst > adaptive.tolerance) choose();
          r.fresh_joined = !chosen.empty();
        });
      }
      throwIfAnyRankFailed(comm, decision.error, decision.numerical);
      round_points = shareFromRoot(comm, rank, p, chosen);
      if (!round_points.empty()) {  // the fresh set joins the stopping set
        probe_points.insert(probe_points.end(), fresh.points.begin(), fresh.points.end());
        for (RomSample& s : fresh.samples) probe_samples.push_back(std::move(s));
        fresh_measured.clear();
      }
    }
    if (rank == 0 && on_round) {
      r.estimate_s = secondsSince(estimate_start);
      r.wall_s = secondsSince(wall_start);
      on_round(r);
    }
  }
  if (rank == 0) {  // the estimate: the stopping probes and the last fresh set
    for (ProbeError& e : fresh_measured) measured.push_back(std::move(e));
    last = summariseScatteredProbes(db, measured);
  }

  double local[6] = {solve_times.assembly_s, solve_times.eigensolve_s, solve_times.extraction_s,
                     static_cast<double>(solve_times.solves), estimate_s, probe_solves_s};
  double sums[6] = {local[0], local[1], local[2], local[3], local[4], local[5]};
  if (comm != MPI_COMM_NULL) MPI_Reduce(local, sums, 6, MPI_DOUBLE, MPI_SUM, 0, comm);
  timing.assembly_s = sums[0];
  timing.eigensolve_s = sums[1];
  timing.extraction_s = sums[2];
  timing.solves = static_cast<int>(sums[3]);
  timing.leave_one_out_s = sums[4];  // Σ over ranks, as the other phases
  timing.probe_solves_s = sums[5];
  if (rank != 0) {
    db.samples.clear();
    if (report) report->timing = timing;
    return db;
  }
  for (std::size_t s = 0; s < db.samples.size(); ++s) {
    db.samples[s].loo_frequency_error = last.frequency_error[s];
    db.samples[s].loo_response_error = last.response_error[s];
  }
  rep.leave_one_out = {last};
  db.probes = std::move(measured);
  db.estimate_from_probes = true;
  timing.probes = static_cast<int>(db.probes.size());
  timing.wall_s = secondsSince(wall_start);
  rep.timing = timing;
  if (report) *report = std::move(rep);
  return db;
}

}  // namespace mastrom::rom
