// The result file of `mastrom rom eval` written through the streamed writer's sinks
// (cli/rom_eval_output.hpp) equals the whole-series writer's (writeDeploymentFileWithStresses):
// h5diff finds no difference in any dataset or attribute, over several series blocks and with a
// stress history.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "cli/rom_eval_output.hpp"
#include "common/hdf5_file.hpp"
#include "fullorder/interface_stress_io.hpp"
#include "fullorder/result_stream.hpp"
#include "fullorder/results_io.hpp"
#include "modes/slepc_session.hpp"
#include "rom/model/modal_stress_extraction.hpp"
#include "tests/rom/direct_modal_solve.hpp"
#include "tests/rom/fixed_model.hpp"

namespace mastrom::cli {
namespace {

rom::RomEvaluation syntheticEvaluation(std::size_t samples, bool history) {
  rom::RomEvaluation e;
  for (std::size_t i = 0; i < samples; ++i) {
    fullorder::DeploymentSample s;
    const double t = 1e-4 * static_cast<double>(i);
    s.time_s = t;
    s.drive_angle_rad = 0.3 * t;
    s.drive_rate_rad_s = 0.3;
    s.drive_acceleration_rad_s2 = std::sin(3.0 * t);
    s.end_angular_acceleration_rad_s2 = {0.1 * t, -t, std::sin(900.0 * t) + std::sin(3.0 * t)};
    s.end_position_m = {std::cos(0.3 * t), std::sin(0.3 * t), 1e-6 * t};
    s.end_acceleration_m_s2 = {std::cos(50.0 * t), 2.0, -t};
    s.joint_force_n = {1.0 + t, std::sin(t), 0.5};
    s.joint_torque_nm = std::cos(700.0 * t);
    e.series.append(s);
  }
  // A ROM's relative angular acceleration comes from its modes, not as α_z − θ̈ again: the
  // writer must keep the column as it is.
  for (double& r : e.series.end_relative_angular_acceleration_rad_s2) r = std::nextafter(r, 1e9);
  e.metrics.peak_abs_end_angular_acceleration = 2.0;
  e.metrics.drive_end_time = 0.2;
  e.metrics.settling_band = 0.017;
  fullorder::InterfaceStressResult& r = e.stresses.emplace();
  r.elements_axial = 1;
  r.elements_circumferential = 2;
  r.recovery_points.assign(9, {0.0, 0.0});
  for (int k = 0; k < 2; ++k) {
    fullorder::InterfaceStressHistory h;
    if (history)
      for (std::size_t i = 0; i < samples; ++i)
        h.max_von_mises_pa.push_back(1e6 * (k + 1) * std::abs(std::sin(1e-3 * i)));
    r.history.push_back(h);
    fullorder::InterfaceStressPeak p;
    p.von_mises_pa = 1e6 * (k + 1);
    p.time_s = 0.1;
    p.field_von_mises_pa.assign(18 * 3, 5e5);
    r.peak.push_back(p);
    r.point_coordinates.push_back(std::vector<std::array<double, 2>>(18, {0.01, 1.0}));
  }
  r.time_s = e.series.time_s;  // a ROM's stresses are on the samples, with or without history
  return e;
}

TEST(RomEvalOutput, StreamedFileEqualsTheWholeSeriesWriters) {
  if (std::system("h5diff --version >/dev/null 2>&1") != 0) GTEST_SKIP() << "no h5diff";
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("rom_eval_output_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  for (bool history : {false, true}) {
    // 9000 samples: two full series blocks of 4096 and a partial one.
    const rom::RomEvaluation e = syntheticEvaluation(9000, history);
    const std::string held = (dir / "held.h5").string(), streamed = (dir / "streamed.h5").string();
    fullorder::writeDeploymentFileWithStresses(held, e.series, e.metrics, "[mast]\n", 1.5,
                                               e.stresses, 2.7e8, fullorder::ResultSource::Rom);
    writeRomEvaluationFile(streamed, e, 0.2, "[mast]\n", 1.5, 2.7e8);
    const std::string diff = "h5diff -q '" + held + "' '" + streamed + "'";
    EXPECT_EQ(std::system(diff.c_str()), 0) << "history " << history;
    // h5diff sees a difference where there is one.
    rom::RomEvaluation other = e;
    other.series.joint_torque_nm[4500] += 1e-9;
    writeRomEvaluationFile(streamed, other, 0.2, "[mast]\n", 1.5, 2.7e8);
    EXPECT_NE(std::system((diff + " >/dev/null").c_str()), 0);
  }
  std::filesystem::remove_all(dir);
}

// SIGINT / SIGTERM between blocks (cmd_rom passes cli/interrupt.hpp's flag): the file ends with
// the blocks written, the series and the stress history alike, and is marked incomplete at the
// last instant written.
TEST(RomEvalOutput, AStopBetweenBlocksLeavesAValidFileMarkedIncomplete) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("rom_eval_output_stop_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const rom::RomEvaluation e = syntheticEvaluation(9000, true);
  const std::string path = (dir / "stopped.h5").string();
  int asked = 0;
  const RomEvaluationFileSummary written = writeRomEvaluationFile(
      path, e, 0.2, "[mast]\n", 1.5, 2.7e8, {}, [&asked] { return ++asked == 1; });
  EXPECT_EQ(asked, 1);
  const std::size_t block = fullorder::DeploymentResultStream::kBlockRows;
  ASSERT_EQ(written.samples, block);
  ASSERT_TRUE(written.stopped_at_s.has_value());
  EXPECT_EQ(*written.stopped_at_s, e.series.time_s[block - 1]);

  const fullorder::DeploymentFile file = fullorder::readDeploymentFile(path);
  EXPECT_FALSE(file.complete);
  ASSERT_EQ(file.series.size(), block);
  for (std::size_t i = 0; i < block; i += 1023) {
    EXPECT_EQ(file.series.time_s[i], e.series.time_s[i]);
    EXPECT_EQ(file.series.end_relative_angular_acceleration_rad_s2[i],
              e.series.end_relative_angular_acceleration_rad_s2[i]);
  }
  const h5::File raw = h5::File::open(path, h5::OpenMode::ReadOnly);
  EXPECT_EQ(raw.readDoubleAttribute("/", "stopped_at_s"), e.series.time_s[block - 1]);
  const std::optional<fullorder::InterfaceStressSummary> stresses =
      fullorder::readInterfaceStressSummary(path);
  ASSERT_TRUE(stresses.has_value());
  for (const auto& history : stresses->max_von_mises_pa) EXPECT_EQ(history.size(), block);

  // Never asked after the last block: a stop requested then leaves the file complete.
  const RomEvaluationFileSummary whole = writeRomEvaluationFile(
      path, syntheticEvaluation(4000, true), 0.2, "[mast]\n", 1.5, 2.7e8, {}, [] { return true; });
  EXPECT_FALSE(whole.stopped_at_s.has_value());
  EXPECT_TRUE(fullorder::readDeploymentFile(path).complete);
  std::filesystem::remove_all(dir);
}

// `rom eval -o` steps its outputs into the file as it writes it (writeStreamedRomEvaluationFile):
// the file equals the one written from the evaluation that holds them, dataset for dataset (the
// wall time apart), and a stop between blocks ends the series and the history at the same row.
TEST(RomEvalOutput, OutputsSteppedIntoTheFileEqualTheHeldEvaluationsFile) {
  if (std::system("h5diff --version >/dev/null 2>&1") != 0) GTEST_SKIP() << "no h5diff";
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("rom_eval_output_stepped_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const modes::SlepcSession session;  // the modal solve's stability check
  Config c = rom::testing::scheme1Config(6);
  rom::testing::DirectSolve d = rom::testing::directModalSolve(c, 6);
  d.modal.stress = rom::extractModalStress(d.model, d.lin.problem, d.lin.q, d.eig.modes,
                                           d.eig.eigenvalues_rad2_s2);
  const rom::testing::FixedModel interpolator(d.modal);
  rom::RomEvaluationInput input;
  input.config = c;
  input.config.output.step_s = 5e-6;  // 10 001 samples: two blocks of 4096 rows and a partial one
  input.stress_history = true;
  const rom::RomEvaluation held = rom::evaluateRomDeployment(interpolator, input);
  ASSERT_GT(held.series.size(), 2 * fullorder::DeploymentResultStream::kBlockRows);
  const std::string held_path = (dir / "held.h5").string();
  const std::string streamed_path = (dir / "streamed.h5").string();
  writeRomEvaluationFile(held_path, held, c.drive.duration_s, "[mast]\n", 1.5, 2.7e8);
  rom::RomEvaluation outcome = rom::evaluateRomOutcome(interpolator, input);
  const RomEvaluationFileSummary written =
      writeStreamedRomEvaluationFile(streamed_path, outcome, input, "[mast]\n", 1.5, 2.7e8);
  EXPECT_EQ(written.samples, held.series.size());
  for (const char* object :
       {"/time", "/drive", "/end", "/joint", "/solver", "/metrics", "/interfaces"}) {
    const std::string diff =
        "h5diff -q '" + held_path + "' '" + streamed_path + "' " + object + " " + object;
    EXPECT_EQ(std::system(diff.c_str()), 0) << object;
  }

  // Stopped after the first block: the series and the history end there, marked incomplete.
  rom::RomEvaluation again = rom::evaluateRomOutcome(interpolator, input);
  const RomEvaluationFileSummary stopped = writeStreamedRomEvaluationFile(
      streamed_path, again, input, "[mast]\n", 1.5, 2.7e8, {}, [] { return true; });
  const std::size_t block = fullorder::DeploymentResultStream::kBlockRows;
  EXPECT_EQ(stopped.samples, block);
  ASSERT_TRUE(stopped.stopped_at_s.has_value());
  EXPECT_EQ(*stopped.stopped_at_s, held.series.time_s[block - 1]);
  EXPECT_FALSE(fullorder::readDeploymentFile(streamed_path).complete);
  const std::optional<fullorder::InterfaceStressSummary> stresses =
      fullorder::readInterfaceStressSummary(streamed_path);
  ASSERT_TRUE(stresses.has_value());
  for (const auto& history : stresses->max_von_mises_pa) EXPECT_EQ(history.size(), block);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace mastrom::cli
