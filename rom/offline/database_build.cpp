#include "rom/offline/database_build.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "common/error.hpp"
#include "common/option_names.hpp"
#include "common/version.hpp"
#include "fullorder/mast_config.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/interpolation/affine_interpolation.hpp"
#include "rom/interpolation/affine_model.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/offline/build_phases.hpp"
#include "rom/offline/leave_one_out.hpp"
#include "rom/offline/mpi_gather.hpp"
#include "rom/offline/probe_estimate.hpp"
#include "rom/offline/rbf_leave_one_out.hpp"

namespace mastrom::rom {
namespace {

/// The affine terms over the box of `axes` (the parameters not on an axis fixed at the base's
/// values), locked at the base's modes.angle_deg.
AffineReducedModel buildAffineTerms(const Config& base, const std::vector<ParameterAxis>& axes,
                                    int modes, EigenBackendKind backend, bool stresses) {
  AffineModelOptions o;
  o.box.thickness_min_m = o.box.thickness_max_m = base.interface.thickness_m;
  o.box.youngs_modulus_min_pa = o.box.youngs_modulus_max_pa = base.material.youngs_modulus_pa;
  o.box.density_min_kg_m3 = o.box.density_max_kg_m3 = base.material.density_kg_m3;
  for (const ParameterAxis& a : axes) {
    const double lo = a.values.front(), hi = a.values.back();
    if (a.key == "interface.thickness") {
      o.box.thickness_min_m = lo;
      o.box.thickness_max_m = hi;
    } else if (a.key == "material.youngs_modulus") {
      o.box.youngs_modulus_min_pa = lo;
      o.box.youngs_modulus_max_pa = hi;
    } else if (a.key == "material.density") {
      o.box.density_min_kg_m3 = lo;
      o.box.density_max_kg_m3 = hi;
    }
  }
  o.lock_angle_rad = base.modes.angleRad();
  o.modes = modes;
  // Snapshots: the stored modes plus the window margin of the samples, at 3 points per varying
  // axis (h, ρ; E does not change a mode shape) — the defaults of rom/interpolation/affine_model.hpp, whose
  // tests measure the truncation error they leave.
  o.snapshot_modes = std::max(o.snapshot_modes, modes + kExtraModes);
  o.backend = backend;
  o.stresses = stresses;
  return AffineModalModel::build(fullorder::mastParametersFromConfig(base), o).reduced();
}

/// The build's settings, checked, before anything is solved.
struct BuildPlan {
  Config base;  ///< the base configuration with the database's fixed settings
  int modes = 0;
  EigenBackendKind backend = EigenBackendKind::Slepc;
  int samples = 0;
};

BuildPlan planBuild(const Config& base_in, const DatabaseBuildOptions& options) {
  MASTROM_REQUIRE(!options.axes.empty(), InputError,
                  "rom build: no parameter axis (give at least one with ",
                  optionName(Option::Param), " KEY=LO:HI:N)");
  BuildPlan plan;
  plan.base = databaseBaseConfig(base_in, options.axes);
  MASTROM_REQUIRE(options.modes >= 0, InputError, "rom build: ", optionName(Option::Modes), " ",
                  options.modes,
                  " is out of range (>= 1, or 0 for modes.count of the configuration)");
  plan.modes = options.modes > 0 ? options.modes : plan.base.modes.count;
  plan.backend = options.backend.value_or(plan.base.modes.backend);
  long total = 1;
  for (const ParameterAxis& a : options.axes) {
    MASTROM_REQUIRE(a.values.size() >= 2, InputError, "rom build: axis ", a.key,
                    " needs at least 2 values");
    total *= static_cast<long>(a.values.size());
  }
  MASTROM_REQUIRE(total <= 1000000, InputError, "rom build: ", total,
                  " samples is too many (at most 1e6)");
  plan.samples = static_cast<int>(total);
  return plan;
}

/// The database's description (no samples yet): its configuration says what ran, its reference
/// sample is the box centre.
RomDatabase describeDatabase(const BuildPlan& plan, const std::vector<ParameterAxis>& axes) {
  RomDatabase db;
  Config stored = plan.base;
  stored.modes.count = plan.modes;
  stored.modes.backend = plan.backend;
  db.base_config_toml = toToml(stored);
  db.axes = axes;
  db.modes_per_sample = plan.modes;
  db.mastrom_version = std::string(kVersion);
  db.default_method = interpolationMethodAvailable(InterpolationMethod::Manifold)
                          ? InterpolationMethod::Manifold
                          : InterpolationMethod::Tracked;
  std::vector<int> centre(axes.size());
  for (std::size_t a = 0; a < axes.size(); ++a)
    centre[a] = static_cast<int>(axes[a].values.size() - 1) / 2;
  db.reference_sample = db.sampleIndex(centre);
  return db;
}

/// This rank's share of the leave-one-out errors: per method and own sample (index, frequency
/// error, response error).
RankOutcome leaveOneOutOfShare(const RomDatabase& db, const std::vector<InterpolationMethod>& methods,
                               const fullorder::DriveLaw& drive,
                               const ModalDeploymentOptions& deploy, int rank, int size) {
  RankOutcome out;
  runCatching(out, "rom build: leave-one-out: ", [&] {
    std::vector<std::vector<double>> exact_series;
    const int samples = static_cast<int>(db.samples.size());
    for (const InterpolationMethod m : methods) {
      const LeaveOneOutResult r = leaveOneOutShare(db, m, drive, deploy, rank, size, exact_series);
      for (int s = rank; s < samples; s += size) {
        out.values.push_back(s);
        out.values.push_back(r.frequency_error[s]);
        out.values.push_back(r.response_error[s]);
      }
    }
  });
  return out;
}

/// Rank 0: the gathered errors (every rank's block holds, method by method, its own samples, in
/// rank order) as one summarised result per method.
std::vector<LeaveOneOutResult> assembleLeaveOneOut(const std::vector<double>& loo,
                                                   const std::vector<InterpolationMethod>& methods,
                                                   const std::vector<ParameterAxis>& axes,
                                                   int samples, int size) {
  std::vector<LeaveOneOutResult> results;
  for (const InterpolationMethod m : methods) {
    LeaveOneOutResult r;
    r.method = m;
    r.frequency_error.assign(static_cast<std::size_t>(samples), -1.0);
    r.response_error.assign(static_cast<std::size_t>(samples), -1.0);
    results.push_back(std::move(r));
  }
  std::size_t pos = 0;
  for (int r = 0; r < size; ++r) {
    const int own = (samples - r + size - 1) / size;
    for (std::size_t m = 0; m < methods.size(); ++m) {
      for (int i = 0; i < own; ++i, pos += 3) {
        const int s = static_cast<int>(loo[pos]);
        results[m].frequency_error[s] = loo[pos + 1];
        results[m].response_error[s] = loo[pos + 2];
      }
    }
  }
  for (LeaveOneOutResult& r : results) summariseLeaveOneOut(r, axes);
  return results;
}

/// Rank 0: the exact affine terms (method (c)) where they apply, and their error at every sample
/// (truncation to the basis only, nothing is interpolated: stored unscaled as the estimate).
std::optional<LeaveOneOutResult> addAffineTerms(const BuildPlan& plan, RomDatabase& db,
                                                const fullorder::DriveLaw& drive,
                                                const ModalDeploymentOptions& deploy,
                                                bool stresses) {
  if (!affineApplicable(plan.base, db.axes)) return std::nullopt;
  db.affine = buildAffineTerms(plan.base, db.axes, plan.modes, plan.backend, stresses);
  const AffineInterpolator interp(db);
  LeaveOneOutResult r;
  r.method = InterpolationMethod::Affine;
  r.frequency_error.assign(db.samples.size(), -1.0);
  r.response_error.assign(db.samples.size(), -1.0);
  for (std::size_t s = 0; s < db.samples.size(); ++s) {
    const RomSample& sample = db.samples[s];
    const ModalModel m = interp.evaluate(sample.parameters);
    const double w = sample.modal.omega_rad_s.minCoeff();
    r.frequency_error[s] = std::abs(m.omega_rad_s.minCoeff() - w) / w;
    r.response_error[s] = responseNrmse(relativeAccelerationSeries(sample.modal, drive, deploy),
                                        relativeAccelerationSeries(m, drive, deploy));
    ++r.estimated;
    r.max_frequency_error = std::max(r.max_frequency_error, r.frequency_error[s]);
    r.max_response_error = std::max(r.max_response_error, r.response_error[s]);
  }
  r.frequency_estimate = r.max_frequency_error;
  r.response_estimate = r.max_response_error;
  db.default_method = InterpolationMethod::Affine;
  return r;
}

}  // namespace

RomDatabase buildDatabase(const Config& base_in, const DatabaseBuildOptions& options,
                          BuildReport* report) {
  const auto wall_start = BuildClock::now();
  const BuildPlan plan = planBuild(base_in, options);
  if (options.method) {
    MASTROM_REQUIRE(
        *options.method != InterpolationMethod::Affine || affineApplicable(plan.base, options.axes),
        InputError,
        "rom build: the affine method needs the exact affine terms, which apply only "
        "to thickness, Young's modulus and density at a fixed radius without gravity");
    MASTROM_REQUIRE(interpolationMethodAvailable(*options.method), InputError, "rom build: the ",
                    toString(*options.method), " method is not available in this build");
  }
  RomDatabase db = describeDatabase(plan, options.axes);
  const MPI_Comm comm = options.communicator;
  int rank = 0, size = 1;
  communicatorRankSize(comm, rank, size);

  // 1. This rank's samples (after the reference, which every rank solves).
  SampleSettings settings{plan.base, options.axes, plan.modes, plan.backend, options.stresses};
  std::vector<std::vector<double>> points;
  for (int s = 0; s < plan.samples; ++s) points.push_back(gridPoint(options.axes, s));
  SolveTimes solve_times;
  RankOutcome solved;
  std::optional<SampleSolution> ref;  // kept for the probes of step 3
  runCatching(solved, "rom build: ", [&] {
    ref = solveReference(settings, points[static_cast<std::size_t>(db.reference_sample)],
                         db.reference_sample, solve_times);
    solveShare(settings, points, 0, *ref, db.reference_sample, rank, size, solve_times, solved,
               options.progress);
  });
  // Assembly, eigensolve, extraction, solves, leave-one-out, probe solves.
  double local_times[6] = {solve_times.assembly_s, solve_times.eigensolve_s,
                           solve_times.extraction_s, static_cast<double>(solve_times.solves),
                           0.0, 0.0};

  // 2. Every rank gets every sample (the leave-one-out estimate is shared out too).
  const auto comm_start = BuildClock::now();
  throwIfAnyRankFailed(comm, solved.error, solved.numerical);
  BuildTiming timing;
  timing.ranks = size;
  const std::vector<double> all = gatherToAll(comm, solved.values);
  timing.communication_s = secondsSince(comm_start);
  BuildReport rep;
  db.samples.assign(static_cast<std::size_t>(plan.samples), RomSample{});
  collectSamples(all, points, 0, db, rep);

  // 3. Leave-one-out errors: samples round-robin again, gathered to rank 0.
  const auto loo_start = BuildClock::now();
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(plan.base));
  const ModalDeploymentOptions deploy = deploymentOptionsFromConfig(plan.base);
  // The cubic weights: the default where the drive-excited modes track cleanly; their error is
  // measured at the cells' centres where the grid is too coarse for their leave-one-out
  // (rom/offline/probe_estimate.hpp). Every rank knows the tracking report, so all decide alike.
  const bool affine = affineApplicable(plan.base, db.axes);
  const bool cubic = options.method ? *options.method == InterpolationMethod::Cubic
                                    : cubicIsDefault(rep, db.axes, affine);
  const bool cubic_probes = cubic && !cubicHasLeaveOneOut(db.axes);
  // The method step 4 makes the default; unless every method is compared, only its error is
  // estimated (the affine terms always carry their own).
  const InterpolationMethod default_method = options.method ? *options.method
                                             : cubic        ? InterpolationMethod::Cubic
                                             : affine       ? InterpolationMethod::Affine
                                                            : db.default_method;
  const auto estimated = [&](InterpolationMethod m) {
    return options.compare_methods || m == default_method;
  };
  std::vector<InterpolationMethod> methods;
  for (const InterpolationMethod m : {InterpolationMethod::Tracked, InterpolationMethod::Manifold})
    if (interpolationMethodAvailable(m) && estimated(m)) methods.push_back(m);
  // The cubic method's estimate needs an axis of >= 5 nodes (rom/offline/leave_one_out.hpp); where
  // some other axis has fewer the probes measure it instead, and its partial leave-one-out (of the
  // axes that have 5) would only be replaced.
  if (!cubic_probes && estimated(InterpolationMethod::Cubic) &&
      std::any_of(db.axes.begin(), db.axes.end(),
                  [](const ParameterAxis& a) { return a.values.size() >= 5; }))
    methods.push_back(InterpolationMethod::Cubic);
  const RankOutcome loo_share = leaveOneOutOfShare(db, methods, drive, deploy, rank, size);
  throwIfAnyRankFailed(comm, loo_share.error, loo_share.numerical);
  const std::vector<double> loo = gatherToRoot(comm, loo_share.values);
  std::vector<Probe> probes;
  std::vector<std::vector<double>> probe_points;  // their parameters, for the solves and unpacking
  std::vector<double> probe_values;
  double probe_solves_s = 0.0;  // this rank's, apart from the leave-one-out
  if (cubic_probes) {
    const auto probe_solves_start = BuildClock::now();
    probes = cellCentreProbes(db);
    for (const Probe& pr : probes) probe_points.push_back(pr.parameters);
    SampleSettings probe_settings = settings;
    probe_settings.stresses = false;  // the estimate deploys the end acceleration only
    SolveTimes probe_times;
    RankOutcome probe_share;
    solveShare(probe_settings, probe_points, 0, *ref, -1, rank, size, probe_times, probe_share);
    throwIfAnyRankFailed(comm, probe_share.error, probe_share.numerical);
    probe_values = gatherToRoot(comm, probe_share.values);
    probe_solves_s = secondsSince(probe_solves_start);
  }
  local_times[4] = secondsSince(loo_start) - probe_solves_s;
  local_times[5] = probe_solves_s;
  double sums[6] = {local_times[0], local_times[1], local_times[2], local_times[3],
                    local_times[4], local_times[5]};
  if (comm != MPI_COMM_NULL) MPI_Reduce(local_times, sums, 6, MPI_DOUBLE, MPI_SUM, 0, comm);
  timing.assembly_s = sums[0];
  timing.eigensolve_s = sums[1];
  timing.extraction_s = sums[2];
  timing.solves = static_cast<int>(sums[3]);
  timing.leave_one_out_s = sums[4];
  timing.probe_solves_s = sums[5];
  if (rank != 0) {
    db.samples.clear();
    if (report) report->timing = timing;
    return db;
  }

