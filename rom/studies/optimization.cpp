// The rounds of `mastrom optimize` (see optimization.hpp); the record's files are in
// optimization_io.cpp.
#include "rom/studies/optimization.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <tuple>

#include "common/error.hpp"
#include "common/text_parsing.hpp"
#include "rom/database/axis_lookup.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/database/stress_arrays.hpp"
#include "rom/studies/full_order_check.hpp"
#include "rom/studies/rom_design_evaluator.hpp"

namespace mastrom::rom {
namespace {

std::size_t metricIndex(const std::vector<std::string>& names, const std::string& metric) {
  return static_cast<std::size_t>(std::find(names.begin(), names.end(), metric) - names.begin());
}

/// The constraint's value in the form c ≤ 0, scaled by its bound's magnitude (COBYLA weighs the
/// constraints against each other and against the objective).
double scaledConstraint(const MetricConstraint& c, double bound, double value, double margin) {
  const double scale = std::abs(c.bound) > 0.0 ? std::abs(c.bound) : 1.0;
  return (c.at_most ? value + margin - bound : bound - (value - margin)) / scale;
}

/// The set-up shared by every round: which axes vary and over what range.
struct Variables {
  std::vector<int> axes;
  std::vector<double> lower, upper;
  std::vector<double> point(const std::vector<double>& base, const std::vector<double>& u) const {
    std::vector<double> p = base;
    for (std::size_t k = 0; k < axes.size(); ++k)
      p[static_cast<std::size_t>(axes[k])] = lower[k] + u[k] * (upper[k] - lower[k]);
    return p;
  }
};

Variables variablesOf(const RomDatabase& db, const OptimizeOptions& options) {
  std::vector<char> fixed(db.axes.size(), 0);
  for (const std::string& o : options.overrides) {
    const int a = axisIndex(db, trimBlanks(o.substr(0, o.find('='))));
    if (a >= 0) fixed[static_cast<std::size_t>(a)] = 1;
  }
  Variables v;
  for (std::size_t a = 0; a < db.axes.size(); ++a) {
    if (fixed[a]) continue;
    v.axes.push_back(static_cast<int>(a));
    v.lower.push_back(db.axes[a].values.front());
    v.upper.push_back(db.axes[a].values.back());
  }
  for (const ParameterBound& b : options.bounds) {
    const int a = axisIndex(db, b.key);
    MASTROM_REQUIRE(!fixed[static_cast<std::size_t>(a)], InputError, "--bound ", b.key,
                    ": the parameter is held by --set; give one of the two");
    const auto k =
        static_cast<std::size_t>(std::find(v.axes.begin(), v.axes.end(), a) - v.axes.begin());
    v.lower[k] = b.lower;
    v.upper[k] = b.upper;
  }
  MASTROM_REQUIRE(!v.axes.empty(), InputError, "optimize: every parameter of the database (",
                  axisKeys(db), ") is held by --set; nothing is left to optimise");
  return v;
}

/// InputError for a first round that found no design meeting the constraints with their margins:
/// the constraint that no design meets alone, or the set of them.
[[noreturn]] void refuseInfeasible(const OptimizeOptions& options, const MultiStartResult& r) {
  for (std::size_t i = 0; i < options.constraints.size(); ++i) {
    if (r.least_constraint[i] <= 0.0) continue;
    const MetricConstraint& c = options.constraints[i];
    const double scale = std::abs(c.bound) > 0.0 ? std::abs(c.bound) : 1.0;
    const double reach = c.at_most ? c.bound + r.least_constraint[i] * scale
                                   : c.bound - r.least_constraint[i] * scale;
    throw InputError(detail::concat(
        "optimize: --subject-to '", c.text, "' is met by no design in the box: the ",
        c.at_most ? "least " : "largest ", c.metric, c.at_most ? " + margin" : " - margin",
        " found is ", shortestText(reach), " (the margin is ", kMarginFactor,
        " x the ROM's estimated error at the design)"));
  }
  std::string all;
  for (const MetricConstraint& c : options.constraints)
    all += (all.empty() ? "'" : ", '") + c.text + "'";
  throw InputError("optimize: no design in the box meets the constraints " + all +
                   " together (each alone is met somewhere; the margin is the ROM's estimated "
                   "error at the design)");
}

}  // namespace

std::vector<double> tightenedBounds(const std::vector<MetricConstraint>& constraints,
                                    const OptimizationRound& round) {
  std::vector<double> bounds = round.bounds;
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    if (round.met[i]) continue;
    // Towards the constraint's safe side, whatever the sign of the difference: a violated
    // constraint never loosens.
    const double d = std::abs(round.full[i + 1] - round.rom[i + 1]);
    bounds[i] += constraints[i].at_most ? -d : d;
  }
  return bounds;
}

