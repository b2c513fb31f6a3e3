// `mastrom rom build` and `mastrom rom eval` (docs/theory.md §4; docs/user_guide.md §3).
//
//   mastrom rom build CONFIG [--set k=v]… --param KEY=LO:HI:N … [--modes K] [--backend B]
//                    [--method M] -o DB.h5
//       samples the box, one modal solve per sample (under `mpirun -n N` the samples are shared
//       round-robin between the ranks; only rank 0 prints and writes), the leave-one-out estimate,
//       and the time split (modal solves vs everything else);
//   mastrom rom build CONFIG … --param KEY=LO:HI … --adaptive --tolerance T [--max-samples N] -o
//   DB.h5
//       a scattered database grown greedily where the rbf estimate is largest, one round of one
//       sample per rank at a time, the estimate printed after each round
//       (rom/offline/adaptive_build.hpp);
//   mastrom rom eval DB [--set k=v]… [--method tracked|manifold|affine|cubic|rbf] [--extrapolate]
//                       [-o FILE.h5]
//       one deployment from the ROM: --set may move the point inside the database's box (its
//       parameter keys) and choose any drive law and timing (free keys); the output step is
//       simulation.time_step × output.every. Prints the metrics like `simulate` and writes the
//       docs/user_guide.md §5 layout with source "rom".
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "cli/cli_common.hpp"
#include "cli/cmd_rom_eval.hpp"
#include "cli/interrupt.hpp"
#include "cli/output_step_note.hpp"
#include "cli/progress.hpp"
#include "cli/resource_estimates.hpp"
#include "cli/rom_eval_output.hpp"
#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "common/text_parsing.hpp"
#include "fullorder/deployment_result.hpp"
#include "fullorder/interface_stress_io.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/mast_mass.hpp"
#include "fullorder/results_io.hpp"
#include "modes/slepc_session.hpp"
#include "rom/database/database_io.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/interpolation/point_error_estimate.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/offline/adaptive_build.hpp"
#include "rom/offline/database_build.hpp"
#include "rom/offline/modulus_reduction.hpp"
#include "rom/studies/default_output_step.hpp"
#include "rom/studies/rom_evaluation.hpp"

