// `mastrom optimize` (docs/theory.md §4.5): the design of a ROM database's box that minimises or
// maximises one metric subject to bounds on others, confirmed by the nonlinear full order.
//
// Each round:
//  1. optimise on the ROM — NLopt's COBYLA from the best of a Halton set of designs
//     (rom/studies/multistart_optimizer.hpp) over the database's parameters (the box, narrowed by
//     bounds; a parameter given with --set is held), every constraint taken with the conservative
//     margin of the ROM's estimated error at the design (rom/studies/optimization_problem.hpp);
//  2. run the full order at that design (rom/studies/full_order_check.hpp) and compare, metric by
//     metric, with its own error estimate beside;
//  3. every constraint met by the full order: confirmed, stop. Otherwise tighten each violated
//     constraint by the measured difference d = full − ROM (towards its safe side: a bound
//     "≤ b" becomes b − d, "≥ b" becomes b + |d|) and go to 1, up to `rounds` rounds.
// This is the surrogate-based loop of Dakota's SBO with the full order as the truth model, where
// the ROM's own error estimate supplies the trust margin.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "common/config.hpp"
#include "fullorder/deployment.hpp"
#include "rom/database/rom_database.hpp"
#include "rom/studies/full_order_check.hpp"
#include "rom/studies/multistart_optimizer.hpp"
#include "rom/studies/optimization_problem.hpp"

namespace mastrom::rom {

/// A parameter's range narrowed inside the database's box: "KEY=LO:HI".
struct ParameterBound {
  std::string key;
  double lower = 0.0, upper = 0.0;
};

/// Parse "KEY=LO:HI" against the database: KEY one of its parameters, LO < HI, both finite and
/// inside its range. InputError (one line naming the text, the key's range) otherwise.
ParameterBound parseParameterBound(const std::string& text, const RomDatabase& db);

struct OptimizeOptions {
  std::string objective;  ///< a screen metric
  OptimizationSense sense = OptimizationSense::Minimize;
  std::vector<MetricConstraint> constraints;
  std::vector<std::string> overrides;  ///< --set: free keys, or database parameters held fixed
  std::vector<ParameterBound> bounds;  ///< narrowed ranges (the rest: the database's box)
  int rounds = 3;                      ///< optimise + full-order check, at most this many times
  MultiStartOptions search;
  /// A line of progress (each round's ROM optimum, the full order's start); may be empty.
  std::function<void(const std::string&)> log;
  fullorder::DeploymentProgress full_order_progress;
  /// The truth each round is checked against; empty: the nonlinear full order
  /// (checkWithFullOrder with full_order_progress).
  FullOrderTruth full_order;
};

/// One round: the ROM's optimum under the round's bounds and the full order there. Metric vectors
/// run over OptimizationResult::metrics (the objective, then one per constraint).
struct OptimizationRound {
  std::vector<double> point;   ///< every database axis
  std::vector<double> bounds;  ///< per constraint, the bound this round used (tightened)
  std::vector<double> rom, margin, full, full_error;
  std::vector<char> met;  ///< per constraint: the full order meets the original bound
  double frequency_estimate = -1.0, response_estimate = -1.0;  ///< (e_ω, e_r) upper, at the point
  int evaluations = 0, runs = 0, feasible_runs = 0;
  double rom_wall_s = 0.0, full_wall_s = 0.0, full_estimate_wall_s = 0.0, full_modes_wall_s = 0.0;
  double full_first_step_s = 0.0;  ///< FullOrderCheck::first_step_s (0: fixed steps)
  std::string full_note;           ///< FullOrderCheck::first_step_note
  bool allMet() const;
};

/// The next round's bounds: `round.bounds` with every constraint the full order violated moved by
/// |full − ROM| of its metric towards its safe side (≤ b → b − |d|, ≥ b → b + |d|).
std::vector<double> tightenedBounds(const std::vector<MetricConstraint>& constraints,
                                    const OptimizationRound& round);

struct OptimizationResult {
  std::vector<std::string> parameter_names, parameter_units;  ///< every database axis
  std::vector<int> variables;                                 ///< axes optimised
  std::vector<double> lower, upper;                           ///< per variable
  std::vector<std::string> metrics, metric_units;  ///< objective, then each constraint's metric
  std::vector<OptimizationRound> rounds;
  bool confirmed = false;   ///< the last round's design meets every constraint in the full order
  std::string stop_reason;  ///< one sentence: why the rounds ended
  bool pointwise_estimate = false;  ///< margins from the point estimate (else box-wide)
  std::string config_toml;          ///< base configuration with --set
  double wall_s = 0.0;
};

/// Run the rounds. Every input error is found before the first full-order run: an unknown or
/// unavailable metric, a constraint (or the set of them) that no design of the box meets with its
/// margin in the first round (InputError naming it), a bound, a --set value.
OptimizationResult runOptimization(const RomDatabase& db, const OptimizeOptions& options);

/// The record of the rounds. HDF5: /optimize/parameter_names, /optimize/variables (axis indices),
/// /optimize/lower, /optimize/upper, /optimize/metric_names, /optimize/metric_units,
/// /optimize/points [R, p], /optimize/bounds [R, c], /optimize/rom, /optimize/margin,
/// /optimize/full_order, /optimize/full_order_error [R, q] (−1: no estimate), /optimize/met [R, c]
/// (0/1), /optimize/evaluations [R], /optimize/rom_wall_time, /optimize/full_wall_time [R];
/// root attributes source = "optimize", objective, sense, constraints (the texts, one string with
/// "; "), confirmed, stop_reason, margin_factor, config, mastrom_version, wall_time_s.
/// CSV: a row per round (round, parameters, then per metric rom, margin, full_order,
/// full_order_error, and per constraint bound and met). Both written atomically.
void writeOptimizationH5(const std::string& path, const OptimizationResult& result,
                         const OptimizeOptions& options);
void writeOptimizationCsv(const std::string& path, const OptimizationResult& result);

}  // namespace mastrom::rom
