// Tests of fullorder/deployment_result.hpp (metrics on analytic signals, against hand-derived
// values) and fullorder/results_io.hpp (the docs/user_guide.md §5 layout, refusal of non-finite
// data, foreign files).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include <unistd.h>

#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "common/version.hpp"
#include "fullorder/deployment_result.hpp"
#include "fullorder/results_io.hpp"

namespace fs = std::filesystem;
using namespace mastrom::fullorder;
using mastrom::InputError;
using mastrom::IoError;
using mastrom::NumericalError;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// A fresh directory under the system temp dir, removed with everything in it at the end.
class TempDir {
public:
  TempDir() {
    const std::string name = "mastrom_test_result_" + std::to_string(::getpid()) + "_" +
                             ::testing::UnitTest::GetInstance()->current_test_info()->name();
    path_ = fs::temp_directory_path() / name;
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const fs::path& path() const { return path_; }

private:
  fs::path path_;
};

template <typename ExceptionType, typename Statement>
void expectThrowContaining(Statement statement, const std::vector<std::string>& parts) {
  try {
    statement();
    ADD_FAILURE() << "no exception thrown";
  } catch (const ExceptionType& e) {
    const std::string message = e.what();
    for (const std::string& part : parts) {
      EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
    }
  }
}

/// Uniformly sampled series on [0, end] with step dt: drive acceleration θ̈(t) and relative
/// acceleration r(t) given; the absolute Z acceleration is θ̈ + r, so append() recovers r.
DeploymentSeries makeSeries(double end_s, double dt_s, const std::function<double(double)>& drive_acc,
                            const std::function<double(double)>& relative) {
  DeploymentSeries series;
  const int steps = static_cast<int>(std::lround(end_s / dt_s));
  series.reserve(static_cast<std::size_t>(steps) + 1);
  for (int i = 0; i <= steps; ++i) {
    DeploymentSample s;
    s.time_s = i * dt_s;
    s.drive_acceleration_rad_s2 = drive_acc(s.time_s);
    s.end_angular_acceleration_rad_s2 = {0.1, -0.2, s.drive_acceleration_rad_s2 + relative(s.time_s)};
    series.append(s);
  }
  return series;
}

/// Trapezoidal drive acceleration of docs/theory.md §1 (ramp 0.1 s, cruise 15 °/s, T = 6.1 s).
double trapezoidalAcceleration(double t) {
  const double peak = (15.0 * kPi / 180.0) / 0.1;
  if (t < 0.1) return peak;
  if (t >= 6.0 && t < 6.1) return -peak;
  return 0.0;
}

/// Series with a few samples of every column, deterministic, for file round trips.
DeploymentSeries makeRichSeries(std::size_t n) {
  DeploymentSeries series;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = 0.01 * static_cast<double>(i);
    DeploymentSample s;
    s.time_s = t;
    s.drive_angle_rad = 0.5 * t * t;
    s.drive_rate_rad_s = t;
    s.drive_acceleration_rad_s2 = 1.0;
    s.end_angular_acceleration_rad_s2 = {std::sin(t), std::cos(t), 1.0 + 0.1 * std::sin(50.0 * t)};
    s.end_position_m = {0.6 * std::cos(t), 0.6 * std::sin(t), 0.0};
    s.end_acceleration_m_s2 = {-t, 2.0 * t, 1e-3};
    s.joint_force_n = {3.0 + t, -4.0, 0.25};
    s.joint_torque_nm = -2.0 + t;
    s.newton_iterations = 2 + static_cast<int>(i % 3);
    s.constraint_residual = 1e-12 * static_cast<double>(i + 1);
    series.append(s);
  }
  return series;
}

}  // namespace

// --- DeploymentSeries --------------------------------------------------------------------------------
TEST(DeploymentSeries, AppendComputesRelativeAccelerationAndChecksTime) {
  DeploymentSeries series;
  DeploymentSample s;
  s.time_s = 0.0;
  s.drive_acceleration_rad_s2 = 2.5;
  s.end_angular_acceleration_rad_s2 = {7.0, 8.0, 3.0};
  series.append(s);
  ASSERT_EQ(series.size(), 1u);
  EXPECT_DOUBLE_EQ(series.end_relative_angular_acceleration_rad_s2[0], 0.5);  // Z − θ̈
  EXPECT_THROW(series.append(s), mastrom::UsageError);                       // same time
  s.time_s = 1.0;
  series.append(s);
  EXPECT_NO_THROW(series.checkConsistent());
  series.joint_torque_nm.pop_back();
  expectThrowContaining<mastrom::UsageError>([&] { series.checkConsistent(); },
                                               {"joint_torque_nm"});
}

