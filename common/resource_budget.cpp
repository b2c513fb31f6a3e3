#include "common/resource_budget.hpp"

#include <sys/statvfs.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.hpp"

namespace mastrom {
namespace {

std::string listDrivers(const std::vector<ResourceDriver>& drivers) {
  std::string text;
  for (const ResourceDriver& d : drivers)
    text += (text.empty() ? "" : ", ") + d.first + " = " + d.second;
  return text;
}

/// "(mast.modules = 100000: 2.28e+07 DOFs)"
std::string because(const std::vector<ResourceDriver>& drivers, const std::string& detail) {
  const std::string keys = listDrivers(drivers);
  if (keys.empty() && detail.empty()) return "";
  if (detail.empty()) return " (" + keys + ")";
  if (keys.empty()) return " (" + detail + ")";
  return " (" + keys + ": " + detail + ")";
}

}  // namespace

std::optional<double> availableMemoryBytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line)) {
    if (line.rfind("MemAvailable:", 0) != 0) continue;
    std::istringstream fields(line.substr(13));
    double kib = 0.0;
    if (fields >> kib) return kib * 1024.0;
  }
  return std::nullopt;
}

std::optional<double> freeDiskBytes(const std::string& path) {
  namespace fs = std::filesystem;
  fs::path probe = path.empty() ? fs::path(".") : fs::path(path);
  std::error_code ec;
  if (!fs::is_directory(probe, ec)) probe = probe.parent_path();
  if (probe.empty()) probe = ".";
  struct statvfs info {};
  if (statvfs(probe.c_str(), &info) != 0) return std::nullopt;
  return static_cast<double>(info.f_bavail) * static_cast<double>(info.f_frsize);
}

ResourceLimits machineLimits(const std::string& output_path) {
  ResourceLimits limits;
  limits.available_memory_bytes = availableMemoryBytes();
  if (!output_path.empty()) limits.free_disk_bytes = freeDiskBytes(output_path);
  return limits;
}

std::string formatBytes(double bytes) {
  static const char* const kUnits[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  int unit = 0;
  while (std::abs(bytes) >= 1000.0 && unit < 6) {
    bytes /= 1000.0;
    ++unit;
  }
  char text[48];
  std::snprintf(text, sizeof text, bytes < 10.0 && unit > 0 ? "%.1f %s" : "%.0f %s", bytes,
                kUnits[unit]);
  return text;
}

std::string checkResources(const ResourceEstimate& e, const ResourceLimits& limits,
                           bool allow_large) {
  const bool memory_over =
      limits.available_memory_bytes && e.memory_bytes > *limits.available_memory_bytes;
  const bool result_over = limits.free_disk_bytes && e.result_bytes > *limits.free_disk_bytes;
  if (!allow_large) {
    MASTROM_REQUIRE(!memory_over, InputError, e.command, " would need about ",
                    formatBytes(e.memory_bytes), " of memory",
                    because(e.memory_drivers, e.memory_detail), ", more than the ",
                    formatBytes(*limits.available_memory_bytes),
                    " available (MemAvailable); reduce them, or pass --allow-large to run anyway");
    MASTROM_REQUIRE(!result_over, InputError, e.command, " would write about ",
                    formatBytes(e.result_bytes), because(e.result_drivers, e.result_detail),
                    ", more than the ", formatBytes(*limits.free_disk_bytes),
                    " free on the output's file system; reduce them, or pass --allow-large to "
                    "run anyway");
  }
  const bool large_memory = limits.available_memory_bytes &&
                            e.memory_bytes > kLargeMemoryShare * *limits.available_memory_bytes;
  const bool large_result = e.result_bytes > kLargeResultBytes;
  if (!(large_memory || large_result || memory_over || result_over)) return "";
  std::string note = "note: ";
  if (large_result || result_over)
    note += "result ≈ " + formatBytes(e.result_bytes) + because(e.result_drivers, e.result_detail);
  if (large_memory || memory_over) {
    if (note.size() > 6) note += ", ";
    note += "memory ≈ " + formatBytes(e.memory_bytes) + because(e.memory_drivers, e.memory_detail);
  }
  if (limits.available_memory_bytes)
    note += "; " + formatBytes(*limits.available_memory_bytes) + " available";
  if (memory_over || result_over) note += " (past the limit: --allow-large)";
  return note;
}

}  // namespace mastrom