namespace mastrom::cli {
namespace {

struct BuildArguments {
  ConfigArguments config;
  std::vector<std::string> params;
  int modes = 0;
  std::string backend;
  std::string method;
  std::string output;
  bool quiet = false;
  bool no_stresses = false;
  bool compare_methods = false;
  bool adaptive = false;
  double tolerance = 0.0;
  int max_samples = 100;
  bool tolerance_given = false, max_samples_given = false;
  bool allow_large = false;
};

double percent(double part, double whole) { return whole > 0 ? 100.0 * part / whole : 0.0; }

/// One line on how well the samples' modes tracked the reference's: the smallest MAC of a matched
/// pair over all modes and over the drive-excited ones, with which reference mode it was. A MAC
/// near 0 means the sample has no mode of that shape among its stored ones (modes enter and leave
/// the window across the box: thin shells bring shell modes down); that matters only for the
/// drive-excited modes.
void printTrackingReport(const rom::BuildReport& report, const rom::RomDatabase& db) {
  const rom::ModalModel& ref = db.samples[static_cast<std::size_t>(db.reference_sample)].modal;
  const auto describe = [&ref](double mac, int sample, int mode) {
    char text[160];
    if (mode < 0) {
      std::snprintf(text, sizeof text, "%.4f", mac);
    } else {
      std::snprintf(text, sizeof text, "%.4f (sample %d, reference mode %d at %.1f Hz%s)", mac,
                    sample, mode + 1, ref.omega_rad_s[mode] / (2.0 * M_PI),
                    mac < 0.5 ? ": no mode of that shape among the sample's" : "");
    }
    return std::string(text);
  };
  std::printf("  mode tracking (MAC of matched pairs against the reference): smallest %s\n",
              describe(report.min_mac, report.min_mac_sample, report.min_mac_mode).c_str());
  std::printf(
      "  drive-excited modes (effective-mass fraction >= %.2g): smallest %s%s\n",
      rom::kExcitedMassFraction,
      describe(report.min_coupled_mac, report.min_coupled_mac_sample, report.min_coupled_mac_mode)
          .c_str(),
      report.min_coupled_mac < 0.8
          ? "  -- weak: a drive-excited mode changes shape or leaves the stored modes "
            "inside the box; narrow the box, add modes (--modes) or use --method manifold"
          : "");
}

void runBuild(const BuildArguments& args) {
  Config config = loadConfig(args.config);
  std::optional<EigenBackendKind> backend;
  if (!args.backend.empty()) {
    backend = parseEigenBackendKind(args.backend);
    MASTROM_REQUIRE(backend.has_value(), InputError, "--backend = '", args.backend,
                    "' is not a backend (allowed: ", allowedEigenBackendNames(), ")");
  }
  MASTROM_REQUIRE(args.modes >= 0, InputError, "--modes = ", args.modes,
                  " is out of range (>= 1, or 0 for modes.count of the configuration)");
  MASTROM_REQUIRE(args.adaptive || !args.tolerance_given, InputError,
                  "--tolerance = ", shortestText(args.tolerance),
                  " is only for an --adaptive build");
  MASTROM_REQUIRE(args.adaptive || !args.max_samples_given, InputError,
                  "--max-samples = ", args.max_samples, " is only for an --adaptive build");
  MASTROM_REQUIRE(!args.adaptive || args.tolerance_given, InputError,
                  "--adaptive needs --tolerance T (the target NRMSE, 0 < T < 1, e.g. 0.03)");
  MASTROM_REQUIRE(!args.adaptive || !args.compare_methods, InputError,
                  "--compare-methods is for a grid build (an --adaptive database has one method, "
                  "rbf)");
  rom::AdaptiveBuildOptions adaptive;
  adaptive.tolerance = args.tolerance;
  adaptive.max_samples = args.max_samples;
  std::vector<rom::ParameterAxis> axes;
  for (const std::string& p : args.params)
    axes.push_back(rom::parseParameterAxis(
        p, config, args.adaptive ? rom::AxisForm::Range : rom::AxisForm::Grid));
  if (args.adaptive) {  // refused before the header is printed, over the axes actually sampled
    const bool exact_modulus = rom::planModulusReduction(config, axes).applies();
    rom::checkAdaptiveBuildOptions(adaptive,
                                   static_cast<int>(axes.size()) - (exact_modulus ? 1 : 0));
  }
  h5::checkWritable(args.output);  // before any work
  {
    double grid_samples = 1.0;
    std::vector<ResourceDriver> grid;
    for (std::size_t a = 0; a < axes.size(); ++a) {
      grid_samples *= static_cast<double>(axes[a].values.size());
      grid.emplace_back("--param", args.params[a]);
    }
    if (args.adaptive) {
      grid_samples = args.max_samples;
      grid = {{"--max-samples", std::to_string(args.max_samples)}};
    }
    Config sized = config;
    if (backend) sized.modes.backend = *backend;
    requireResources(romBuildEstimate(sized, grid_samples,
                                      args.modes > 0 ? args.modes : config.modes.count, grid),
                     args.output, args.allow_large);
  }

  const modes::SlepcSession session;  // MPI + PETSc + SLEPc for the life of the command
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const bool root = rank == 0;

  long samples = 1;
  for (const rom::ParameterAxis& a : axes) samples *= static_cast<long>(a.values.size());
  const int modes = args.modes > 0 ? args.modes : config.modes.count;
  if (root) {
    if (args.adaptive) {
      std::printf(
          "mastrom rom build --adaptive: up to %d samples x %d modes until the NRMSE measured "
          "at held-out probes <= %.3g %%, %s backend, %d rank%s (rounds of %d samples, about "
          "N/%d beyond %d)\n",
          args.max_samples, modes, 100.0 * args.tolerance,
          toString(backend.value_or(config.modes.backend)).c_str(), ranks, ranks == 1 ? "" : "s",
          rom::kAdaptiveRoundSize, rom::kAdaptiveRoundGrowth,
          3 * rom::kAdaptiveRoundGrowth / 2);
    } else {
      std::printf("mastrom rom build: %ld samples x %d modes, %s backend, %d rank%s\n", samples,
                  modes, toString(backend.value_or(config.modes.backend)).c_str(), ranks,
                  ranks == 1 ? "" : "s");
    }
    for (const rom::ParameterAxis& a : axes) {
      if (args.adaptive) {
        std::printf("  %-28s range [%.6g, %.6g] %s\n", a.key.c_str(), a.values.front(),
                    a.values.back(), rom::configKeyUnits(a.key).c_str());
      } else {
        std::printf("  %-28s %zu values in [%.6g, %.6g] %s\n", a.key.c_str(), a.values.size(),
                    a.values.front(), a.values.back(), rom::configKeyUnits(a.key).c_str());
      }
    }
    if (args.adaptive) {  // the grid build samples E as given
      const rom::ModulusReduction plan = rom::planModulusReduction(config, axes);
      if (!plan.reason.empty()) std::printf("  %s\n", plan.reason.c_str());
    }
    std::fflush(stdout);
  }

  ProgressReporter reporter("rom build", 2.0, root && !args.quiet, ProgressUnit::kItems);
  rom::DatabaseBuildOptions options;
  options.stresses = !args.no_stresses;
  options.compare_methods = args.compare_methods;
  options.axes = axes;
  options.modes = args.modes;
  options.backend = backend;
  if (!args.method.empty())
    options.method =
        rom::interpolationMethodOr(args.method, rom::InterpolationMethod::Manifold, "--method");
  options.communicator = MPI_COMM_WORLD;
  options.progress = [&reporter, ranks](int done, int total) {
    char detail[96];
    std::snprintf(detail, sizeof detail, "sample %d / %d on rank 0 (of %d rank%s)", done, total,
                  ranks, ranks == 1 ? "" : "s");
    reporter.update(done, total, detail);
  };
  rom::BuildReport report;
  const auto on_round = [&args](const rom::AdaptiveRound& r) {
    std::printf(
        "  round %d: %d samples, NRMSE of the relative end angular acceleration %.3g %% at the "
        "worst of %d held-out probes (omega_1 %.3g %%); leave-one-out estimate %.3g %% (largest "
        "left out %.3g %%) picks the next; estimate %.3f s (%d left-out deployments, %d carried "
        "over), wall %.1f s\n",
        r.round, r.samples, 100.0 * r.response_estimate, r.probes, 100.0 * r.frequency_estimate,
        100.0 * r.inferred_response_estimate, 100.0 * r.largest_left_out, r.estimate_s,
        r.deployed, r.reused, r.wall_s);
    if (r.fresh_probes > 0)
      std::printf("  %d fresh probes (never used to stop) measured: NRMSE %.3g %% at the worst "
                  "(omega_1 %.3g %%)%s\n",
                  r.fresh_probes, 100.0 * r.fresh_response_estimate,
                  100.0 * r.fresh_frequency_estimate,
                  r.fresh_joined ? ": above the tolerance, they join the stopping probes"
                  : r.response_estimate <= args.tolerance &&
                          r.fresh_response_estimate <= args.tolerance
                      ? ": done"
                      : ": the budget is spent");
    std::fflush(stdout);
  };
  const rom::RomDatabase db =
      args.adaptive ? rom::buildAdaptiveDatabase(config, options, adaptive, &report, on_round)
                    : rom::buildDatabase(config, options, &report);
  if (!root) return;

  const auto write_start = std::chrono::steady_clock::now();
  rom::writeDatabase(args.output, db, &report);
  const double write_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - write_start).count();

