// Screening (rom/studies/screening.hpp): --grid parsing, the table against direct evaluations, the box
// check before any work, and the CSV / HDF5 layouts the report tool reads.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "fullorder/mast_config.hpp"
#include "rom/offline/database_build.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/studies/screen_filter.hpp"
#include "rom/studies/screening.hpp"
#include "rom_fixtures.hpp"

namespace mastrom::rom {
namespace {

RomDatabase syntheticDatabase() {
  return testing::bilinearDatabase(testing::randomBilinearModel(4, 31), {1e-3, 1.5e-3, 2e-3},
                                   {0.4, 0.6}, 3);
}

std::string gridError(const std::string& text, const RomDatabase& db) {
  try {
    parseScreenAxis(text, db);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ScreenAxis, ParsesRangesAndLists) {
  const RomDatabase db = syntheticDatabase();
  const ScreenAxis h = parseScreenAxis("interface.thickness=0.001:0.002:5", db);
  EXPECT_EQ(h.values.size(), 5u);
  EXPECT_EQ(h.values.back(), 0.002);
  EXPECT_FALSE(h.named);
  const ScreenAxis law = parseScreenAxis("drive.law=trapezoidal,cubic,cycloidal", db);
  EXPECT_TRUE(law.named);
  EXPECT_EQ(law.labels, (std::vector<std::string>{"trapezoidal", "cubic", "cycloidal"}));
  EXPECT_EQ(law.values, (std::vector<double>{0, 1, 2}));
  const ScreenAxis t = parseScreenAxis("drive.duration=4,6.1", db);
  EXPECT_EQ(t.values, (std::vector<double>{4, 6.1}));
}

TEST(ScreenAxis, RejectsBadAxesWithOneLine) {
  const RomDatabase db = syntheticDatabase();
  EXPECT_NE(gridError("interface.thickness", db).find("is malformed"), std::string::npos);
  EXPECT_NE(gridError("interface.thickness=1:2", db).find("is malformed"), std::string::npos);
  EXPECT_NE(gridError("material.density=2000:3000:3", db)
                .find("not a parameter of this database (parameters: interface.thickness, "
                      "module.mass) nor a free key"),
            std::string::npos);
  EXPECT_NE(gridError("drive.law=trapezoidal,sideways", db).find("is not a known drive law"),
            std::string::npos);
  EXPECT_NE(gridError("module.mass=light,heavy", db).find("numeric database parameter"),
            std::string::npos);
  EXPECT_NE(gridError("drive.duration=-1,2", db).find("drive.duration"), std::string::npos);
}

TEST(Screen, TheStepIsTwoMillisecondsUnlessOutputStepIsSet) {
  EXPECT_EQ(screenStep({}, 2e-3, PeakResolution::Continuous), 2e-3);
  EXPECT_EQ(screenStep({"drive.law=cubic"}, 2e-3, PeakResolution::Continuous), 2e-3);
  for (const char* interval : {" output.step = 2e-4", "output.every=3", "simulation.time_step=1e-5"})
    EXPECT_EQ(screenStep({interval}, 2e-3, PeakResolution::Continuous), 0.0) << interval;
  EXPECT_EQ(screenStep({}, 2e-3, PeakResolution::Samples), 0.0);  // sample metrics: config's
  EXPECT_EQ(screenStep({}, 0.0, PeakResolution::Continuous), 0.0);
  EXPECT_THROW(checkScreenStep(2e-3, {"output.every=2"}, "--step"), InputError);
  EXPECT_THROW(checkScreenStep(-1.0, {}, "--step"), InputError);
  EXPECT_NO_THROW(checkScreenStep(2e-3, {"drive.law=cubic"}, "--step"));

  // Every metric is taken on the continuous response, so the default 2 ms screen reads what a
  // 0.1 ms one does: the peaks within twice their tolerance (rom/model/deployment_metrics.hpp), the
  // RMS and the settling time to round-off of their exact evaluation.
  const RomDatabase db = syntheticDatabase();
  ScreenOptions o;
  o.axes = {parseScreenAxis("module.mass=0.4:0.6:3", db),
            parseScreenAxis("drive.law=trapezoidal,cubic,cycloidal", db)};
  o.overrides = {"interface.thickness=0.0012"};
  const ScreenTable coarse = runScreen(db, o);
  EXPECT_EQ(coarse.step_s, kDefaultScreenStepS);
  EXPECT_EQ(kDefaultScreenStepS, 2e-3);
  o.overrides.push_back("output.step=1e-4");
  const ScreenTable fine = runScreen(db, o);
  EXPECT_EQ(fine.step_s, 1e-4);
  ASSERT_EQ(coarse.metrics.size(), fine.metrics.size());
  const std::size_t q = coarse.metric_names.size();
  for (std::size_t d = 0; d < static_cast<std::size_t>(coarse.designs); ++d) {
    for (std::size_t j = 0; j < q; ++j) {
      const double a = coarse.metrics[d * q + j], b = fine.metrics[d * q + j];
      const std::string& name = coarse.metric_names[j];
      const double scale = name == "settling_time" ? 1.0 : std::max(std::abs(b), 1.0 * (M_PI / 180.0));
      const double tolerance = name.rfind("peak", 0) == 0 || name.rfind("residual", 0) == 0
                                   ? 2.0 * kContinuousPeakTolerance
                                   : 1e-7;
      EXPECT_NEAR(a, b, tolerance * scale) << name << ", design " << d;
    }
  }
}

TEST(Screen, TableMatchesDirectEvaluations) {
  const RomDatabase db = syntheticDatabase();
  ScreenOptions o;
  o.step_s = 0.0;  // the configuration's output step, as the direct evaluations below
  o.axes = {parseScreenAxis("module.mass=0.4:0.6:3", db),
            parseScreenAxis("drive.law=trapezoidal,quintic", db)};
  o.overrides = {"interface.thickness=0.0012", "simulation.end_time=7"};
  const ScreenTable t = runScreen(db, o);
  ASSERT_EQ(t.designs, 6);
  const std::size_t q = t.metric_names.size();
  // The deployment's 10 metrics, the mass (total, 2 modules, 1 interface), the 3 lowest
  // frequencies and their estimated errors (rom/studies/design_metrics.hpp).
  ASSERT_EQ(q, 10u + 4 + 6);
  EXPECT_EQ(t.metric_names[1], "peak_rel_end_angular_acceleration");
  EXPECT_EQ(t.metric_names[10], "mass");
  EXPECT_EQ(t.metric_names[14], "frequency_1");
  ASSERT_EQ(t.metrics.size(), 6 * q);
  // Design 4 = (mass index 1, law index 1): mass 0.5, quintic.
  EXPECT_EQ(t.parameters[2 * 4], 0.5);
  EXPECT_EQ(t.parameters[2 * 4 + 1], 1.0);
  const Config c = evaluationConfig(db, {"interface.thickness=0.0012", "simulation.end_time=7",
                                         "module.mass=0.5", "drive.law=quintic"});
  const ModalModel m = makeInterpolator(db, InterpolationMethod::Tracked)->evaluate({0.0012, 0.5});
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(c));
  const ModalDeploymentOptions deploy = deploymentOptionsFromConfig(c);
  // The screen's peaks are the continuous ones (rom/model/deployment_metrics.hpp), its RMS that of the
  // series `rom eval` writes.
  const fullorder::DeploymentMetrics direct =
      modalDeploymentMetrics(m, drive, deploy, c.drive.duration_s);
  const fullorder::DeploymentMetrics series_metrics =
      fullorder::computeMetrics(simulateModalDeployment(m, drive, deploy), c.drive.duration_s);
  EXPECT_EQ(t.metrics[4 * q + 1], direct.peak_rel_end_angular_acceleration);
  EXPECT_EQ(t.metrics[4 * q + 7], direct.peak_drive_torque);
  EXPECT_GE(t.metrics[4 * q + 1], series_metrics.peak_rel_end_angular_acceleration);
  // The design's mass (docs/theory.md (1.12)) and the lowest frequency of its interpolated model
  // (no gravity: the modes at θ₀ are those at the deployed angle).
  EXPECT_EQ(t.metrics[4 * q + 10], configuredMass(c).total_kg);
  EXPECT_EQ(t.metrics[4 * q + 14], m.omega_rad_s[0] / (2.0 * M_PI));
  // The RMS is the exact integral of the continuous response (docs/theory.md §4.2a); the
  // trapezoidal rule on the series' 0.1 ms samples is within 1e-3 of it (7.9e-4 measured on a
  // coarse Scheme 3 with a trapezoidal law, tests/rom/test_square_integral.cpp).
  EXPECT_EQ(t.metrics[4 * q + 2], direct.rms_rel_end_angular_acceleration);
  EXPECT_NEAR(t.metrics[4 * q + 2], series_metrics.rms_rel_end_angular_acceleration,
              1e-3 * series_metrics.rms_rel_end_angular_acceleration);
  // CSV: the grid keys, then the metrics; names for a list of names.
  std::ostringstream csv;
  writeScreenCsv(csv, t);
  const std::string text = csv.str();
  EXPECT_EQ(text.substr(0, text.find('\n')),
            "module.mass,drive.law,peak_abs_end_angular_acceleration,"
            "peak_rel_end_angular_acceleration,rms_rel_end_angular_acceleration,"
            "residual_rel_end_angular_acceleration,settling_time,settled,peak_joint_force,"
            "peak_drive_torque,drive_end_time,settling_band,mass,mass_module_1,mass_module_2,"
            "mass_interface_1,frequency_1,frequency_2,frequency_3,frequency_1_error,"
            "frequency_2_error,frequency_3_error");
  EXPECT_NE(text.find("\n0.5,quintic,"), std::string::npos);
}

TEST(Screen, RefusesDesignsOutsideTheBoxBeforeAnyWork) {
  const RomDatabase db = syntheticDatabase();
  ScreenOptions o;
  o.axes = {parseScreenAxis("module.mass=0.5:0.7:3", db)};
  try {
    runScreen(db, o);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("module.mass = 0.7 lies outside"), std::string::npos);
  }
  o.box = BoxPolicy::Extrapolate;
  EXPECT_EQ(runScreen(db, o).designs, 3);
  // A drive combination whose record ends before the drive does.
  ScreenOptions d;
  d.axes = {parseScreenAxis("drive.duration=4,9", db)};
  EXPECT_THROW(runScreen(db, d), InputError);
}

TEST(Screen, HdfLayoutIsWhatTheReportReads) {
  const RomDatabase db = syntheticDatabase();
  ScreenOptions o;
  o.axes = {parseScreenAxis("interface.thickness=0.001:0.002:2", db),
            parseScreenAxis("drive.law=cubic,cycloidal", db)};
  const ScreenTable t = runScreen(db, o);
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("mastrom_screen_" + std::to_string(::getpid()) + ".h5"))
                               .string();
  writeScreenH5(path, t);
  const h5::File f = h5::File::open(path, h5::OpenMode::ReadOnly);
  EXPECT_EQ(f.readStringAttribute("/", "source"), "screen");
  EXPECT_EQ(f.datasetShape("/screen/parameter_names"), (std::vector<std::size_t>{2}));
  const std::size_t q = t.metric_names.size();
  EXPECT_EQ(f.datasetShape("/screen/metric_names"), (std::vector<std::size_t>{q}));
  const Eigen::MatrixXd p = f.readMatrix("/screen/parameters");
  ASSERT_EQ(p.rows(), 4);
  EXPECT_EQ(p(3, 0), 0.002);
  EXPECT_EQ(p(3, 1), 1.0);
  const Eigen::MatrixXd m = f.readMatrix("/screen/metrics");
  EXPECT_EQ(m.rows(), 4);
  EXPECT_EQ(m(2, 0), t.metrics[2 * q]);
  std::filesystem::remove(path);
}

