#include "fullorder/run_footprint.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mastrom::fullorder {
namespace {

// Measured (benchmarks/README.md "Resource estimates": peak RSS of `simulate` over 1 ms, one
// thread): the process before the model, the growth per shell element (matrix patterns, element
// data, factorisations) and a term in elements × interfaces: today's memory grows faster than the
// length of the chain (64 modules take 11× the memory of 4, not 16×), and with the length, not
// with the ring's refinement. Fitted at 4, 32 and 128 modules of the default 2 × 8 ring; checked
// at 2, 8, 16 and 64 modules and on a 4 × 16 ring.
constexpr double kProcessBytes = 38.7e6;
constexpr double kBytesPerElement = 265e3;
constexpr double kBytesPerElementInterface = 16 * 301.0;

// Per output instant in a file (results_io.hpp): /time, /drive ×3, /end/angular_acceleration ×3,
// /end/relative_angular_acceleration, /end/position ×3, /end/acceleration ×3,
// /end/tangential_acceleration, /joint/force ×3, /joint/torque, /solver/constraint_residual
// (23 doubles) and /solver/newton_iterations (int32).
constexpr double kSeriesBytesPerSample = 23 * 8 + 4;
// Per interface in memory (interface_stress.hpp): max von Mises and four 3-vectors of edge
// resultants; in the file (interface_stress_io.hpp) also the axial, shear, torsional and bending
// parts of both edges.
constexpr double kStressBytesPerSample = 13 * 8;
constexpr double kStressFileBytesPerSample = 21 * 8;
// A file's least size: one chunk of 4096 rows of every series dataset is allocated however few
// rows there are, and the stress fields, mesh and attributes.
constexpr double kFileBaseBytes = 4096 * (23 * 8 + 4) + 0.1e6;
// A deployment series in memory (DeploymentSeries: the same columns without the tangential
// acceleration) and the vector growth slack, on average half again.
constexpr double kSeriesMemoryPerSample = 1.5 * (22 * 8 + 4);
// A streamed run's buffer: one block of the result stream (fullorder/result_stream.hpp).
constexpr double kStreamBlockBytes = 4096 * (22 * 8 + 4);

std::string text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", value);
  return buffer;
}

}  // namespace

std::string countText(double count) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", count);
  return buffer;
}

MastSize mastSize(const Config& config) {
  MastSize s;
  s.modules = config.mast.modules;
  s.interfaces = std::max(0, s.modules - 1);
  s.dofs = 12.0 * s.modules;
  s.constraints = 6.0 * s.modules + 6.0;
  // Interfaces without their own [interface.K] keys share the [interface] mesh: count those at
  // once (a typo of 10⁵ modules must not loop 10⁵ times over the items to be refused).
  const auto add = [&s](const InterfaceConfig& itf, double count) {
    const double ring = itf.elements_circumferential;
    s.elements += count * itf.elements_axial * ring;
    s.dofs += count * 9.0 * (itf.elements_axial + 1) * ring;
    s.constraints += count * 7.0 * 2.0 * ring;
  };
  int itemised = 0;
  for (const auto& [k, item] : config.interface_items) {
    if (k < 1 || k > s.interfaces) continue;
    add(config.interfaceItem(k), 1.0);
    ++itemised;
  }
  add(config.interface, static_cast<double>(s.interfaces - itemised));
  return s;
}

double fullOrderModelBytes(const MastSize& size) {
  return kProcessBytes + kBytesPerElement * size.elements +
         kBytesPerElementInterface * size.elements * size.interfaces;
}

double outputSampleCount(const Config& config) {
  const double end = config.simulation.end_time_s;
  if (config.simulation.adaptive) return std::floor(end / outputInterval(config)) + 2.0;
  const double steps = std::ceil(end / config.simulation.time_step_s - 1e-9);
  return std::floor(steps / config.output.every) + 2.0;
}

double resultBytesPerSample(const MastSize& size, bool with_stresses) {
  return kSeriesBytesPerSample +
         (with_stresses ? kStressFileBytesPerSample * size.interfaces : 0.0);
}

std::vector<ResourceDriver> mastDrivers(const Config& config) {
  return {{"mast.modules", std::to_string(config.mast.modules)},
          {"interface.elements_axial", std::to_string(config.interface.elements_axial)},
          {"interface.elements_circumferential",
           std::to_string(config.interface.elements_circumferential)}};
}

std::vector<ResourceDriver> horizonDrivers(const Config& config) {
  std::vector<ResourceDriver> drivers{{"simulation.end_time", text(config.simulation.end_time_s)}};
  if (config.simulation.adaptive) {
    drivers.emplace_back("output.step", config.output.step_s
                                            ? text(*config.output.step_s)
                                            : text(outputInterval(config)) + " (default)");
  } else {
    drivers.emplace_back("simulation.time_step", text(config.simulation.time_step_s));
    drivers.emplace_back("output.every", std::to_string(config.output.every));
  }
  return drivers;
}

double stressHistoryMemoryBytes(const MastSize& size, double samples) {
  // The monitor's histories with their growth slack (up to 2×), and the resampled copy written at
  // the end; measured 1.3× (2 s of Scheme 3) to 2.1× (8 s) the histories' bytes at the peak.
  return samples * ((kStressBytesPerSample * size.interfaces + 8.0) * 2.2 + 1.5 * 8.0);
}

double seriesMemoryBytes(double samples) { return kSeriesMemoryPerSample * samples; }

ResourceEstimate simulateEstimate(const Config& config, bool series_in_memory, bool with_stresses,
                                  bool estimate_error) {
  const MastSize size = mastSize(config);
  const double samples = outputSampleCount(config);
  ResourceEstimate e;
  e.command = "simulate";
  e.memory_bytes = fullOrderModelBytes(size) + kStreamBlockBytes;
  e.memory_drivers = mastDrivers(config);
  e.memory_detail = countText(size.dofs) + " DOFs, " + countText(size.elements) + " shell elements";
  const bool grows = series_in_memory || estimate_error;
  if (grows) {
    for (ResourceDriver& d : horizonDrivers(config)) e.memory_drivers.push_back(std::move(d));
    e.memory_detail += ", " + countText(samples) + " output samples held";
  }
  // Streamed, the stress histories cost the appender's block (InterfaceStressAppender: about
  // 4096 rows of 21 doubles in all, with the rows' own vectors) and the resampler's few instants.
  if (with_stresses)
    e.memory_bytes +=
        series_in_memory ? stressHistoryMemoryBytes(size, samples) : kStreamBlockBytes;
  // The adaptive run's step points (about one per output instant at the default output.step)
  // and the output series; the error estimate's second run holds both again.
  if (series_in_memory) e.memory_bytes += 2.0 * seriesMemoryBytes(samples);
  else if (estimate_error)
    e.memory_bytes += sizeof(double) * samples;
  e.result_bytes = kFileBaseBytes + samples * resultBytesPerSample(size, with_stresses);
  e.result_drivers = horizonDrivers(config);
  if (with_stresses)
    e.result_drivers.emplace_back("mast.modules", std::to_string(config.mast.modules));
  e.result_detail = countText(samples) + " output samples";
  return e;
}

}  // namespace mastrom::fullorder
