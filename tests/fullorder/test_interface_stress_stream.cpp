// Interface stress histories resampled while a run goes (fullorder/interface_stress_stream.hpp):
// the rows equal, bit for bit, the resampling of the whole history at the end (the reference: the
// histories kept, each output instant interpolated in its piece once everything is known), in
// whatever order evaluations and output instants arrive, and the instants held stay bounded.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "coarse_mast.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/interface_stress.hpp"
#include "fullorder/interface_stress_stream.hpp"
#include "fullorder/mast_config.hpp"

namespace mastrom::fullorder {
namespace {

/// The whole-history resampling: every τ within the evaluated span interpolated in the piece that
/// holds it by start time (InterfaceStressMonitor::resample's rule).
std::vector<InterfaceStressRow> resampleWhole(const std::vector<double>& t,
                                              const std::vector<InterfaceStressHistory>& h,
                                              const std::vector<long>& starts,
                                              const std::vector<double>& taus) {
  std::vector<InterfaceStressRow> rows;
  for (double tau : taus) {
    if (tau < t.front() - 1e-12 || tau > t.back() + 1e-12) continue;
    std::size_t piece = 0;
    while (piece + 1 < starts.size() && t[static_cast<size_t>(starts[piece + 1])] <= tau) ++piece;
    const long end = piece + 1 < starts.size() ? starts[piece + 1] : static_cast<long>(t.size());
    InterfaceStressRow row;
    interpolateStressRow(t, h, starts[piece], end, tau, row);
    rows.push_back(row);
  }
  return rows;
}

void expectSameRows(const std::vector<InterfaceStressRow>& a,
                    const std::vector<InterfaceStressRow>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].time_s, b[i].time_s) << "row " << i;
    for (std::size_t k = 0; k < a[i].max_von_mises_pa.size(); ++k) {
      ASSERT_EQ(a[i].max_von_mises_pa[k], b[i].max_von_mises_pa[k]) << "row " << i;
      ASSERT_EQ(a[i].base_force_n[k], b[i].base_force_n[k]) << "row " << i;
      ASSERT_EQ(a[i].base_moment_nm[k], b[i].base_moment_nm[k]) << "row " << i;
      ASSERT_EQ(a[i].tip_force_n[k], b[i].tip_force_n[k]) << "row " << i;
      ASSERT_EQ(a[i].tip_moment_nm[k], b[i].tip_moment_nm[k]) << "row " << i;
    }
  }
}

/// Irregular evaluation instants in pieces of 1, 2, 3, 4, 5 and many instants, outputs on a
/// grid finer and coarser than the evaluations, handed over with random lags either way.
TEST(InterfaceStressStream, RowsEqualTheWholeHistoryResampledInAnyArrivalOrder) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const std::size_t interfaces = 2;
  std::vector<double> t;
  std::vector<long> starts;
  std::vector<InterfaceStressHistory> h(interfaces);
  std::vector<InterfaceStressRow> evaluated;
  double time = 0.0;
  for (int piece_length : {5, 1, 2, 3, 4, 3000, 2, 2500}) {
    starts.push_back(static_cast<long>(t.size()));
    for (int j = 0; j < piece_length; ++j) {
      InterfaceStressRow row;
      row.resize(interfaces);
      row.time_s = time;
      for (std::size_t k = 0; k < interfaces; ++k) {
        // A signal that crosses zero, so the clip of the von Mises at 0 is exercised.
        row.max_von_mises_pa[k] = 1e6 * std::sin(40.0 * time + k) + 2e5 * (unit(rng) - 0.5);
        row.base_force_n[k] = Eigen::Vector3d::Random();
        row.base_moment_nm[k] = Eigen::Vector3d::Random();
        row.tip_force_n[k] = Eigen::Vector3d::Random();
        row.tip_moment_nm[k] = Eigen::Vector3d::Random();
        h[k].max_von_mises_pa.push_back(row.max_von_mises_pa[k]);
        h[k].base_force_n.push_back(row.base_force_n[k]);
        h[k].base_moment_nm.push_back(row.base_moment_nm[k]);
        h[k].tip_force_n.push_back(row.tip_force_n[k]);
        h[k].tip_moment_nm.push_back(row.tip_moment_nm[k]);
      }
      t.push_back(time);
      evaluated.push_back(row);
      time += 1e-4 * (0.2 + 2.0 * unit(rng));
    }
  }
  for (double output_step : {3e-5, 1e-4, 7e-4}) {
    std::vector<double> taus;
    for (int k = 0; k * output_step <= t.back(); ++k) taus.push_back(k * output_step);
    taus.push_back(t.back());
    taus.erase(std::unique(taus.begin(), taus.end()), taus.end());
    const std::vector<InterfaceStressRow> expected = resampleWhole(t, h, starts, taus);
    ASSERT_EQ(expected.size(), taus.size());

    std::vector<InterfaceStressRow> streamed;
    InterfaceStressResampler resampler(
        interfaces, [&](const InterfaceStressRow& row) { streamed.push_back(row); });
    std::size_t next_eval = 0, next_tau = 0, most_held = 0;
    std::size_t start_index = 0;
    while (next_eval < evaluated.size() || next_tau < taus.size()) {
      // Evaluations lead or lag the output instants by up to 0.3 ms (a few evaluations), as the
      // deployment loops hand them over.
      const bool eval_first = next_tau >= taus.size() ||
                              (next_eval < evaluated.size() &&
                               t[next_eval] <= taus[next_tau] + 3e-4 * (2.0 * unit(rng) - 1.0));
      if (eval_first) {
        const bool piece_start =
            start_index < starts.size() && starts[start_index] == static_cast<long>(next_eval);
        if (piece_start) ++start_index;
        resampler.addEvaluation(evaluated[next_eval++], piece_start);
      } else {
        resampler.addOutputInstant(taus[next_tau++]);
      }
      most_held = std::max(most_held, resampler.heldEvaluations());
    }
    resampler.finish();
    expectSameRows(streamed, expected);
    EXPECT_EQ(resampler.rowsEmitted(), taus.size());
    // Bounded: the compaction slack (64), a stencil and the lag, against 5 517 instants evaluated.
    EXPECT_LT(most_held, 80u) << "output step " << output_step;
  }
}

