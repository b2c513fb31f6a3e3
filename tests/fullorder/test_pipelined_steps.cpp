// The pipelined time step (GeneralizedAlphaOptions::pipelined_steps): with two threads
// the integrator evaluates each Newton iterate together with the next step's predicted state
// (EliminatedSystem::evaluatePair) and runs a deferred index-1 recovery beside the next Newton
// solve. It must change nothing but the wall time: the pair evaluation equals two evaluate() calls
// bit for bit, a failure of the speculative second state is not an error of the step, and a
// deployment — states, recovered outputs, restarts — is bit-identical to the unpipelined one.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "coarse_mast.hpp"
#include "common/error.hpp"
#include "fullorder/eliminated_system.hpp"
#include "fullorder/generalized_alpha.hpp"
#include "fullorder/mast_config.hpp"

namespace mastrom::fullorder {
namespace {

/// A turned, slightly deformed state with elastic velocities (reduced coordinates).
void perturbedState(const testing::EliminatedTurningMast& mast, unsigned seed, Eigen::VectorXd& q,
                    Eigen::VectorXd& v) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  q = mast.reduced.restrict(mast.model.rotatedReference(0.3 + 0.1 * seed));
  v = mast.v0;
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    q[i] += 1e-6 * u(gen);
    v[i] += 1e-2 * u(gen);
  }
}

struct Evaluated {
  Eigen::VectorXd force, phi;
  SparseMatrix jac;
};

TEST(PipelinedSteps, APairEvaluationEqualsTwoSingleOnesBitForBit) {
  for (int threads : {1, 2}) {
    testing::EliminatedTurningMast mast(threads);
    Eigen::VectorXd q[2], v[2];
    perturbedState(mast, 1, q[0], v[0]);
    perturbedState(mast, 2, q[1], v[1]);
    const double t[2] = {0.01, 0.0101};
    Evaluated single[2], pair[2];
    for (int k = 0; k < 2; ++k)
      mast.reduced.evaluate(q[k], v[k], t[k], single[k].force, single[k].phi, single[k].jac);
    const DaeSystem::Evaluation first{&q[0],          &v[0],        t[0],
                                      &pair[0].force, &pair[0].phi, &pair[0].jac};
    const DaeSystem::Evaluation second{&q[1],          &v[1],        t[1],
                                       &pair[1].force, &pair[1].phi, &pair[1].jac};
    ASSERT_TRUE(mast.reduced.evaluatePair(first, second));
    for (int k = 0; k < 2; ++k) {
      EXPECT_EQ(pair[k].force, single[k].force) << "state " << k << ", " << threads << " threads";
      EXPECT_EQ(pair[k].phi, single[k].phi) << "state " << k << ", " << threads << " threads";
      EXPECT_EQ(Eigen::MatrixXd(pair[k].jac), Eigen::MatrixXd(single[k].jac))
          << "state " << k << ", " << threads << " threads";
    }
  }
}

TEST(PipelinedSteps, AFailureOfTheSecondStateIsReportedNotThrown) {
  testing::EliminatedTurningMast mast(2);
  Eigen::VectorXd q, v;
  perturbedState(mast, 3, q, v);
  Eigen::VectorXd broken = q;
  broken.setConstant(std::numeric_limits<double>::quiet_NaN());  // every element degenerate
  Evaluated good, spare, single;
  mast.reduced.evaluate(q, v, 0.01, single.force, single.phi, single.jac);
  const DaeSystem::Evaluation ok{&q, &v, 0.01, &good.force, &good.phi, &good.jac};
  const DaeSystem::Evaluation bad{&broken, &v, 0.01, &spare.force, &spare.phi, &spare.jac};
  EXPECT_FALSE(mast.reduced.evaluatePair(ok, bad));
  EXPECT_EQ(good.force, single.force);  // the first state's results are complete
  EXPECT_THROW(mast.reduced.evaluatePair(bad, ok), NumericalError);
}

