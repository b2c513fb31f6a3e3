// The thread tuner (fullorder/thread_tuner.hpp): it keeps the user's threads unless one thread is
// measured clearly faster, re-probes with a doubling back-off, is not swayed by one slow step, and
// a deployment whose thread count changes between steps gives the one-thread result bit for bit
// (fixed and adaptive steps; the pipelined evaluation and the deferred recovery cross the
// changes).
#include <gtest/gtest.h>

#include "coarse_mast.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/thread_tuner.hpp"

namespace mastrom::fullorder {
namespace {

/// Feeds the tuner `steps` steps, each taking one_s on one thread and many_s on more; returns the
/// thread count of every step.
std::vector<int> drive(ThreadTuner& tuner, long steps, double one_s, double many_s) {
  std::vector<int> used;
  for (long k = 0; k < steps; ++k) {
    used.push_back(tuner.threads());
    tuner.record(tuner.threads() == 1 ? one_s : many_s);
  }
  return used;
}

long countOnes(const std::vector<int>& used, std::size_t from, std::size_t to) {
  long ones = 0;
  for (std::size_t k = from; k < to; ++k) ones += used[k] == 1;
  return ones;
}

TEST(ThreadTuner, KeepsTheThreadsWhenTheyAreFaster) {
  ThreadTunerOptions o;  // probe 16 + 16, then hold 256
  ThreadTuner tuner(2, o);
  const std::vector<int> used = drive(tuner, 32 + 256, 1.0, 0.6);
  EXPECT_EQ(countOnes(used, 0, 16), 0);    // the probe on the user's threads first
  EXPECT_EQ(countOnes(used, 16, 32), 16);  // then on one
  EXPECT_EQ(countOnes(used, 32, used.size()), 0);
  EXPECT_EQ(tuner.singleThreadSteps(), 16);
}

TEST(ThreadTuner, TakesOneThreadWhenItIsFasterAndProbesLessOftenWhileThatHolds) {
  ThreadTunerOptions o;
  ThreadTuner tuner(2, o);
  // Contended cores: two threads 5× slower per step.
  const std::vector<int> used = drive(tuner, 32 + 256 + 32 + 512 + 32, 1.0, 5.0);
  EXPECT_EQ(countOnes(used, 32, 32 + 256), 256);           // the first hold
  EXPECT_EQ(countOnes(used, 288, 288 + 16), 0);            // a probe on two threads
  EXPECT_EQ(countOnes(used, 304, 304 + 16 + 512), 16 + 512);  // same verdict: hold doubled
  EXPECT_EQ(countOnes(used, 832, 832 + 16), 0);            // the next probe
}

TEST(ThreadTuner, AVerdictThatChangesRestartsTheShortHold) {
  ThreadTunerOptions o;
  ThreadTuner tuner(2, o);
  drive(tuner, 32 + 256 + 32, 1.0, 5.0);  // two probes that chose one thread
  // The other work ends: two threads win the next probe, and are held for the first hold only.
  std::vector<int> used = drive(tuner, 512 + 32 + 256 + 16, 1.0, 0.6);
  // The hold still running (512 steps of one thread), then the probe, then 256 on two threads.
  EXPECT_EQ(countOnes(used, 0, 512), 512);
  EXPECT_EQ(countOnes(used, 512, 528), 0);
  EXPECT_EQ(countOnes(used, 528, 544), 16);
  EXPECT_EQ(countOnes(used, 544, 800), 0);
  EXPECT_EQ(countOnes(used, 800, 816), 0);  // the next probe comes after 256, not 512
}

TEST(ThreadTuner, AWinInsideTheMarginKeepsTheThreads) {
  ThreadTuner tuner(2);
  const std::vector<int> used = drive(tuner, 32 + 100, 0.98, 1.0);  // one thread 2 % faster
  EXPECT_EQ(countOnes(used, 32, used.size()), 0);
}

TEST(ThreadTuner, OneSlowStepDoesNotDecide) {
  ThreadTuner tuner(2);
  for (int k = 0; k < 16; ++k) tuner.record(k == 3 ? 100.0 : 1.0);  // a refactorisation, say
  for (int k = 0; k < 16; ++k) tuner.record(1.5);
  EXPECT_EQ(tuner.threads(), 2);
}

TEST(ThreadTuner, OneThreadOrTuningOffNeverProbes) {
  ThreadTuner single(1);
  EXPECT_EQ(countOnes(drive(single, 100, 1.0, 5.0), 0, 100), 100);
  EXPECT_EQ(single.singleThreadSteps(), 0);  // one was all the user allowed
  ThreadTunerOptions off;
  off.enabled = false;
  ThreadTuner fixed(2, off);
  EXPECT_EQ(countOnes(drive(fixed, 100, 1.0, 5.0), 0, 100), 0);
}

TEST(ThreadTuner, RejectsBadOptions) {
  ThreadTunerOptions o;
  o.margin = 0.5;
  EXPECT_THROW(ThreadTuner(2, o), InputError);
  EXPECT_THROW(ThreadTuner(0), InputError);
}

/// 5° in 40 ms with 10 ms ramps on the coarse Scheme 1 mast, 11 ms simulated (a breakpoint
/// crossed).
Config shortSwing(bool adaptive) {
  Config c = testing::coarseScheme1();
  c.drive.angle_deg = 5.0;
  c.drive.duration_s = 0.04;
  c.drive.ramp_s = 0.01;
  c.simulation.end_time_s = 0.011;
  c.simulation.adaptive = adaptive;
  c.simulation.time_step_s = adaptive ? 1e-5 : 2e-5;
  c.output.every = 2;
  return c;
}

DeploymentSeries run(const Config& c, int threads, const ThreadTunerOptions& tuning,
                     DeploymentStatistics& stats) {
  MastModel model = buildMast(mastParametersFromConfig(c));
  model.system().setThreadCount(threads);
  DeploymentOptions o = deploymentFromConfig(c);
  o.thread_tuning = tuning;
  DeploymentSeries series = simulateDeployment(model, o, &stats);
  EXPECT_EQ(model.system().threadCount(), threads) << "the run must leave the model as it was";
  return series;
}

void expectThreadChangesChangeNothing(bool adaptive) {
  // Probe one step each way and hold one: the count changes every one or two steps whatever the
  // timing, so every transition (a pipelined step followed by a serial one, a deferred recovery
  // run serially, and back) occurs.
  ThreadTunerOptions toggling;
  toggling.probe_steps = 1;
  toggling.first_hold_steps = toggling.max_hold_steps = 1;
  ThreadTunerOptions off;
  off.enabled = false;
  DeploymentStatistics one, changing;
  const Config c = shortSwing(adaptive);
  const DeploymentSeries a = run(c, 1, off, one);
  const DeploymentSeries b = run(c, 2, toggling, changing);
  EXPECT_EQ(one.steps, changing.steps);
  EXPECT_EQ(one.newton_iterations, changing.newton_iterations);
  EXPECT_EQ(one.single_thread_steps, 0);
  const long tried = changing.steps + changing.rejected_steps;
  EXPECT_GE(changing.single_thread_steps, tried / 3);
  EXPECT_LE(changing.single_thread_steps, 2 * tried / 3 + 1);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_TRUE(a.time_s == b.time_s);
  EXPECT_TRUE(a.end_relative_angular_acceleration_rad_s2 ==
              b.end_relative_angular_acceleration_rad_s2);
  EXPECT_TRUE(a.joint_torque_nm == b.joint_torque_nm);
  EXPECT_TRUE(a.joint_force_n == b.joint_force_n);
}

TEST(ThreadTuner, FixedStepsGiveTheSameResultWhileTheThreadCountChanges) {
  expectThreadChangesChangeNothing(false);
}

TEST(ThreadTuner, AdaptiveStepsGiveTheSameResultWhileTheThreadCountChanges) {
  expectThreadChangesChangeNothing(true);
}

}  // namespace
}  // namespace mastrom::fullorder