  const rom::BuildTiming& t = report.timing;
  const double modal = t.assembly_s + t.eigensolve_s;
  const double other =
      t.extraction_s + t.communication_s + t.leave_one_out_s + t.affine_s + write_s;
  const double total = modal + t.probe_solves_s + other;
  // The probes' modal solves are measurements at new points, shown apart from the samples' solves
  // and from the estimate's own work (its deployments), so that each share is visible.
  char probe_part[160] = "";
  if (t.probes > 0)
    std::snprintf(probe_part, sizeof probe_part,
                  "held-out probes' modal solves %.3f s = %.1f %% (%d probes), ", t.probe_solves_s,
                  percent(t.probe_solves_s, total), t.probes);
  std::printf(
      "  time split (seconds summed over ranks): samples' modal solves %.3f s = %.1f %% "
      "(eigen-solver %.3f s, assembly + statics + linearisation %.3f s; %d solves), %s"
      "everything else %.3f s = %.1f %% (extraction + tracking %.3f s, gather %.3f s, "
      "error estimate (leave-one-out%s deployments) %.3f s, affine terms %.3f s, write %.3f s)\n",
      modal, percent(modal, total), t.eigensolve_s, t.assembly_s, t.solves, probe_part,
      other, percent(other, total), t.extraction_s, t.communication_s,
      t.probes > 0 ? " and probe" : "", t.leave_one_out_s, t.affine_s, write_s);
  std::printf("  wall time %.2f s on %d rank%s\n", t.wall_s + write_s, t.ranks,
              t.ranks == 1 ? "" : "s");
  printTrackingReport(report, db);
  for (const rom::LeaveOneOutResult& l : report.leave_one_out) {
    if (l.estimated == 0) {
      std::printf("  leave-one-out (%s): no interior sample (use N >= 3 on an axis)\n",
                  rom::toString(l.method).c_str());
      continue;
    }
    if (l.method == rom::InterpolationMethod::Affine) {
      std::printf(
          "  exact affine terms (h, E, rho at fixed R): error at the %d samples (basis "
          "truncation only) omega_1 %.3g %%, NRMSE of the relative end angular acceleration "
          "%.3g %%\n",
          l.estimated, 100.0 * l.frequency_estimate, 100.0 * l.response_estimate);
      continue;
    }
    if (l.method == rom::InterpolationMethod::Rbf && db.estimate_from_probes && !db.isGrid()) {
      std::printf(
          "  error measured at %d held-out probes (%s, Halton points that are never samples; "
          "the stopping ones and the fresh set that confirmed the stop): omega_1 %.3g %%, NRMSE "
          "of the relative end angular acceleration %.3g %% at the worst\n",
          t.probes, rom::toString(l.method).c_str(), 100.0 * l.frequency_estimate,
          100.0 * l.response_estimate);
      if (args.adaptive && l.response_estimate > args.tolerance)
        std::printf("  note: that is above --tolerance %.3g %%: the budget of %d samples ended the "
                    "build; raise --max-samples for a database within it\n",
                    100.0 * args.tolerance, args.max_samples);
      continue;
    }
    if (l.method == rom::InterpolationMethod::Cubic && db.estimate_from_probes) {
      std::printf(
          "  error measured at %d held-out cell centres (%s, the grid is too coarse for its "
          "leave-one-out): omega_1 %.3g %%, NRMSE of the relative end angular acceleration "
          "%.3g %% at the worst\n",
          t.probes, rom::toString(l.method).c_str(), 100.0 * l.frequency_estimate,
          100.0 * l.response_estimate);
      continue;
    }
    std::printf(
        "  leave-one-out error estimate (%s, %d of %zu samples): omega_1 %.3g %%, NRMSE of the "
        "relative end angular acceleration %.3g %% between samples (%.3g %% left out)\n",
        rom::toString(l.method).c_str(), l.estimated, db.samples.size(),
        100.0 * l.frequency_estimate, 100.0 * l.response_estimate, 100.0 * l.max_response_error);
  }
  std::printf("wrote %s (%s, method %s, checksum %s)\n", args.output.c_str(), rom::kDatabaseFormat,
              rom::toString(db.default_method).c_str(), rom::databaseChecksum(db).c_str());
  std::fflush(stdout);
}

}  // namespace

