// The `mastrom` executable: parses the command line with CLI11, hands over to one subcommand, and
// turns every failure into exactly one line on stderr, `mastrom: error: <message>`, and an exit
// code: 2 for bad input or files (and command-line mistakes), 3 for numerical failure, 130 when
// interrupted by Ctrl-C or SIGTERM (cli/interrupt.hpp), 1 otherwise.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>

#include <unistd.h>

#include "cli/cli_common.hpp"
#include "cli/interrupt.hpp"
#include "common/error.hpp"

namespace {

using RegisterFunction = void (*)(CLI::App&);

/// Every subcommand, in the order `mastrom --help` lists them.
constexpr RegisterFunction kCommands[] = {
    mastrom::cli::registerConfigCommand,   mastrom::cli::registerSimulateCommand,
    mastrom::cli::registerModesCommand,    mastrom::cli::registerRomCommand,
    mastrom::cli::registerScreenCommand,   mastrom::cli::registerValidateCommand,
    mastrom::cli::registerOptimizeCommand, mastrom::cli::registerCompareCommand,
    mastrom::cli::registerStudyCommand,    mastrom::cli::registerUqCommand,
    mastrom::cli::registerReportCommand,
};

/// Rank of this process in an mpirun job (Open MPI, PMIx or MPICH environment), 0 outside one.
int launcherRank() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"}) {
    if (const char* value = std::getenv(name)) return std::atoi(value);
  }
  return 0;
}

/// One line on stderr. Under mpirun the ranks fail alike (every rank reads the same inputs, and
/// rom/offline/mpi_gather.hpp's throwIfAnyRankFailed hands a rank's failure to all), so only rank 0 reports
/// mastrom's own errors: one line, not one per rank. The line goes out in one write, so lines of
/// several processes sharing the terminal cannot interleave.
int fail(int code, std::string message, bool every_rank = false) {
  for (char& c : message)
    if (c == '\n' || c == '\r') c = ' ';
  if (!every_rank && launcherRank() != 0) return code;
  const std::string line = "mastrom: error: " + message + "\n";
  std::fputs(line.c_str(), stderr);
  std::fflush(stderr);
  return code;
}

std::string commandNames(CLI::App& app) {
  std::string names;
  for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
    names += (names.empty() ? "" : ", ") + sub->get_name();
  return names;
}

}  // namespace

namespace {

/// OpenMP threads that wait at a barrier spin before they sleep; libgomp's default spin (300 000
/// rounds) makes a two-thread run up to ten times slower than one thread when other processes
/// share the cores (measured: two 0.4 s Scheme 3 runs at once, 34.8 s for the slower against 4.4 s
/// alone). The spin can only be set in the environment before the OpenMP runtime starts, which is
/// before main(): so, unless the user chose a wait policy, run again with a short spin (about the
/// time of one element-force pass: waits longer than that sleep). The result is unchanged; only
/// how the threads wait. Running again loads the executable and its libraries a second time
/// (29 ms of the 60 ms `mastrom --version` took), so it is done only for a command line that can
/// open a region of two threads (mayRunThreads).
void boundOpenMpSpinning(int argc, char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT") ||
      std::getenv("MASTROM_OPENMP_WAIT_SET") || !mastrom::cli::mayRunThreads(argc, argv))
    return;
  ::setenv("GOMP_SPINCOUNT", "10000", 1);
  ::setenv("MASTROM_OPENMP_WAIT_SET", "1", 1);
  ::execv("/proc/self/exe", argv);  // returns only on failure: then run as we are
}

}  // namespace

int main(int argc, char** argv) {
  boundOpenMpSpinning(argc, argv);
  using namespace mastrom::cli;
  CLI::App app{"mastrom: deployment dynamics and modal reduced-order model of a modular rover mast",
               "mastrom"};
  app.set_version_flag("--version", "mastrom " + std::string(mastrom::kVersion));
  app.require_subcommand(1);
  for (const RegisterFunction add : kCommands) add(app);
  // Set after the subcommands exist, so that they do not inherit it.
  app.footer(
      "Run 'mastrom COMMAND --help' for the options of one command.");

  installInterruptHandlers();
  try {
    app.parse(argc, argv);  // runs the chosen subcommand's callback
    return kExitOk;
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    if (argc > 1 && argv[1][0] != '-' && app.get_subcommands().empty()) {
      return fail(kExitInput, std::string("unknown command '") + argv[1] +
                                  "': available: " + commandNames(app) + " (run 'mastrom --help')");
    }
    return fail(kExitInput, std::string(e.what()) + " (run 'mastrom --help')");
  } catch (const Interrupted& e) {
    return fail(kExitInterrupted, e.what());
  } catch (const mastrom::InputError& e) {
    return fail(kExitInput, e.what());
  } catch (const mastrom::IoError& e) {
    return fail(kExitInput, e.what());
  } catch (const mastrom::NumericalError& e) {
    return fail(kExitNumerical, e.what());
  } catch (const mastrom::Error& e) {
    return fail(kExitFailure, e.what());
  } catch (const std::exception& e) {  // unexpected: possibly on one rank only
    return fail(kExitFailure, e.what(), true);
  } catch (...) {
    return fail(kExitFailure, "unknown exception", true);
  }
}