void expectSameMetrics(const fullorder::DeploymentMetrics& a,
                       const fullorder::DeploymentMetrics& b) {
  const auto near = [](double x, double y) {
    return std::abs(x - y) <= 1e-10 * std::abs(y) + 1e-14;
  };
  EXPECT_TRUE(near(a.peak_abs_end_angular_acceleration, b.peak_abs_end_angular_acceleration))
      << a.peak_abs_end_angular_acceleration << " vs " << b.peak_abs_end_angular_acceleration;
  EXPECT_TRUE(near(a.peak_rel_end_angular_acceleration, b.peak_rel_end_angular_acceleration));
  EXPECT_TRUE(near(a.rms_rel_end_angular_acceleration, b.rms_rel_end_angular_acceleration));
  EXPECT_TRUE(
      near(a.residual_rel_end_angular_acceleration, b.residual_rel_end_angular_acceleration));
  EXPECT_TRUE(near(a.settling_time, b.settling_time))
      << a.settling_time << " vs " << b.settling_time;
  EXPECT_EQ(a.settled, b.settled);
  EXPECT_TRUE(near(a.peak_joint_force, b.peak_joint_force))
      << a.peak_joint_force << " vs " << b.peak_joint_force;
  EXPECT_TRUE(near(a.peak_drive_torque, b.peak_drive_torque));
  EXPECT_EQ(a.drive_end_time, b.drive_end_time);
  EXPECT_EQ(a.settling_band, b.settling_band);
}

