// Constrained optimisation (rom/studies/multistart_optimizer.hpp, optimization_problem.hpp,
// optimization.hpp): the multi-start COBYLA against analytic optima (KKT points, two wells), the
// diagnosis of infeasible constraints, the margins' rules by hand, and on a small real database
// (Scheme 1, 1 × 6 mesh, thickness × module mass on 3 × 3, a compressed drive) the ROM optimum
// against brute force over a dense grid and the full order's confirmation.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "fullorder/configured_deployment.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/database/rom_database.hpp"
#include "rom/offline/database_build.hpp"
#include "rom/studies/full_order_check.hpp"
#include "rom/studies/multistart_optimizer.hpp"
#include "rom/studies/optimization.hpp"
#include "rom/studies/optimization_problem.hpp"
#include "rom/studies/rom_design_evaluator.hpp"

namespace mastrom::rom {
namespace {

// ---- the engine on analytic problems ---------------------------------------------------------

TEST(MultiStart, FindsTheConstrainedMinimumOfAQuadratic) {
  // min (u0 − 0.7)² + (u1 − 0.2)² subject to u0 + u1 ≥ 1.2: the unconstrained minimum violates the
  // constraint, so the optimum is its projection onto the line, (0.85, 0.35), f = 0.045 (KKT).
  BoxProblem p;
  p.dimension = 2;
  p.constraints = 1;
  p.evaluate = [](const std::vector<double>& u, double& f, std::vector<double>& c) {
    f = (u[0] - 0.7) * (u[0] - 0.7) + (u[1] - 0.2) * (u[1] - 0.2);
    c[0] = 1.2 - u[0] - u[1];
  };
  const MultiStartResult r = minimizeOnUnitBox(p);
  ASSERT_TRUE(r.feasible);
  // COBYLA's last trust radius is 1e-4 (point_tolerance): the point to a few of it.
  EXPECT_NEAR(r.u[0], 0.85, 5e-4);
  EXPECT_NEAR(r.u[1], 0.35, 5e-4);
  EXPECT_NEAR(r.objective, 0.045, 1e-4);
  EXPECT_LE(r.constraints[0], 0.0);  // met on the point returned, not to a tolerance
  EXPECT_GE(r.runs, 1);
  EXPECT_TRUE(r.least_constraint.empty());
}

TEST(MultiStart, FindsTheDeeperWellAndHonoursAConstraintThatExcludesIt) {
  // Two Gaussian wells, the deeper at (0.8, 0.8), the shallower at (0.2, 0.3): a local method
  // started near the shallow one stays there, the multi-start finds the deep one.
  const auto well = [](const std::vector<double>& u, double x, double y, double depth) {
    return -depth * std::exp(-((u[0] - x) * (u[0] - x) + (u[1] - y) * (u[1] - y)) / 0.02);
  };
  BoxProblem p;
  p.dimension = 2;
  p.constraints = 0;
  p.evaluate = [&](const std::vector<double>& u, double& f, std::vector<double>&) {
    f = well(u, 0.2, 0.3, 1.0) + well(u, 0.8, 0.8, 2.0);
  };
  MultiStartResult r = minimizeOnUnitBox(p);
  ASSERT_TRUE(r.feasible);
  EXPECT_NEAR(r.u[0], 0.8, 1e-3);
  EXPECT_NEAR(r.u[1], 0.8, 1e-3);
  // The deep well excluded by u0 ≤ 0.5: the shallow one's bottom (its neighbour's tail shifts it
  // by e^(−0.37/0.02)·… < 1e-7), at its own depth.
  p.constraints = 1;
  p.evaluate = [&](const std::vector<double>& u, double& f, std::vector<double>& c) {
    f = well(u, 0.2, 0.3, 1.0) + well(u, 0.8, 0.8, 2.0);
    c[0] = u[0] - 0.5;
  };
  r = minimizeOnUnitBox(p);
  ASSERT_TRUE(r.feasible);
  EXPECT_NEAR(r.u[0], 0.2, 1e-3);
  EXPECT_NEAR(r.u[1], 0.3, 1e-3);
  EXPECT_NEAR(r.objective, -1.0, 1e-5);
}

TEST(MultiStart, TellsAConstraintNoPointMeetsFromConstraintsThatExcludeEachOther) {
  BoxProblem p;
  p.dimension = 2;
  p.constraints = 3;
  // c0: u0 ≥ 0.6, c1: u0 ≤ 0.3 (each met somewhere, never together), c2: u1 ≥ 1.25 (nowhere:
  // its least value in the box is 0.25, at u1 = 1).
  p.evaluate = [](const std::vector<double>& u, double& f, std::vector<double>& c) {
    f = u[0] + u[1];
    c[0] = 0.6 - u[0];
    c[1] = u[0] - 0.3;
    c[2] = 1.25 - u[1];
  };
  const MultiStartResult r = minimizeOnUnitBox(p);
  EXPECT_FALSE(r.feasible);
  ASSERT_EQ(r.least_constraint.size(), 3u);
  EXPECT_LE(r.least_constraint[0], 0.0);
  EXPECT_LE(r.least_constraint[1], 0.0);
  EXPECT_NEAR(r.least_constraint[2], 0.25, 1e-6);
}

// ---- objective, constraints, margins --------------------------------------------------------

TEST(OptimizationProblem, ParsesConstraintsAndRefusesEqualities) {
  const MetricConstraint c = parseMetricConstraint("peak_rel_end_angular_acceleration <= 5.5");
  EXPECT_EQ(c.metric, "peak_rel_end_angular_acceleration");
  EXPECT_TRUE(c.at_most);
  EXPECT_EQ(c.bound, 5.5);
  EXPECT_FALSE(parseMetricConstraint("min_margin_of_safety>1").at_most);
  try {
    parseMetricConstraint("mass == 2");
    FAIL() << "an equality was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--subject-to 'mass == 2': OP must be <= (≤) or >= (≥)"),
              std::string::npos)
        << e.what();
  }
  try {
    parseMetricConstraint("mass is light");
    FAIL() << "a malformed constraint was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("--subject-to 'mass is light'", 0), 0u) << e.what();
  }
}

