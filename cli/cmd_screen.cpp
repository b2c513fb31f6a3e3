// `mastrom screen DB --grid KEY=LO:HI:N … [--grid drive.law=trapezoidal,cubic] [--set k=v]…
//  [--method tracked|manifold|affine|cubic] [--extrapolate] [-o FILE.h5|FILE.csv]` (docs/user_guide.md
// §3): the metrics of docs/theory.md §1 over a grid of designs and drive laws, one ROM deployment
// per design (rom/studies/screening.hpp). Under `mpirun -n N` the designs are shared between the ranks and
// merged in design order (the table does not depend on N); only rank 0 prints and writes. Without
// -o the table is printed as CSV on stdout.
#include <cstdio>
#include <iostream>
#include <memory>

#include "cli/cli_common.hpp"
#include "cli/progress.hpp"
#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "modes/slepc_session.hpp"
#include "rom/database/database_io.hpp"
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
  for (const std::string& g : args.grid) options.axes.push_back(rom::parseScreenAxis(g, db));
  options.overrides = args.overrides;
  options.box = args.extrapolate ? rom::BoxPolicy::Extrapolate : rom::BoxPolicy::Refuse;
  if (format != TableFormat::Stdout) h5::checkWritable(args.output);

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
  const rom::ScreenTable table = rom::runScreen(db, options);
  if (!root) return;

  FILE* info = format == TableFormat::Stdout ? stderr : stdout;
  std::fprintf(info,
               "mastrom screen: %ld designs x %zu metrics from %s (method %s) on %d rank%s: "
               "%.3f s, %.0f designs/s\n",
               table.designs, table.metric_names.size(), args.database.c_str(),
               rom::toString(table.method).c_str(), table.ranks, table.ranks == 1 ? "" : "s",
               table.wall_s,
               table.wall_s > 0 ? static_cast<double>(table.designs) / table.wall_s : 0.0);
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
  command->add_flag("-q,--quiet", args->quiet, "No progress lines on stderr");
  command->footer("MPI: mpirun -n N mastrom screen ... shares the designs between the ranks.");
  command->callback([args]() { run(*args); });
}

}  // namespace mastrom::cli