/// The continuous metrics against the sample ones of the same run — every peak is a max over a
/// superset of the samples, never below — and against `fine`, the samples' metrics of the same
/// deployment at 10 µs: the RMS is the exact integral (docs/theory.md §4.2a), which the
/// trapezoidal rule there meets within 1e-4 (O(δ) at the jumps of θ̈: 7.6e-5 measured on a coarse
/// Scheme 3; the 1 ms hold of θ̇² and gravity adds ~1e-6); the settling time is the continuous
/// response's last exit from the band (§4.2b), which the 10 µs samples' linear re-entry meets
/// within about a sample.
void expectContinuousExtendsSamples(const fullorder::DeploymentMetrics& c,
                                    const fullorder::DeploymentMetrics& s,
                                    const fullorder::DeploymentMetrics& fine) {
  EXPECT_NEAR(c.rms_rel_end_angular_acceleration, fine.rms_rel_end_angular_acceleration,
              2e-4 * fine.rms_rel_end_angular_acceleration);
  EXPECT_EQ(c.settled, fine.settled);
  EXPECT_NEAR(c.settling_time, fine.settling_time, 2e-5);
  EXPECT_EQ(c.settled, s.settled);
  EXPECT_EQ(c.drive_end_time, s.drive_end_time);
  EXPECT_EQ(c.settling_band, s.settling_band);
  EXPECT_GE(c.peak_abs_end_angular_acceleration, s.peak_abs_end_angular_acceleration);
  EXPECT_GE(c.peak_rel_end_angular_acceleration, s.peak_rel_end_angular_acceleration);
  EXPECT_GE(c.residual_rel_end_angular_acceleration, s.residual_rel_end_angular_acceleration);
  EXPECT_GE(c.peak_joint_force, s.peak_joint_force);
  EXPECT_GE(c.peak_drive_torque, s.peak_drive_torque);
}