TEST(OptimizationProblem, MarginsFollowTheMetricKind) {
  const std::vector<std::string> names{"peak_abs_end_angular_acceleration",
                                       "peak_rel_end_angular_acceleration",
                                       "peak_joint_force",
                                       "max_peak_von_mises",
                                       "min_margin_of_safety",
                                       "mass",
                                       "first_frequency"};
  const std::vector<double> values{10.0, 2.0, 30.0, 1e6, 3.0, 1.7, 50.0};
  const double ef = 0.01, er = 0.05;
  const auto margin = [&](std::size_t i) { return conservativeMargin(names, values, i, ef, er); };
  // The absolute peak moves by the error of r alone: 2 · 0.05 · peak |r| = 0.2 (not 2 · 0.05 · 10).
  EXPECT_DOUBLE_EQ(margin(0), kMarginFactor * er * 2.0);
  EXPECT_DOUBLE_EQ(margin(1), kMarginFactor * er * 2.0);
  EXPECT_DOUBLE_EQ(margin(2), kMarginFactor * er * 30.0);
  EXPECT_DOUBLE_EQ(margin(3), kMarginFactor * er * 1e6);
  // MS = σ_y/σ − 1 = 3 with σ 5 % high reads σ_y/(1.05σ) − 1 = 4/1.05 − 1: lower by 0.19 ≤ the
  // margin per unit factor, (1 + MS) · 0.05 = 0.2.
  EXPECT_DOUBLE_EQ(margin(4), kMarginFactor * er * 4.0);
  EXPECT_LE(4.0 - 4.0 / 1.05, margin(4) / kMarginFactor);
  EXPECT_EQ(margin(5), 0.0);
  EXPECT_DOUBLE_EQ(margin(6), kMarginFactor * ef * 50.0);
  // A frequency with its own estimate (4.15) in the screen takes the larger of it and e_ω.
  const std::vector<std::string> f_names{"frequency_3", "frequency_3_error"};
  EXPECT_DOUBLE_EQ(conservativeMargin(f_names, {300.0, 0.05}, 0, ef, er),
                   kMarginFactor * 0.05 * 300.0);
  EXPECT_DOUBLE_EQ(conservativeMargin(f_names, {300.0, 0.001}, 0, ef, er),
                   kMarginFactor * ef * 300.0);
  EXPECT_DOUBLE_EQ(conservativeMargin(f_names, {300.0, -1.0}, 0, ef, er),
                   kMarginFactor * ef * 300.0);
  EXPECT_EQ(metricErrorKind("settling_time"), MetricErrorKind::NoEstimate);
  EXPECT_EQ(metricErrorKind("settled"), MetricErrorKind::NotADesignResult);
}