bool OptimizationRound::allMet() const {
  return std::all_of(met.begin(), met.end(), [](char m) { return m != 0; });
}

ParameterBound parseParameterBound(const std::string& text, const RomDatabase& db) {
  const std::string given = "--bound '" + text + "'";
  const std::size_t eq = text.find('=');
  const std::vector<std::string> parts =
      splitAt(eq == std::string::npos ? std::string() : text.substr(eq + 1), ':');
  ParameterBound b;
  b.key = trimBlanks(text.substr(0, eq));
  MASTROM_REQUIRE(eq != std::string::npos && parts.size() == 2 && !b.key.empty() &&
                      parseStrictNumber(parts[0], b.lower) && parseStrictNumber(parts[1], b.upper),
                  InputError, given,
                  " is malformed: expected KEY=LO:HI with finite numbers, e.g. "
                  "--bound interface.thickness=0.001:0.0015");
  const int a = axisIndex(db, b.key);
  MASTROM_REQUIRE(a >= 0, InputError, given, ": ", b.key,
                  " is not a parameter of this database (parameters: ", axisKeys(db), ")");
  const ParameterAxis& axis = db.axes[static_cast<std::size_t>(a)];
  const double lo = axis.values.front(), hi = axis.values.back();
  MASTROM_REQUIRE(b.lower < b.upper && b.lower >= lo && b.upper <= hi, InputError, given,
                  ": allowed LO < HI inside the database's range [", shortestText(lo), ", ",
                  shortestText(hi), "]");
  return b;
}

