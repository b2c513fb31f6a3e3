#include "cli/cli_common.hpp"

#include <cstdio>
#include <cstdlib>
#include <string>

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
  std::printf("  peak |abs| end angular acceleration  %12.4f deg/s^2\n",
              m.peak_abs_end_angular_acceleration * kRadToDeg);
  std::printf("  peak |rel| end angular acceleration  %12.4f deg/s^2\n",
              m.peak_rel_end_angular_acceleration * kRadToDeg);
  std::printf("  rms rel end angular acceleration     %12.4f deg/s^2\n",
              m.rms_rel_end_angular_acceleration * kRadToDeg);
  std::printf("  residual rel after drive end         %12.4f deg/s^2\n",
              m.residual_rel_end_angular_acceleration * kRadToDeg);
  std::printf("  settling time (band %.2f deg/s^2)    %12.4f s%s\n", m.settling_band * kRadToDeg,
              m.settling_time, m.settled ? "" : "  (not settled by the end of the record)");
  std::printf("  peak joint force                     %12.4f N\n", m.peak_joint_force);
  std::printf("  peak drive torque                    %12.4f N*m\n", m.peak_drive_torque);
}

}  // namespace mastrom::cli
