// `mastrom uq` through the ROM (rom/studies/uncertainty_study.hpp) on a synthetic database: the
// samples' metrics are the screen's bit for bit, the mean and an exceedance probability agree with
// a quadrature of the same ROM over the input's law, the first-order Sobol index with a brute-force
// one on a grid, the conservative probability counts the error bounds, and bad studies are
// refused with one line before any deployment; a study runs the database's interpolation unless
// told otherwise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "common/error.hpp"
#include "rom/studies/design_screen.hpp"
#include "rom/studies/uncertainty_errors.hpp"
#include "rom/studies/uncertainty_study.hpp"
#include "rom_fixtures.hpp"

namespace mastrom::rom {
namespace {

RomDatabase syntheticDatabase() {
  return testing::bilinearDatabase(testing::randomBilinearModel(4, 31), {1e-3, 1.5e-3, 2e-3},
                                   {0.4, 0.6}, 3);
}

/// The database's own configuration with uniform inputs (and a shorter record: cheaper, the same
/// pipeline).
Config studyConfig(const RomDatabase& db, bool thickness_too) {
  std::vector<std::string> set{"drive.duration=2.0",
                               "simulation.end_time=2.5",
                               "interface.thickness=0.0015",
                               "uncertainty.module.mass.distribution=uniform",
                               "uncertainty.module.mass.lower=0.42",
                               "uncertainty.module.mass.upper=0.58"};
  if (thickness_too) {
    set.insert(set.end(), {"uncertainty.interface.thickness.distribution=uniform",
                           "uncertainty.interface.thickness.lower=0.0011",
                           "uncertainty.interface.thickness.upper=0.0019"});
  }
  return applyConfigOverrides(parseConfigText(db.base_config_toml, "db"), set);
}

/// The screen of explicit designs, the metric m of each.
std::vector<double> screenColumn(const RomDatabase& db, const Config& config,
                                 const std::vector<DesignColumn>& columns, std::size_t m) {
  Config run = config;
  run.uncertainty.clear();
  DesignScreenOptions o;
  o.overrides = {"drive.duration=2.0", "simulation.end_time=2.5", "interface.thickness=0.0015"};
  const auto interpolator = makeInterpolator(db, db.default_method);
  const DesignScreenTable t = screenDesigns(db, *interpolator, columns, o);
  std::vector<double> out;
  for (long d = 0; d < t.designs; ++d) out.push_back(t.metrics[d * t.metric_names.size() + m]);
  return out;
}

constexpr std::size_t kPeak = 1;  // peak_rel_end_angular_acceleration

TEST(UncertaintyStudy, MeanAndExceedanceAgreeWithQuadrature) {
  const RomDatabase db = syntheticDatabase();
  const Config config = studyConfig(db, false);
  // Reference: the same ROM on a 400-point midpoint rule over U(0.42, 0.58).
  DesignColumn mass{"module.mass", {}, {}};
  for (int i = 0; i < 400; ++i) mass.values.push_back(0.42 + 0.16 * (i + 0.5) / 400);
  const std::vector<double> f = screenColumn(db, config, {mass}, kPeak);
  const double mean = std::accumulate(f.begin(), f.end(), 0.0) / f.size();
  std::vector<double> sorted = f;
  std::sort(sorted.begin(), sorted.end());
  const double threshold = sorted[280];  // P(f > threshold) = 119/400 on the rule
  const double p_exact = static_cast<double>(std::count_if(
                             f.begin(), f.end(), [&](double v) { return v > threshold; })) /
                         f.size();

  UqOptions o;
  o.samples = 512;
  o.sensitivity = false;
  o.confidence = 0.99;
  o.limits = {
      parseColumnCondition("peak_rel_end_angular_acceleration > " + std::to_string(threshold))};
  o.limits.front().value = threshold;
  const UqResult r = runUncertaintyStudy(db, config, o);
  ASSERT_EQ(r.rows, 512);
  EXPECT_EQ(r.metric_names[kPeak], "peak_rel_end_angular_acceleration");
  const stats::SampleSummary& s = r.summaries[kPeak];
  EXPECT_TRUE(s.mean.contains(mean))
      << mean << " outside [" << s.mean.lower << ", " << s.mean.upper << "]";
  // Informative: the interval is far narrower than the metric's spread over the box.
  EXPECT_LT(s.mean.width(), 0.2 * (sorted.back() - sorted.front()));
  const LimitProbability& p = r.limits.front();
  EXPECT_TRUE(p.probability.contains(p_exact))
      << p_exact << " outside [" << p.probability.lower << ", " << p.probability.upper << "]";
  // The synthetic database has no error estimate: the conservative value is the plain one.
  EXPECT_FALSE(p.has_error_estimate);
  EXPECT_EQ(p.conservative.estimate, p.probability.estimate);

  // Every sample's metrics are the screen's, bit for bit.
  DesignColumn rows{"module.mass", {}, {}};
  for (long row = 0; row < 5; ++row) rows.values.push_back(r.input_values[row]);
  const std::vector<double> direct = screenColumn(db, config, {rows}, kPeak);
  for (long row = 0; row < 5; ++row) EXPECT_EQ(r.metric(row, kPeak), direct[row]) << row;
}

TEST(UncertaintyStudy, InterpolatesWithTheDatabasesMethodUnlessTold) {
  // A study that names no method runs the database's own (the one `mastrom uq` uses and the
  // only one whose error the database estimates), not a fixed one.
  RomDatabase db = syntheticDatabase();
  db.default_method = InterpolationMethod::Cubic;
  const Config config = studyConfig(db, false);
  UqOptions o;
  o.samples = 6;
  o.sensitivity = false;
  const UqResult r = runUncertaintyStudy(db, config, o);
  DesignColumn rows{"module.mass", {}, {}};
  for (long row = 0; row < r.rows; ++row) rows.values.push_back(r.input_values[row]);
  const std::vector<double> own = screenColumn(db, config, {rows}, kPeak);
  o.method = InterpolationMethod::Tracked;
  const UqResult tracked = runUncertaintyStudy(db, config, o);
  double largest_difference = 0.0;
  for (long row = 0; row < r.rows; ++row) {
    EXPECT_EQ(r.metric(row, kPeak), own[static_cast<std::size_t>(row)]) << row;
    largest_difference =
        std::max(largest_difference, std::abs(tracked.metric(row, kPeak) - own[row]));
  }
  EXPECT_GT(largest_difference, 0.0);  // the two methods differ here: the test can tell them apart
}

TEST(UncertaintyStudy, FirstOrderIndexAgreesWithBruteForce) {
  const RomDatabase db = syntheticDatabase();
  const Config config = studyConfig(db, true);
  // Brute force on a 40 × 40 midpoint grid of the two uniform inputs:
  // S_mass = Var_mass(E[f | mass]) / Var(f).
  const int n = 40;
  DesignColumn mass{"module.mass", {}, {}}, thickness{"interface.thickness", {}, {}};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      mass.values.push_back(0.42 + 0.16 * (i + 0.5) / n);
      thickness.values.push_back(0.0011 + 0.0008 * (j + 0.5) / n);
    }
  const std::vector<double> f = screenColumn(db, config, {mass, thickness}, kPeak);
  double mean = 0, var = 0, var_conditional = 0;
  for (const double v : f) mean += v / f.size();
  for (const double v : f) var += (v - mean) * (v - mean) / f.size();
  for (int i = 0; i < n; ++i) {
    double m = 0;
    for (int j = 0; j < n; ++j) m += f[i * n + j] / n;
    var_conditional += (m - mean) * (m - mean) / n;
  }
  const double s_mass = var_conditional / var;

