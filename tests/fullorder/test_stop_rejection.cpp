// A rejected step that lands on a stop (a drive breakpoint or the end) is retried shorter
// (docs/theory.md §5.3). The step to a stop is stretched when a step of the controller's size would
// leave less than min_step before it; a rejected stretched step then came back stretched to the
// same length, was rejected again with the same error, and the run never ended. Measured on
// Scheme 1 (1 × 6 ring, 1° drive, first steps 1.25 µs): from t = 1.99528 ms the step of 4.72 µs to
// the end at 2 ms read err = 1.195, and the controller's shorter step (3.91 µs) left 0.81 µs.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <future>
#include <string>
#include <thread>

#include "common/config.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/mast_model.hpp"

namespace mastrom::fullorder {
namespace {

TEST(StopRejection, ARejectedStepToTheEndIsRetriedShorterAndTheRunEnds) {
  const Config config = loadConfig(
      std::string(MASTROM_SOURCE_DIR) + "/configs/scheme1.toml",
      {"interface.elements_axial=1", "interface.elements_circumferential=6", "drive.duration=0.3",
       "drive.ramp=0.05", "drive.angle_deg=1", "interface.thickness=0.0015", "module.mass=0.5",
       "output.step=1e-6", "simulation.end_time=2e-3", "simulation.time_step=1.25e-6"});
  MastModel model = buildMast(mastParametersFromConfig(config));
  const DeploymentOptions options = deploymentFromConfig(config);
  DeploymentStatistics stats;
  // The defect was an endless loop: the run goes on a thread, and a run that has not ended long
  // after its 0.2 s (Release) fails the test instead of hanging the suite.
  std::future<DeploymentSeries> run =
      std::async(std::launch::async, [&] { return simulateDeployment(model, options, &stats); });
  if (run.wait_for(std::chrono::minutes(3)) != std::future_status::ready) {
    ADD_FAILURE() << "the run did not end within 3 minutes (a step to the end rejected forever)";
    std::fflush(nullptr);
    std::_Exit(1);
  }
  const DeploymentSeries series = run.get();
  EXPECT_DOUBLE_EQ(series.time_s.back(), 2e-3);
  EXPECT_GT(stats.rejected_steps, 0);
  // The retry splits the rest in two steps of at least min_step: none is shorter.
  EXPECT_GE(stats.min_step_s, options.step_control.min_step_s * (1.0 - 1e-9));
}

}  // namespace
}  // namespace mastrom::fullorder