/// A real run: one monitor keeps its histories and resamples at the end, the other streams them
/// on the run's output instants as they come (adaptive steps, across the drive's breakpoints).
TEST(InterfaceStressStream, StreamedMonitorEqualsTheHeldOneInAnAdaptiveRun) {
  Config c = testing::turningScheme1();  // 10° in 0.5 s, 20 ms ramps
  c.simulation.adaptive = true;
  c.drive.duration_s = 0.02;
  c.drive.ramp_s = 0.005;
  c.simulation.end_time_s = 0.03;
  c.output.step_s = 2e-4;
  MastModel model = buildMast(mastParametersFromConfig(c));
  DeploymentOptions o = deploymentFromConfig(c);
  InterfaceStressMonitor held = stressMonitorFor(model, o);
  InterfaceStressMonitor streamed = stressMonitorFor(model, o);
  std::vector<InterfaceStressRow> rows;
  std::size_t most_held = 0;
  streamed.streamHistories([&](const InterfaceStressRow& row) { rows.push_back(row); });
  const DeploymentStateObserver observe_held = observeInterfaceStresses(held);
  const DeploymentStateObserver observe_streamed = observeInterfaceStresses(streamed);
  o.state_observer = [&](const DaeState& s, const Eigen::VectorXd& qdot, bool start) {
    observe_held(s, qdot, start);
    observe_streamed(s, qdot, start);
  };
  std::vector<double> times;
  o.output_sink = [&](const DeploymentSample& sample) {
    times.push_back(sample.time_s);
    streamed.outputInstant(sample.time_s);
    most_held = std::max(most_held, streamed.heldEvaluations());
  };
  simulateDeployment(model, o);
  streamed.finishHistories();
  ASSERT_EQ(times.size(), 151u);
  const InterfaceStressResult whole = held.resample(times);
  std::vector<InterfaceStressRow> expected(times.size());
  for (std::size_t i = 0; i < times.size(); ++i) {
    expected[i].resize(1);
    expected[i].time_s = whole.time_s[i];
    expected[i].max_von_mises_pa[0] = whole.history[0].max_von_mises_pa[i];
    expected[i].base_force_n[0] = whole.history[0].base_force_n[i];
    expected[i].base_moment_nm[0] = whole.history[0].base_moment_nm[i];
    expected[i].tip_force_n[0] = whole.history[0].tip_force_n[i];
    expected[i].tip_moment_nm[0] = whole.history[0].tip_moment_nm[i];
  }
  expectSameRows(rows, expected);
  // The peaks are the same; the streamed monitor holds no history and only a few instants.
  EXPECT_EQ(streamed.result().peak[0].von_mises_pa, whole.peak[0].von_mises_pa);
  EXPECT_EQ(streamed.result().peak[0].time_s, whole.peak[0].time_s);
  EXPECT_TRUE(streamed.result().history[0].max_von_mises_pa.empty());
  EXPECT_EQ(streamed.evaluationCount(), held.evaluationCount());
  EXPECT_LT(most_held, 80u);
}

}  // namespace
}  // namespace mastrom::fullorder
