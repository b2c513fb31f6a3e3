// RomDatabase.optimize (see optimize_bindings.hpp).
#include "python/src/optimize_bindings.hpp"

#include <pybind11/stl.h>

#include <cmath>

#include "common/error.hpp"
#include "common/text_parsing.hpp"
#include "python/src/overrides.hpp"
#include "python/src/runtime.hpp"
#include "rom/studies/optimization.hpp"

namespace py = pybind11;

namespace mastrom::python {
namespace {

/// {metric: value} of one round's vector (NaN → None: no value).
py::dict byMetric(const std::vector<std::string>& names, const std::vector<double>& values) {
  py::dict d;
  for (std::size_t m = 0; m < names.size(); ++m)
    d[py::str(names[m])] = std::isfinite(values[m]) ? py::cast(values[m]) : py::none();
  return d;
}

}  // namespace

const char* const kOptimizeDoc =
    R"doc(Constrained optimisation on the ROM, confirmed by the full order, as `mastrom optimize`.

minimize or maximize: the objective, a metric of screen() (exactly one). subject_to: constraints
"METRIC OP VALUE" with OP <= or >= (SI units). set: free keys and database parameters held fixed,
as screen(). bounds: {key: (low, high)} narrowing a parameter's range inside the box. rounds: at
most this many optimise-and-confirm rounds; starts: COBYLA runs per round from the best of
candidates Halton designs (0: 16 per parameter). path: also write the record (.h5 or .csv).

Each round optimises on the ROM with every constraint taken with a margin of 2 x the database's
upper error estimate at the design, then runs the nonlinear full order there (and a second run at
8 x its tolerance for its own error estimate); a constraint the full order violates is tightened
by the measured difference for the next round (docs/theory.md §4.5).

Returns {"confirmed": bool, "stop_reason": str, "variables": [keys], "metrics": [objective, then
each constraint's metric], "wall_s", "rounds": [{"point": {key: value}, "bounds": [per
constraint], "rom", "margin", "full_order", "full_order_error": {metric: value or None}, "met":
[bool per constraint], "evaluations", "rom_s", "full_order_s"}]}. Bad input (an unknown metric, a
metric the database cannot give, a constraint no design meets) raises InputError before the full
order runs; the GIL is released while it runs.)doc";

py::dict optimizeDatabase(const rom::RomDatabase& db, const std::optional<std::string>& minimize,
                          const std::optional<std::string>& maximize,
                          const std::vector<std::string>& subject_to, py::handle set,
                          py::handle bounds, int rounds, int starts, int candidates,
                          const std::optional<std::string>& path) {
  MASTROM_REQUIRE(minimize.has_value() != maximize.has_value(), InputError,
                  "optimize: give exactly one of minimize= and maximize=");
  rom::OptimizeOptions options;
  options.objective = minimize ? *minimize : *maximize;
  options.sense = minimize ? rom::OptimizationSense::Minimize : rom::OptimizationSense::Maximize;
  for (const std::string& s : subject_to)
    options.constraints.push_back(rom::parseMetricConstraint(s));
  options.overrides = overridesFrom(set);
  if (!bounds.is_none()) {
    for (const auto item : py::cast<py::dict>(bounds)) {
      const auto range = py::cast<std::pair<double, double>>(item.second);
      options.bounds.push_back(rom::parseParameterBound(py::cast<std::string>(item.first) + "=" +
                                                            shortestText(range.first) + ":" +
                                                            shortestText(range.second),
                                                        db));
    }
  }
  options.rounds = rounds;
  MASTROM_REQUIRE(starts >= 1 && candidates >= 0, InputError, "optimize: starts = ", starts,
                  ", candidates = ", candidates, "; allowed: starts >= 1, candidates >= 0");
  options.search.starts = starts;
  options.search.candidates = candidates;
  rom::OptimizationResult result;
  {
    py::gil_scoped_release release;
    // The full-order check solves modes (its first step, the frequencies): SLEPc where configured.
    const std::unique_lock<std::mutex> lock = lockEigenSolvers(true);
    result = rom::runOptimization(db, options);
    if (path) {
      const bool csv = path->size() >= 4 && path->compare(path->size() - 4, 4, ".csv") == 0;
      if (csv) {
        rom::writeOptimizationCsv(*path, result);
      } else {
        rom::writeOptimizationH5(*path, result, options);
      }
    }
  }
  py::dict out;
  out["confirmed"] = result.confirmed;
  out["stop_reason"] = result.stop_reason;
  py::list variables;
  for (const int a : result.variables)
    variables.append(result.parameter_names[static_cast<std::size_t>(a)]);
  out["variables"] = variables;
  out["metrics"] = result.metrics;
  out["wall_s"] = result.wall_s;
  py::list rounds_out;
  for (const rom::OptimizationRound& r : result.rounds) {
    py::dict d;
    d["point"] = byMetric(result.parameter_names, r.point);
    d["bounds"] = r.bounds;
    d["rom"] = byMetric(result.metrics, r.rom);
    d["margin"] = byMetric(result.metrics, r.margin);
    d["full_order"] = byMetric(result.metrics, r.full);
    d["full_order_error"] = byMetric(result.metrics, r.full_error);
    py::list met;
    for (const char m : r.met) met.append(m != 0);
    d["met"] = met;
    d["evaluations"] = r.evaluations;
    d["rom_s"] = r.rom_wall_s;
    d["full_order_s"] = r.full_wall_s + r.full_estimate_wall_s;
    rounds_out.append(d);
  }
  out["rounds"] = rounds_out;
  return out;
}

}  // namespace mastrom::python
