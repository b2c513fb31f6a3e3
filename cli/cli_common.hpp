// Pieces shared by the `mastrom` subcommands: the subcommand registry, the CONFIG + --set arguments
// every config-driven command takes, and the exit codes.
//
// Adding a subcommand = one new file cli/cmd_<name>.cpp that defines register<Name>Command, one
// declaration below, and one entry in kCommands in cli/main.cpp. A subcommand does its work in a
// CLI11 callback and reports failure by throwing mastrom::Error; main() turns that into one line on
// stderr and the exit code (2 input/IO, 3 numerical, 1 otherwise).
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "common/config.hpp"
#include "common/version.hpp"
#include "fullorder/deployment_result.hpp"

namespace mastrom::cli {

/// Exit codes of the executable.
enum ExitCode : int { kExitOk = 0, kExitFailure = 1, kExitInput = 2, kExitNumerical = 3 };

/// CONFIG plus any number of `--set section.key=value` overrides.
struct ConfigArguments {
  std::string path;
  std::vector<std::string> overrides;
};

/// Add the positional CONFIG and the repeatable --set option to a subcommand; args must outlive
/// parsing (keep it in a shared_ptr captured by the subcommand's callback).
void addConfigArguments(CLI::App& command, ConfigArguments& args);

/// Load, override and validate (common/config.hpp); throws InputError / IoError.
Config loadConfig(const ConfigArguments& args);

/// What a numeric command-line option accepts.
enum class NumberKind { kWhole, kReal };

/// A CLI11 check for a numeric option: the text must be a finite number (a whole one for kWhole)
/// with lo <= value <= hi. On failure CLI11 prints "OPTION: <value> is out of range; allowed: …"
/// (or "… is not a number; allowed: …") in plain words: CLI11's own range check prints the limits
/// with six decimals, up to 1.8e308, and calls 0 "not in range 0.000000 to …".
CLI::Validator numberInRange(NumberKind kind, double lo, double hi = HUGE_VAL);

/// Print the docs/theory.md §1 metrics of a deployment for people (angles in degrees, units shown).
/// `--frequencies N` of the commands that describe designs (screen, rom eval, validate): the N
/// lowest natural frequencies of the mast locked at the deployed angle (docs/theory.md §1.7), unset
/// = the default. `columns` says where they appear.
void addFrequenciesOption(CLI::App& command, std::optional<int>& frequencies,
                          const std::string& columns);

void printDeploymentMetrics(const fullorder::DeploymentMetrics& metrics);

/// The interfaces' peak stresses sit at the bonded edges and converge slowly with the axial mesh
/// (docs/user_guide.md §7): a warning line saying how far off a mesh coarser than 32 axial
/// elements reads (simulate, rom eval).
void printStressMeshWarning(int elements_axial);

/// The full order's thread count when `simulate --threads` is absent: two where the machine has two
/// cores and this process is alone on them; one under an MPI launcher (the ranks take the cores,
/// and waiting helper threads spin); never more than OMP_NUM_THREADS or OMP_THREAD_LIMIT.
int defaultThreadCount();

/// Whether the command line argv may open a parallel region with more than one thread: only
/// `simulate` does (every other command runs the full order on one thread, and the modal
/// solvers and Eigen are not threaded), unless `--threads 1`, `--help`, or defaultThreadCount() = 1
/// without --threads. cli/main.cpp bounds the OpenMP spin only then.
bool mayRunThreads(int argc, char** argv);

// ---- subcommand registry: one function per file cli/cmd_<name>.cpp ----
void registerConfigCommand(CLI::App& app);    ///< cli/cmd_config.cpp
void registerSimulateCommand(CLI::App& app);  ///< cli/cmd_simulate.cpp
void registerModesCommand(CLI::App& app);     ///< cli/cmd_modes.cpp
void registerRomCommand(CLI::App& app);       ///< cli/cmd_rom.cpp (rom build, rom eval)
void registerScreenCommand(CLI::App& app);    ///< cli/cmd_screen.cpp
void registerReportCommand(CLI::App& app);    ///< cli/cmd_report.cpp
void registerCompareCommand(CLI::App& app);   ///< cli/cmd_compare.cpp
void registerValidateCommand(CLI::App& app);  ///< cli/cmd_validate.cpp
void registerOptimizeCommand(CLI::App& app);  ///< cli/cmd_optimize.cpp
void registerStudyCommand(CLI::App& app);     ///< cli/cmd_study.cpp
void registerUqCommand(CLI::App& app);        ///< cli/cmd_uq.cpp

}  // namespace mastrom::cli