// --- metrics on analytic signals ---------------------------------------------------------------------
TEST(DeploymentMetrics, ConstantSignalNeverSettles) {
  // r = 0.5 rad/s² throughout, θ̈ = 0.2: |a_z| = 0.7, every r-metric is 0.5, and the record ends
  // outside the 1 °/s² band.
  DeploymentSeries series = makeSeries(10.0, 0.01, [](double) { return 0.2; },
                                       [](double) { return 0.5; });
  for (std::size_t i = 0; i < series.size(); ++i) {
    series.joint_force_n[i] = {3.0, 4.0, 0.0};
    series.joint_torque_nm[i] = i == 500 ? -2.0 : 1.0;
  }
  const DeploymentMetrics m = computeMetrics(series, 6.1);
  EXPECT_NEAR(m.peak_abs_end_angular_acceleration, 0.7, 1e-14);
  EXPECT_NEAR(m.peak_rel_end_angular_acceleration, 0.5, 1e-14);
  EXPECT_NEAR(m.rms_rel_end_angular_acceleration, 0.5, 1e-14);
  EXPECT_NEAR(m.residual_rel_end_angular_acceleration, 0.5, 1e-14);
  EXPECT_FALSE(m.settled);
  EXPECT_DOUBLE_EQ(m.settling_time, 10.0);  // the record end
  EXPECT_DOUBLE_EQ(m.peak_joint_force, 5.0);  // ‖(3, 4, 0)‖
  EXPECT_DOUBLE_EQ(m.peak_drive_torque, 2.0);
  EXPECT_DOUBLE_EQ(m.drive_end_time, 6.1);
  EXPECT_DOUBLE_EQ(m.settling_band, kPi / 180.0);
}

TEST(DeploymentMetrics, SignalInsideTheBandSettlesAtDriveEnd) {
  const DeploymentSeries series = makeSeries(8.0, 0.01, trapezoidalAcceleration,
                                             [](double) { return -0.01; });
  const DeploymentMetrics m = computeMetrics(series, 6.1);
  EXPECT_TRUE(m.settled);
  EXPECT_DOUBLE_EQ(m.settling_time, 6.1);
  EXPECT_NEAR(m.residual_rel_end_angular_acceleration, 0.01, 1e-15);
  // |a_z| peaks during the ramps: 15 °/s over 0.1 s plus |r|.
  EXPECT_NEAR(m.peak_abs_end_angular_acceleration, 15.0 * kPi / 180.0 / 0.1 + 0.01, 1e-12);
}

TEST(DeploymentMetrics, ExponentialDecaySettlesAtTheBandCrossing) {
  // r = A e^{−σ(t−t_d)} after the drive stops: |r| = b at t_d + ln(A/b)/σ exactly.
  const double t_d = 6.1, amplitude = 1.0, sigma = 2.0, band = kPi / 180.0;
  const DeploymentSeries series = makeSeries(
      10.0, 1e-3, trapezoidalAcceleration,
      [&](double t) { return t < t_d ? 0.0 : amplitude * std::exp(-sigma * (t - t_d)); });
  const DeploymentMetrics m = computeMetrics(series, t_d);
  EXPECT_TRUE(m.settled);
  // Linear interpolation of e^{−σt} over 1 ms is accurate to ≈ σ²Δt²/8 relative: far below 1e-6 s.
  EXPECT_NEAR(m.settling_time, t_d + std::log(amplitude / band) / sigma, 1e-6);
  // Sampled at 1 ms, the first post-drive sample is within 1 ms of t_d: r ≥ A e^{−σ·1e-3}.
  EXPECT_LE(m.residual_rel_end_angular_acceleration, amplitude);
  EXPECT_GE(m.residual_rel_end_angular_acceleration, amplitude * std::exp(-sigma * 1e-3));
}