TEST(DeploymentMetrics, StreamingEqualsSeriesThenComputeMetrics) {
  // Every drive law, with and without gravity (θ₀ = 0.3 rad), a record that settles and one that
  // ends outside the band (band 1e-3 °/s² is never reached). PeakResolution::Samples is
  // computeMetrics of the series to round-off; Continuous raises its peaks only and takes the
  // RMS and the settling time of the continuous response.
  const RomDatabase db = syntheticDatabase();
  ModalModel m = makeInterpolator(db, InterpolationMethod::Tracked)->evaluate({0.0013, 0.47});
  for (const bool gravity : {false, true}) {
    if (gravity) {
      m.gravity_m_s2 = Eigen::Vector3d(0.5, -9.81, 0.0);
      m.reference_angle_rad = 0.3;
    }
    for (const DriveLawKind law : {DriveLawKind::Trapezoidal, DriveLawKind::Cubic,
                                   DriveLawKind::Quintic, DriveLawKind::Cycloidal}) {
      fullorder::DriveLawParameters p;
      p.kind = law;
      p.duration_s = 1.0;
      p.ramp_s = 0.1;
      const fullorder::DriveLaw drive(p);
      ModalDeploymentOptions o;
      o.end_time_s = 1.5;
      o.step_s = 1e-3;
      const fullorder::DeploymentSeries series = simulateModalDeployment(m, drive, o);
      ModalDeploymentOptions fine = o;
      fine.step_s = 1e-5;
      for (const double band : {fullorder::kDefaultSettlingBandRadS2, 1e-8}) {
        SCOPED_TRACE(toString(law) + (gravity ? " with gravity" : "") + " band " +
                     std::to_string(band));
        const fullorder::DeploymentMetrics samples =
            modalDeploymentMetrics(m, drive, o, 1.0, band, PeakResolution::Samples);
        expectSameMetrics(samples, fullorder::computeMetrics(series, 1.0, band));
        expectContinuousExtendsSamples(
            modalDeploymentMetrics(m, drive, o, 1.0, band, PeakResolution::Continuous), samples,
            modalDeploymentMetrics(m, drive, fine, 1.0, band, PeakResolution::Samples));
      }
      double peak = 0.0;
      for (const double r : series.end_relative_angular_acceleration_rad_s2)
        peak = std::max(peak, std::abs(r));
      EXPECT_NEAR(peakRelativeEndAcceleration(m, drive, o), peak, 1e-10 * peak);
    }
  }
  fullorder::DriveLawParameters p;
  p.duration_s = 2.0;
  ModalDeploymentOptions o;
  o.end_time_s = 1.0;
  EXPECT_THROW(modalDeploymentMetrics(m, fullorder::DriveLaw(p), o, 2.0), InputError);
}

}  // namespace
}  // namespace mastrom::rom

