// Multi-start COBYLA on the unit box (see multistart_optimizer.hpp).
#include "rom/studies/multistart_optimizer.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <nlopt.hpp>
#include <numeric>

#include "common/error.hpp"
#include "rom/offline/space_filling.hpp"

namespace mastrom::rom {
namespace {

/// COBYLA ends on the constraints' boundary to within its own round-off, on either side. It is
/// handed c_i + kInsideShift so that its end point meets c_i ≤ 0 itself (the problem's constraints
/// are scaled to O(1) by the caller: rom/studies/optimization.cpp).
constexpr double kInsideShift = 1e-7;
/// The first trust-region radius in the unit box: about the spacing of 16 n Halton points in
/// n ≤ 5 dimensions, so that a run explores its start's neighbourhood before it contracts.
constexpr double kInitialStep = 0.1;

struct Point {
  std::vector<double> u;
  double objective = 0.0;
  std::vector<double> constraints;
  double violation() const {
    double v = 0.0;
    for (double c : constraints) v += std::max(c, 0.0);
    return v;
  }
  bool feasible() const { return violation() == 0.0; }
};

/// Feasible first (by objective), then by total violation.
bool better(const Point& a, const Point& b) {
  if (a.feasible() != b.feasible()) return a.feasible();
  if (a.feasible()) return a.objective < b.objective;
  return a.violation() < b.violation();
}

/// The evaluations of one problem, with the last point cached (COBYLA asks the objective and then
/// the constraints at the same point) and the best point seen kept.
class Evaluator {
public:
  explicit Evaluator(const BoxProblem& p) : problem_(p) {}

  const Point& at(const double* u) {
    if (has_last_ && std::equal(last_.u.begin(), last_.u.end(), u)) return last_;
    last_.u.assign(u, u + problem_.dimension);
    last_.constraints.assign(static_cast<std::size_t>(problem_.constraints), 0.0);
    problem_.evaluate(last_.u, last_.objective, last_.constraints);
    // A non-finite value is no design: treated as violating every constraint.
    if (!std::isfinite(last_.objective)) last_.objective = std::numeric_limits<double>::max();
    for (double& c : last_.constraints)
      if (!std::isfinite(c)) c = std::numeric_limits<double>::max();
    has_last_ = true;
    ++evaluations;
    return last_;
  }

