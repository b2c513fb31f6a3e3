// Checkpoint/restart of a full-order deployment (crash safety; fullorder/checkpoint.hpp):
// a run continued from any checkpoint — written to a file and read back — reproduces the
// uninterrupted run bit for bit. The reference is the uninterrupted run itself; equality is exact
// (bitwise), not a tolerance, because modified Newton makes round-off history part of the result and
// the restart must reproduce that history, not merely a converged solution.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "common/config.hpp"
#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "fullorder/checkpoint.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/results_io.hpp"
#include "fullorder/streamed_result_file.hpp"

namespace mastrom::fullorder {
namespace {

namespace fs = std::filesystem;

/// Scheme 1 on the coarse 1 × 6 ring, 60 steps of 1 ms through a 40 ms drive: cheap, yet the drive's
/// jumps of θ̈ make Newton renew its factorisation at irregular steps, so a checkpoint falls between
/// reuses of a factorisation formed steps earlier.
Config smallRun() {
  Config c;
  c.mast.modules = 2;
  c.interface.elements_axial = 1;
  c.interface.elements_circumferential = 6;
  c.drive.angle_deg = 5.0;
  c.drive.duration_s = 0.04;
  c.drive.ramp_s = 0.01;
  c.simulation.time_step_s = 1e-3;
  c.simulation.end_time_s = 0.06;
  return c;
}

DeploymentOptions optionsFor(const Config& c) {
  DeploymentOptions o;
  o.integrator = integratorFromConfig(c);
  o.end_time_s = c.simulation.end_time_s;
  // Outputs every 4th step and checkpoints every 7th: most checkpoints fall between outputs, where
  // the index-1 recovery's starting values are those of an earlier output instant.
  o.output_every = 4;
  return o;
}

fs::path scratchDir() {
  const fs::path dir = fs::temp_directory_path() / ("mastrom_test_checkpoint_" +
                                                    std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

bool bitwiseEqual(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}
bool bitwiseEqual(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::memcmp(a[i].data(), b[i].data(), 3 * sizeof(double)) != 0) return false;
  }
  return true;
}

/// Names of the columns that differ in any bit.
std::string differingColumns(const DeploymentSeries& a, const DeploymentSeries& b) {
  std::string d;
  const auto check = [&](bool same, const char* name) {
    if (!same) d += std::string(d.empty() ? "" : ", ") + name;
  };
  check(bitwiseEqual(a.time_s, b.time_s), "time");
  check(bitwiseEqual(a.drive_angle_rad, b.drive_angle_rad), "drive angle");
  check(bitwiseEqual(a.end_angular_acceleration_rad_s2, b.end_angular_acceleration_rad_s2),
        "end angular acceleration");
  check(bitwiseEqual(a.end_relative_angular_acceleration_rad_s2,
                     b.end_relative_angular_acceleration_rad_s2),
        "relative angular acceleration");
  check(bitwiseEqual(a.end_position_m, b.end_position_m), "end position");
  check(bitwiseEqual(a.end_acceleration_m_s2, b.end_acceleration_m_s2), "end acceleration");
  check(bitwiseEqual(a.joint_force_n, b.joint_force_n), "joint force");
  check(bitwiseEqual(a.joint_torque_nm, b.joint_torque_nm), "joint torque");
  check(a.newton_iterations == b.newton_iterations, "newton iterations");
  check(bitwiseEqual(a.constraint_residual, b.constraint_residual), "constraint residual");
  return d;
}

struct Reference {
  DeploymentSeries series;
  DeploymentStatistics statistics;
  std::vector<std::string> checkpoint_files;
};

/// The uninterrupted run, writing a checkpoint file every `every` steps (each kept under its own name).
Reference uninterrupted(const Config& c, long every, const fs::path& dir) {
  Reference r;
  MastModel model = buildMast(mastParametersFromConfig(c));
  DeploymentOptions o = optionsFor(c);
  o.checkpoint_every_steps = every;
  o.checkpoint_sink = [&](const DeploymentCheckpoint& checkpoint) {
    const std::string path = (dir / ("step" + std::to_string(checkpoint.step) + ".h5")).string();
    writeCheckpointFile(path, checkpoint, toToml(c), 0.0);
    r.checkpoint_files.push_back(path);
  };
  r.series = simulateDeployment(model, o, &r.statistics);
  return r;
}

DeploymentSeries restarted(const Config& c, const DeploymentCheckpoint& from,
                           DeploymentStatistics* statistics) {
  MastModel model = buildMast(mastParametersFromConfig(c));
  return simulateDeployment(model, optionsFor(c), statistics, {}, &from);
}

TEST(Checkpoint, RestartFromAnyCheckpointFileReproducesTheUninterruptedRunBitForBit) {
  const Config c = smallRun();
  const fs::path dir = scratchDir();
  const Reference ref = uninterrupted(c, 7, dir);
  // Checkpoints after steps 7, 14, …, 56 (none after the last step, 60).
  ASSERT_EQ(ref.checkpoint_files.size(), 8u);

  // Checkpointing itself must not disturb the run.
  MastModel plain_model = buildMast(mastParametersFromConfig(c));
  const DeploymentSeries plain = simulateDeployment(plain_model, optionsFor(c));
  EXPECT_EQ(differingColumns(plain, ref.series), "");

  for (const std::string& file : ref.checkpoint_files) {
    SCOPED_TRACE(file);
    const CheckpointFile saved = readCheckpointFile(file);
    EXPECT_EQ(saved.config_toml, toToml(c));
    DeploymentStatistics stats;
    const DeploymentSeries series = restarted(c, saved.checkpoint, &stats);
    EXPECT_EQ(differingColumns(series, ref.series), "");
    EXPECT_EQ(stats.steps, ref.statistics.steps);
    EXPECT_EQ(stats.newton_iterations, ref.statistics.newton_iterations);
    EXPECT_EQ(stats.factorizations, ref.statistics.factorizations);
  }
  fs::remove_all(dir);
}

// The test above can see round-off: renewing the factorisation at the restart instead of rebuilding
// the one in use converges to a different iterate within the Newton tolerance, and the restarted
// run is then close to the reference but not equal to it.
TEST(Checkpoint, ARestartWithARenewedFactorisationWouldDiffer) {
  const Config c = smallRun();
  const fs::path dir = scratchDir();
  const Reference ref = uninterrupted(c, 7, dir);
  int differing = 0;
  for (const std::string& file : ref.checkpoint_files) {
    DeploymentCheckpoint checkpoint = readCheckpointFile(file).checkpoint;
    checkpoint.integrator.factor_valid = false;  // what setState() does: renew on the next step
    const DeploymentSeries series = restarted(c, checkpoint, nullptr);
    if (!differingColumns(series, ref.series).empty()) ++differing;
    // Same solution to the accuracy of the Newton tolerance (force_tolerance 1e-6 relative).
    const double torque_scale = std::abs(ref.series.joint_torque_nm.back()) + 1e-12;
    EXPECT_NEAR(series.joint_torque_nm.back(), ref.series.joint_torque_nm.back(),
                1e-4 * torque_scale);
  }
  EXPECT_GT(differing, 0);
  fs::remove_all(dir);
}

/// A streamed run's file (fullorder/streamed_result_file.hpp) finished at `path` with the series
/// written so far; `run` feeds it.
void finishStreamed(StreamedResultFile& file, const Config& c) {
  file.finish(file.sampleMetrics(), toToml(c), 0.0, ResultSource::FullOrder, std::nullopt,
              std::nullopt, std::nullopt);
}

// Fixed steps stream their outputs with checkpoints too: a checkpoint holds the last output and
// the count streamed (not the series), and a restart rebuilds the file from the one the run was
// writing, then appends. The reference is the uninterrupted run that holds its series; equality is
// bitwise.
TEST(Checkpoint, AStreamedRunRestartedFromItsFileEqualsTheUninterruptedRunBitForBit) {
  const Config c = smallRun();
  const fs::path dir = scratchDir();
  MastModel plain_model = buildMast(mastParametersFromConfig(c));
  const DeploymentSeries held = simulateDeployment(plain_model, optionsFor(c));

  // The streamed run with a checkpoint every 7 steps; each checkpoint names the file being written.
  const std::string streamed_path = (dir / "streamed.h5").string();
  std::vector<std::string> checkpoints;
  {
    StreamedResultFile file(streamed_path, c.drive.duration_s, {});
    MastModel model = buildMast(mastParametersFromConfig(c));
    DeploymentOptions o = optionsFor(c);
    o.output_sink = [&](const DeploymentSample& sample) { file.addSample(sample); };
    o.checkpoint_every_steps = 7;
    o.checkpoint_sink = [&](const DeploymentCheckpoint& checkpoint) {
      EXPECT_EQ(checkpoint.series.size(), 1u);  // the last output, not the series
      EXPECT_EQ(static_cast<std::size_t>(checkpoint.streamed_outputs), file.rows());
      file.flushSeries();
      const std::string path = (dir / ("s" + std::to_string(checkpoint.step) + ".h5")).string();
      writeCheckpointFile(path, checkpoint, toToml(c), 0.0, file.temporaryPath());
      checkpoints.push_back(path);
    };
    EXPECT_TRUE(simulateDeployment(model, o).empty());
    finishStreamed(file, c);
  }
  ASSERT_EQ(checkpoints.size(), 8u);
  EXPECT_EQ(differingColumns(readDeploymentFile(streamed_path).series, held), "");

  for (const std::string& path : checkpoints) {
    SCOPED_TRACE(path);
    const CheckpointFile saved = readCheckpointFile(path);
    EXPECT_GT(saved.checkpoint.streamed_outputs, 0);
    EXPECT_NE(saved.series_file.find("streamed.h5.tmp."), std::string::npos) << saved.series_file;
    // The temporary file was renamed when the run finished: its outputs are a prefix of the result.
    const std::string restarted_path = (dir / "restarted.h5").string();
    {
      StreamedResultFile file(restarted_path, c.drive.duration_s, {});
      rebuildStreamedSeries(file, streamed_path,
                            static_cast<std::size_t>(saved.checkpoint.streamed_outputs),
                            saved.checkpoint.series);
      MastModel model = buildMast(mastParametersFromConfig(c));
      DeploymentOptions o = optionsFor(c);
      o.output_sink = [&](const DeploymentSample& sample) { file.addSample(sample); };
      simulateDeployment(model, o, nullptr, {}, &saved.checkpoint);
      finishStreamed(file, c);
    }
    EXPECT_EQ(differingColumns(readDeploymentFile(restarted_path).series, held), "");
  }

  // The file must be this run's, up to the checkpoint: fewer rows, or another output there, fail.
  const CheckpointFile saved = readCheckpointFile(checkpoints.back());
  const auto rebuild = [&](std::size_t rows, const DeploymentSeries& last) {
    StreamedResultFile file((dir / "other.h5").string(), c.drive.duration_s, {});
    rebuildStreamedSeries(file, streamed_path, rows, last);
  };
  EXPECT_THROW(rebuild(held.size() + 1, saved.checkpoint.series), IoError);
  DeploymentSeries other = saved.checkpoint.series;
  double& z = other.end_angular_acceleration_rad_s2[0].z();
  z = std::nextafter(z, HUGE_VAL);  // one bit
  try {
    rebuild(static_cast<std::size_t>(saved.checkpoint.streamed_outputs), other);
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("is not the result of the checkpointed run"),
              std::string::npos)
        << e.what();
  }
  // A streamed run's checkpoint does not continue a run that holds its series.
  MastModel model = buildMast(mastParametersFromConfig(c));
  EXPECT_THROW(simulateDeployment(model, optionsFor(c), nullptr, {}, &saved.checkpoint),
               InputError);
  fs::remove_all(dir);
}

/// smallRun() with error-controlled steps: three breakpoints (10, 30, 40 ms) restart the stream's
/// pieces, and checkpoints every 12 ms fall inside a ringing, between breakpoints.
Config smallAdaptiveRun() {
  Config c = smallRun();
  c.simulation.adaptive = true;
  c.simulation.time_step_s = 1e-5;  // the first step
  c.simulation.end_time_s = 0.05;
  c.output.step_s = 1e-4;
  return c;
}

bool samePeaks(const ContinuousPeaks& a, const ContinuousPeaks& b) {
  return std::memcmp(&a, &b, sizeof(ContinuousPeaks)) == 0;
}

// Adaptive steps stream their outputs with checkpoints too: a checkpoint holds the last output,
// the count streamed and the continuous response's window (a few step points) and peaks, not the
// step points so far. A restart from each checkpoint file rebuilds the result from the file the
// run was writing and continues; the reference is the adaptive run that holds its step points and
// resamples them at the end. Equality is bitwise, the peaks included.
TEST(Checkpoint, AStreamedAdaptiveRunRestartedFromItsFileEqualsTheHeldRunBitForBit) {
  const Config c = smallAdaptiveRun();
  const fs::path dir = scratchDir();
  DeploymentStatistics held_stats;
  MastModel plain_model = buildMast(mastParametersFromConfig(c));
  const DeploymentSeries held =
      simulateDeployment(plain_model, deploymentFromConfig(c), &held_stats);
  ASSERT_GT(held.size(), 400u);

  const std::string streamed_path = (dir / "adaptive.h5").string();
  std::vector<std::string> checkpoints;
  {
    StreamedResultFile file(streamed_path, c.drive.duration_s, {});
    MastModel model = buildMast(mastParametersFromConfig(c));
    DeploymentOptions o = deploymentFromConfig(c);
    o.output_sink = [&](const DeploymentSample& sample) { file.addSample(sample); };
    o.checkpoint_every_s = 0.012;
    o.checkpoint_sink = [&](const DeploymentCheckpoint& checkpoint) {
      EXPECT_EQ(checkpoint.series.size(), 1u);  // the last output, not the step points
      EXPECT_LE(checkpoint.stream.window.size(), 4u);
      EXPECT_EQ(static_cast<std::size_t>(checkpoint.streamed_outputs), file.rows());
      file.flushSeries();
      const std::string path = (dir / ("a" + std::to_string(checkpoint.step) + ".h5")).string();
      writeCheckpointFile(path, checkpoint, toToml(c), 0.0, file.temporaryPath());
      checkpoints.push_back(path);
    };
    DeploymentStatistics stats;
    EXPECT_TRUE(simulateDeployment(model, o, &stats).empty());
    EXPECT_TRUE(samePeaks(stats.continuous_peaks, held_stats.continuous_peaks));
    finishStreamed(file, c);
  }
  ASSERT_EQ(checkpoints.size(), 4u);  // at 12, 24, 36 and 48 ms
  EXPECT_EQ(differingColumns(readDeploymentFile(streamed_path).series, held), "");

  for (const std::string& path : checkpoints) {
    SCOPED_TRACE(path);
    const CheckpointFile saved = readCheckpointFile(path);
    ASSERT_GT(saved.checkpoint.streamed_outputs, 0);
    ASSERT_GT(saved.checkpoint.stream.points, 0u);
    EXPECT_FALSE(saved.checkpoint.piece_start_times_s.empty());
    const std::string restarted_path = (dir / "adaptive_restarted.h5").string();
    DeploymentStatistics stats;
    {
      StreamedResultFile file(restarted_path, c.drive.duration_s, {});
      rebuildStreamedSeries(file, streamed_path,
                            static_cast<std::size_t>(saved.checkpoint.streamed_outputs),
                            saved.checkpoint.series);
      MastModel model = buildMast(mastParametersFromConfig(c));
      DeploymentOptions o = deploymentFromConfig(c);
      o.output_sink = [&](const DeploymentSample& sample) { file.addSample(sample); };
      simulateDeployment(model, o, &stats, {}, &saved.checkpoint);
      finishStreamed(file, c);
    }
    EXPECT_EQ(differingColumns(readDeploymentFile(restarted_path).series, held), "");
    EXPECT_TRUE(samePeaks(stats.continuous_peaks, held_stats.continuous_peaks));
    EXPECT_EQ(stats.piece_start_times_s, held_stats.piece_start_times_s);
    EXPECT_EQ(stats.steps, held_stats.steps);
  }
  // A streamed adaptive run's checkpoint does not continue one that holds its step points.
  const CheckpointFile saved = readCheckpointFile(checkpoints.front());
  MastModel model = buildMast(mastParametersFromConfig(c));
  EXPECT_THROW(simulateDeployment(model, deploymentFromConfig(c), nullptr, {}, &saved.checkpoint),
               InputError);
  fs::remove_all(dir);
}

TEST(Checkpoint, ADifferentConfigurationIsRefusedNamingTheKey) {
  Config a = smallRun();
  Config b = a;
  b.interface.thickness_m = 2.5e-3;
  try {
    requireSameConfiguration("c.h5", toToml(a), toToml(b));
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("interface.thickness = "), std::string::npos) << what;
    EXPECT_NE(what.find("0.0025 now"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
  // A string value: the comment toToml writes after it is not part of the value.
  Config law = a;
  law.drive.law = DriveLawKind::Cubic;
  try {
    requireSameConfiguration("c.h5", toToml(a), toToml(law));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "drive.law = \"trapezoidal\" in the checkpoint, \"cubic\" now"),
              std::string::npos)
        << e.what();
  }
  // The result file name does not change the results.
  Config d = a;
  d.output.file = "elsewhere.h5";
  EXPECT_NO_THROW(requireSameConfiguration("c.h5", toToml(a), toToml(d)));
}

TEST(Checkpoint, ADeploymentResultFileIsNotACheckpoint) {
  const fs::path dir = scratchDir();
  const std::string path = (dir / "result.h5").string();
  DeploymentSeries series;
  DeploymentSample sample;
  series.append(sample);
  sample.time_s = 1.0;
  series.append(sample);
  writeDeploymentFile(path, series, computeMetrics(series, 0.5), "", 0.0,
                      ResultSource::FullOrder);
  try {
    readCheckpointFile(path);
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("is not a mastrom checkpoint"), std::string::npos)
        << e.what();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace mastrom::fullorder