// --where / --sort-by (rom/studies/screen_filter.hpp) on a hand-made table.
namespace mastrom::rom {
namespace {

ScreenTable tinyTable() {
  ScreenTable t;
  t.axes = {ScreenAxis{"interface.thickness", {1e-3, 2e-3, 3e-3, 4e-3}, {"0.001", "0.002", "0.003", "0.004"}, false}};
  t.metric_names = {"peak_von_mises_interface_1", "min_margin_of_safety"};
  t.designs = 4;
  t.parameters = {1e-3, 2e-3, 3e-3, 4e-3};
  t.metrics = {4e6, 0.2, 2e6, 1.5, 3e6, std::nan(""), 1e6, 0.9};
  return t;
}

TEST(ScreenFilter, KeepsTheRowsThatHoldAndSortsStably) {
  ScreenTable t = tinyTable();
  const long removed = filterAndSort(t, {parseColumnCondition("min_margin_of_safety > 0.5")},
                                     parseSortOrder("peak_von_mises_interface_1"));
  EXPECT_EQ(removed, 2);  // 0.2 fails, NaN never holds
  ASSERT_EQ(t.designs, 2);
  EXPECT_EQ(t.parameters, (std::vector<double>{4e-3, 2e-3}));  // ascending peak: 1e6, 2e6
  EXPECT_EQ(t.metrics, (std::vector<double>{1e6, 0.9, 2e6, 1.5}));
  ScreenTable u = tinyTable();
  filterAndSort(u, {parseColumnCondition("interface.thickness<=0.003")},
                parseSortOrder("min_margin_of_safety:desc"));
  EXPECT_EQ(u.parameters, (std::vector<double>{2e-3, 1e-3, 3e-3}));  // 1.5, 0.2, then NaN last
}

TEST(ScreenFilter, RefusesMalformedConditionsAndUnknownColumns) {
  EXPECT_THROW(parseColumnCondition("settled"), InputError);
  EXPECT_THROW(parseColumnCondition("a > b"), InputError);
  EXPECT_THROW(parseColumnCondition("> 1"), InputError);
  EXPECT_THROW(parseColumnCondition("x < nan"), InputError);
  EXPECT_THROW(parseSortOrder("x:up"), InputError);
  const ScreenTable t = tinyTable();
  EXPECT_THROW(checkColumns(t, {parseColumnCondition("margin > 1")}, std::nullopt), InputError);
  EXPECT_THROW(checkColumns(t, {}, parseSortOrder("nope")), InputError);
  EXPECT_NO_THROW(checkColumns(t, {parseColumnCondition("min_margin_of_safety >= 0")},
                               parseSortOrder("interface.thickness:desc")));
}

}  // namespace
}  // namespace mastrom::rom
