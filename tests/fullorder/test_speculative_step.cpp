// Speculative steps (GeneralizedAlpha::beginSpeculation, docs/theory.md §5.6): the step after the
// one just taken, computed while another thread recovers the index-1 values of the step before.
// Kept or taken back, the run must be the one without speculation bit for bit — its states, its
// recovered values and its factorisations — including when the step before is rejected after the
// speculation, and a step that would renew its factorisation must be abandoned, not taken. The
// recovering thread also evaluates the next predictor for the speculative step when it is free.
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "coarse_mast.hpp"
#include "common/error.hpp"
#include "fullorder/eliminated_system.hpp"
#include "fullorder/generalized_alpha.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/work_offer.hpp"

namespace mastrom::fullorder {
namespace {

constexpr double kStep = 2e-4;  // s, through the ramp's end (0.02 s) into the cruise
constexpr int kSteps = 150;

/// What a run leaves: every accepted state with its recovered values, and the counters.
struct Trace {
  std::vector<DaeState> states;
  long factorizations = 0;
  int abandoned = 0, kept = 0;
  long long pipelined = 0;  ///< steps that began with an evaluation the other thread made
};

/// The end of step k: t_k = t_{k−1} + h, as the adaptive loop adds its steps (and as the pipelined
/// evaluation predicts the next step's time).
double timeOfStep(int k) {
  double t = 0.0;
  for (int i = 0; i < k; ++i) t += kStep;
  return t;
}

/// Whether the step to step k is rejected once (and taken again) after it is first taken: an
/// error estimate's verdict, the same in both runs.
bool rejectedOnce(int k) { return k % 7 == 3; }

/// The adaptive loop's WorkOffer, made patient: the offering thread begins its own part only once
/// the serving thread has taken the offer, so every offer made while the other thread serves runs.
/// A plain WorkOffer withdraws an offer its server has not taken by the time the own part is done,
/// which on a loaded machine (the test suite runs two jobs on two cores) can happen to every offer
/// of the run: no value changes, but the offer path would go untested. The server serves until
/// close(), which comes after the step, so the wait ends.
class PatientOffer final : public PairRunner {
public:
  explicit PatientOffer(WorkOffer& offer) : offer_(offer) {}
  bool secondThreadFree() const override { return offer_.secondThreadFree(); }
  bool run(const std::function<void()>& first, const std::function<void()>& second) override {
    std::atomic<bool> taken{false};
    return offer_.run(
        [&] {
          while (!taken.load(std::memory_order_acquire)) std::this_thread::yield();
          first();
        },
        [&] {
          taken.store(true, std::memory_order_release);
          second();
        });
  }

private:
  WorkOffer& offer_;
};

/// Without speculation: take, recover, reject where told (then take again), accept.
Trace serial(const GeneralizedAlphaOptions& o) {
  testing::EliminatedTurningMast mast;
  GeneralizedAlpha integrator(mast.reduced, o);
  integrator.initialize(mast.q0, mast.v0, 0.0);
  Trace trace;
  for (int k = 1; k <= kSteps; ++k) {
    integrator.stepTo(timeOfStep(k));
    integrator.updateIndexOneAccelerations();
    if (rejectedOnce(k)) {
      integrator.rejectStep();
      integrator.stepTo(timeOfStep(k));
      integrator.updateIndexOneAccelerations();
    }
    trace.states.push_back(integrator.state());
  }
  trace.factorizations = integrator.factorizations();
  return trace;
}

/// With speculation on two threads: after each step, the next one beside the recovery; kept on
/// even steps, taken back on odd ones, and taken back together with the step before where that
/// one is rejected.
Trace speculative(const GeneralizedAlphaOptions& o) {
  testing::EliminatedTurningMast mast;
  GeneralizedAlpha integrator(mast.reduced, o);
  integrator.initialize(mast.q0, mast.v0, 0.0);
  Trace trace;
  WorkOffer offer;
  PatientOffer patient(offer);
  bool have_next = false;
  for (int k = 1; k <= kSteps; ++k) {
    if (!have_next) integrator.stepTo(timeOfStep(k));
    have_next = false;
    integrator.deferIndexOneAccelerations();
    integrator.beginSpeculation();
    bool taken = false, abandoned = false;
    // As the adaptive loop does, the other thread then evaluates the next predictor beside the
    // speculative step's Newton evaluations (GeneralizedAlpha::setPairRunner). On this small mast
    // a recovery outlasts the Newton step, so in every third round it is done before and the
    // step waits until the other thread serves: with the patient offer, those rounds take the
    // offer path for certain.
    const bool offered = k % 3 == 0;
    if (offered) integrator.recoverDeferredIndexOne();
    offer.open();
    integrator.setPairRunner(&patient);
    std::thread other([&] {
      integrator.recoverDeferredIndexOne();
      offer.serve();
    });
    while (offered && !offer.secondThreadFree()) std::this_thread::yield();
    try {
      integrator.stepTo(timeOfStep(k + 1));
      taken = true;
    } catch (const SpeculationAbandoned&) {
      abandoned = true;
    }
    offer.close();
    other.join();
    integrator.setPairRunner(nullptr);
    const DaeState recovered = integrator.completeDeferredIndexOne();
    trace.abandoned += abandoned ? 1 : 0;
    if (rejectedOnce(k)) {
      integrator.endSpeculation(false);
      integrator.rejectStep();
      integrator.stepTo(timeOfStep(k));
      integrator.updateIndexOneAccelerations();
      trace.states.push_back(integrator.state());
      continue;
    }
    trace.states.push_back(recovered);
    const bool keep = k % 2 == 0 && k < kSteps;
    integrator.endSpeculation(keep);
    if (keep && taken) {
      have_next = true;
      ++trace.kept;
    }
  }
  trace.factorizations = integrator.factorizations();
  trace.pipelined = integrator.pipelinedSteps();
  return trace;
}

void expectSameRun(const Trace& a, const Trace& b) {
  ASSERT_EQ(a.states.size(), b.states.size());
  for (std::size_t i = 0; i < a.states.size(); ++i) {
    const DaeState &x = a.states[i], &y = b.states[i];
    ASSERT_EQ(x.time_s, y.time_s) << "step " << i + 1;
    EXPECT_EQ(x.q, y.q) << "step " << i + 1;
    EXPECT_EQ(x.qdot, y.qdot) << "step " << i + 1;
    EXPECT_EQ(x.lambda, y.lambda) << "step " << i + 1;
    EXPECT_EQ(x.qddot_index1, y.qddot_index1) << "step " << i + 1;
    EXPECT_EQ(x.lambda_index1, y.lambda_index1) << "step " << i + 1;
  }
  EXPECT_EQ(a.factorizations, b.factorizations);
}

TEST(SpeculativeStep, KeptOrTakenBackTheRunIsTheSerialOneBitForBit) {
  GeneralizedAlphaOptions o = integratorFromConfig(testing::turningScheme1());
  o.recover_index1_accelerations = false;
  const Trace a = serial(o), b = speculative(o);
  expectSameRun(a, b);
  EXPECT_GT(b.kept, kSteps / 3);  // the speculations did run and were kept
  // Steps that began with the other thread's evaluation of their predictor (the run's values are
  // the same either way, which is what the comparison above checks).
  EXPECT_GT(b.pipelined, 0);
}

TEST(SpeculativeStep, AStepThatWouldRenewItsFactorisationIsAbandoned) {
  GeneralizedAlphaOptions o = integratorFromConfig(testing::turningScheme1());
  o.recover_index1_accelerations = false;
  o.refactor_after_iterations = 1;  // a step after one of two iterations renews its factorisation
  const Trace a = serial(o), b = speculative(o);
  expectSameRun(a, b);
  EXPECT_GT(b.abandoned, 0);
}

TEST(SpeculativeStep, RefusesMisuse) {
  testing::EliminatedTurningMast mast;
  GeneralizedAlphaOptions o = integratorFromConfig(mast.config);
  {
    GeneralizedAlpha recovering(mast.reduced, o);  // recovers on every acceptance
    recovering.initialize(mast.q0, mast.v0, 0.0);
    recovering.stepTo(kStep);
    recovering.deferIndexOneAccelerations();
    EXPECT_THROW(recovering.beginSpeculation(), Error);
  }
  o.recover_index1_accelerations = false;
  GeneralizedAlpha integrator(mast.reduced, o);
  integrator.initialize(mast.q0, mast.v0, 0.0);
  integrator.stepTo(kStep);
  EXPECT_THROW(integrator.beginSpeculation(), Error);  // no deferred recovery
  integrator.deferIndexOneAccelerations();
  integrator.beginSpeculation();
  EXPECT_THROW(integrator.beginSpeculation(), Error);  // already speculating
  // Another step size would swap factorisations, which taking the step back does not undo.
  EXPECT_THROW(integrator.stepTo(2.5 * kStep), SpeculationAbandoned);
  EXPECT_EQ(integrator.state().time_s, kStep);
  integrator.stepTo(2 * kStep);
  EXPECT_THROW(integrator.endSpeculation(true), Error);  // the recovery is still outstanding
  integrator.completeDeferredIndexOne();
  integrator.endSpeculation(false);
  EXPECT_EQ(integrator.state().time_s, kStep);
  integrator.rejectStep();  // the undo record of the step before the speculation is back
  EXPECT_EQ(integrator.state().time_s, 0.0);
}

}  // namespace
}  // namespace mastrom::fullorder
