// Pareto fronts of a screen (`mastrom screen --pareto OBJ[:min|max],…`, docs/user_guide.md §3):
// the designs no other design beats in every objective at once.
//
// With every objective turned into one to minimise (a maximised one negated), design a dominates
// design b when a is no worse in every objective and better in at least one; the front is the set
// of designs no design dominates. Equal designs do not dominate each other: both stay on the front.
// A design with a NaN objective is on no front and dominates nothing.
//
// Algorithm: in lexicographic order of the objective vectors a design can be dominated only by one
// before it (a dominates b implies a ≤ b componentwise and a ≠ b, so a precedes b), and if it is
// dominated at all, then by a design of the front (dominance is transitive and the chain ends on
// the front). So one pass in that order, comparing each design with the front found so far, decides
// every design: O(n log n + n·|front|·k) instead of the O(n² k) of comparing all pairs.
#pragma once

#include <string>
#include <vector>

#include "rom/studies/design_metrics.hpp"
#include "rom/studies/screening.hpp"

namespace mastrom::rom {

struct ParetoObjective {
  std::string metric;
  bool maximize = false;  ///< ":max"; ":min" or nothing minimises
};

/// Parse "OBJ[:min|max],OBJ[:min|max],…" (at least two objectives, none repeated). InputError
/// naming `option` and the text otherwise. The names are checked against a table separately.
std::vector<ParetoObjective> parseParetoObjectives(const std::string& text,
                                                   const std::string& option = "--pareto");

/// The objectives as the root attribute of a screen file: "mass:min,frequency_1:max".
std::string paretoText(const std::vector<ParetoObjective>& objectives);

/// 1 for every row of `values` (rows × k, row-major, objective j in column j) on the front, 0 for
/// the others; maximize[j] says the sense of column j.
std::vector<char> nonDominated(const std::vector<double>& values, std::size_t k,
                               const std::vector<bool>& maximize);

/// The name of the front's column in a screen table (1: on the front, 0: not).
inline constexpr const char* kParetoColumn = "pareto_front";

/// Check the objectives against a table's metric columns (metricIndex: one line naming `option`,
/// the metric and why it is unknown or not available).
void checkParetoObjectives(const MetricColumns& columns,
                           const std::vector<ParetoObjective>& objectives,
                           const std::string& option = "--pareto");

/// Append the kParetoColumn metric to `table` (1 on the front of `objectives` over its rows) and
/// record the objectives (ScreenTable::pareto_objectives).
void markParetoFront(ScreenTable& table, const std::vector<ParetoObjective>& objectives);

/// Keep only the rows on the front (in their order); the number removed.
long keepParetoFront(ScreenTable& table);

}  // namespace mastrom::rom
