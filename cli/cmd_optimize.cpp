// `mastrom optimize DB --minimize|--maximize METRIC [--subject-to "METRIC OP VALUE"]…
//  [--set k=v]… [--bound KEY=LO:HI]… [--rounds N] [-o FILE.h5|FILE.csv]`: the design of the
// database's box that is best on the ROM, every constraint taken with the ROM's estimated error,
// confirmed by the nonlinear full order round by round (rom/studies/optimization.hpp). Prints the
// table of every round, writes the record, exits 4 when the full order does not confirm a design.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "cli/cli_common.hpp"
#include "cli/progress.hpp"
#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "modes/slepc_session.hpp"
#include "rom/database/database_io.hpp"
#include "rom/studies/optimization.hpp"

namespace mastrom::cli {
namespace {

struct OptimizeArguments {
  std::string database;
  std::string minimize, maximize;
  std::vector<std::string> subject_to;
  std::vector<std::string> overrides;
  std::vector<std::string> bounds;
  int rounds = 3;
  int starts = 4;
  int candidates = 0;
  std::string output = "optimize.h5";
  bool quiet = false;
};

bool isCsv(const std::string& path) {
  return path.size() >= 4 && path.compare(path.size() - 4, 4, ".csv") == 0;
}

void checkOutput(const std::string& path) {
  const auto ends = [&path](const std::string& s) {
    return path.size() >= s.size() && path.compare(path.size() - s.size(), s.size(), s) == 0;
  };
  MASTROM_REQUIRE(ends(".csv") || ends(".h5") || ends(".hdf5"), InputError, "-o ", path,
                  ": the record of the rounds is written as .csv or .h5 (.hdf5)");
  h5::checkWritable(path);
}

/// printf's width for `text` to take `columns` columns on a terminal: its bytes minus the
/// continuation bytes of multi-byte UTF-8 characters (≤, ≥) count once.
int paddedWidth(const char* text, int columns) {
  int extra = 0;
  for (const char* c = text; *c; ++c)
    if ((static_cast<unsigned char>(*c) & 0xC0) == 0x80) ++extra;
  return columns + extra;
}

void printRound(const rom::OptimizationResult& result, const rom::OptimizeOptions& options,
                std::size_t index) {
  const rom::OptimizationRound& r = result.rounds[index];
  std::printf("round %zu: %d ROM designs (%d COBYLA runs, %d ended feasible), %.3f s\n", index + 1,
              r.evaluations, r.runs, r.feasible_runs, r.rom_wall_s);
  std::printf("  design:");
  for (std::size_t a = 0; a < r.point.size(); ++a)
    std::printf("%s %s = %.6g %s", a ? "," : "", result.parameter_names[a].c_str(), r.point[a],
                result.parameter_units[a].c_str());
  std::printf("\n  ROM's estimated error there (upper): omega_1 %.3g %%, response NRMSE %.3g %%\n",
              100.0 * r.frequency_estimate, 100.0 * r.response_estimate);
  std::printf("  %-36s %-8s %12s %12s %12s %12s %12s %12s %12s %4s\n", "metric", "unit", "bound",
              "ROM", "ROM est.err", "margin", "full order", "FO est.err", "FO - ROM", "met");
  for (std::size_t m = 0; m < result.metrics.size(); ++m) {
    std::string label = result.metrics[m];
    char bound[32] = "-";
    if (m == 0) {
      label += options.sense == rom::OptimizationSense::Minimize ? " (min)" : " (max)";
    } else {
      const rom::MetricConstraint& c = options.constraints[m - 1];
      // The operator as the user wrote it (<=, ≤, <, …): the bound of a round is that constraint.
      std::snprintf(bound, sizeof bound, "%s %.5g", c.op.c_str(), r.bounds[m - 1]);
    }
    char error[32] = "n/a";
    if (std::isfinite(r.full_error[m])) std::snprintf(error, sizeof error, "%.4g", r.full_error[m]);
    // The database's estimate carried to the metric: the margin without its factor.
    std::printf("  %-36s %-8s %*s %12.6g %12.4g %12.4g %12.6g %12s %+12.4g %4s\n", label.c_str(),
                result.metric_units[m].c_str(), paddedWidth(bound, 12), bound, r.rom[m],
                r.margin[m] / rom::kMarginFactor, r.margin[m], r.full[m], error,
                r.full[m] - r.rom[m], m == 0 ? "" : (r.met[m - 1] ? "yes" : "NO"));
  }
  std::printf(
      "  full order %.2f s (its error estimate, a second run at 8 x simulation.tolerance: "
      "%.2f s; modal solves %.2f s)\n",
      r.full_wall_s, r.full_estimate_wall_s, r.full_modes_wall_s);
  if (!r.full_note.empty()) std::printf("  full order: %s\n", r.full_note.c_str());
}

void runOptimize(const OptimizeArguments& args) {
  MASTROM_REQUIRE(args.minimize.empty() != args.maximize.empty(), InputError,
                  "optimize: give exactly one of --minimize METRIC and --maximize METRIC");
  checkOutput(args.output);
  const modes::SlepcSession session;  // MPI and PETSc for the solvers the full order may use
  const rom::RomDatabase db = rom::readDatabase(args.database);
  rom::OptimizeOptions options;
  options.objective = args.minimize.empty() ? args.maximize : args.minimize;
  options.sense =
      args.minimize.empty() ? rom::OptimizationSense::Maximize : rom::OptimizationSense::Minimize;
  for (const std::string& s : args.subject_to)
    options.constraints.push_back(rom::parseMetricConstraint(s));
  for (const std::string& b : args.bounds)
    options.bounds.push_back(rom::parseParameterBound(b, db));
  options.overrides = args.overrides;
  options.rounds = args.rounds;
  options.search.starts = args.starts;
  options.search.candidates = args.candidates;
  options.log = [&args](const std::string& line) {
    if (!args.quiet) std::fprintf(stderr, "optimize: %s\n", line.c_str());
  };
  ProgressReporter reporter("full order", 2.0, !args.quiet, ProgressUnit::kSimulatedSeconds);
  options.full_order_progress = [&reporter](double t, double end,
                                            const fullorder::DeploymentStatistics&) {
    reporter.update(t, end);
  };

  std::printf(
      "mastrom optimize: %s %s over the box of %s (method %s), %zu constraint%s, at most "
      "%d round%s\n",
      args.minimize.empty() ? "maximize" : "minimize", options.objective.c_str(),
      args.database.c_str(), rom::toString(db.default_method).c_str(), options.constraints.size(),
      options.constraints.size() == 1 ? "" : "s", options.rounds, options.rounds == 1 ? "" : "s");
  std::fflush(stdout);
  const rom::OptimizationResult result = rom::runOptimization(db, options);
  std::printf("  variables:");
  for (std::size_t k = 0; k < result.variables.size(); ++k) {
    const auto a = static_cast<std::size_t>(result.variables[k]);
    std::printf("%s %s in [%.6g, %.6g] %s", k ? "," : "", result.parameter_names[a].c_str(),
                result.lower[k], result.upper[k], result.parameter_units[a].c_str());
  }
  std::printf(
      "\n  a constraint counts as met on the ROM only with its margin: %g x the database's "
      "upper estimate of the ROM's error at the design (%s), carried to the metric "
      "(docs/theory.md §4.5)\n",
      rom::kMarginFactor,
      result.pointwise_estimate ? "its held-out probes, (4.13) / (4.14)"
                                : "its box-wide estimate: no held-out probes");
  for (std::size_t i = 0; i < result.rounds.size(); ++i) printRound(result, options, i);
  std::printf("%s: %s (%zu round%s, %.1f s)\n", result.confirmed ? "confirmed" : "NOT confirmed",
              result.stop_reason.c_str(), result.rounds.size(),
              result.rounds.size() == 1 ? "" : "s", result.wall_s);
  if (isCsv(args.output)) {
    rom::writeOptimizationCsv(args.output, result);
  } else {
    rom::writeOptimizationH5(args.output, result, options);
  }
  std::printf("wrote %s\n", args.output.c_str());
  std::fflush(stdout);
  if (!result.confirmed) {
    std::fprintf(stderr, "mastrom: error: optimize: not confirmed by the full order: %s\n",
                 result.stop_reason.c_str());
    std::exit(4);
  }
}

}  // namespace

void registerOptimizeCommand(CLI::App& app) {
  CLI::App* command = app.add_subcommand("optimize",
                                         "Best design of the database's box on the ROM under "
                                         "constraints, confirmed by the full order");
  auto args = std::make_shared<OptimizeArguments>();
  command->add_option("DB", args->database, "ROM database (mastrom rom build)")->required();
  auto* minimize = command->add_option("--minimize", args->minimize,
                                       "Metric to minimise (a column of mastrom screen)");
  auto* maximize = command->add_option("--maximize", args->maximize, "Metric to maximise");
  minimize->excludes(maximize);
  command
      ->add_option("--subject-to", args->subject_to,
                   "Constraint METRIC OP VALUE, OP <= (≤) or >= (≥) (SI units), e.g. --subject-to "
                   "\"peak_rel_end_angular_acceleration <= 5\" (repeatable: all must hold)")
      ->type_name("CONSTRAINT")
      ->allow_extra_args(false);
  command
      ->add_option("--set", args->overrides,
                   "Free key (drive.*, simulation.*, material.yield_strength) or a database "
                   "parameter held fixed (repeatable)")
      ->type_name("SECTION.KEY=VALUE")
      ->allow_extra_args(false);
  command
      ->add_option("--bound", args->bounds,
                   "Narrow a parameter's range inside the database's box, KEY=LO:HI (repeatable)")
      ->type_name("KEY=LO:HI")
      ->allow_extra_args(false);
  command
      ->add_option("--rounds", args->rounds,
                   "Optimise-and-confirm rounds at most (default 3): after a full-order violation "
                   "the constraint is tightened by the measured difference")
      ->check(numberInRange(NumberKind::kWhole, 1, 20));
  command
      ->add_option("--starts", args->starts,
                   "COBYLA runs per round, from the best Halton designs (default 4)")
      ->check(numberInRange(NumberKind::kWhole, 1, 64));
  command
      ->add_option("--candidates", args->candidates,
                   "Halton designs evaluated before the runs (default 16 per parameter)")
      ->check(numberInRange(NumberKind::kWhole, 1, 100000));
  command->add_option("-o,--output", args->output,
                      "Record of the rounds: .h5 (/optimize layout) or .csv (default optimize.h5)");
  command->add_flag("-q,--quiet", args->quiet, "No progress lines on stderr");
  command->callback([args]() { runOptimize(*args); });
}

}  // namespace mastrom::cli