  UqOptions o;
  o.samples = 512;
  o.confidence = 0.99;
  const UqResult r = runUncertaintyStudy(db, config, o);
  ASSERT_EQ(r.rows, 512 * 4);
  ASSERT_EQ(r.input_names, (std::vector<std::string>{"interface.thickness", "module.mass"}));
  const stats::Interval& s = r.sobol[kPeak].first[1];
  EXPECT_TRUE(s.contains(s_mass)) << s_mass << " outside [" << s.lower << ", " << s.upper << "]";
  EXPECT_LT(s.width(), 0.3);
  // Total ≥ first for both inputs, up to the estimators' scatter.
  for (int i = 0; i < 2; ++i)
    EXPECT_GT(r.sobol[kPeak].total[i].upper, r.sobol[kPeak].first[i].lower);
}

TEST(UncertaintyStudy, AdaptiveSampleGrowsUntilTheIntervalsAreNarrow) {
  const RomDatabase db = syntheticDatabase();
  UqOptions o;
  o.samples = 32;
  o.target_width = 0.15;
  o.max_evaluations = 4 * 1024;
  const UqResult r = runUncertaintyStudy(db, studyConfig(db, true), o);
  EXPECT_GT(r.base_samples, 32);
  EXPECT_LE(r.rows, 4 * 1024);
  double widest = 0;
  for (const stats::SobolIndices& s : r.sobol) widest = std::max(widest, s.widestInterval());
  EXPECT_TRUE(widest <= 0.15 || 2 * r.rows > 4 * 1024) << widest << " at " << r.rows;
}

TEST(UncertaintyStudy, ConservativeProbabilityCountsTheErrorBounds) {
  UqResult r;
  r.metric_names = {"peak_rel_end_angular_acceleration", "min_margin_of_safety", "settling_time"};
  r.metric_units = {"rad/s^2", "1", "s"};
  r.rows = 10;
  for (long row = 0; row < 10; ++row) {
    r.metrics.insert(r.metrics.end(), {1.0 + row, 0.5, 1.0});
    r.rom_error.insert(r.rom_error.end(), {0.01, 0.1});
    r.statistic_rows.push_back(row);
  }
  metricErrorBounds(r);
  EXPECT_DOUBLE_EQ(r.metric_error[9 * 3], 1.0);                  // 10 × 0.1
  EXPECT_DOUBLE_EQ(r.metric_error[9 * 3 + 1], 1.5 * 0.1 / 0.9);  // (1 + M) e / (1 − e)
  EXPECT_EQ(r.metric_error[9 * 3 + 2], 0.0);
  EXPECT_FALSE(r.metric_has_error[2]);
  // Values 1 … 10: "> 8.5" holds for 9, 10; within 10 % also for 8 (8.8 > 8.5), not 7 (7.7).
  const LimitProbability p =
      limitProbability(r, parseColumnCondition("peak_rel_end_angular_acceleration > 8.5"), 0.95);
  EXPECT_DOUBLE_EQ(p.probability.estimate, 0.2);
  EXPECT_DOUBLE_EQ(p.conservative.estimate, 0.3);
  EXPECT_EQ(p.critical_row, 9);
  // The margin 0.5 ± 0.167 may fall below 0.4: every sample counts.
  EXPECT_DOUBLE_EQ(limitProbability(r, parseColumnCondition("min_margin_of_safety < 0.4"), 0.95)
                       .conservative.estimate,
                   1.0);
}

std::string studyError(const RomDatabase& db, const Config& config, UqOptions o = {}) {
  try {
    (void)runUncertaintyStudy(db, config, o);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(UncertaintyStudy, RefusesBadStudiesWithOneLine) {
  const RomDatabase db = syntheticDatabase();
  const Config good = studyConfig(db, false);
  const auto expect = [](const std::string& message, const std::string& part) {
    EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  };
  expect(studyError(db,
                    applyConfigOverrides(good, {"uncertainty.material.density.distribution=uniform",
                                                "uncertainty.material.density.lower=2600",
                                                "uncertainty.material.density.upper=2800"})),
         "uq: uncertainty.material.density is not a parameter of this database (parameters: "
         "interface.thickness, module.mass)");
  expect(studyError(db, applyConfigOverrides(good, {"interface.length=0.06"})),
         "uq: the configuration's interface.length = 0.06 differs from the database's 0.05");
  Config none = good;
  none.uncertainty.clear();
  expect(studyError(db, none), "uq: the configuration has no uncertain input");
  UqOptions o;
  o.limits = {parseColumnCondition("peak_force > 1")};
  expect(studyError(db, good, o), "uq: --limit \"peak_force > 1\": peak_force is not a metric");
  o.limits = {parseColumnCondition("settled == 1")};
  expect(studyError(db, good, o), "the operator must be one of < <= > >=");
  expect(studyError(db, applyConfigOverrides(good, {"uncertainty.module.mass.distribution=normal",
                                                    "uncertainty.module.mass.mean=0.5",
                                                    "uncertainty.module.mass.std=0.1"})),
         "uq: sample ");
}

}  // namespace
}  // namespace mastrom::rom