void registerRomCommand(CLI::App& app) {
  CLI::App* rom = app.add_subcommand(
      "rom", "Parameter-interpolated modal reduced-order model: build a database, evaluate it");
  rom->require_subcommand(1);

  CLI::App* build = rom->add_subcommand(
      "build", "Sample a parameter box, one modal solve per sample, and write the ROM database");
  auto b = std::make_shared<BuildArguments>();
  addConfigArguments(*build, b->config);
  build
      ->add_option("--param", b->params,
                   "One database axis: a floating-point config key and N >= 2 evenly spaced "
                   "values from LO to HI, e.g. --param interface.thickness=0.001:0.002:3; with "
                   "--adaptive the range KEY=LO:HI only (repeatable)")
      ->type_name("KEY=LO:HI[:N]")
      ->required()
      ->allow_extra_args(false);
  build->add_option("--modes", b->modes, "Modes per sample (default: [modes] count)")
      ->check(numberInRange(NumberKind::kWhole, 1));
  build
      ->add_option("--backend", b->backend,
                   "Eigen-solver backend, overrides [modes] backend: slepc, arpack or dense")
      ->type_name("NAME");
  build
      ->add_option(
          "--method", b->method,
          "The database's default interpolation: " + rom::allowedInterpolationMethodNames() +
              " (default: affine where its exact terms apply, else cubic where the drive-excited "
                "modes track cleanly (MAC >= 0.9), else manifold)")
      ->type_name("NAME");
  build->add_option("-o,--output", b->output, "Database file (HDF5)")->required();
  build->add_flag(
      "--no-stresses", b->no_stresses,
      "A vibration-only database: no interface stress modes (each sample stores 6 x "
      "recovery points x (modes + 5) values for them, 0.5 MB for Scheme 3 at 20 modes)");
  build->add_flag("--compare-methods", b->compare_methods,
                  "Grid: also estimate the error of every other interpolation method (tracked, "
                  "manifold, cubic, rbf) for the report, not only the default's (on a 3^5 grid "
                  "that more than doubles the build)");
  build->add_flag("--adaptive", b->adaptive,
                  "Scattered samples chosen greedily where the rbf error estimate is largest "
                  "(from the box centre and 2p Halton points; rounds of 2 samples, about N/16 "
                  "beyond 24, the same on any number of ranks) until the NRMSE measured at "
                  "held-out probes, confirmed on a fresh set, is <= --tolerance, or --max-samples; "
                  "--param KEY=LO:HI");
  CLI::Option* tolerance =
      build
          ->add_option(
              "--tolerance", b->tolerance,
              "--adaptive: target NRMSE of the relative end angular acceleration at the worst "
              "held-out probe (relative, 0 < T < 1, e.g. 0.03)")
          ->type_name("T");
  CLI::Option* max_samples =
      build
          ->add_option("--max-samples", b->max_samples,
                       "--adaptive: sample budget (default 100; at least 2p + 1 for p parameters)")
          ->type_name("N");
  build->add_flag("-q,--quiet", b->quiet, "No progress lines on stderr");
  addAllowLargeFlag(*build, b->allow_large);
  build->footer("MPI: mpirun -n N mastrom rom build ... shares the samples between the ranks.");
  build->callback([b, tolerance, max_samples]() {
    b->tolerance_given = tolerance->count() > 0;
    b->max_samples_given = max_samples->count() > 0;
    runBuild(*b);
  });

  CLI::App* eval = rom->add_subcommand("eval", "One deployment from the ROM database");
  auto e = std::make_shared<EvalArguments>();
  eval->add_option("DB", e->database, "ROM database (from mastrom rom build)")->required();
  eval->add_option("--set", e->overrides,
                   "The point and the deployment: a database parameter (default: the base "
                   "config's value) or a free key (drive.*, simulation.end_time, "
                   "simulation.time_step, output.every), e.g. --set drive.law=cubic (repeatable)")
      ->type_name("SECTION.KEY=VALUE")
      ->allow_extra_args(false);
  eval->add_option(
          "--method", e->method,
          "Interpolation: " + rom::allowedInterpolationMethodNames() + " (default: the database's)")
      ->type_name("NAME");
  eval->add_flag("--extrapolate", e->extrapolate,
                 "Allow a point outside the sampled box (linear extrapolation)");
  CLI::Option* no_stresses = eval->add_flag(
      "--no-stresses", e->no_stresses,
      "Skip the interface stresses (by default their peaks, where and when, and the margins)");
  eval->add_flag("--stress-history", e->stress_history,
                 "Also the largest von Mises of every interface at every output sample (written "
                 "to the result file as /interfaces/K/max_von_mises)")
      ->excludes(no_stresses);
  eval->add_option("-o,--output", e->output,
                   "Result file (HDF5, layout of README.md \"Outputs and units\", source \"rom\"); "
                   "default: none");
  addFrequenciesOption(*eval, e->frequencies, "printed with the design's mass");
  eval->add_flag("-q,--quiet", e->quiet, "Accepted for symmetry; eval prints no progress");
  addAllowLargeFlag(*eval, e->allow_large);
  eval->callback([e]() { runEval(*e); });
}

}  // namespace mastrom::cli