struct SteppedRun {
  std::vector<DaeState> outputs;  ///< every 2nd step, with the index-1 values (deferred)
  DaeState last;
  long long pipelined_steps = 0;
};

/// `steps` steps of the turning mast with an output every 2nd step, as simulateDeployment defers
/// them; with `restart_at` > 0 the run is snapshotted there and continued by a new integrator.
SteppedRun run(int threads, bool pipelined, int steps, int restart_at = 0) {
  testing::EliminatedTurningMast mast(threads);
  GeneralizedAlphaOptions o = integratorFromConfig(mast.config);
  o.recover_index1_accelerations = false;
  o.pipelined_steps = pipelined;
  auto integrator = std::make_unique<GeneralizedAlpha>(mast.reduced, o);
  integrator->initialize(mast.q0, mast.v0, 0.0);
  SteppedRun r;
  for (int k = 1; k <= steps; ++k) {
    integrator->step();
    if (integrator->hasDeferredIndexOne())
      r.outputs.push_back(integrator->completeDeferredIndexOne());
    if (k % 2 == 0) integrator->deferIndexOneAccelerations();
    if (k == restart_at) {
      if (integrator->hasDeferredIndexOne())
        r.outputs.push_back(integrator->completeDeferredIndexOne());
      const IntegratorSnapshot s = integrator->snapshot();
      r.pipelined_steps += integrator->pipelinedSteps();
      integrator = std::make_unique<GeneralizedAlpha>(mast.reduced, o);
      integrator->restore(s);
    }
  }
  if (integrator->hasDeferredIndexOne())
    r.outputs.push_back(integrator->completeDeferredIndexOne());
  r.last = integrator->state();
  r.pipelined_steps += integrator->pipelinedSteps();
  return r;
}

void expectSameRun(const SteppedRun& a, const SteppedRun& b, const char* what) {
  ASSERT_EQ(a.outputs.size(), b.outputs.size()) << what;
  for (std::size_t i = 0; i < a.outputs.size(); ++i) {
    ASSERT_EQ(a.outputs[i].time_s, b.outputs[i].time_s) << what;
    EXPECT_EQ(a.outputs[i].q, b.outputs[i].q) << what << ", output " << i;
    EXPECT_EQ(a.outputs[i].qddot_index1, b.outputs[i].qddot_index1) << what << ", output " << i;
    EXPECT_EQ(a.outputs[i].lambda_index1, b.outputs[i].lambda_index1) << what << ", output " << i;
  }
  EXPECT_EQ(a.last.q, b.last.q) << what;
  EXPECT_EQ(a.last.qdot, b.last.qdot) << what;
  EXPECT_EQ(a.last.qddot, b.last.qddot) << what;
  EXPECT_EQ(a.last.lambda, b.last.lambda) << what;
}

TEST(PipelinedSteps, ADeploymentIsBitIdenticalToTheUnpipelinedOne) {
  constexpr int kSteps = 300;  // the drive's ramp (0.02 s) and the start of its cruise
  const SteppedRun reference = run(1, true, kSteps);  // one thread: nothing to pipeline
  EXPECT_EQ(reference.pipelined_steps, 0);
  const SteppedRun plain = run(2, false, kSteps);
  EXPECT_EQ(plain.pipelined_steps, 0);
  const SteppedRun pipelined = run(2, true, kSteps);
  // Every step whose predecessor was accepted after its first Newton iteration starts from the
  // pipelined evaluation: all but a few (the first step, the ramp's corners).
  EXPECT_GE(pipelined.pipelined_steps, kSteps - 10);
  expectSameRun(reference, plain, "2 threads unpipelined vs 1 thread");
  expectSameRun(reference, pipelined, "2 threads pipelined vs 1 thread");
  // A restart drops the pipelined evaluation; the next step makes its own, with the same values.
  const SteppedRun restarted = run(2, true, kSteps, kSteps / 2 + 1);
  expectSameRun(reference, restarted, "pipelined with a restart vs 1 thread");
}

}  // namespace
}  // namespace mastrom::fullorder
