// The deferred index-1 recovery (GeneralizedAlpha::deferIndexOneAccelerations): computed inside
// the next step — on the calling thread while another evaluates element forces — it must give the
// recovered (q̈, λ) of the immediate recovery bit for bit, leave the stepping untouched, and refuse
// the misuses (a second deferral, completing none, a snapshot with one outstanding).
#include <gtest/gtest.h>

#include "coarse_mast.hpp"
#include "common/error.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/eliminated_system.hpp"
#include "fullorder/generalized_alpha.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/mast_model.hpp"

namespace mastrom::fullorder {
namespace {

struct Recorded {
  std::vector<DaeState> outputs;  ///< every 3rd step: the state with its index-1 values
  DaeState last;                  ///< the integrator's state after the last step
};

Recorded run(bool deferred, int threads) {
  testing::EliminatedTurningMast mast(threads);
  GeneralizedAlphaOptions o = integratorFromConfig(mast.config);
  o.recover_index1_accelerations = false;
  GeneralizedAlpha integrator(mast.reduced, o);
  integrator.initialize(mast.q0, mast.v0, 0.0);
  Recorded r;
  for (int k = 1; k <= 300; ++k) {  // the ramp (0.02 s) and the start of the cruise
    integrator.step();
    if (integrator.hasDeferredIndexOne()) {
      r.outputs.push_back(integrator.completeDeferredIndexOne());  // ran inside this step
    }
    if (k % 3 == 0) {
      if (deferred) {
        integrator.deferIndexOneAccelerations();
      } else {
        integrator.updateIndexOneAccelerations();
        r.outputs.push_back(integrator.state());
      }
    }
  }
  if (integrator.hasDeferredIndexOne()) r.outputs.push_back(integrator.completeDeferredIndexOne());
  r.last = integrator.state();
  return r;
}

TEST(DeferredIndexOneRecovery, EqualsTheImmediateRecoveryBitForBit) {
  const Recorded immediate = run(false, 1);
  for (int threads : {1, 2}) {
    const Recorded deferred = run(true, threads);
    ASSERT_EQ(deferred.outputs.size(), immediate.outputs.size());
    ASSERT_EQ(deferred.outputs.size(), 100u);
    for (std::size_t i = 0; i < immediate.outputs.size(); ++i) {
      const DaeState &a = immediate.outputs[i], &b = deferred.outputs[i];
      ASSERT_EQ(a.time_s, b.time_s);
      EXPECT_EQ(a.q, b.q) << "output " << i << ", " << threads << " threads";
      EXPECT_EQ(a.qddot_index1, b.qddot_index1) << "output " << i << ", " << threads << " threads";
      EXPECT_EQ(a.lambda_index1, b.lambda_index1)
          << "output " << i << ", " << threads << " threads";
    }
    // The stepping itself is not affected.
    EXPECT_EQ(deferred.last.q, immediate.last.q);
    EXPECT_EQ(deferred.last.lambda, immediate.last.lambda);
  }
}

TEST(DeferredIndexOneRecovery, RefusesMisuse) {
  testing::EliminatedTurningMast mast;
  GeneralizedAlpha integrator(mast.reduced, integratorFromConfig(mast.config));
  integrator.initialize(mast.q0, mast.v0, 0.0);
  integrator.step();
  EXPECT_THROW(integrator.completeDeferredIndexOne(), Error);  // none deferred
  integrator.deferIndexOneAccelerations();
  EXPECT_THROW(integrator.deferIndexOneAccelerations(), Error);  // one is outstanding
  EXPECT_THROW(integrator.snapshot(), Error);                    // it may still refactorise
  EXPECT_THROW(integrator.updateIndexOneAccelerations(), Error);
  const DaeState& s = integrator.completeDeferredIndexOne();
  EXPECT_EQ(s.qddot_index1.size(), s.q.size());
  EXPECT_FALSE(integrator.hasDeferredIndexOne());
  EXPECT_NO_THROW(integrator.snapshot());
}

TEST(DeferredIndexOneRecovery, DeploymentOnTwoThreadsEqualsOneThread) {
  // simulateDeployment defers the output recoveries when the system has a second thread.
  const Config c = testing::turningScheme1();
  DeploymentOptions o;
  o.integrator = integratorFromConfig(c);
  o.end_time_s = 0.03;
  o.thread_tuning.enabled = false;  // two threads throughout, whatever else runs on the machine
  DeploymentSeries series[2];
  for (int threads : {1, 2}) {
    MastModel model = buildMast(mastParametersFromConfig(c));
    model.system().setThreadCount(threads);
    series[threads - 1] = simulateDeployment(model, o);
  }
  ASSERT_EQ(series[0].size(), series[1].size());
  ASSERT_EQ(series[0].size(), 301u);
  for (std::size_t i = 0; i < series[0].size(); ++i) {
    EXPECT_EQ(series[0].time_s[i], series[1].time_s[i]);
    EXPECT_EQ(series[0].end_relative_angular_acceleration_rad_s2[i],
              series[1].end_relative_angular_acceleration_rad_s2[i]);
    EXPECT_EQ(series[0].joint_torque_nm[i], series[1].joint_torque_nm[i]);
    EXPECT_EQ(series[0].joint_force_n[i], series[1].joint_force_n[i]);
  }
}

}  // namespace
}  // namespace mastrom::fullorder