OptimizationResult runOptimization(const RomDatabase& db, const OptimizeOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  MASTROM_REQUIRE(options.rounds >= 1 && options.rounds <= 20, InputError, "--rounds ",
                  options.rounds, " is out of range; allowed: 1 to 20");
  const RomDesignEvaluator rom(db, options.overrides);
  const bool stresses = databaseHasStresses(db);
  requireOptimizable(options.objective,
                     options.sense == OptimizationSense::Minimize ? "--minimize" : "--maximize",
                     options.objective, false, rom.names(), stresses);
  for (const MetricConstraint& c : options.constraints)
    requireOptimizable(c.metric, "--subject-to", c.text, true, rom.names(), stresses);
  const auto [f_est, r_est] = rom.upperErrorEstimate(rom.basePoint());
  MASTROM_REQUIRE(options.constraints.empty() || (f_est >= 0.0 && r_est >= 0.0), InputError,
                  "optimize: this database carries no error estimate (no held-out probes, no "
                  "leave-one-out), so no constraint can be taken with the ROM's error against "
                  "it; rebuild it with rom build");
  const Variables vars = variablesOf(db, options);

  OptimizationResult result;
  for (const ParameterAxis& a : db.axes) {
    result.parameter_names.push_back(a.key);
    result.parameter_units.push_back(configKeyUnits(a.key));
  }
  result.variables = vars.axes;
  result.lower = vars.lower;
  result.upper = vars.upper;
  std::vector<std::size_t> columns{metricIndex(rom.names(), options.objective)};
  for (const MetricConstraint& c : options.constraints)
    columns.push_back(metricIndex(rom.names(), c.metric));
  for (const std::size_t c : columns) {
    result.metrics.push_back(rom.names()[c]);
    result.metric_units.push_back(rom.units()[c]);
  }
  result.pointwise_estimate = rom.pointwiseEstimate();
  result.config_toml = toToml(rom.config());

  const std::size_t nc = options.constraints.size();
  const FullOrderTruth truth =
      options.full_order
          ? options.full_order
          : FullOrderTruth([&options](const Config& c, const std::vector<std::string>& names) {
              return checkWithFullOrder(c, names, options.full_order_progress);
            });
  std::vector<double> bounds;
  for (const MetricConstraint& c : options.constraints) bounds.push_back(c.bound);
  const double sign = options.sense == OptimizationSense::Minimize ? 1.0 : -1.0;

  for (int round = 1; round <= options.rounds; ++round) {
    // 1. The ROM's optimum under this round's bounds.
    const auto rom_start = std::chrono::steady_clock::now();
    BoxProblem problem;
    problem.dimension = static_cast<int>(vars.axes.size());
    problem.constraints = static_cast<int>(nc);
    problem.evaluate = [&](const std::vector<double>& u, double& objective,
                           std::vector<double>& constraints) {
      const std::vector<double> p = vars.point(rom.basePoint(), u);
      const std::vector<double> m = rom.metrics(p);
      objective = sign * m[columns[0]];
      if (nc == 0) return;
      const auto [ef, er] = rom.upperErrorEstimate(p);
      for (std::size_t i = 0; i < nc; ++i) {
        const double margin = conservativeMargin(rom.names(), m, columns[i + 1], ef, er);
        constraints[i] =
            scaledConstraint(options.constraints[i], bounds[i], m[columns[i + 1]], margin);
      }
    };
    const MultiStartResult best = minimizeOnUnitBox(problem, options.search);
    if (!best.feasible) {
      if (round == 1) refuseInfeasible(options, best);
      result.stop_reason = detail::concat(
          "after round ", round - 1,
          " the tightened constraints are met by no design in the box "
          "with their margins: the ROM cannot reach a design the full order accepts here");
      break;
    }
    OptimizationRound r;
    r.point = vars.point(rom.basePoint(), best.u);
    r.bounds = bounds;
    r.evaluations = best.evaluations;
    r.runs = best.runs;
    r.feasible_runs = best.feasible_runs;
    const std::vector<double> m = rom.metrics(r.point);
    std::tie(r.frequency_estimate, r.response_estimate) = rom.upperErrorEstimate(r.point);
    for (const std::size_t c : columns) {
      r.rom.push_back(m[c]);
      r.margin.push_back(conservativeMargin(rom.names(), m, c, std::max(r.frequency_estimate, 0.0),
                                            std::max(r.response_estimate, 0.0)));
    }
    // The objective's margin is reported (what its value may be off by), not applied.
    r.rom_wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - rom_start).count();
    if (options.log)
      options.log(detail::concat("round ", round, ": ROM optimum after ", r.evaluations,
                                 " designs (", r.runs, " COBYLA runs), ", r.rom_wall_s,
                                 " s; full order at that design..."));

    // 2. The full order there.
    const Config at = applyOverrides(rom.config(), parameterOverrides(db.axes, r.point));
    const FullOrderCheck full = truth(at, result.metrics);
    MASTROM_REQUIRE(
        full.values.size() == columns.size() && full.estimated_error.size() == columns.size(),
        UsageError, "optimize: the full-order check returned ", full.values.size(), " values for ",
        columns.size(), " metrics");
    r.full = full.values;
    r.full_error = full.estimated_error;
    r.full_wall_s = full.wall_s;
    r.full_estimate_wall_s = full.estimate_wall_s;
    r.full_modes_wall_s = full.modes_wall_s;
    r.full_first_step_s = full.first_step_s;
    r.full_note = full.first_step_note;
    for (std::size_t i = 0; i < nc; ++i) {
      const MetricConstraint& c = options.constraints[i];
      const double f = r.full[i + 1];
      r.met.push_back(std::isfinite(f) && (c.at_most ? f <= c.bound : f >= c.bound));
    }
    result.rounds.push_back(r);
    const auto missing =
        std::find_if(r.full.begin(), r.full.end(), [](double v) { return !std::isfinite(v); });
    if (missing != r.full.end()) {
      result.stop_reason = "the full order gives no value of " +
                           result.metrics[static_cast<std::size_t>(missing - r.full.begin())] +
                           ": the design cannot be confirmed";
      break;
    }
    if (r.allMet()) {
      result.confirmed = true;
      result.stop_reason = detail::concat("round ", round,
                                          ": the full order meets every constraint at the ROM's "
                                          "optimum");
      break;
    }
    // 3. Tighten each violated constraint by the measured difference.
    bounds = tightenedBounds(options.constraints, r);
    if (round == options.rounds)
      result.stop_reason = detail::concat("the full order still violates a constraint after ",
                                          options.rounds, " rounds (--rounds)");
  }
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace mastrom::rom
