#include "cli/resource_estimates.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "fullorder/run_footprint.hpp"

namespace mastrom::cli {
namespace {

// A database in memory: its arrays as read, with the interpolators' copies (about its file size
// again).
constexpr double kDatabaseMemoryFactor = 2.0;
// Dense backend: K, M, the null-space basis, the reduced pencil and its eigenvectors, about 2.5
// n × n matrices of doubles at the peak (measured: 305 MB at 16 modules, 3432 DOFs; estimate 355).
constexpr double kDenseMatrices = 2.5;
// Database entry per sample and mode: the per-mode quantities (frequency, damping, Γ, ψ, …) and
// for the stress modes 9 recovery points × 3 stations × 3 stress components per shell element.
constexpr double kModeBytes = 400.0;
constexpr double kStressModeBytesPerElement = 9 * 3 * 3 * 8.0;
// rom eval's metrics' pass, per sample of its grid: the drive sampled there, and the states the
// stress peaks' refinement keeps (η, η̇ and the stress inputs). Its streamed outputs: one block.
constexpr double kDriveSampleBytes = 72.0;
constexpr double kStressStateBytes = 184.0;
constexpr double kStreamBlockBytes = 4096 * 64 * 8.0;

using fullorder::countText;

}  // namespace

void addAllowLargeFlag(CLI::App& command, bool& allow_large) {
  command.add_flag("--allow-large", allow_large,
                   "Run even when the memory or the result estimated up front exceeds what this "
                   "machine has (docs/user_guide.md §4, Resources)");
}

void requireResources(const ResourceEstimate& estimate, const std::string& output_path,
                      bool allow_large) {
  const std::string note = checkResources(estimate, machineLimits(output_path), allow_large);
  if (note.empty()) return;
  std::printf("%s\n", note.c_str());
  std::fflush(stdout);
}

double fileBytes(const std::string& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  return ec ? 0.0 : static_cast<double>(size);
}

ResourceEstimate modesEstimate(const Config& config) {
  const fullorder::MastSize size = fullorder::mastSize(config);
  ResourceEstimate e;
  e.command = "modes";
  e.memory_drivers = fullorder::mastDrivers(config);
  e.memory_bytes = fullorder::fullOrderModelBytes(size);
  e.memory_detail = countText(size.dofs) + " DOFs";
  if (config.modes.backend == EigenBackendKind::Dense) {
    e.memory_bytes += kDenseMatrices * 8.0 * size.dofs * size.dofs;
    e.memory_drivers.emplace_back("modes.backend", "dense");
    e.memory_detail += " in dense matrices";
  }
  e.result_bytes = 2.0 * 8.0 * config.modes.count * size.dofs;
  e.result_drivers = {{"modes.count", std::to_string(config.modes.count)},
                      {"mast.modules", std::to_string(config.mast.modules)}};
  e.result_detail = countText(config.modes.count * size.dofs) + " shape entries";
  return e;
}

ResourceEstimate romBuildEstimate(const Config& config, double samples, int modes,
                                  const std::vector<ResourceDriver>& grid) {
  ResourceEstimate e = modesEstimate(config);
  const fullorder::MastSize size = fullorder::mastSize(config);
  e.command = "rom build";
  const double per_sample = modes * (kModeBytes + kStressModeBytesPerElement * size.elements);
  e.result_bytes = samples * per_sample;
  e.result_drivers = grid;
  e.result_drivers.emplace_back("--modes", std::to_string(modes));
  e.result_drivers.emplace_back("mast.modules", std::to_string(config.mast.modules));
  e.result_detail = countText(samples) + " samples x " + std::to_string(modes) + " modes";
  // The database is gathered in memory before it is written.
  e.memory_bytes += kDatabaseMemoryFactor * e.result_bytes;
  for (const ResourceDriver& d : grid) e.memory_drivers.push_back(d);
  e.memory_detail += ", " + e.result_detail;
  return e;
}

ResourceEstimate romEvalEstimate(const Config& c, double metrics_step_s, double database_bytes,
                                 bool stresses) {
  const fullorder::MastSize size = fullorder::mastSize(c);
  const double samples = fullorder::outputSampleCount(c);
  // The metrics' pass holds, per step of its grid, the drive sampled there and, for the stress
  // peaks' refinement between samples, η, η̇ and the stress inputs (heap profile of the streaming
  // memory benchmark: 72 and 184 bytes). The series and the stress history are streamed into the
  // file a block at a time (cli/rom_eval_output.hpp).
  const double metric_samples = std::floor(c.simulation.end_time_s / metrics_step_s) + 2.0;
  const double bytes_per_metric_sample = kDriveSampleBytes + (stresses ? kStressStateBytes : 0.0);
  ResourceEstimate e;
  e.command = "rom eval";
  e.memory_bytes = kDatabaseMemoryFactor * database_bytes + 40e6 + kStreamBlockBytes +
                   metric_samples * bytes_per_metric_sample;
  e.memory_drivers = fullorder::horizonDrivers(c);
  e.memory_detail =
      countText(metric_samples) + " metric samples held, every " + countText(metrics_step_s) + " s";
  // Per output instant in the file: the series and one largest von Mises per interface.
  const double stress_per_sample = stresses ? 8.0 * size.interfaces : 0.0;
  e.result_bytes = samples * (fullorder::resultBytesPerSample(size, false) + stress_per_sample);
  e.result_drivers = e.memory_drivers;
  e.result_detail = countText(samples) + " output samples";
  return e;
}

ResourceEstimate screenEstimate(double designs, double columns, double database_bytes,
                                const std::vector<ResourceDriver>& grid) {
  ResourceEstimate e;
  e.command = "screen";
  // The table (parameters and metrics, 8 bytes each) in memory, and its CSV or HDF5 copy.
  e.result_bytes = designs * columns * 8.0;
  e.memory_bytes = kDatabaseMemoryFactor * database_bytes + 40e6 + 2.0 * e.result_bytes;
  e.memory_drivers = grid;
  e.memory_detail = countText(designs) + " designs x " + countText(columns) + " columns";
  e.result_drivers = grid;
  e.result_detail = e.memory_detail;
  return e;
}

ResourceEstimate validateEstimate(const Config& c, int points, double database_bytes) {
  ResourceEstimate e = fullorder::simulateEstimate(c, true, true);
  e.command = "validate";
  e.memory_bytes += kDatabaseMemoryFactor * database_bytes;
  // The result: a row of errors per point (small), not the runs' series.
  e.result_bytes = points * 1e3;
  e.result_drivers = {{"--points", std::to_string(points)}};
  e.result_detail = "";
  return e;
}

}  // namespace mastrom::cli
