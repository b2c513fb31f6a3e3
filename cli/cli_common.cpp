#include "cli/cli_common.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>

namespace mastrom::cli {

void addConfigArguments(CLI::App& command, ConfigArguments& args) {
  command.add_option("CONFIG", args.path, "TOML configuration file (docs: README.md)")->required();
  // One value per --set, so that `--set a=1 CONFIG` never swallows CONFIG.
  command
      .add_option("--set", args.overrides,
                  "Override one key, e.g. --set interface.thickness=0.001 (repeatable; applied "
                  "after the file, in order)")
      ->type_name("SECTION.KEY=VALUE")
      ->allow_extra_args(false);
}

Config loadConfig(const ConfigArguments& args) {
  return ::mastrom::loadConfig(args.path, args.overrides);
}

namespace {

/// "a whole number >= 1", "a number with 0 <= value <= 1", … (shortest round-trip limits).
std::string allowedText(NumberKind kind, double lo, double hi) {
  const std::string what = kind == NumberKind::kWhole ? "a whole number" : "a number";
  const auto text = [](double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.10g", v);
    return std::string(buffer);
  };
  if (std::isinf(hi)) return what + " >= " + text(lo);
  return what + " from " + text(lo) + " to " + text(hi);
}

}  // namespace

CLI::Validator numberInRange(NumberKind kind, double lo, double hi) {
  const std::string allowed = allowedText(kind, lo, hi);
  return CLI::Validator(
      [kind, lo, hi, allowed](std::string& input) -> std::string {
        const char* begin = input.c_str();
        char* end = nullptr;
        const double value = std::strtod(begin, &end);
        const bool parsed = !input.empty() && end == begin + input.size() && std::isfinite(value);
        if (!parsed) return input + " is not a number; allowed: " + allowed;
        if ((kind == NumberKind::kWhole && value != std::floor(value)) || value < lo || value > hi)
          return input + " is out of range; allowed: " + allowed;
        return {};
      },
      allowed, "NUMBER_IN_RANGE");
}

void printDeploymentMetrics(const fullorder::DeploymentMetrics& m) {
  constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;
  // The full order's estimated discretisation error of a metric, where it has one.
  const auto estimate = [](double relative_error) {
    char text[64] = "";
    if (std::isfinite(relative_error)) {
      std::snprintf(text, sizeof text, "  (+- %.2g %% discretisation, estimated)",
                    100.0 * relative_error);
    }
    return std::string(text);
  };
  std::printf("  peak |abs| end angular acceleration  %12.4f deg/s^2%s\n",
              m.peak_abs_end_angular_acceleration * kRadToDeg,
              estimate(m.estimated_error_peak_abs_end_angular_acceleration).c_str());
  std::printf("  peak |rel| end angular acceleration  %12.4f deg/s^2%s\n",
              m.peak_rel_end_angular_acceleration * kRadToDeg,
              estimate(m.estimated_error_peak_rel_end_angular_acceleration).c_str());
  std::printf("  rms rel end angular acceleration     %12.4f deg/s^2\n",
              m.rms_rel_end_angular_acceleration * kRadToDeg);
  if (std::isfinite(m.residual_rel_end_angular_acceleration)) {
    std::printf("  residual rel after drive end         %12.4f deg/s^2\n",
                m.residual_rel_end_angular_acceleration * kRadToDeg);
  } else {
    std::printf("  residual rel after drive end         %12s\n", "n/a");
  }
  if (std::isfinite(m.settling_time)) {
    std::printf("  settling time (band %.2f deg/s^2)    %12.4f s%s\n", m.settling_band * kRadToDeg,
                m.settling_time, m.settled ? "" : "  (not settled by the end of the record)");
  } else {
    std::printf("  settling time (band %.2f deg/s^2)    %12s\n", m.settling_band * kRadToDeg,
                "n/a");
  }
  std::printf("  peak joint force                     %12.4f N%s\n", m.peak_joint_force,
              estimate(m.estimated_error_peak_joint_force).c_str());
  std::printf("  peak drive torque                    %12.4f N*m\n", m.peak_drive_torque);
  if (!m.not_available.empty()) std::printf("  n/a: %s\n", m.not_available.c_str());
  if (std::isfinite(m.estimated_nrmse_rel_end_angular_acceleration)) {
    std::printf("  estimated discretisation error: NRMSE %.2g %% of the relative end angular "
                "acceleration\n",
                100.0 * m.estimated_nrmse_rel_end_angular_acceleration);
  }
  if (!m.peaks_resolved.empty()) std::printf("  peaks from: %s\n", m.peaks_resolved.c_str());
}

void printStressMeshWarning(int elements_axial) {
  constexpr int kConvergedAxial = 32;
  if (elements_axial >= kConvergedAxial) return;
  const char* low = elements_axial <= 2   ? "at least 30 %"
                    : elements_axial <= 4 ? "at least 20 %"
                    : elements_axial <= 8 ? "at least 10 %"
                                          : "at least 5 %";
  std::printf("  warning: interface.elements_axial = %d resolves the edge stresses coarsely: the "
              "peaks read %s low (Scheme 3, docs/user_guide.md §7); check strength with >= %d axial "
              "elements\n",
              elements_axial, low, kConvergedAxial);
}

int defaultThreadCount() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"})
    if (const char* value = std::getenv(name); value != nullptr && std::atoi(value) > 1) return 1;
  // The user's OpenMP limits are the limits (OMP_NUM_THREADS=1 means one thread, every region).
  int threads = std::thread::hardware_concurrency() >= 2 ? 2 : 1;
  for (const char* name : {"OMP_NUM_THREADS", "OMP_THREAD_LIMIT"}) {
    if (const char* value = std::getenv(name); value != nullptr && std::atoi(value) >= 1)
      threads = std::min(threads, std::atoi(value));
  }
  return threads;
}

bool mayRunThreads(int argc, char** argv) {
  // The first word that is not an option names the subcommand (the top level has only flags).
  int command = 1;
  while (command < argc && argv[command][0] == '-') ++command;
  if (command >= argc || std::strcmp(argv[command], "simulate") != 0) return false;
  const char* threads = nullptr;  // the last --threads value, as CLI11 takes it
  for (int i = command + 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (word == "-h" || word == "--help") return false;
    if (word == "--threads" && i + 1 < argc) threads = argv[++i];
    else if (word.rfind("--threads=", 0) == 0) threads = argv[i] + std::strlen("--threads=");
  }
  if (threads == nullptr || std::atoi(threads) == 0) return defaultThreadCount() > 1;
  return std::atoi(threads) != 1;  // a value CLI11 rejects also ends the run before any region
}

void addFrequenciesOption(CLI::App& command, std::optional<int>& frequencies,
                          const std::string& columns) {
  command
      .add_option("--frequencies", frequencies,
                  "The N lowest natural frequencies of the mast locked at the deployed angle, each "
                  "with the database's estimate of its error (" +
                      columns + "); default 3 where the database can give them, 0: none")
      ->type_name("N");
}

}  // namespace mastrom::cli