  int evaluations = 0;

private:
  const BoxProblem& problem_;
  Point last_;
  bool has_last_ = false;
};

/// What the NLopt callbacks see: the evaluator, which function (objective or constraint `only`),
/// the objective's scale, and the first exception a callback met (NLopt's C++ wrapper would
/// swallow it).
struct RunContext {
  Evaluator* evaluator = nullptr;
  int only = -1;  ///< ≥ 0: minimise constraint `only` alone, no constraints
  double scale = 1.0;
  std::exception_ptr error;
  nlopt::opt* opt = nullptr;
};

double objectiveCallback(unsigned n, const double* u, double* /*gradient*/, void* data) {
  auto* ctx = static_cast<RunContext*>(data);
  try {
    const Point& p = ctx->evaluator->at(u);
    (void)n;
    return (ctx->only >= 0 ? p.constraints[static_cast<std::size_t>(ctx->only)] : p.objective) /
           ctx->scale;
  } catch (...) {
    if (!ctx->error) ctx->error = std::current_exception();
    ctx->opt->force_stop();
    return 0.0;
  }
}

void constraintCallback(unsigned m, double* result, unsigned /*n*/, const double* u,
                        double* /*gradient*/, void* data) {
  auto* ctx = static_cast<RunContext*>(data);
  try {
    const Point& p = ctx->evaluator->at(u);
    for (unsigned i = 0; i < m; ++i) result[i] = p.constraints[i] + kInsideShift;
  } catch (...) {
    if (!ctx->error) ctx->error = std::current_exception();
    ctx->opt->force_stop();
    for (unsigned i = 0; i < m; ++i) result[i] = 0.0;
  }
}

/// One COBYLA run from `start`; returns its end point (evaluated).
Point runCobyla(const BoxProblem& problem, Evaluator& evaluator, const Point& start, int only,
                double scale, const MultiStartOptions& options, int max_evaluations) {
  const auto n = static_cast<unsigned>(problem.dimension);
  nlopt::opt opt(nlopt::LN_COBYLA, n);
  RunContext ctx;
  ctx.evaluator = &evaluator;
  ctx.only = only;
  ctx.scale = scale;
  ctx.opt = &opt;
  opt.set_lower_bounds(std::vector<double>(n, 0.0));
  opt.set_upper_bounds(std::vector<double>(n, 1.0));
  opt.set_min_objective(objectiveCallback, &ctx);
  if (only < 0 && problem.constraints > 0)
    opt.add_inequality_mconstraint(constraintCallback, &ctx,
                                   std::vector<double>(problem.constraints, 0.0));
  opt.set_xtol_abs(options.point_tolerance);
  opt.set_maxeval(max_evaluations);
  opt.set_initial_step(kInitialStep);
  std::vector<double> u = start.u;
  double value = 0.0;
  try {
    opt.optimize(u, value);
  } catch (const nlopt::roundoff_limited&) {
    // The best point so far is kept in u: a result, not a failure.
  } catch (const nlopt::forced_stop&) {
    // Our own callback stopped the run: its exception is rethrown below.
  } catch (const std::exception& e) {
    if (!ctx.error)
      throw NumericalError(detail::concat("optimize: NLopt's COBYLA failed: ", e.what()));
  }
  if (ctx.error) std::rethrow_exception(ctx.error);
  const Point& end = evaluator.at(u.data());
  return end;
}

}  // namespace

MultiStartResult minimizeOnUnitBox(const BoxProblem& problem, const MultiStartOptions& options) {
  MASTROM_REQUIRE(problem.dimension >= 1 && problem.evaluate && problem.constraints >= 0,
                  UsageError, "minimizeOnUnitBox: dimension ", problem.dimension,
                  " and an evaluation are needed");
  const int n = problem.dimension;
  const int candidates = options.candidates > 0 ? options.candidates : std::max(16, 16 * n);
  const int per_start = options.evaluations_per_start > 0 ? options.evaluations_per_start : 100 * n;
  Evaluator evaluator(problem);

  // The space-filling candidates. Halton index 0 is the origin, a corner: start at 1.
  std::vector<Point> points;
  for (int i = 1; i <= candidates; ++i) {
    const Eigen::VectorXd h = haltonPoint(i, n);
    points.push_back(evaluator.at(h.data()));
  }
  std::stable_sort(points.begin(), points.end(), better);
  // The objective's scale for COBYLA's merit function, against constraints scaled to O(1).
  double scale = std::abs(points.front().objective);
  if (!(scale > 0.0) || !std::isfinite(scale)) scale = 1.0;

  MultiStartResult result;
  Point best = points.front();
  const int starts = std::min(options.starts, candidates);
  for (int s = 0; s < starts; ++s) {
    const Point end = runCobyla(problem, evaluator, points[static_cast<std::size_t>(s)], -1, scale,
                                options, per_start);
    ++result.runs;
    if (end.feasible()) ++result.feasible_runs;
    if (better(end, best)) best = end;
  }

  if (!best.feasible()) {
    // Which constraint no point meets: each one minimised alone, from its own best candidate.
    for (int i = 0; i < problem.constraints; ++i) {
      const auto ci = static_cast<std::size_t>(i);
      const auto lowest = std::min_element(
          points.begin(), points.end(),
          [ci](const Point& a, const Point& b) { return a.constraints[ci] < b.constraints[ci]; });
      double least = lowest->constraints[ci];
      if (least > 0.0) {
        const Point end = runCobyla(problem, evaluator, *lowest, i, 1.0, options, per_start);
        least = std::min(least, end.constraints[ci]);
      }
      result.least_constraint.push_back(least);
    }
  }
  result.feasible = best.feasible();
  result.u = best.u;
  result.objective = best.objective;
  result.constraints = best.constraints;
  result.evaluations = evaluator.evaluations;
  return result;
}

}  // namespace mastrom::rom
