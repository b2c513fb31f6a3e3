// Constrained minimisation on the unit box by NLopt, started from a space-filling set
// (docs/theory.md §4.5): the engine of `mastrom optimize`, kept free of the ROM so that it can be
// checked on analytic problems with known optima.
//
// The problem: minimise f(u) over u ∈ [0, 1]^n subject to c_i(u) ≤ 0, where one evaluation gives
// f and every c_i (a ROM deployment gives all metrics at once). No derivatives: the metrics are
// peaks of a time response, continuous but only piecewise smooth in the parameters, and a finite
// difference would cost n deployments per gradient. So the local solver is COBYLA [Pow94] (linear
// approximations of f and c on a simplex, a trust region that shrinks to the requested tolerance),
// the derivative-free method of NLopt that takes nonlinear inequality constraints directly.
//
// COBYLA is local. The starts: the first `candidates` Halton points of the box [Hal60] (the same
// sequence as rom/offline/space_filling.hpp) are evaluated, ranked feasible first by objective,
// then infeasible by total violation, and the best `starts` of them each start one COBYLA run. The
// result is the best feasible end point of all runs (the evaluated candidates included).
//
// When no evaluated point is feasible, each constraint is minimised alone (from its best point) to
// tell a constraint that no design in the box meets from constraints that only exclude each other.
#pragma once

#include <functional>
#include <vector>

namespace mastrom::rom {

/// What one evaluation at u returns: the objective and every constraint value (≤ 0 is met).
using BoxProblemEvaluation = std::function<void(const std::vector<double>& u, double& objective,
                                                std::vector<double>& constraints)>;

struct BoxProblem {
  int dimension = 0;    ///< n ≥ 1
  int constraints = 0;  ///< number of c_i
  BoxProblemEvaluation evaluate;
};

struct MultiStartOptions {
  int candidates = 0;  ///< Halton points evaluated first; 0: 16 n (at least 16)
  int starts = 4;      ///< COBYLA runs from the best candidates
  /// COBYLA's last trust-region radius in the unit box: the optimum's position to about this.
  double point_tolerance = 1e-4;
  int evaluations_per_start = 0;  ///< 0: 100 n
};

struct MultiStartResult {
  bool feasible = false;  ///< a point with every c_i ≤ 0 was found
  std::vector<double> u;  ///< the best point (feasible, else of least total violation)
  double objective = 0.0;
  std::vector<double> constraints;
  int evaluations = 0;    ///< of the problem, over the candidates, the runs and any diagnosis
  int runs = 0;           ///< COBYLA runs made
  int feasible_runs = 0;  ///< runs that ended at a feasible point
  /// When !feasible: per constraint the least value found minimising it alone (> 0: no point of
  /// the box meets it); empty when a feasible point was found.
  std::vector<double> least_constraint;
};

/// Minimise `problem` (see the header). Throws UsageError for a problem without evaluation or
/// dimension < 1, NumericalError when NLopt fails for a reason other than its stopping tests.
MultiStartResult minimizeOnUnitBox(const BoxProblem& problem,
                                   const MultiStartOptions& options = {});

}  // namespace mastrom::rom