std::string optimizableError(const std::string& metric, bool constraint,
                             const std::vector<std::string>& available, bool stresses) {
  try {
    requireOptimizable(metric, constraint ? "--subject-to" : "--minimize", metric + " <= 1",
                       constraint, available, stresses);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(OptimizationProblem, RefusesMetricsTheDatabaseCannotGive) {
  const std::vector<std::string> plain = screenMetricNames();
  const std::vector<std::string> stressed = screenMetricNames({2, false});
  EXPECT_EQ(optimizableError("peak_rel_end_angular_acceleration", true, plain, false), "");
  EXPECT_NE(optimizableError("peak_rel_end_angular_acceleratoin", false, plain, false)
                .find("peak_rel_end_angular_acceleratoin is not a metric (metrics: "
                      "peak_abs_end_angular_acceleration, "),
            std::string::npos);
  EXPECT_NE(optimizableError("max_peak_von_mises", false, plain, false)
                .find("this database carries no stress modes (built with --no-stresses), so it "
                      "cannot give max_peak_von_mises"),
            std::string::npos);
  EXPECT_NE(optimizableError("min_margin_of_safety", true, stressed, true)
                .find("min_margin_of_safety needs a yield strength (e.g. --set "
                      "material.yield_strength="),
            std::string::npos);
  EXPECT_NE(optimizableError("peak_von_mises_interface_3", true, stressed, true)
                .find("peak_von_mises_interface_3 is not an interface of this mast"),
            std::string::npos);
  EXPECT_NE(optimizableError("settling_band", false, plain, false)
                .find("is a setting of the metrics, not a result of the design"),
            std::string::npos);
  EXPECT_EQ(optimizableError("settling_time", false, plain, false), "");
  EXPECT_NE(optimizableError("settling_time", true, plain, false)
                .find("may be the objective but not a constraint"),
            std::string::npos);
}

TEST(Optimization, AViolatedConstraintIsTightenedByTheMeasuredDifference) {
  const std::vector<MetricConstraint> c{parseMetricConstraint("a <= 10"),
                                        parseMetricConstraint("b >= 2"),
                                        parseMetricConstraint("c <= 1")};
  OptimizationRound r;
  r.bounds = {9.0, 2.0, 1.0};    // a tightened in an earlier round
  r.rom = {0.0, 8.5, 2.3, 0.9};  // objective, then a, b, c
  r.full = {0.0, 10.5, 1.9, 0.95};
  r.met = {0, 0, 1};
  const std::vector<double> next = tightenedBounds(c, r);
  EXPECT_DOUBLE_EQ(next[0], 9.0 - 2.0);  // full − ROM = 2 below the bound used
  EXPECT_DOUBLE_EQ(next[1], 2.0 + 0.4);  // ≥: raised by |full − ROM|
  EXPECT_DOUBLE_EQ(next[2], 1.0);        // met: unchanged
}

}  // namespace
}  // namespace mastrom::rom