TEST(DeploymentMetrics, DecayingSinusoidAfterTheDrive) {
  // r(τ) = A e^{−στ} sin(ωτ), τ = t − t_d ≥ 0, zero during the drive (T = 6.1 s), record to 10 s.
  const double t_d = 6.1, t_end = 10.0, dt = 1e-4;
  const double amplitude = 1.0, sigma = 2.0, omega = 2.0 * kPi * 5.0, band = kPi / 180.0;
  const DeploymentSeries series =
      makeSeries(t_end, dt, trapezoidalAcceleration, [&](double t) {
        const double tau = t - t_d;
        return tau < 0.0 ? 0.0 : amplitude * std::exp(-sigma * tau) * std::sin(omega * tau);
      });
  const DeploymentMetrics m = computeMetrics(series, t_d);

  // First extremum where d/dτ = 0: tan(ωτ*) = ω/σ; it is the largest |r|.
  const double tau_peak = std::atan(omega / sigma) / omega;
  const double peak = amplitude * std::exp(-sigma * tau_peak) * std::sin(omega * tau_peak);
  // Sampling at Δt misses the crest by at most ½|r''|(Δt/2)² ≈ ½ A ω² (Δt/2)².
  const double sampling = 0.5 * amplitude * omega * omega * 0.25 * dt * dt;
  EXPECT_NEAR(m.peak_rel_end_angular_acceleration, peak, sampling);
  EXPECT_NEAR(m.residual_rel_end_angular_acceleration, peak, sampling);
  EXPECT_NEAR(m.peak_abs_end_angular_acceleration, 15.0 * kPi / 180.0 / 0.1, 1e-12);

  // RMS over [0, t_end]: A² ∫₀ᴸ e^{−2στ} sin²(ωτ) dτ / t_end, L = t_end − t_d, with
  // ∫ e^{−2στ} sin² = ½[(1 − e^{−2σL})/(2σ) − (2σ + e^{−2σL}(2ω sin 2ωL − 2σ cos 2ωL))/(4σ² + 4ω²)].
  const double L = t_end - t_d, e = std::exp(-2.0 * sigma * L);
  const double cos_integral =
      (2.0 * sigma + e * (2.0 * omega * std::sin(2.0 * omega * L) -
                          2.0 * sigma * std::cos(2.0 * omega * L))) /
      (4.0 * sigma * sigma + 4.0 * omega * omega);
  const double integral = 0.5 * ((1.0 - e) / (2.0 * sigma) - cos_integral);
  const double rms = amplitude * std::sqrt(integral / t_end);
  EXPECT_NEAR(m.rms_rel_end_angular_acceleration, rms, 1e-6 * rms);

  // Settling: the envelope A e^{−στ} reaches b at τ_e = ln(A/b)/σ ≈ 2.02 s, inside the record; no
  // excursion beyond b comes later. Crests of |r| are π/ω apart and reach ω/√(ω²+σ²) ≈ 0.998 of the
  // envelope, so the crest in the last half period before τ_e (less ≈ ln(1.002)/σ) still exceeds b.
  const double t_envelope = t_d + std::log(amplitude / band) / sigma;
  ASSERT_LT(t_envelope, t_end);
  EXPECT_TRUE(m.settled);
  EXPECT_LE(m.settling_time, t_envelope);
  EXPECT_GE(m.settling_time, t_envelope - kPi / omega - 2e-3);
}

TEST(DeploymentMetrics, RmsWeightsUnequalStepsAndSettlingInterpolates) {
  // Samples (t, r): (0, 0), (1, 2), (3, 2). Trapezoidal ∫r² = ½(0+4)·1 + ½(4+4)·2 = 10 over 3 s.
  DeploymentSeries series;
  const double times[] = {0.0, 1.0, 3.0};
  const double values[] = {0.0, 2.0, 2.0};
  for (int i = 0; i < 3; ++i) {
    DeploymentSample s;
    s.time_s = times[i];
    s.end_angular_acceleration_rad_s2.z() = values[i];
    series.append(s);
  }
  EXPECT_NEAR(computeMetrics(series, 0.0).rms_rel_end_angular_acceleration, std::sqrt(10.0 / 3.0),
              1e-15);

  // r = (−0.5, 0.1, 0.0) at t = (0, 1, 2), band 0.2: r crosses −0.2 at t = 0.5 (linear, through a
  // sign change); with t_d = 1.5 the settling time is clamped to t_d.
  DeploymentSeries crossing;
  const double r[] = {-0.5, 0.1, 0.0};
  for (int i = 0; i < 3; ++i) {
    DeploymentSample s;
    s.time_s = i;
    s.end_angular_acceleration_rad_s2.z() = r[i];
    crossing.append(s);
  }
  DeploymentMetrics m = computeMetrics(crossing, 0.0, 0.2);
  EXPECT_TRUE(m.settled);
  EXPECT_NEAR(m.settling_time, 0.5, 1e-15);
  EXPECT_NEAR(m.residual_rel_end_angular_acceleration, 0.5, 1e-15);
  m = computeMetrics(crossing, 1.5, 0.2);
  EXPECT_DOUBLE_EQ(m.settling_time, 1.5);
  EXPECT_NEAR(m.residual_rel_end_angular_acceleration, 0.0, 1e-15);  // only t = 2 counts

  // A single sample: RMS is |r|.
  DeploymentSeries single;
  DeploymentSample s;
  s.end_angular_acceleration_rad_s2.z() = -3.0;
  single.append(s);
  EXPECT_DOUBLE_EQ(computeMetrics(single, 0.0).rms_rel_end_angular_acceleration, 3.0);
}

