// Resources up front (docs/user_guide.md §4 "Resources"): every command estimates the memory it
// will hold and the bytes it will write before it starts, and refuses with one line when either
// exceeds what the machine has — the memory the kernel reports available (/proc/meminfo
// MemAvailable) and the free space of the output's file system — naming the keys that drive the
// estimate and their values. `--allow-large` lets an expert go on; a run that is large but feasible
// says so on its first line ("note: result ≈ 3.2 GB, memory ≈ 1.1 GB (…)").
//
// The estimates themselves are counts of what a command allocates (DOFs, matrix entries, output
// samples × datasets, database entries) made by the layer that knows the structure
// (fullorder/run_footprint.hpp and the commands); this file only holds the arithmetic of the
// budget and the wording.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mastrom {

/// A configuration key or command-line flag that drives an estimate, with its value as the user
/// wrote it: {"mast.modules", "100000"}, {"--points", "20"}.
using ResourceDriver = std::pair<std::string, std::string>;

/// What a command will need, estimated before any work.
struct ResourceEstimate {
  std::string command;        ///< "simulate", "rom eval", …
  double memory_bytes = 0.0;  ///< peak resident memory of the process
  double result_bytes = 0.0;  ///< bytes written to the result file(s)
  /// The keys that drive each estimate (named in a refusal), and a few words on the sizes they
  /// make ("2.28e+07 DOFs", "8e+09 output samples").
  std::vector<ResourceDriver> memory_drivers, result_drivers;
  std::string memory_detail, result_detail;
};

/// What the machine offers; absent: not known (then not checked).
struct ResourceLimits {
  std::optional<double> available_memory_bytes;  ///< MemAvailable
  std::optional<double> free_disk_bytes;         ///< of the result's directory
};

/// MemAvailable of /proc/meminfo [bytes]; empty when it cannot be read (not Linux).
std::optional<double> availableMemoryBytes();
/// Free bytes for an unprivileged user on the file system holding `path` (its directory when it
/// does not exist yet); empty when that cannot be found out.
std::optional<double> freeDiskBytes(const std::string& path);
/// The machine's limits for a command writing to `output_path` ("" when it writes nothing).
ResourceLimits machineLimits(const std::string& output_path);

/// "3.2 GB", "41 MB", "812 kB" (decimal units, two significant digits at least).
std::string formatBytes(double bytes);

/// A run is "large" when it holds more than this share of the available memory, or writes more
/// than kLargeResultBytes: it then says so on its first line.
inline constexpr double kLargeMemoryShare = 0.25;
inline constexpr double kLargeResultBytes = 1e9;

/// Check `estimate` against `limits`. Throws InputError with one line — what is needed, the keys
/// that drive it with their values, what is available, and the way out (--allow-large) — when
/// the memory or the result exceeds its limit and `allow_large` is false. Returns the line a large
/// but feasible run (or an expert's run past the limit) prints first, or "" for an ordinary run.
std::string checkResources(const ResourceEstimate& estimate, const ResourceLimits& limits,
                           bool allow_large);

}  // namespace mastrom