  // 4. Rank 0: the affine terms where they apply, the estimates, the default method's errors.
  const auto affine_start = BuildClock::now();
  std::optional<LeaveOneOutResult> affine_errors =
      addAffineTerms(plan, db, drive, deploy, options.stresses);
  if (affine_errors) timing.affine_s = secondsSince(affine_start);
  rep.leave_one_out = assembleLeaveOneOut(loo, methods, db.axes, plan.samples, size);
  if (affine_errors) rep.leave_one_out.push_back(std::move(*affine_errors));
  // The rbf method's estimate (rom/offline/rbf_leave_one_out.hpp: cheap, rank 0 alone), where the
  // samples determine its weights (p + 2 of them on a grid always span the box).
  const int p = static_cast<int>(db.axes.size());
  if (plan.samples >= p + 2 && estimated(InterpolationMethod::Rbf)) {
    const auto rbf_start = BuildClock::now();
    LeaveOneOutCache cache;
    const RadialBasisErrorEstimate estimate(db, radialBasisLeaveOneOut(db, drive, deploy, cache));
    const std::vector<std::vector<double>> candidates =
        estimateCandidates(db.axes, kCandidatesPerParameter * p, 2L * p + 1);
    rep.leave_one_out.push_back(
        summariseRadialBasis(estimate, db, candidates, estimate.atPoints(candidates)));
    timing.leave_one_out_s += secondsSince(rbf_start);
  }
  if (!probes.empty()) {
    const auto probes_start = BuildClock::now();
    RomDatabase solved_probes;  // the probes as samples, only to unpack them
    solved_probes.axes = db.axes;
    solved_probes.samples.assign(probes.size(), RomSample{});
    BuildReport probe_report;
    collectSamples(probe_values, probe_points, 0, solved_probes, probe_report);
    std::vector<ModalModel> models;
    for (const RomSample& s : solved_probes.samples) models.push_back(s.modal);
    rep.leave_one_out.push_back(  // the cubic entry (no leave-one-out of it was run)
        probeErrors(db, InterpolationMethod::Cubic, probes, models, drive, deploy, db.probes));
    db.estimate_from_probes = true;
    timing.probes = static_cast<int>(probes.size());
    timing.leave_one_out_s += secondsSince(probes_start);
  }
  if (cubic) db.default_method = InterpolationMethod::Cubic;
  if (options.method) db.default_method = *options.method;  // checked before the solves
  for (const LeaveOneOutResult& r : rep.leave_one_out) {
    if (r.method != db.default_method) continue;
    for (int s = 0; s < plan.samples; ++s) {
      db.samples[s].loo_frequency_error = r.frequency_error[s];
      db.samples[s].loo_response_error = r.response_error[s];
    }
  }
  timing.wall_s = secondsSince(wall_start);
  rep.timing = timing;
  if (report) *report = std::move(rep);
  return db;
}

}  // namespace mastrom::rom