TEST(DeploymentMetrics, RejectsBadInput) {
  DeploymentSeries series = makeSeries(5.0, 0.1, [](double) { return 0.0; },
                                       [](double) { return 0.0; });
  // A record that ends before the drive: residual and settling are not available, and say why.
  const DeploymentMetrics short_record = computeMetrics(series, 6.1);
  EXPECT_TRUE(std::isnan(short_record.residual_rel_end_angular_acceleration));
  EXPECT_TRUE(std::isnan(short_record.settling_time));
  EXPECT_FALSE(short_record.settled);
  EXPECT_NE(short_record.not_available.find("the record ends at t = 5 s, before the drive does ("),
            std::string::npos)
      << short_record.not_available;
  expectThrowContaining<InputError>([&] { computeMetrics(series, 1.0, 0.0); }, {"settling band"});
  expectThrowContaining<InputError>(
      [&] { computeMetrics(series, std::numeric_limits<double>::quiet_NaN()); }, {"drive end"});
  EXPECT_THROW(computeMetrics(DeploymentSeries{}, 0.0), mastrom::UsageError);
  series.end_relative_angular_acceleration_rad_s2[7] = std::numeric_limits<double>::infinity();
  expectThrowContaining<NumericalError>([&] { computeMetrics(series, 1.0); },
                                        {"end_relative_angular_acceleration_rad_s2[7]", "inf"});
}

