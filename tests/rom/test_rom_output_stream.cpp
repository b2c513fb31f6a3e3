// `rom eval -o`'s outputs stepped as they are written (rom/studies/rom_evaluation.hpp
// streamRomOutputs, rom/model/modal_deployment.hpp streamModalDeployment): the series handed over
// in blocks and the stress histories block by block equal, bit for bit, what the evaluation that
// holds them computes (evaluateRomDeployment), whatever the block size. The reference is that held
// evaluation itself: the streamed path must not change a single output.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "fullorder/mast_config.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/model/modal_stepping.hpp"
#include "rom/model/modal_stress_extraction.hpp"
#include "rom/studies/rom_evaluation.hpp"
#include "tests/rom/direct_modal_solve.hpp"
#include "tests/rom/fixed_model.hpp"

namespace mastrom::rom {
namespace {

template <typename T>
bool sameBits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

/// Every column of `b`, appended block by block as handed over, equals `a`'s bit for bit.
void expectSameSeries(const fullorder::DeploymentSeries& a, const fullorder::DeploymentSeries& b) {
  EXPECT_TRUE(sameBits(a.time_s, b.time_s));
  EXPECT_TRUE(sameBits(a.drive_angle_rad, b.drive_angle_rad));
  EXPECT_TRUE(sameBits(a.drive_rate_rad_s, b.drive_rate_rad_s));
  EXPECT_TRUE(sameBits(a.drive_acceleration_rad_s2, b.drive_acceleration_rad_s2));
  EXPECT_TRUE(sameBits(a.end_angular_acceleration_rad_s2, b.end_angular_acceleration_rad_s2));
  EXPECT_TRUE(sameBits(a.end_relative_angular_acceleration_rad_s2,
                       b.end_relative_angular_acceleration_rad_s2));
  EXPECT_TRUE(sameBits(a.end_position_m, b.end_position_m));
  EXPECT_TRUE(sameBits(a.end_acceleration_m_s2, b.end_acceleration_m_s2));
  EXPECT_TRUE(sameBits(a.joint_force_n, b.joint_force_n));
  EXPECT_TRUE(sameBits(a.joint_torque_nm, b.joint_torque_nm));
}

/// The blocks' rows appended as stored (the relative angular acceleration comes from the modes).
void appendRows(const fullorder::DeploymentSeries& block, fullorder::DeploymentSeries& all) {
  for (std::size_t i = 0; i < block.size(); ++i) {
    all.append(block.sample(i));
    all.end_relative_angular_acceleration_rad_s2.back() =
        block.end_relative_angular_acceleration_rad_s2[i];
  }
}

TEST(RomOutputStream, StreamedSeriesAndHistoriesEqualTheHeldEvaluationBitForBit) {
  Config c = testing::scheme1Config(10);
  testing::DirectSolve d = testing::directModalSolve(c, 10);
  d.modal.stress =
      extractModalStress(d.model, d.lin.problem, d.lin.q, d.eig.modes, d.eig.eigenvalues_rad2_s2);
  const testing::FixedModel interpolator(d.modal);
  RomEvaluationInput input;
  input.config = c;
  input.config.output.step_s = 1e-5;  // 5001 samples
  input.stress_history = true;
  const RomEvaluation held = evaluateRomDeployment(interpolator, input);
  ASSERT_TRUE(held.stresses.has_value());
  ASSERT_GT(held.series.size(), 1000u);

  // Blocks of 1 row, of 333 (not a divisor of the samples) and one block of everything.
  for (std::size_t block_rows : {std::size_t{1}, std::size_t{333}, held.series.size()}) {
    SCOPED_TRACE(block_rows);
    RomEvaluation e = evaluateRomOutcome(interpolator, input);
    EXPECT_TRUE(e.series.empty());
    EXPECT_EQ(e.output_samples, held.series.size());
    // The numbers printed are the held evaluation's.
    EXPECT_EQ(std::memcmp(&e.metrics.peak_rel_end_angular_acceleration,
                          &held.metrics.peak_rel_end_angular_acceleration, sizeof(double)),
              0);
    ASSERT_TRUE(e.stresses.has_value());
    ASSERT_EQ(e.stresses->peak.size(), held.stresses->peak.size());
    for (std::size_t i = 0; i < held.stresses->peak.size(); ++i)
      EXPECT_EQ(e.stresses->peak[i].von_mises_pa, held.stresses->peak[i].von_mises_pa);

    fullorder::DeploymentSeries series;
    std::size_t largest_block = 0;
    std::vector<std::vector<double>> history(held.stresses->history.size());
    long next_first = 0;
    streamRomOutputs(
        e, input, block_rows,
        [&](const fullorder::DeploymentSeries& block) {
          largest_block = std::max(largest_block, block.size());
          appendRows(block, series);
        },
        [&](long first, const std::vector<std::vector<double>>& values) {
          EXPECT_EQ(first, next_first);  // in order, no gap
          ASSERT_EQ(values.size(), history.size());
          for (std::size_t k = 0; k < values.size(); ++k)
            history[k].insert(history[k].end(), values[k].begin(), values[k].end());
          next_first += static_cast<long>(values.front().size());
        });
    EXPECT_EQ(largest_block, block_rows);
    expectSameSeries(held.series, series);
    for (std::size_t k = 0; k < history.size(); ++k)
      EXPECT_TRUE(sameBits(history[k], held.stresses->history[k].max_von_mises_pa)) << k;
  }
}

}  // namespace
}  // namespace mastrom::rom
