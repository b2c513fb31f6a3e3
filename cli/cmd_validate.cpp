// `mastrom validate DB [--points N] [--seed S] [--set k=v]… [--method M] [--tolerance T] [-o F.h5]`:
// the ROM against the nonlinear full order at N random points of the database box
// (rom/studies/validation.hpp), distributed over MPI ranks under mpirun. Prints the error table, writes it
// to HDF5, exits 4 when an error exceeds --tolerance.
#include <mpi.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "cli/cli_common.hpp"
#include "cli/progress.hpp"
#include "cli/resource_estimates.hpp"
#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "modes/slepc_session.hpp"
#include "rom/database/database_io.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/studies/validation.hpp"

namespace mastrom::cli {
namespace {

struct ValidateArguments {
  std::string database;
  int points = 4;
  unsigned long long seed = 1;
  std::vector<std::string> overrides;
  std::string method;
  double tolerance = -1.0;
  std::string output = "validation.h5";
  bool strict_reference = false;
  bool allow_large = false;
  std::optional<int> frequencies;
};

void runValidate(const ValidateArguments& args) {
  const modes::SlepcSession session;  // MPI (and PETSc/SLEPc for the modal solves)
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (rank == 0) h5::checkWritable(args.output);
  const rom::RomDatabase db = rom::readDatabase(args.database);
  rom::ValidationOptions options;
  options.points = args.points;
  options.seed = args.seed;
  options.overrides = args.overrides;
  options.method = rom::interpolationMethodOr(args.method, db.default_method, "--method");
  options.communicator = size > 1 ? MPI_COMM_WORLD : MPI_COMM_NULL;
  if (args.frequencies) options.frequencies = {*args.frequencies, true, "--frequencies"};
  if (rank == 0) {
    requireResources(validateEstimate(rom::evaluationConfig(db, args.overrides), args.points,
                                      fileBytes(args.database)),
                     args.output, args.allow_large);
    std::printf("mastrom validate: %s, %d points (seed %llu) on %d rank(s), method %s\n",
                args.database.c_str(), args.points, args.seed, size,
                rom::toString(options.method).c_str());
    // The reference's step setting (runValidation applies the same --set keys): a ROM error is
    // judged against a full order only as good as this.
    const SimulationConfig sim = rom::evaluationConfig(db, args.overrides).simulation;
    if (sim.adaptive) {
      std::printf("  full order: adaptive steps, simulation.tolerance = %g\n", sim.tolerance);
    } else {
      std::printf("  full order: fixed steps, simulation.time_step = %g s\n", sim.time_step_s);
    }
  }
  std::fflush(stdout);
  ProgressReporter reporter("validate", 2.0, rank == 0, ProgressUnit::kItems);
  const rom::ValidationReport report = rom::runValidation(
      db, options, [&reporter](int done, int total) { reporter.update(done, total); });
  if (rank != 0) return;
  int suspect_points = 0;

  std::printf("%-6s", "point");
  for (const std::string& name : report.parameter_names) std::printf(" %22s", name.c_str());
  const bool rom_estimates = !db.probes.empty() && options.method == db.default_method;
  std::printf(" %9s %9s %9s %9s %9s %9s %9s %10s%s\n", "NRMSE", "peak_rel", "peak_abs", "force",
              "torque", "f1", "speed-up", "full-est", rom_estimates ? "   rom-est" : "");
  for (std::size_t i = 0; i < report.points.size(); ++i) {
    const rom::ValidationPoint& p = report.points[i];
    std::printf("%-6zu", i);
    for (double v : p.parameters) std::printf(" %22.6g", v);
    std::printf(" %8.3f%% %8.3f%% %8.3f%% %8.3f%% %8.3f%% %8.3f%% %8.0fx",
                100 * p.errors.nrmse_relative_acceleration, 100 * p.errors.peak_rel_error,
                100 * p.errors.peak_abs_error, 100 * p.errors.peak_force_error,
                100 * p.errors.peak_torque_error, 100 * p.first_frequency_error, p.speedup());
    if (std::isfinite(p.full_estimated_nrmse)) {
      // The reference is too coarse to judge the ROM by when its own error is a third of the
      // tolerance or more.
      const bool suspect = args.tolerance > 0 && p.full_estimated_nrmse > args.tolerance / 3.0;
      if (suspect) ++suspect_points;
      std::printf(" %8.3f%%%s", 100 * p.full_estimated_nrmse, suspect ? " !" : "  ");
    } else {
      std::printf(" %9s ", "n/a");
    }
    if (rom_estimates) std::printf(" %8.3f%%", 100 * p.rom_estimated_nrmse);
    std::printf("\n");
  }
  std::printf("(relative errors of the ROM against the full order; NRMSE of the relative end "
              "angular acceleration, RMS-normalised; f1 = first frequency vs a direct modal "
              "solve; full-est = the full order's own estimated NRMSE, from a second run at 8x "
              "its tolerance: a ROM error near it is the reference's)\n");
  if (rom_estimates && db.isGrid())
    std::printf("(rom-est = the database's estimate of the NRMSE at the point, from the error "
                "measured at its cell's centre, docs/theory.md (4.13))\n");
  if (rom_estimates && !db.isGrid())
    std::printf("(rom-est = the database's typical NRMSE at the point, the power function times "
                "the held-out probes' scale, docs/theory.md (4.14): centred, but half of the points "
                "lie outside [1/2, 2] of it; the database's own estimate, the worst probe, is the "
                "bound)\n");
  // The designs themselves: mass and natural frequencies at the deployed angle, the ROM's against
  // a direct modal solve's, with the database's estimate (docs/theory.md §1.7, (4.15)).
  std::printf("%-6s %12s", "point", "mass [kg]");
  for (int k = 1; k <= report.frequencies; ++k)
    std::printf("   f%d rom [Hz] direct [Hz]  error estimate", k);
  std::printf("\n");
  for (std::size_t i = 0; i < report.points.size(); ++i) {
    const rom::ValidationPoint& p = report.points[i];
    std::printf("%-6zu %12.6g", i, p.mass_kg);
    for (int k = 0; k < report.frequencies; ++k) {
      const double rom = p.frequency_hz[k], direct = p.frequency_direct_hz[k];
      std::printf("  %12.6g %11.6g %5.2g%% %6.2g%%", rom, direct,
                  100 * std::abs(rom - direct) / direct, 100 * p.frequency_error_estimate[k]);
    }
    std::printf("\n");
  }
  if (report.frequencies == 0)
    std::printf("(no natural frequencies: %s)\n", report.no_frequency_reason.c_str());
  std::printf("worst error %.3f%%\n", 100 * report.worst());
  if (suspect_points > 0) {
    std::printf("%d point%s marked '!': the full order's estimated error exceeds a third of "
                "--tolerance; tighten simulation.tolerance for a sharper reference\n",
                suspect_points, suspect_points == 1 ? "" : "s");
  }
  rom::writeValidationFile(args.output, report, options);
  std::printf("wrote %s\n", args.output.c_str());
  std::fflush(stdout);
  if (args.strict_reference && suspect_points > 0) {
    std::fprintf(stderr, "mastrom: error: validate: %d point%s whose full-order reference is "
                 "not accurate enough for --tolerance %.3g (--strict-reference)\n",
                 suspect_points, suspect_points == 1 ? "" : "s", args.tolerance);
    std::exit(4);
  }
  if (args.tolerance >= 0 && report.worst() > args.tolerance) {
    std::fprintf(stderr, "mastrom: error: validate: worst error %.3g exceeds the tolerance %.3g\n",
                 report.worst(), args.tolerance);
    std::exit(4);
  }
}

}  // namespace

void registerValidateCommand(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "validate", "Run ROM and nonlinear full order at random points of the database box");
  auto args = std::make_shared<ValidateArguments>();
  command->add_option("DB", args->database, "ROM database (mastrom rom build)")->required();
  command->add_option("--points", args->points, "Number of random points (default 4)")
      ->check(numberInRange(NumberKind::kWhole, 1));
  command->add_option("--seed", args->seed, "Seed of the point generator (default 1)")
      ->check(numberInRange(NumberKind::kWhole, 0, 18446744073709551615.0));
  command
      ->add_option("--set", args->overrides,
                   "Free key for every point (drive.*, simulation.*, output.*), e.g. --set "
                   "drive.law=cubic, or --set simulation.tolerance=6.25e-7 for a full-order "
                   "reference sharper than the default 1e-5 (repeatable)")
      ->type_name("SECTION.KEY=VALUE")
      ->allow_extra_args(false);
  command->add_option("--method", args->method,
                      "Interpolation: " + rom::allowedInterpolationMethodNames() +
                          " (default: the database's)");
  command->add_option("--tolerance", args->tolerance,
                      "Exit 4 when any relative error exceeds this (e.g. 0.05)")
      ->check(numberInRange(NumberKind::kReal, 0));
  command->add_option("-o,--output", args->output, "Result file (default validation.h5)");
  addFrequenciesOption(*command, args->frequencies,
                       "per point, against a direct modal solve's at the same point");
  command->add_flag("--strict-reference", args->strict_reference,
                    "Also exit 4 when a point's full-order reference has an estimated error "
                    "above a third of --tolerance");
  addAllowLargeFlag(*command, args->allow_large);
  command->callback([args]() { runValidate(*args); });
}

}  // namespace mastrom::cli