// --- files ---------------------------------------------------------------------------------------------
TEST(ResultsIo, RoundTripHasTheDesignLayout) {
  TempDir dir;
  const std::string path = dir.file("deployment.h5");
  const DeploymentSeries series = makeRichSeries(40);
  const DeploymentMetrics metrics = computeMetrics(series, 0.2);
  const std::string config = "[mast]\nmodules = 4\n[drive]\nlaw = \"cubic\"\n";
  writeDeploymentFile(path, series, metrics, config, 12.5, ResultSource::Rom);
  EXPECT_EQ(fs::directory_iterator(dir.path())->path().filename(), "deployment.h5");  // no temp left

  const DeploymentFile back = readDeploymentFile(path);
  EXPECT_EQ(back.series.time_s, series.time_s);
  EXPECT_EQ(back.series.drive_angle_rad, series.drive_angle_rad);
  EXPECT_EQ(back.series.drive_rate_rad_s, series.drive_rate_rad_s);
  EXPECT_EQ(back.series.drive_acceleration_rad_s2, series.drive_acceleration_rad_s2);
  EXPECT_EQ(back.series.end_angular_acceleration_rad_s2, series.end_angular_acceleration_rad_s2);
  EXPECT_EQ(back.series.end_relative_angular_acceleration_rad_s2,
            series.end_relative_angular_acceleration_rad_s2);
  EXPECT_EQ(back.series.end_position_m, series.end_position_m);
  EXPECT_EQ(back.series.end_acceleration_m_s2, series.end_acceleration_m_s2);
  EXPECT_EQ(back.series.joint_force_n, series.joint_force_n);
  EXPECT_EQ(back.series.joint_torque_nm, series.joint_torque_nm);
  EXPECT_EQ(back.series.newton_iterations, series.newton_iterations);
  EXPECT_EQ(back.series.constraint_residual, series.constraint_residual);
  EXPECT_EQ(back.metrics.peak_abs_end_angular_acceleration,
            metrics.peak_abs_end_angular_acceleration);
  EXPECT_EQ(back.metrics.peak_rel_end_angular_acceleration,
            metrics.peak_rel_end_angular_acceleration);
  EXPECT_EQ(back.metrics.rms_rel_end_angular_acceleration, metrics.rms_rel_end_angular_acceleration);
  EXPECT_EQ(back.metrics.residual_rel_end_angular_acceleration,
            metrics.residual_rel_end_angular_acceleration);
  EXPECT_EQ(back.metrics.settling_time, metrics.settling_time);
  EXPECT_EQ(back.metrics.settled, metrics.settled);
  EXPECT_EQ(back.metrics.peak_joint_force, metrics.peak_joint_force);
  EXPECT_EQ(back.metrics.peak_drive_torque, metrics.peak_drive_torque);
  EXPECT_EQ(back.metrics.drive_end_time, 0.2);
  EXPECT_EQ(back.metrics.settling_band, kDefaultSettlingBandRadS2);
  EXPECT_EQ(back.config_toml, config);
  EXPECT_EQ(back.mastrom_version, std::string(mastrom::kVersion));
  EXPECT_EQ(back.source, ResultSource::Rom);
  EXPECT_EQ(back.wall_time_s, 12.5);

  // The layout itself, as another program (h5py, h5dump) sees it.
  const mastrom::h5::File file = mastrom::h5::File::open(path, mastrom::h5::OpenMode::ReadOnly);
  const std::vector<std::pair<std::string, std::string>> datasets{
      {"/time", "s"},
      {"/drive/angle", "rad"},
      {"/drive/rate", "rad/s"},
      {"/drive/acceleration", "rad/s^2"},
      {"/end/angular_acceleration", "rad/s^2"},
      {"/end/relative_angular_acceleration", "rad/s^2"},
      {"/end/position", "m"},
      {"/end/acceleration", "m/s^2"},
      {"/joint/force", "N"},
      {"/joint/torque", "N*m"},
      {"/solver/newton_iterations", "1"},
      {"/solver/constraint_residual", "1"}};
  const std::set<std::string> matrices{"/end/angular_acceleration", "/end/position",
                                       "/end/acceleration", "/joint/force"};
  for (const auto& [name, units] : datasets) {
    EXPECT_EQ(file.readUnits(name), units) << name;
    const std::vector<std::size_t> expected =
        matrices.count(name) ? std::vector<std::size_t>{40, 3} : std::vector<std::size_t>{40};
    EXPECT_EQ(file.datasetShape(name), expected) << name;
  }
  EXPECT_EQ(
      file.attributeNames("/"),
      (std::vector<std::string>{"complete", "config", "mastrom_version", "source", "wall_time_s"}));
  EXPECT_EQ(file.readIntAttribute("/", "complete"), 1);
  EXPECT_EQ(file.readStringAttribute("/", "source"), "rom");
  EXPECT_EQ(file.readIntAttribute("/metrics", "settled"), metrics.settled ? 1 : 0);
  // The nine metrics, settled and peaks_resolved; the estimates of the full order's own error are
  // left out when there are none (never written as NaN).
  EXPECT_EQ(file.attributeNames("/metrics").size(), 11u);
}

TEST(ResultsIo, NonFiniteDataIsRefusedAndNoFileIsCreated) {
  TempDir dir;
  const std::string path = dir.file("nan.h5");
  DeploymentSeries series = makeRichSeries(10);
  const DeploymentMetrics metrics = computeMetrics(series, 0.05);
  series.end_position_m[7][1] = std::numeric_limits<double>::quiet_NaN();
  expectThrowContaining<NumericalError>(
      [&] { writeDeploymentFile(path, series, metrics, "", 1.0, ResultSource::FullOrder); },
      {"nan.h5", "/end/position[7, 1]", "nan", "t = 0.07"});
  EXPECT_TRUE(fs::is_empty(dir.path()));  // neither the final nor a temporary file

  // A previous good result under the same name survives a refused rewrite.
  const DeploymentSeries good = makeRichSeries(10);
  writeDeploymentFile(path, good, metrics, "", 1.0, ResultSource::FullOrder);
  DeploymentMetrics bad_metrics = metrics;
  bad_metrics.settling_time = std::numeric_limits<double>::infinity();
  expectThrowContaining<NumericalError>(
      [&] { writeDeploymentFile(path, good, bad_metrics, "", 1.0, ResultSource::FullOrder); },
      {"/metrics", "settling_time", "inf"});
  expectThrowContaining<NumericalError>(
      [&] {
        writeDeploymentFile(path, good, metrics, "", std::numeric_limits<double>::quiet_NaN(),
                            ResultSource::FullOrder);
      },
      {"wall_time_s"});
  DeploymentSeries bad_time = good;
  bad_time.time_s[3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(writeDeploymentFile(path, bad_time, metrics, "", 1.0, ResultSource::FullOrder),
               mastrom::UsageError);  // a NaN time also breaks the increasing-time invariant
  EXPECT_EQ(readDeploymentFile(path).series.end_position_m, good.end_position_m);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator()), 1);
}

