// The metric table of a design (rom/studies/design_metrics.hpp), the Pareto front of a screen
// (rom/studies/pareto_front.hpp, against brute force on random data) and the mass of a design of a
// database (rom/studies/design_description.hpp, against the configuration the point makes).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "common/error.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/studies/design_description.hpp"
#include "rom/studies/design_metrics.hpp"
#include "rom/studies/pareto_front.hpp"

namespace mastrom::rom {
namespace {

std::string refusal(const MetricColumns& c, const std::string& name) {
  try {
    metricIndex(c, name, "--pareto");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(DesignMetrics, ColumnsInTableOrderWithUnits) {
  MetricColumns c;
  c.stress_interfaces = 2;
  c.margin = true;
  c.modules = 3;
  c.frequencies = 2;
  const std::vector<MetricDefinition> m = designMetrics(c);
  const std::vector<std::string> names = metricNames(m);
  ASSERT_EQ(names.size(), 10u + 2 + 1 + 1 + (1 + 3 + 2) + 2 * 2);
  EXPECT_EQ(names[10], "peak_von_mises_interface_1");
  EXPECT_EQ(names[12], "max_peak_von_mises");
  EXPECT_EQ(names[13], "min_margin_of_safety");
  EXPECT_EQ(names[14], "mass");
  EXPECT_EQ(names[15], "mass_module_1");
  EXPECT_EQ(names[18], "mass_interface_1");
  EXPECT_EQ(names[20], "frequency_1");
  EXPECT_EQ(names[22], "frequency_1_error");
  EXPECT_EQ(metricUnits(m)[14], "kg");
  EXPECT_EQ(metricUnits(m)[20], "Hz");
  // Every getter reads its own field.
  DesignValues v;
  v.deployment.peak_rel_end_angular_acceleration = 3.5;
  v.deployment.settled = true;
  v.peak_von_mises_pa = {1e6, 3e6};
  v.min_margin_of_safety = 0.25;
  v.mass.total_kg = 2.5;
  v.mass.module_kg = {0.5, 0.6, 0.7};
  v.mass.interface_kg = {0.3, 0.4};
  v.frequency_hz = {10.0, 20.0};
  v.frequency_error = {0.01, 0.02};
  std::vector<double> out;
  appendMetricValues(m, v, out);
  ASSERT_EQ(out.size(), names.size());
  EXPECT_EQ(out[1], 3.5);
  EXPECT_EQ(out[5], 1.0);
  EXPECT_EQ(out[11], 3e6);
  EXPECT_EQ(out[12], 3e6);
  EXPECT_EQ(out[13], 0.25);
  EXPECT_EQ(out[14], 2.5);
  EXPECT_EQ(out[17], 0.7);
  EXPECT_EQ(out[19], 0.4);
  EXPECT_EQ(out[21], 20.0);
  EXPECT_EQ(out[23], 0.02);
  EXPECT_EQ(metricIndex(c, "frequency_2_error", "--pareto"), 23u);
}

TEST(DesignMetrics, RefusesUnknownAndUnavailableMetricsWithTheReason) {
  MetricColumns c;
  c.modules = 2;
  c.frequencies = 3;
  c.no_stress_reason = "the database carries no stress modes (built with --no-stresses)";
  EXPECT_EQ(refusal(c, "mass"), "");
  EXPECT_NE(refusal(c, "weight").find("--pareto weight: unknown metric (known: "),
            std::string::npos);
  EXPECT_NE(refusal(c, "max_peak_von_mises")
                .find("--pareto max_peak_von_mises: no stresses here: the database carries no "
                      "stress modes"),
            std::string::npos);
  EXPECT_NE(refusal(c, "min_margin_of_safety").find("no stresses here"), std::string::npos);
  EXPECT_NE(refusal(c, "frequency_4").find("only the lowest 3 frequencies are computed"),
            std::string::npos);
  EXPECT_NE(refusal(c, "mass_module_3").find("the mast has 2 modules"), std::string::npos);
  EXPECT_NE(refusal(c, "mass_interface_2").find("the mast has 1 interfaces"), std::string::npos);
  EXPECT_NE(refusal(c, "frequency_01").find("unknown metric"), std::string::npos);
  c.stress_interfaces = 1;
  EXPECT_NE(refusal(c, "min_margin_of_safety").find("material.yield_strength"), std::string::npos);
  c.frequencies = 0;
  c.no_frequency_reason = "the database holds modes at 0 deg only";
  EXPECT_NE(refusal(c, "frequency_1").find("no natural frequencies here: the database holds"),
            std::string::npos);
}

/// The front by definition: every pair compared.
std::vector<char> bruteForceFront(const std::vector<double>& v, std::size_t k,
                                  const std::vector<bool>& maximize) {
  const std::size_t n = v.size() / k;
  const auto cost = [&](std::size_t r, std::size_t j) {
    return maximize[j] ? -v[r * k + j] : v[r * k + j];
  };
  std::vector<char> front(n, 0);
  for (std::size_t b = 0; b < n; ++b) {
    bool finite = true;
    for (std::size_t j = 0; j < k; ++j) finite = finite && !std::isnan(v[b * k + j]);
    if (!finite) continue;
    bool dominated = false;
    for (std::size_t a = 0; a < n && !dominated; ++a) {
      bool no_worse = true, better = false;
      for (std::size_t j = 0; j < k; ++j) {
        if (std::isnan(cost(a, j))) no_worse = false;
        no_worse = no_worse && cost(a, j) <= cost(b, j);
        better = better || cost(a, j) < cost(b, j);
      }
      dominated = no_worse && better;
    }
    front[b] = dominated ? 0 : 1;
  }
  return front;
}

TEST(ParetoFront, EqualsBruteForceOnRandomData) {
  std::mt19937 rng(20261128);
  int fronts_checked = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const std::size_t k = 2 + static_cast<std::size_t>(trial % 3);
    const std::size_t n = 1 + static_cast<std::size_t>(rng() % 200);
    // Continuous values, or few levels (ties and duplicate designs), some NaN.
    const bool ties = trial % 2 == 1;
    std::vector<double> v(n * k);
    for (double& x : v)
      x = ties ? static_cast<double>(rng() % 4)
               : std::uniform_real_distribution<double>(-1, 1)(rng);
    if (trial % 5 == 0) v[(rng() % n) * k] = std::numeric_limits<double>::quiet_NaN();
    std::vector<bool> maximize;
    for (std::size_t j = 0; j < k; ++j) maximize.push_back(rng() % 2 == 1);
    const std::vector<char> fast = nonDominated(v, k, maximize);
    const std::vector<char> brute = bruteForceFront(v, k, maximize);
    ASSERT_EQ(fast, brute) << "trial " << trial << ", " << n << " designs, " << k << " objectives";
    fronts_checked += std::count(brute.begin(), brute.end(), 1) > 1 ? 1 : 0;
  }
  EXPECT_GT(fronts_checked, 200);  // the fronts compared are not trivial
}

TEST(ParetoFront, TwoObjectivesByHand) {
  // (mass, f1): minimise mass, maximise f1. (1, 10) and (2, 20) are the front; (2, 10) is beaten by
  // (1, 10); the duplicate (2, 20) stays with its twin; (3, 15) is beaten by (2, 20).
  const std::vector<double> v{1, 10, 2, 10, 2, 20, 3, 15, 2, 20};
  EXPECT_EQ(nonDominated(v, 2, {false, true}), (std::vector<char>{1, 0, 1, 0, 1}));
}

TEST(ParetoFront, ParsesObjectivesAndRefusesBadOnes) {
  const std::vector<ParetoObjective> o =
      parseParetoObjectives("mass:min, frequency_1:max,peak_rel_end_angular_acceleration");
  ASSERT_EQ(o.size(), 3u);
  EXPECT_FALSE(o[0].maximize);
  EXPECT_TRUE(o[1].maximize);
  EXPECT_FALSE(o[2].maximize);
  EXPECT_EQ(paretoText(o), "mass:min,frequency_1:max,peak_rel_end_angular_acceleration:min");
  EXPECT_THROW(parseParetoObjectives("mass:lowest,frequency_1"), InputError);
  EXPECT_THROW(parseParetoObjectives("mass"), InputError);
  EXPECT_THROW(parseParetoObjectives("mass,mass:max"), InputError);
}

TEST(ParetoFront, MarksAndKeepsTheFrontOfATable) {
  ScreenTable t;
  t.axes = {ScreenAxis{"module.mass", {0.4, 0.5, 0.6, 0.7}, {"0.4", "0.5", "0.6", "0.7"}, false}};
  t.columns.modules = 2;
  t.columns.frequencies = 1;
  t.metric_names = metricNames(designMetrics(t.columns));
  t.metric_units = metricUnits(designMetrics(t.columns));
  t.designs = 4;
  t.parameters = {0.4, 0.5, 0.6, 0.7};
  const std::size_t q = t.metric_names.size();
  t.metrics.assign(4 * q, 0.0);
  const std::size_t mass = metricIndex(t.columns, "mass", "--pareto");
  const std::size_t f1 = metricIndex(t.columns, "frequency_1", "--pareto");
  const double masses[] = {1.0, 2.0, 1.5, 3.0}, f[] = {10.0, 30.0, 9.0, 20.0};
  for (std::size_t r = 0; r < 4; ++r) {
    t.metrics[r * q + mass] = masses[r];
    t.metrics[r * q + f1] = f[r];
  }
  markParetoFront(t, parseParetoObjectives("mass:min,frequency_1:max"));
  ASSERT_EQ(t.metric_names.back(), kParetoColumn);
  EXPECT_EQ(t.pareto_objectives, "mass:min,frequency_1:max");
  const std::size_t q1 = q + 1;
  EXPECT_EQ(t.metrics[0 * q1 + q], 1.0);
  EXPECT_EQ(t.metrics[1 * q1 + q], 1.0);
  EXPECT_EQ(t.metrics[2 * q1 + q], 0.0);     // heavier and lower than design 0
  EXPECT_EQ(t.metrics[3 * q1 + q], 0.0);     // heavier and lower than design 1
  EXPECT_EQ(t.metrics[1 * q1 + mass], 2.0);  // the other columns kept
  EXPECT_EQ(keepParetoFront(t), 2);
  EXPECT_EQ(t.designs, 2);
  EXPECT_EQ(t.parameters, (std::vector<double>{0.4, 0.5}));
  EXPECT_EQ(t.metrics.size(), 2 * q1);
}

TEST(DesignDescription, MassAtAPointEqualsTheConfigurationThePointMakes) {
  // A database over every kind of key that moves a mass — the inner diameter (the radius follows
  // it and the thickness, (1.1)), the thickness, one item's length, one module's mass, the density
  // — and one that does not (E). Its samples are not needed for the mass.
  Config base;
  base.mast.modules = 3;
  base.interface.inner_diameter_m = 0.08;
  base.interface.radius_m = 0.5 * (0.08 + base.interface.thickness_m);
  base = applyOverrides(base, {});
  RomDatabase db;
  db.base_config_toml = toToml(base);
  db.axes = {
      {"interface.inner_diameter", {0.078, 0.09}}, {"interface.thickness", {0.001, 0.002}},
      {"interface.2.length", {0.04, 0.07}},        {"module.3.mass", {0.5, 1.5}},
      {"material.density", {1200.0, 2800.0}},      {"material.youngs_modulus", {60e9, 80e9}}};
  db.layout = SampleLayout::Scattered;
  const Config evaluation = evaluationConfig(db, {});
  const DesignDescriber describer(db, evaluation, FrequencyRequest{0, false, "--frequencies"},
                                  {evaluation.drive.angle_deg}, BoxPolicy::Refuse);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<double> point;
    for (const ParameterAxis& a : db.axes)
      point.push_back(a.values.front() + std::uniform_real_distribution<double>(0, 1)(rng) *
                                             (a.values.back() - a.values.front()));
    const fullorder::MastMass fast = describer.massAt(point);
    const fullorder::MastMass exact =
        configuredMass(applyOverrides(evaluation, parameterOverrides(db.axes, point)));
    EXPECT_EQ(fast.total_kg, exact.total_kg) << "trial " << trial;
    EXPECT_EQ(fast.module_kg, exact.module_kg);
    EXPECT_EQ(fast.interface_kg, exact.interface_kg);
    // And by hand: R = (D + h)/2, so r_o = D/2 + h and r_i = D/2.
    const double d = point[0], h = point[1], rho = point[4];
    const double shell = M_PI * ((d / 2 + h) * (d / 2 + h) - (d / 2) * (d / 2)) * rho;
    const double by_hand = 0.5 + 0.5 + point[3] + shell * 0.05 + shell * point[2];
    EXPECT_NEAR(exact.total_kg, by_hand, 1e-14 * by_hand);
  }
}

}  // namespace
}  // namespace mastrom::rom
