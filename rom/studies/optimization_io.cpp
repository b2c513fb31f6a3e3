// The record of an optimisation's rounds as HDF5 and CSV (layouts in optimization.hpp).
#include <cmath>
#include <sstream>

#include "common/hdf5_file.hpp"
#include "common/text_file.hpp"
#include "common/text_parsing.hpp"
#include "common/version.hpp"
#include "rom/database/h5_arrays.hpp"
#include "rom/studies/optimization.hpp"

namespace mastrom::rom {
namespace {

/// Files never hold NaN: −1 marks "no estimate" (as in the validation file).
double orMinusOne(double v) { return std::isfinite(v) ? v : -1.0; }

std::string constraintTexts(const OptimizeOptions& options) {
  std::string s;
  for (const MetricConstraint& c : options.constraints) s += (s.empty() ? "" : "; ") + c.text;
  return s;
}

}  // namespace

void writeOptimizationH5(const std::string& path, const OptimizationResult& result,
                         const OptimizeOptions& options) {
  const std::size_t nr = result.rounds.size(), p = result.parameter_names.size(),
                    q = result.metrics.size(), nc = q - 1;
  std::vector<double> points, bounds, rom, margin, full, full_error, evaluations, rom_wall,
      full_wall, modes_wall, first_step, met;
  std::vector<std::string> notes;
  for (const OptimizationRound& r : result.rounds) {
    points.insert(points.end(), r.point.begin(), r.point.end());
    bounds.insert(bounds.end(), r.bounds.begin(), r.bounds.end());
    rom.insert(rom.end(), r.rom.begin(), r.rom.end());
    margin.insert(margin.end(), r.margin.begin(), r.margin.end());
    for (std::size_t m = 0; m < q; ++m) {
      full.push_back(orMinusOne(r.full[m]));
      full_error.push_back(orMinusOne(r.full_error[m]));
    }
    for (const char m : r.met) met.push_back(m ? 1.0 : 0.0);
    evaluations.push_back(r.evaluations);
    rom_wall.push_back(r.rom_wall_s);
    full_wall.push_back(r.full_wall_s + r.full_estimate_wall_s);
    modes_wall.push_back(r.full_modes_wall_s);
    first_step.push_back(r.full_first_step_s);
    notes.push_back(r.full_note);
  }
  std::vector<int> variables(result.variables.begin(), result.variables.end());
  h5::AtomicH5Writer writer(path);
  h5::File& f = writer.file();
  f.createGroup("/optimize");
  h5x::writeStrings(f, "/optimize/parameter_names", result.parameter_names);
  h5x::setStringArrayAttribute(f, "/optimize/parameter_names", "units", result.parameter_units);
  h5x::writeInts(f, "/optimize/variables", {variables.size()}, variables.data(), "1");
  h5x::writeDoubles(f, "/optimize/lower", {result.lower.size()}, result.lower.data(), "SI");
  h5x::writeDoubles(f, "/optimize/upper", {result.upper.size()}, result.upper.data(), "SI");
  h5x::writeStrings(f, "/optimize/metric_names", result.metrics);
  h5x::writeStrings(f, "/optimize/metric_units", result.metric_units);
  h5x::writeDoubles(f, "/optimize/points", {nr, p}, points.data(), "SI (see parameter_names)");
  h5x::writeDoubles(f, "/optimize/bounds", {nr, nc}, bounds.data(), "SI (see metric_units)");
  h5x::writeDoubles(f, "/optimize/rom", {nr, q}, rom.data(), "SI (see metric_units)");
  h5x::writeDoubles(f, "/optimize/margin", {nr, q}, margin.data(), "SI (see metric_units)");
  h5x::writeDoubles(f, "/optimize/full_order", {nr, q}, full.data(), "SI (see metric_units)");
  h5x::writeDoubles(f, "/optimize/full_order_error", {nr, q}, full_error.data(),
                    "SI (see metric_units; -1: none)");
  h5x::writeDoubles(f, "/optimize/met", {nr, nc}, met.data(), "1");
  h5x::writeDoubles(f, "/optimize/evaluations", {nr}, evaluations.data(), "1");
  h5x::writeDoubles(f, "/optimize/rom_wall_time", {nr}, rom_wall.data(), "s");
  h5x::writeDoubles(f, "/optimize/full_wall_time", {nr}, full_wall.data(), "s");
  // The full-order check's modal solves (its first step's, the frequencies') and the first step
  // they gave, with the note saying why it is shorter than simulation.time_step (empty if not).
  h5x::writeDoubles(f, "/optimize/full_modes_wall_time", {nr}, modes_wall.data(), "s");
  h5x::writeDoubles(f, "/optimize/full_first_step", {nr}, first_step.data(), "s (0: fixed steps)");
  h5x::writeStrings(f, "/optimize/full_first_step_note", notes);
  f.setStringAttribute("/", "source", "optimize");
  f.setStringAttribute("/", "objective", options.objective);
  f.setStringAttribute("/", "sense",
                       options.sense == OptimizationSense::Minimize ? "minimize" : "maximize");
  f.setStringAttribute("/", "constraints", constraintTexts(options));
  f.setDoubleAttribute("/", "confirmed", result.confirmed ? 1.0 : 0.0);
  f.setStringAttribute("/", "stop_reason", result.stop_reason);
  f.setDoubleAttribute("/", "margin_factor", kMarginFactor);
  f.setDoubleAttribute("/", "max_rounds", options.rounds);
  f.setStringAttribute("/", "config", result.config_toml);
  f.setStringAttribute("/", "mastrom_version", kVersion);
  f.setDoubleAttribute("/", "wall_time_s", result.wall_s);
  writer.commit();
}

void writeOptimizationCsv(const std::string& path, const OptimizationResult& result) {
  std::ostringstream out;
  out << "round";
  for (const std::string& n : result.parameter_names) out << ',' << n;
  for (std::size_t m = 0; m < result.metrics.size(); ++m) {
    const std::string& n = result.metrics[m];
    if (m > 0) out << ",bound:" << n;
    out << ",rom:" << n << ",margin:" << n << ",full_order:" << n << ",full_order_error:" << n;
    if (m > 0) out << ",met:" << n;
  }
  out << '\n';
  for (std::size_t i = 0; i < result.rounds.size(); ++i) {
    const OptimizationRound& r = result.rounds[i];
    out << i + 1;
    for (const double v : r.point) out << ',' << shortestText(v);
    for (std::size_t m = 0; m < result.metrics.size(); ++m) {
      if (m > 0) out << ',' << shortestText(r.bounds[m - 1]);
      out << ',' << shortestText(r.rom[m]) << ',' << shortestText(r.margin[m]) << ','
          << shortestText(orMinusOne(r.full[m])) << ','
          << shortestText(orMinusOne(r.full_error[m]));
      if (m > 0) out << ',' << (r.met[m - 1] ? 1 : 0);
    }
    out << '\n';
  }
  writeTextFileAtomically(path, out.str());
}

}  // namespace mastrom::rom
