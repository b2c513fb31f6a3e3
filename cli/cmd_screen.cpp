// `mastrom screen DB --grid KEY=LO:HI:N … [--grid drive.law=trapezoidal,cubic] [--set k=v]…
//  [--method tracked|manifold|affine|cubic] [--extrapolate] [-o FILE.h5|FILE.csv]` (docs/user_guide.md
// §3): the metrics of docs/theory.md §1 over a grid of designs and drive laws, one ROM deployment
// per design (rom/studies/screening.hpp). Under `mpirun -n N` the designs are shared between the ranks and
// merged in design order (the table does not depend on N); only rank 0 prints and writes. Without
// -o the table is printed as CSV on stdout.
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/cli_common.hpp"
#include "cli/progress.hpp"
#include "cli/resource_estimates.hpp"
#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "modes/slepc_session.hpp"
#include "rom/database/database_io.hpp"
#include "rom/studies/pareto_front.hpp"
#include "rom/studies/screen_filter.hpp"
#include "rom/studies/screening.hpp"

namespace mastrom::cli {
namespace {

struct ScreenArguments {
  std::string database;
  std::vector<std::string> grid;
  std::vector<std::string> overrides;
  std::string method;
  bool extrapolate = false;
  std::string output;
  bool quiet = false;
  bool no_stresses = false;
  std::vector<std::string> where;
  std::string sort_by;
  std::optional<double> step_s;
  bool allow_large = false;
  std::optional<int> frequencies;
  std::string pareto;
  bool pareto_only = false;
};

enum class TableFormat { Stdout, Csv, Hdf5 };

TableFormat formatOf(const std::string& path) {
  if (path.empty()) return TableFormat::Stdout;
  const auto ends = [&path](const std::string& suffix) {
    return path.size() >= suffix.size() &&
           path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  if (ends(".csv")) return TableFormat::Csv;
  if (ends(".h5") || ends(".hdf5")) return TableFormat::Hdf5;
  throw InputError("-o " + path + ": the screen table is written as .csv or .h5 (.hdf5)");
}

void run(const ScreenArguments& args) {
  const TableFormat format = formatOf(args.output);
  const rom::RomDatabase db = rom::readDatabase(args.database);
  rom::ScreenOptions options;
  options.method = rom::interpolationMethodOr(args.method, db.default_method, "--method");
  for (const std::string& g : args.grid)
    options.axes.push_back(rom::parseScreenAxis(g, db, args.overrides));
  options.overrides = args.overrides;
  options.box = args.extrapolate ? rom::BoxPolicy::Extrapolate : rom::BoxPolicy::Refuse;
  options.stresses = !args.no_stresses;
  if (args.step_s) {
    rom::checkScreenStep(*args.step_s, args.overrides, "--step");
    options.step_s = *args.step_s;
  }
  if (args.frequencies) options.frequencies = {*args.frequencies, true, "--frequencies"};
  std::vector<rom::ParetoObjective> objectives;
  if (!args.pareto.empty()) objectives = rom::parseParetoObjectives(args.pareto, "--pareto");
  MASTROM_REQUIRE(!args.pareto_only || !objectives.empty(), InputError,
                  "--pareto-only needs --pareto OBJ[:min|max],... (the objectives of the front)");
  if (format != TableFormat::Stdout) h5::checkWritable(args.output);
  // The conditions and the order, checked against the table's columns before any work.
  std::vector<rom::ColumnCondition> conditions;
  for (const std::string& w : args.where) conditions.push_back(rom::parseColumnCondition(w));
  std::optional<rom::SortOrder> order;
  if (!args.sort_by.empty()) order = rom::parseSortOrder(args.sort_by);
  {
    rom::ScreenTable columns;
    columns.axes = options.axes;
    columns.columns = rom::screenTableColumns(db, options);
    columns.metric_names = rom::metricNames(rom::designMetrics(columns.columns));
    rom::checkParetoObjectives(columns.columns, objectives, "--pareto");
    if (!objectives.empty()) columns.metric_names.push_back(rom::kParetoColumn);
    rom::checkColumns(columns, conditions, order);
    double designs = 1.0;
    std::vector<ResourceDriver> grid;
    for (std::size_t a = 0; a < options.axes.size(); ++a) {
      designs *= static_cast<double>(options.axes[a].values.size());
      grid.emplace_back("--grid", args.grid[a]);
    }
    requireResources(
        screenEstimate(designs,
                       static_cast<double>(options.axes.size() + columns.metric_names.size()),
                       fileBytes(args.database), grid),
        format == TableFormat::Stdout ? std::string() : args.output, args.allow_large);
  }

  const modes::SlepcSession session;  // MPI for the life of the command
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const bool root = rank == 0;
  options.communicator = MPI_COMM_WORLD;
  ProgressReporter reporter("screen", 2.0, root && !args.quiet, ProgressUnit::kItems);
  options.progress = [&reporter](long done, long total) {
    reporter.update(static_cast<double>(done), static_cast<double>(total), "rank 0's designs");
  };
  rom::ScreenTable table = rom::runScreen(db, options);
  if (!root) return;
  const long screened = table.designs;
  // --where first (the front of the designs that meet the conditions), then the front, then the
  // order.
  const long removed = rom::filterAndSort(table, conditions, std::nullopt);
  long off_front = 0;
  if (!objectives.empty()) {
    rom::markParetoFront(table, objectives);
    if (args.pareto_only) off_front = rom::keepParetoFront(table);
  }
  if (order) rom::filterAndSort(table, {}, order);

  FILE* info = format == TableFormat::Stdout ? stderr : stdout;
  std::fprintf(info,
               "mastrom screen: %ld designs x %zu metrics from %s (method %s) on %d rank%s: "
               "%.3f s, %.0f designs/s\n",
               screened, table.metric_names.size(), args.database.c_str(),
               rom::toString(table.method).c_str(), table.ranks, table.ranks == 1 ? "" : "s",
               table.wall_s, table.wall_s > 0 ? static_cast<double>(screened) / table.wall_s : 0.0);
  std::fprintf(info,
               "  ROM step %g ms; metrics of the continuous response (peaks within 4e-4, RMS "
               "integrated exactly, settling at the last exit from the band): at 2 ms within "
               "2.1e-4 of a 10 us screen\n",
               1e3 * table.step_s);
  if (!conditions.empty())
    std::fprintf(info, "  --where kept %ld of %ld designs (%ld removed)\n", table.designs, screened,
                 removed);
  if (!objectives.empty()) {
    long on_front = 0;
    const std::size_t q = table.metric_names.size();
    for (long d = 0; d < table.designs; ++d)
      on_front += table.metrics[static_cast<std::size_t>(d) * q + q - 1] == 1.0 ? 1 : 0;
    std::fprintf(
        info, "  Pareto front of %s: %ld designs%s\n", table.pareto_objectives.c_str(), on_front,
        args.pareto_only ? detail::concat(" (--pareto-only removed ", off_front, ")").c_str()
                         : " (column pareto_front = 1)");
  }
  if (order)
    std::fprintf(info, "  sorted by %s, %s\n", order->column.c_str(),
                 order->descending ? "descending" : "ascending");
  switch (format) {
    case TableFormat::Csv:
      rom::writeScreenCsv(args.output, table);
      break;
    case TableFormat::Hdf5:
      rom::writeScreenH5(args.output, table);
      break;
    case TableFormat::Stdout:
      std::fflush(stdout);
      rom::writeScreenCsv(std::cout, table);
      std::cout.flush();
      break;
  }
  if (format != TableFormat::Stdout) std::printf("wrote %s\n", args.output.c_str());
  std::fflush(stdout);
}

}  // namespace

void registerScreenCommand(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "screen", "Metrics over a grid of designs and drive laws, from a ROM database");
  auto args = std::make_shared<ScreenArguments>();
  command->add_option("DB", args->database, "ROM database (from mastrom rom build)")->required();
  command
      ->add_option(
          "--grid", args->grid,
          "One grid axis: KEY=LO:HI:N (N evenly spaced values) or KEY=V1,V2,... for a "
          "database parameter or a free key, e.g. --grid interface.thickness=0.001:0.002:5 "
          "--grid drive.law=trapezoidal,cubic (repeatable; first axis varies fastest)")
      ->type_name("KEY=RANGE")
      ->required()
      ->allow_extra_args(false);
  command
      ->add_option("--set", args->overrides,
                   "Fix a database parameter or a free key for every design (repeatable)")
      ->type_name("SECTION.KEY=VALUE")
      ->allow_extra_args(false);
  command
      ->add_option("--method", args->method,
                   "Interpolation: " + rom::allowedInterpolationMethodNames() +
                       " (affine: databases over thickness at fixed radius, E or rho only; "
                       "default: the database's)")
      ->type_name("NAME");
  command->add_flag("--extrapolate", args->extrapolate,
                    "Allow designs outside the sampled box (linear extrapolation)");
  command->add_option("-o,--output", args->output,
                      "Table file: .csv (columns = grid keys, then metrics) or .h5 (/screen "
                      "layout); default: CSV on stdout");
  command
      ->add_option("--where", args->where,
                   "Keep the designs whose column satisfies COLUMN OP NUMBER (OP: < <= > >= == "
                   "!=; a grid key or a metric, SI units), e.g. --where \"min_margin_of_safety > "
                   "0.5\" (repeatable: all must hold)")
      ->type_name("CONDITION")
      ->allow_extra_args(false);
  command->add_option("--sort-by", args->sort_by,
                      "Order the rows by a column: COLUMN (ascending) or COLUMN:desc");
  command->add_flag("--no-stresses", args->no_stresses,
                    "Leave out the interface-stress columns (peak von Mises per interface, "
                    "min margin of safety) that a database with stress modes gives");
  command
      ->add_option("--step", args->step_s,
                   "ROM step [s] of every deployment (default 2e-3, or output.step when given "
                   "with --set): every metric is taken on the continuous response, so the step "
                   "sets the cost, not the answer (a 2 ms screen is within 2.1e-4 of a 10 us one, "
                   "relative to max(value, settling band) for the metrics of r)")
      ->type_name("SECONDS");
  addFrequenciesOption(*command, args->frequencies, "columns frequency_K [Hz], frequency_K_error");
  command
      ->add_option("--pareto", args->pareto,
                   "Mark the designs on the Pareto front of these metrics (column pareto_front), "
                   "after --where, e.g. --pareto mass:min,frequency_1:max,"
                   "peak_rel_end_angular_acceleration:min")
      ->type_name("OBJ[:min|max],...");
  command->add_flag("--pareto-only", args->pareto_only,
                    "Keep only the designs on the front of --pareto");
  command->add_flag("-q,--quiet", args->quiet, "No progress lines on stderr");
  addAllowLargeFlag(*command, args->allow_large);
  command->footer("MPI: mpirun -n N mastrom screen ... shares the designs between the ranks.");
  command->callback([args]() { run(*args); });
}

}  // namespace mastrom::cli
