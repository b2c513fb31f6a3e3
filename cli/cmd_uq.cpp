// `mastrom uq DB CONFIG [--set k=v]… [--limit "METRIC OP VALUE"]… [--samples N] [--sampling
// sobol|mc] [--seed S] [--no-sensitivity] [--target-width W] [--max-evaluations M]
// [--confidence C] [--tail-runs|--no-tail-runs] [-o FILE.h5] [--csv FILE.csv]` (docs/user_guide.md
// "mastrom uq"): uncertainty and sensitivity of every screen metric through the ROM
// (rom/studies/uncertainty_study.hpp), then the full order at the tails of each limited metric
// (rom/studies/uncertainty_tails.hpp). Under `mpirun -n N` the ROM samples are shared between the
// ranks (the results do not depend on N), and so are the full-order runs at the tails (one run per
// rank at a time); rank 0 prints and writes.
#include <cstdio>
#include <memory>
#include <optional>

#include "cli/cli_common.hpp"
#include "cli/progress.hpp"
#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "modes/slepc_session.hpp"
#include "rom/database/database_io.hpp"
#include "rom/studies/uncertainty_output.hpp"
#include "rom/studies/uncertainty_study.hpp"
#include "rom/studies/uncertainty_tails.hpp"

namespace mastrom::cli {
namespace {

struct UqArguments {
  std::string database;
  ConfigArguments config;
  std::vector<std::string> limits;
  long samples = 4096;
  std::string sampling = "sobol";
  unsigned long seed = 1;
  bool no_sensitivity = false;
  double target_width = 0.0;
  long max_evaluations = 1000000;
  double confidence = 0.95;
  bool no_tail_runs = false;
  std::string method;
  bool extrapolate = false;
  bool no_stresses = false;
  std::optional<double> step_s;
  std::string output = "uq.h5";
  std::string csv;
  bool quiet = false;
};

std::string interval(const stats::Interval& i) {
  char text[96];
  std::snprintf(text, sizeof text, "%-11.5g [%.5g, %.5g]", i.estimate, i.lower, i.upper);
  return text;
}

void printSummary(const rom::UqResult& r) {
  std::printf(
      "metrics (%zu samples of the inputs' laws; %.0f %% intervals from the sample size):\n",
      r.statistic_rows.size(), 100.0 * r.confidence);
  for (std::size_t m = 0; m < r.metric_names.size(); ++m) {
    const stats::SampleSummary& s = r.summaries[m];
    if (s.count == 0) continue;
    std::printf("  %-38s mean %s  std %s  [%s]\n", r.metric_names[m].c_str(),
                interval(s.mean).c_str(), interval(s.std_dev).c_str(), r.metric_units[m].c_str());
    std::printf("  %-38s q01 %.5g  q05 %.5g  q50 %.5g  q95 %.5g  q99 %.5g\n", "",
                s.quantiles[0].estimate, s.quantiles[1].estimate, s.quantiles[2].estimate,
                s.quantiles[3].estimate, s.quantiles[4].estimate);
  }
  for (const rom::LimitProbability& p : r.limits) {
    std::printf("P(%s) = %s", p.limit.text.c_str(), interval(p.probability).c_str());
    if (p.has_error_estimate)
      std::printf("; conservative (ROM error estimate against the limit) %s\n",
                  interval(p.conservative).c_str());
    else
      std::printf("; no ROM error estimate for %s: the conservative value is the same\n",
                  p.limit.column.c_str());
  }
  if (!r.has_sensitivity) return;
  std::printf("Sobol indices, first-order and total [%.0f %% bootstrap intervals]:\n",
              100.0 * r.confidence);
  for (std::size_t m = 0; m < r.metric_names.size(); ++m) {
    const stats::SobolIndices& s = r.sobol[m];
    if (s.first.empty() || !(s.variance > 0.0)) continue;
    std::printf("  %s\n", r.metric_names[m].c_str());
    for (std::size_t i = 0; i < s.first.size(); ++i)
      std::printf("    %-32s S %s  ST %s\n", r.input_names[i].c_str(), interval(s.first[i]).c_str(),
                  interval(s.total[i]).c_str());
  }
}

void printTails(const rom::UqResult& r, const std::vector<rom::TailCheck>& tails) {
  if (tails.empty()) return;
  std::printf(
      "full order at the tails (ROM +- its error bound | full order +- its own estimate):\n");
  for (const rom::TailCheck& c : tails) {
    std::printf(
        "  %-34s %-8s sample %-7ld ROM %.5g +- %.3g | full %.5g +- %.3g | ROM - full %+.3g\n",
        r.limits[c.limit].limit.text.c_str(), c.label.c_str(), c.row, c.rom_value,
        c.rom_error_bound, c.full_value, c.full_error_estimate, c.rom_value - c.full_value);
  }
}

void run(const UqArguments& args) {
  const rom::RomDatabase db = rom::readDatabase(args.database);
  const Config config = loadConfig(args.config);
  rom::UqOptions options;
  const std::optional<stats::SamplingKind> sampling = stats::parseSamplingKind(args.sampling);
  MASTROM_REQUIRE(sampling.has_value(), InputError, "--sampling ", args.sampling,
                  " is not a sampling: allowed: sobol, mc");
  options.sampling = *sampling;
  options.samples = args.samples;
  options.seed = args.seed;
  options.sensitivity = !args.no_sensitivity;
  options.target_width = args.target_width;
  options.max_evaluations = args.max_evaluations;
  options.confidence = args.confidence;
  for (const std::string& l : args.limits) options.limits.push_back(rom::parseColumnCondition(l));
  options.method = rom::interpolationMethodOr(args.method, db.default_method, "--method");
  options.box = args.extrapolate ? rom::BoxPolicy::Extrapolate : rom::BoxPolicy::Refuse;
  options.stresses = !args.no_stresses;
  if (args.step_s) {
    rom::checkScreenStep(*args.step_s, {}, "--step");
    options.step_s = *args.step_s;
  }
  h5::checkWritable(args.output);
  if (!args.csv.empty()) h5::checkWritable(args.csv);
  rom::checkUqConfig(db, config);

  const modes::SlepcSession session;  // MPI for the life of the command
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  const bool root = rank == 0;
  options.communicator = MPI_COMM_WORLD;
  ProgressReporter reporter("uq", 2.0, root && !args.quiet, ProgressUnit::kItems);
  options.progress = [&reporter](const std::string& phase, long done, long total) {
    reporter.update(static_cast<double>(done), static_cast<double>(total), "rank 0's " + phase);
  };
  const rom::UqResult result = rom::runUncertaintyStudy(db, config, options);
  std::vector<rom::TailCheck> tails;
  if (root) {
    std::printf(
        "mastrom uq: %ld ROM evaluations (%ld base samples, %s, seed %lu) of %zu inputs x "
        "%zu metrics from %s on %d rank%s: %.3f s\n",
        result.rows, result.base_samples, stats::toString(result.sampling).c_str(), result.seed,
        result.input_names.size(), result.metric_names.size(), args.database.c_str(), result.ranks,
        result.ranks == 1 ? "" : "s", result.wall_s);
    printSummary(result);
    tails = rom::tailChecks(result);
  }
  if (!args.no_tail_runs) {
    // Every rank takes its share of the tail runs (one run per rank at a time, one thread each).
    ProgressReporter tail_progress("uq full order", 0.0, root && !args.quiet, ProgressUnit::kItems);
    rom::runTailChecks(
        db, config, &result, &tails,
        [&tail_progress](long done, long total) {
          tail_progress.update(static_cast<double>(done), static_cast<double>(total),
                               "rank 0's full-order runs at the tails");
        },
        MPI_COMM_WORLD);
    if (!root) return;
    if (!tails.empty()) printTails(result, tails);
  } else {
    if (!root) return;
    if (!tails.empty()) std::printf("full order at the tails: skipped (--no-tail-runs)\n");
    tails.clear();
  }
  rom::writeUqH5(args.output, result, tails);
  std::printf("wrote %s\n", args.output.c_str());
  if (!args.csv.empty()) {
    rom::writeUqCsv(args.csv, result, tails);
    std::printf("wrote %s\n", args.csv.c_str());
  }
  std::fflush(stdout);
}

}  // namespace

void registerUqCommand(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "uq",
      "Uncertainty and sensitivity of every metric from a ROM database: moments, quantiles, "
      "exceedance probabilities, Sobol indices, and the full order at the tails");
  auto args = std::make_shared<UqArguments>();
  command->add_option("DB", args->database, "ROM database (from mastrom rom build)")->required();
  addConfigArguments(*command, args->config);
  command
      ->add_option("--limit", args->limits,
                   "An exceedance event METRIC OP VALUE (OP: < <= > >=, SI units), e.g. --limit "
                   "\"min_margin_of_safety < 0\" (repeatable)")
      ->type_name("CONDITION")
      ->allow_extra_args(false);
  command
      ->add_option("--samples", args->samples,
                   "Base samples N (default 4096; with Sobol "
                   "indices N (k + 2) ROM evaluations)")
      ->check(numberInRange(NumberKind::kWhole, 2, 1e9));
  command->add_option("--sampling", args->sampling,
                      "sobol (randomised Sobol sequence, default) or mc (plain Monte Carlo)");
  command->add_option("--seed", args->seed, "Seed of the random shift / generator (default 1)")
      ->check(numberInRange(NumberKind::kWhole, 0, 4294967295.0));
  command->add_flag("--no-sensitivity", args->no_sensitivity,
                    "No Sobol indices: N evaluations instead of N (k + 2)");
  command
      ->add_option("--target-width", args->target_width,
                   "Double N until every Sobol index interval is at most this wide (default 0: "
                   "a fixed N)")
      ->check(numberInRange(NumberKind::kReal, 0, 1));
  command
      ->add_option("--max-evaluations", args->max_evaluations,
                   "Budget of ROM evaluations for --target-width (default 1000000)")
      ->check(numberInRange(NumberKind::kWhole, 1, 1e9));
  command
      ->add_option("--confidence", args->confidence,
                   "Confidence level of every interval (default 0.95)")
      ->check(numberInRange(NumberKind::kReal, 0.5, 0.9999));
  command->add_flag("--no-tail-runs", args->no_tail_runs,
                    "Skip the full-order runs at the tails of each limited metric");
  command
      ->add_option("--method", args->method,
                   "Interpolation: " + rom::allowedInterpolationMethodNames() +
                       " (default: the database's; the ROM error estimate is the default "
                       "method's only)")
      ->type_name("NAME");
  command->add_flag("--extrapolate", args->extrapolate,
                    "Allow samples outside the sampled box (linear extrapolation)");
  command->add_flag("--no-stresses", args->no_stresses, "Leave out the interface-stress metrics");
  command->add_option("--step", args->step_s, "ROM step [s] of every deployment (default 2e-3)")
      ->type_name("SECONDS");
  command->add_option("-o,--output", args->output, "HDF5 result file (default uq.h5)");
  command->add_option("--csv", args->csv,
                      "CSV summary file (one estimate with its interval a line)");
  command->add_flag("-q,--quiet", args->quiet, "No progress lines on stderr");
  command->footer("MPI: mpirun -n N mastrom uq ... shares the ROM samples between the ranks.");
  command->callback([args]() { run(*args); });
}

}  // namespace mastrom::cli