TEST(ResultsIo, UnwritableDestinationFailsBeforeWriting) {
  TempDir dir;
  const std::string path = dir.file("missing_dir/out.h5");
  const DeploymentSeries series = makeRichSeries(3);
  expectThrowContaining<IoError>(
      [&] {
        writeDeploymentFile(path, series, computeMetrics(series, 0.0), "", 0.0,
                            ResultSource::FullOrder);
      },
      {"missing_dir", "does not exist"});
}

TEST(ResultsIo, ForeignFilesAreRefusedWithAClearMessage) {
  TempDir dir;
  const std::string foreign = dir.file("foreign.h5");
  {
    mastrom::h5::File file =
        mastrom::h5::File::create(foreign, mastrom::h5::CreateMode::Exclusive);
    file.writeDoubles("/time", {0.0, 1.0}, "s");
    file.writeDoubles("/something/else", {1.0}, "1");
    file.close();
  }
  // 25 items missing: the first six are named, the rest counted.
  expectThrowContaining<IoError>([&] { readDeploymentFile(foreign); },
                                 {"foreign.h5", "not a mastrom deployment file", "/drive/angle",
                                  "/drive/rate", "and 19 more"});

  const std::string text = dir.file("text.h5");
  std::ofstream(text) << "time,angle\n0,0\n";
  expectThrowContaining<IoError>([&] { readDeploymentFile(text); }, {"text.h5", "not an HDF5"});
  expectThrowContaining<IoError>([&] { readDeploymentFile(dir.file("absent.h5")); },
                                 {"absent.h5", "no such file"});

  // A deployment file with a few parts removed names exactly those.
  const std::string edited = dir.file("edited.h5");
  const DeploymentSeries series = makeRichSeries(5);
  writeDeploymentFile(edited, series, computeMetrics(series, 0.0), "", 0.0, ResultSource::FullOrder);
  {
    mastrom::h5::File file = mastrom::h5::File::open(edited, mastrom::h5::OpenMode::ReadWrite);
    ASSERT_GE(H5Ldelete(file.id(), "/joint/force", H5P_DEFAULT), 0);
    ASSERT_GE(H5Adelete_by_name(file.id(), "/metrics", "settling_time", H5P_DEFAULT), 0);
    ASSERT_GE(H5Adelete(file.id(), "source"), 0);
    file.close();
  }
  expectThrowContaining<IoError>(
      [&] { readDeploymentFile(edited); },
      {"missing /joint/force, /metrics attribute settling_time, / attribute source"});

  // A deployment file whose columns disagree in length (edited by hand).
  writeDeploymentFile(edited, series, computeMetrics(series, 0.0), "", 0.0, ResultSource::FullOrder);
  {
    mastrom::h5::File file = mastrom::h5::File::open(edited, mastrom::h5::OpenMode::ReadWrite);
    ASSERT_GE(H5Ldelete(file.id(), "/joint/torque", H5P_DEFAULT), 0);
    file.writeDoubles("/joint/torque", {1.0, 2.0}, "N*m");
    file.close();
  }
  expectThrowContaining<IoError>([&] { readDeploymentFile(edited); },
                                 {"edited.h5", "/joint/torque", "2 rows", "/time has 5"});
}

TEST(ResultsIo, SourceNames) {
  EXPECT_EQ(toString(ResultSource::FullOrder), "full-order");
  EXPECT_EQ(toString(ResultSource::Rom), "rom");
  EXPECT_EQ(parseResultSource("rom"), ResultSource::Rom);
  EXPECT_EQ(parseResultSource("full-order"), ResultSource::FullOrder);
  EXPECT_FALSE(parseResultSource("full_order").has_value());
}
