// The local error estimate and the step controller of adaptive generalized-α
// (fullorder/step_control.hpp): the error constant against its closed form, the third-difference
// estimate against the exact local error of a sinusoid, the ladder of step sizes, and the
// acceptance at the estimate's noise floor.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>

#include "common/error.hpp"
#include "fullorder/step_control.hpp"

namespace mastrom::fullorder {
namespace {

TEST(StepControl, ErrorConstantOfTheTrapezoidalRuleAndOfRhoInf09) {
  // ρ∞ = 1: α_m = α_f = ½, γ = ½, β = ¼ → c = ¼ − 1/6 = 1/12 (Newmark's trapezoidal rule).
  EXPECT_NEAR(generalizedAlphaErrorConstant(1.0), 1.0 / 12.0, 1e-15);
  // ρ∞ = 0.9 by hand: α_m = 0.8/1.9, α_f = 0.9/1.9, γ = ½ + 0.1/1.9, β = ¼ (γ + ½)².
  const double am = 0.8 / 1.9, af = 0.9 / 1.9, g = 0.5 + af - am, b = 0.25 * (g + 0.5) * (g + 0.5);
  EXPECT_NEAR(generalizedAlphaErrorConstant(0.9), b + 0.5 * (am - af) - 1.0 / 6.0, 1e-15);
}

TEST(StepControl, EstimateIsTheThirdDerivativeTermOfASinusoid) {
  // y = sin(ωt) at five equally spaced points, averaged in pairs: 6 c h³ ȳ[m0..m3] → c h³ y‴(2h)
  // to O(h) relative (the difference is centred on the middle point; the averaging adds
  // h²y⁽⁵⁾/8 relative to y‴, a few 1e-4 here).
  StepControlOptions o;
  o.tolerance = 1.0;
  o.error_constant = 0.1;
  o.initial_step_s = o.max_step_s = 1e-3;
  o.min_step_s = 1e-9;
  StepController c(o, Eigen::VectorXd::Ones(1));
  const double w = 2.0 * M_PI * 10.0, h = 1e-3;
  const auto y = [&](double t) { return Eigen::VectorXd::Constant(1, std::sin(w * t)); };
  c.restart(0.0, y(0.0));
  Eigen::VectorXd e;
  for (int k = 1; k <= 3; ++k) {
    EXPECT_FALSE(c.canEstimate());
    c.accept(k * h, y(k * h), 0.0, h);
  }
  ASSERT_TRUE(c.canEstimate());
  const double err = c.estimate(4 * h, y(4 * h), e);
  const double expected = -0.1 * h * h * h * w * w * w * std::cos(w * 2.0 * h);
  EXPECT_NEAR(e[0], expected, 5e-3 * std::abs(expected));
  // Scaled by tolerance · the peak seen so far (|y| ≤ sin(4ωh) here).
  EXPECT_NEAR(err, std::abs(e[0]) / std::abs(std::sin(w * 4 * h)), 1e-12);
}

TEST(StepControl, VelocityCriterionReadsTheVibrationUnderALargeSmoothAcceleration) {
  // A vibration x = a sin(ωt) (v = aω cos ωt, acceleration amplitude aω² ≈ 0.1 m/s²) on top of
  // a rigid acceleration ~10⁴ times larger and linear in t: the acceleration criterion, scaled by
  // the peak total acceleration, hardly sees it; the velocity criterion's estimate is
  // c h³ ÿ = c h³ aω⁴ sin(ωt) at the middle m2 = 2.5h of the last three averaged points, to O(h²)
  // relative (the averages move ÿ by h²y⁽⁴⁾/8).
  StepControlOptions o;
  o.tolerance = 1e-5;
  o.error_constant = 0.1;
  o.initial_step_s = o.max_step_s = 1e-4;
  o.min_step_s = 1e-9;
  o.velocity_tolerance_share = 0.25;
  const double a = 1e-6, w = 2.0 * M_PI * 50.0, h = 1e-4, rigid = 1e3;
  const auto y = [&](double t) {
    return Eigen::VectorXd::Constant(1, rigid * (1.0 + 10.0 * t) - a * w * w * std::sin(w * t));
  };
  const auto v = [&](double t) { return Eigen::VectorXd::Constant(1, a * w * std::cos(w * t)); };
  // A controller with the four step points 0, h, 2h, 3h: the next estimate is of the step to 4h.
  const auto primed = [&](const StepControlOptions& options) {
    StepController c(options, Eigen::VectorXd::Ones(1));
    c.restart(0.0, y(0.0), v(0.0));
    for (int k = 1; k <= 3; ++k) c.accept(k * h, y(k * h), v(k * h), 0.0, h);
    return c;
  };
  StepController c = primed(o);
  Eigen::VectorXd e;
  double velocity_error = 0.0;
  Eigen::Vector2d parts;
  const double err = c.estimate(4 * h, y(4 * h), v(4 * h), e, velocity_error, &parts);
  const double expected = o.error_constant * h * h * h * a * std::pow(w, 4) * std::sin(w * 2.5 * h);
  EXPECT_NEAR(velocity_error, expected, 1e-3 * expected);
  // Scaled by a quarter of the tolerance times the peak vibration velocity aω.
  EXPECT_NEAR(parts[1], velocity_error / (0.25 * o.tolerance * a * w), 1e-12 * parts[1]);
  EXPECT_LT(parts[0], 1e-2 * parts[1]);
  EXPECT_EQ(err, parts[1]);
  // Switched off, only the acceleration criterion remains.
  o.velocity_tolerance_share = 0.0;
  StepController off = primed(o);
  EXPECT_EQ(off.estimate(4 * h, y(4 * h), v(4 * h), e, velocity_error), parts[0]);
}

TEST(StepControl, AnOscillationFromStepToStepDoesNotReachTheEstimate) {
  // Round-off and the parasitic root alternate in sign from step to step; a plain third difference
  // reads them as 8 × their amplitude at any step size. Added to a smooth y, they leave the
  // estimate unchanged to round-off.
  StepControlOptions o;
  o.tolerance = 1e-5;
  o.error_constant = 0.0841;
  o.initial_step_s = o.max_step_s = 1e-5;
  o.min_step_s = 1e-7;
  const double w = 2.0 * M_PI * 50.0, h = 1e-5, noise = 1e-3;
  const auto run = [&](double amplitude) {
    StepController c(o, Eigen::VectorXd::Ones(1));
    const auto y = [&](int k) {
      return Eigen::VectorXd::Constant(1, std::sin(w * k * h) + amplitude * (k % 2 == 0 ? 1 : -1));
    };
    c.restart(0.0, y(0));
    for (int k = 1; k <= 3; ++k) c.accept(k * h, y(k), 0.0, h);
    Eigen::VectorXd e;
    c.estimate(4 * h, y(4), e);
    return e[0];
  };
  const double clean = run(0.0), noisy = run(noise);
  EXPECT_NEAR(noisy, clean, 1e-12 * noise);
  // The smooth part is well below the tolerance; the noise alone would have read err ≈ 8 c · 1e-3 /
  // (1e-5 · 1) ≈ 67 without the averaging.
  EXPECT_LT(std::abs(clean), 1e-2 * o.tolerance);
}

TEST(StepControl, TheNoiseFloorMetOnceNoLongerHoldsTheStepDown) {
  StepControlOptions o;
  o.tolerance = 1e-5;
  o.max_step_s = 1e-3;
  o.initial_step_s = 1e-6;
  o.min_step_s = 1e-7;
  StepController c(o, Eigen::VectorXd::Ones(1));
  // Irregular values of size 1 ± 1e-4: noise far above tolerance × peak = 1e-5.
  const double jitter[] = {0.0, 1.0, 0.3, -0.7, 0.9, -0.2, 0.6, -1.0};
  const auto y = [&](int k) { return Eigen::VectorXd::Constant(1, 1.0 + 1e-4 * jitter[k % 8]); };
  c.restart(0.0, y(0));
  for (int k = 1; k <= 3; ++k) c.accept(k * 1e-6, y(k), 0.0, 1e-6);
  Eigen::VectorXd e;
  const double err = c.estimate(4e-6, y(4), e);
  ASSERT_GT(err, 1.0);
  // At a step that can still be cut, a large error is not yet noise.
  EXPECT_FALSE(c.errorIsNoise(3e-6, 1e-6, err));
  EXPECT_FALSE(c.atShortestStep(1e-6));
  EXPECT_TRUE(c.atShortestStep(1e-7));
  // Rejected, retried at a quarter of the step: an error that fell by less than 4^1.5 is noise.
  c.reject(err, 1e-6, 3e-6);
  ASSERT_TRUE(c.errorIsNoise(3e-6, 2.5e-7, 0.9 * err));
  c.acceptAtNoiseFloor(e);
  EXPECT_EQ(c.state().noise_limited, 1);
  const double floor = std::abs(e[0]) / y(1)[0];  // relative to the peak: y(1)
  EXPECT_DOUBLE_EQ(c.relativeNoiseFloor(), floor);
  // The same noise now reads at most 1/kNoiseFloorMargin.
  EXPECT_NEAR(c.estimate(4e-6, y(4), e), 1.0 / kNoiseFloorMargin, 1e-12);
  // The floor halves every 64 accepted steps.
  for (int k = 0; k < 64; ++k) c.accept(3e-6 + (k + 1) * 2.5e-7, y(1), 0.0, 2.5e-7);
  EXPECT_NEAR(c.relativeNoiseFloor(), 0.5 * floor, 1e-3 * floor);
}

TEST(StepControl, AGrownStepThatFailedWaitsBeforeItIsTriedAgain) {
  StepControlOptions o;
  o.max_step_s = 1e-3;
  o.min_step_s = 1e-7;
  o.initial_step_s = 1e-3 / 32.0;
  StepController c(o, Eigen::VectorXd::Ones(1));
  const double small = 1e-3 / 32.0, large = 1e-3 / 16.0;
  const Eigen::VectorXd y = Eigen::VectorXd::Ones(1);
  c.restart(0.0, y);
  double t = 0.0;
  const auto acceptTiny = [&] {  // an error that asks for growth
    t += c.step();
    c.accept(t, y, 1e-6, c.step());
  };
  for (int k = 0; k < 3; ++k) {  // no estimate yet while the history fills
    t += c.step();
    c.accept(t, y, 0.0, c.step());
  }
  acceptTiny();
  ASSERT_DOUBLE_EQ(c.step(), large);
  c.reject(3.0, large, t);  // the grown step fails
  ASSERT_DOUBLE_EQ(c.step(), small);
  // kGrowthWaitSteps accepted steps at the smaller size before the larger is asked for again.
  for (long k = 0; k < kGrowthWaitSteps; ++k) {
    EXPECT_DOUBLE_EQ(c.step(), small) << "after " << k << " steps";
    acceptTiny();
  }
  EXPECT_DOUBLE_EQ(c.step(), large);
  // A second failure at that size waits twice as long.
  c.reject(3.0, large, t);
  for (long k = 0; k < 2 * kGrowthWaitSteps; ++k) {
    EXPECT_DOUBLE_EQ(c.step(), small);
    acceptTiny();
  }
  EXPECT_DOUBLE_EQ(c.step(), large);
  // Accepted at last: the barrier is gone, and the next growth is not held.
  acceptTiny();
  EXPECT_EQ(c.state().growth_barrier_s, 0.0);
  EXPECT_DOUBLE_EQ(c.step(), 2.0 * large);
}

TEST(StepControl, ErrorsThatDoNotFallWithTheStepAreNoise) {
  StepControlOptions o;
  o.max_step_s = 1e-3;
  o.min_step_s = 1e-7;
  StepController c(o, Eigen::VectorXd::Ones(1));
  c.reject(2.0, 1e-4, 0.5);
  // A quarter of the step should cut a local error 64-fold; an error that stays is noise.
  EXPECT_TRUE(c.noiseLimited(0.5, 2.5e-5, 1.9));
  EXPECT_FALSE(c.noiseLimited(0.5, 2.5e-5, 0.05));  // fell like h³: a real error
  EXPECT_FALSE(c.noiseLimited(0.6, 2.5e-5, 1.9));   // another instant
  EXPECT_TRUE(c.noiseLimited(0.6, 1e-7, 5.0));      // at the smallest step: nothing shorter
  // Nor just above it: a step that short lands on the breakpoint or end it is stretched to.
  EXPECT_TRUE(c.noiseLimited(0.6, 1.05e-7, 5.0));
  EXPECT_FALSE(c.noiseLimited(0.6, 1.2e-7, 5.0));
  // A Newton failure at the smallest step is an error, with the instant (also a step stretched to
  // a breakpoint from within kBreakpointStretch of it, which would otherwise be retried forever).
  EXPECT_THROW(c.reject(HUGE_VAL, 1e-7, 0.7), NumericalError);
  EXPECT_THROW(c.reject(HUGE_VAL, 1.05e-7, 0.7), NumericalError);
}

TEST(StepControl, RefusesInconsistentBounds) {
  StepControlOptions o;
  o.min_step_s = 1e-3;
  o.initial_step_s = 1e-4;
  o.max_step_s = 1e-2;
  EXPECT_THROW(StepController(o, Eigen::VectorXd::Ones(1)), InputError);
  o = StepControlOptions{};
  o.tolerance = 0.0;
  EXPECT_THROW(StepController(o, Eigen::VectorXd::Ones(1)), InputError);
}


TEST(StepControl, TheScalesFloorsBoundTheToleranceFromBelow) {
  // A start from rest: y and v tiny. With floors known before the first step (docs/theory.md
  // §5.3a) the same local error reads smaller by exactly the ratio of the scales.
  StepControlOptions o;
  o.tolerance = 1e-5;
  o.error_constant = 0.1;
  o.initial_step_s = o.max_step_s = 1e-5;
  o.min_step_s = 1e-7;
  StepControlOptions floored = o;
  floored.acceleration_scale_floor = 0.2;  // m/s²
  floored.velocity_scale_floor = 4e-8;     // m/s
  StepController plain(o, Eigen::VectorXd::Ones(1)), held(floored, Eigen::VectorXd::Ones(1));
  const auto y = [](double t) { return Eigen::VectorXd::Constant(1, 1e-3 * t * t * t); };
  const auto v = [](double t) { return Eigen::VectorXd::Constant(1, 1e-9 * std::sin(1e4 * t)); };
  for (StepController* c : {&plain, &held}) {
    c->restart(0.0, y(0.0), v(0.0));
    for (int k = 1; k <= 3; ++k) c->accept(k * 1e-5, y(k * 1e-5), v(k * 1e-5), 0.5, 1e-5);
  }
  Eigen::VectorXd e_plain, e_held;
  double ve_plain = 0.0, ve_held = 0.0;
  Eigen::Vector2d parts_plain, parts_held;
  plain.estimate(4e-5, y(4e-5), v(4e-5), e_plain, ve_plain, &parts_plain);
  held.estimate(4e-5, y(4e-5), v(4e-5), e_held, ve_held, &parts_held);
  EXPECT_EQ(e_plain[0], e_held[0]);
  EXPECT_EQ(ve_plain, ve_held);
  // Without floors the scales are the fixed round-off floors (10⁻⁶ m/s², and the vibration's
  // velocity seen so far): with them, 0.2 m/s² and 4e-8 m/s.
  EXPECT_NEAR(parts_held[0], parts_plain[0] * 1e-6 / 0.2, 1e-12 * parts_plain[0]);
  const double v_seen = std::max(plain.state().peak_velocity, std::abs(v(4e-5)[0]));
  EXPECT_NEAR(parts_held[1], parts_plain[1] * std::max(v_seen, 1e-9) / 4e-8,
              1e-12 * parts_plain[1]);
  // Bad floors are input errors.
  StepControlOptions bad = o;
  bad.velocity_scale_floor = -1.0;
  EXPECT_THROW(StepController(bad, Eigen::VectorXd::Ones(1)), InputError);
}

/// The options of the round-off tests: a step on the ladder (1e-3 · 2^−7) far above min_step.
StepControlOptions roundOffOptions() {
  StepControlOptions o;
  o.tolerance = 1e-5;
  o.error_constant = 0.1;
  o.initial_step_s = 7.8125e-6;
  o.min_step_s = 1e-7;
  return o;
}

TEST(StepControl, TheVelocityRoundOffBoundsTheVelocityCriterionFromBelow) {
  // docs/theory.md §5.3b. A vibration of 1e-8 m/s asks at s · tol for local errors of 2.5e-14 m/s,
  // below what the rounding of the positions resolves: against a round-off of 1e-12 m/s the
  // velocity part reads e_v / (kNoiseFloorMargin · 1e-12) exactly, and a step it sets at ≤ ½
  // grows by a ladder level. A vibration whose tolerance is above the round-off (the trapezoidal
  // drives: s · tol · V ~ 1e-9 m/s) reads the same with and without it, bit for bit.
  StepControlOptions o = roundOffOptions();
  o.velocity_tolerance_share = 0.25;
  const double h = o.initial_step_s;
  StepControlOptions floored = o;
  floored.velocity_roundoff_m_s = 1e-12;
  const auto y = [](double t) { return Eigen::VectorXd::Constant(1, 0.2 + 1e-3 * t); };
  const auto parts = [&](const StepControlOptions& opt, double amplitude, double* step = nullptr) {
    // The vibration x = a sin(ωt) seen in y as −aω² sin(ωt) and in v as aω cos(ωt).
    const double w = 2e4;
    const auto yv = [&](double t) {
      return Eigen::VectorXd(y(t).array() - amplitude * w * w * std::sin(w * t));
    };
    const auto v = [&](double t) {
      return Eigen::VectorXd::Constant(1, amplitude * w * std::cos(w * t));
    };
    StepController c(opt, Eigen::VectorXd::Ones(1));
    c.restart(0.0, yv(0.0), v(0.0));
    for (int k = 1; k <= 3; ++k) c.accept(k * h, yv(k * h), v(k * h), 0.5, h);
    Eigen::VectorXd e;
    double ve = 0.0;
    Eigen::Vector2d p;
    c.estimate(4 * h, yv(4 * h), v(4 * h), e, ve, &p);
    if (step) {
      const Eigen::Vector2d set_by_velocity(0.1, 0.4);
      c.accept(4 * h, yv(4 * h), v(4 * h), 0.4, h, &set_by_velocity);
      *step = c.step();
    }
    return std::make_pair(p, ve);
  };
  const double tiny = 5e-13;  // m: velocities ~1e-8 m/s
  const auto [plain, ve_plain] = parts(o, tiny);
  const auto [held, ve_held] = parts(floored, tiny);
  EXPECT_EQ(ve_plain, ve_held);  // the estimate itself is not touched
  EXPECT_EQ(plain[0], held[0]);
  EXPECT_GT(plain[1], 1.0);  // chasing below the round-off
  EXPECT_NEAR(held[1], ve_held / (kNoiseFloorMargin * 1e-12), 1e-12 * held[1]);
  double step_plain = 0.0, step_held = 0.0;
  parts(o, tiny, &step_plain);
  parts(floored, tiny, &step_held);
  EXPECT_EQ(step_plain, h);     // err 0.4 against the tolerance's scale: kept
  EXPECT_EQ(step_held, 2 * h);  // against the round-off: one ladder level up
  const double large = 5e-8;    // m: velocities ~1e-3 m/s, s · tol · V ~ 2.5e-9 m/s
  EXPECT_EQ(parts(o, large).first, parts(floored, large).first);
  StepControlOptions bad = o;
  bad.velocity_roundoff_m_s = -1e-12;
  EXPECT_THROW(StepController(bad, Eigen::VectorXd::Ones(1)), InputError);
}

TEST(StepControl, TheAccelerationRoundOffBoundsTheAccelerationCriterionFromBelow) {
  // docs/theory.md §5.3c. Positions known to a rounding δ carry no acceleration finer than
  // δ / (β h²) over a step h: the acceleration criterion's scale is at least kNoiseFloorMargin
  // times acceleration_roundoff_m / h², so a local error below it reads err ≤ 1 where the
  // tolerance alone (tol · Y = 1e-6 m/s² here) would cut the step; the floor falls like 1/h² as the
  // step grows, and where the tolerance's scale is above it nothing changes, bit for bit.
  StepControlOptions o = roundOffOptions();
  o.velocity_tolerance_share = 0.0;
  StepControlOptions floored = o;
  floored.acceleration_roundoff_m = 4e-16;  // ≈ ε · 0.5 m / β: 6.6e-6 m/s² at this step
  const auto err = [&](const StepControlOptions& opt, double amplitude, double h) {
    // A vibration of 20 kHz in y on a constant 0.1 m/s² (Y = 0.1: tol · Y = 1e-6 m/s²).
    const double w = 1.25e5;
    const auto y = [&](double t) {
      return Eigen::VectorXd::Constant(1, 0.1 + amplitude * std::sin(w * t));
    };
    StepController c(opt, Eigen::VectorXd::Ones(1));
    c.restart(0.0, y(0.0));
    for (int k = 1; k <= 3; ++k) c.accept(k * h, y(k * h), 0.5, h);
    Eigen::VectorXd e;
    const double scaled = c.estimate(4 * h, y(4 * h), e);
    return std::make_pair(scaled, e.cwiseAbs().maxCoeff());
  };
  const double h = o.initial_step_s;
  const double floor_h = kNoiseFloorMargin * floored.acceleration_roundoff_m / (h * h);
  // m/s²: content near the step's resolution (ωh ≈ 1), read by e_y at ~3 % of its amplitude:
  // above tol · Y, below the floor.
  const double noise = 1.5e-4;
  const auto [plain, e_plain] = err(o, noise, h);
  const auto [held, e_held] = err(floored, noise, h);
  EXPECT_EQ(e_plain, e_held);  // the estimate itself is not touched
  EXPECT_GT(plain, 1.0);       // chasing the round-off
  EXPECT_LT(held, 1.0);
  EXPECT_NEAR(held, e_held / floor_h, 1e-12 * held);
  // Twice the step: a quarter of the floor.
  const auto [held2, e_held2] = err(floored, noise, 2 * h);
  EXPECT_NEAR(held2, e_held2 / (0.25 * floor_h), 1e-12 * held2);
  // A large acceleration (Y = 100 m/s², tol · Y = 1e-3 m/s² above the floor): the same bits.
  const auto big = [&](const StepControlOptions& opt) {
    StepController c(opt, Eigen::VectorXd::Ones(1));
    const auto y = [](double t) { return Eigen::VectorXd::Constant(1, 100.0 * std::cos(3e3 * t)); };
    c.restart(0.0, y(0.0));
    for (int k = 1; k <= 3; ++k) c.accept(k * h, y(k * h), 0.5, h);
    Eigen::VectorXd e;
    return c.estimate(4 * h, y(4 * h), e);
  };
  EXPECT_EQ(big(o), big(floored));
  StepControlOptions bad = o;
  bad.acceleration_roundoff_m = -1e-16;
  EXPECT_THROW(StepController(bad, Eigen::VectorXd::Ones(1)), InputError);
  bad = o;
  bad.velocity_step_roundoff_m = std::numeric_limits<double>::infinity();
  EXPECT_THROW(StepController(bad, Eigen::VectorXd::Ones(1)), InputError);
}

TEST(StepControl, AGrownStepReadsItsNeighboursRoundOffThroughItsStencil) {
  // docs/theory.md §5.3c, (5.11). Step points 0, h/2, h, 3h/2 and a candidate grown to h (at 5h/2).
  // Round-off of a point reached by a step h_i is ∝ 1/h_i² ((5.10)): 4σ at the first four, σ at
  // the candidate. e_v = 2 c h³ ȳ[m1, m2, m3] has the weights (0, 4/5, −8/15, −4/5, 8/15) / h²
  // on the five points there (by hand: midpoints 3h/4, 5h/4, 2h; each midpoint value the
  // average of two points), against (0, 1/4, −1/4, −1/4, 1/4) / h² on uniform steps h: the
  // worst-case round-off reads (4 (4/5 + 8/15 + 4/5) + 8/15) = 136/15 times the uniform one's.
  // e_y's third difference: 832/35. A round-off that reads err_v = ½ on uniform steps must not
  // reject the grown step (without the gain it reads 4.5).
  StepControlOptions o;
  o.tolerance = 1e-5;
  o.initial_step_s = 1e-3 / 256.0;  // h/2 on the ladder
  o.min_step_s = 1e-6;
  o.velocity_roundoff_m_s = 5e-13;  // the floor alone sets the velocity scale: 2 V_r = 1e-12 m/s
  const double c = o.error_constant;
  const double h = 2.0 * o.initial_step_s;
  // σ: on uniform steps h the worst case e_v = 2 c h³ Σ|w| σ = 2 c h σ is V_r: err_v = ½.
  const double sigma = o.velocity_roundoff_m_s / (2.0 * c * h);
  const double t[5] = {0.0, 0.5 * h, h, 1.5 * h, 2.5 * h};
  const double sign[5] = {0.0, 1.0, -1.0, -1.0, 1.0};  // of the weights: the worst case
  const double noise[5] = {4.0, 4.0, 4.0, 4.0, 1.0};
  const auto y = [&](int i) {
    return Eigen::VectorXd::Constant(1, 1.0 + sign[i] * noise[i] * sigma);
  };
  const Eigen::VectorXd v = Eigen::VectorXd::Constant(1, 1e-8);  // s · tol · V = 2.5e-14 m/s
  StepController grown(o, Eigen::VectorXd::Ones(1));
  grown.restart(t[0], y(0), v);
  for (int i = 1; i <= 3; ++i) grown.accept(t[i], y(i), v, 0.5, 0.5 * h);
  ASSERT_EQ(grown.step(), 0.5 * h);
  const Eigen::Vector2d gains = grown.noiseGains(t[4]);
  EXPECT_NEAR(gains[0], 832.0 / 35.0, 1e-9);
  EXPECT_NEAR(gains[1], 136.0 / 15.0, 1e-9);
  Eigen::VectorXd e;
  double ev = 0.0;
  Eigen::Vector2d parts;
  const double err = grown.estimate(t[4], y(4), v, e, ev, &parts);
  EXPECT_NEAR(ev, 136.0 / 15.0 * o.velocity_roundoff_m_s, 1e-9 * ev);
  EXPECT_GT(ev / (kNoiseFloorMargin * o.velocity_roundoff_m_s),
            4.0);                    // the uniform floor: rejected
  EXPECT_NEAR(parts[1], 0.5, 1e-9);  // the stencil's: accepted
  EXPECT_LE(err, 1.0);
  // Uniform steps h with 0.9 σ at every point: gains 1, err_v 0.45, and a step so measured
  // against its floor (err ≤ ½) grows by a ladder level (docs/theory.md §5.3a).
  StepControlOptions ou = o;
  ou.initial_step_s = h;
  StepController uniform(ou, Eigen::VectorXd::Ones(1));
  const auto yu = [&](int i) { return Eigen::VectorXd::Constant(1, 1.0 + sign[i] * 0.9 * sigma); };
  uniform.restart(0.0, yu(0), v);
  for (int i = 1; i <= 3; ++i) uniform.accept(i * h, yu(i), v, 0.5, h);
  EXPECT_EQ(uniform.noiseGains(4 * h), Eigen::Vector2d::Ones());
  const double err_u = uniform.estimate(4 * h, yu(4), v, e, ev, &parts);
  EXPECT_NEAR(parts[1], 0.45, 1e-9);
  uniform.accept(4 * h, yu(4), v, err_u, h, &parts);
  EXPECT_EQ(uniform.step(), 2 * h);
}

TEST(StepControl, AGrownStepMeasuredAgainstARaisedFloorDoesNotGrowAgain) {
  // The same grown step as above, asked for by the controller and accepted against its raised
  // floor. The next step is proposed from its error as uniform steps would read it (here 4.5:
  // the amplified round-off): it does not grow again, it returns to h/2, the size it grew from and
  // whose error was known, not below (docs/theory.md §5.3c).
  StepControlOptions o;
  o.tolerance = 1e-5;
  o.initial_step_s = 1e-3 / 256.0;
  o.min_step_s = 1e-6;
  o.velocity_roundoff_m_s = 5e-13;
  const double h = 2.0 * o.initial_step_s;
  const double sigma = o.velocity_roundoff_m_s / (2.0 * o.error_constant * h);
  const double t[5] = {0.0, 0.5 * h, h, 1.5 * h, 2.5 * h};
  const double sign[5] = {0.0, 1.0, -1.0, -1.0, 1.0};
  const double noise[5] = {4.0, 4.0, 4.0, 4.0, 1.0};
  const auto y = [&](int i) {
    return Eigen::VectorXd::Constant(1, 1.0 + sign[i] * noise[i] * sigma);
  };
  const Eigen::VectorXd v = Eigen::VectorXd::Constant(1, 1e-8);
  StepController c(o, Eigen::VectorXd::Ones(1));
  c.restart(t[0], y(0), v);
  for (int i = 1; i <= 2; ++i) c.accept(t[i], y(i), v, 0.5, 0.5 * h);
  // The third step, measured against the uniform floor at err ½: grows to h (§5.3a).
  const Eigen::Vector2d at_floor(0.01, 0.5);
  c.accept(t[3], y(3), v, 0.5, 0.5 * h, &at_floor);
  ASSERT_EQ(c.step(), h);
  Eigen::VectorXd e;
  double ev = 0.0;
  Eigen::Vector2d parts;
  const double err = c.estimate(t[4], y(4), v, e, ev, &parts);
  ASSERT_LE(err, 1.0);
  c.accept(t[4], y(4), v, err, h, &parts);
  EXPECT_EQ(c.step(), 0.5 * h);  // back to the size it grew from, not below
}

TEST(StepControl, TheGeneralizedAlphaWeightsOfTheRoundOff) {
  // ρ∞ = 1 is the trapezoidal rule: γ = ½, β = ¼; ρ∞ = 0.9: α_m = 0.8/1.9, α_f = 0.9/1.9.
  EXPECT_DOUBLE_EQ(generalizedAlphaGamma(1.0), 0.5);
  EXPECT_DOUBLE_EQ(generalizedAlphaBeta(1.0), 0.25);
  const double gamma = 0.5 + (0.9 - 0.8) / 1.9;
  EXPECT_NEAR(generalizedAlphaGamma(0.9), gamma, 1e-15);
  EXPECT_NEAR(generalizedAlphaBeta(0.9), 0.25 * (gamma + 0.5) * (gamma + 0.5), 1e-15);
}

TEST(StepControl, AStepMeasuredAgainstItsNoiseFloorGrowsByALadderLevel) {
  // Round-off does not grow like h³: where the criterion that set the error is measured against
  // its noise floor, an error of at most ½ lets the step double; the same error against the
  // tolerance's own scale does not (the PI controller asks for 0.9 · 0.4^(−0.7/3) = 1.1×).
  StepControlOptions o;
  o.tolerance = 1e-5;
  o.initial_step_s = 7.8125e-6;  // on the ladder 1e-3 · 2^−7
  o.min_step_s = 1e-7;
  const auto run = [&](double noise_floor) {
    StepController c(o, Eigen::VectorXd::Ones(1));
    const Eigen::VectorXd y = Eigen::VectorXd::Constant(1, 1.0);
    c.restart(0.0, y);
    if (noise_floor > 0.0) {
      c.acceptAtNoiseFloor(Eigen::VectorXd::Constant(1, noise_floor));
    }
    const Eigen::Vector2d parts(0.4, 0.1);  // the acceleration criterion set err
    c.accept(o.initial_step_s, y, Eigen::VectorXd(), 0.4, o.initial_step_s, &parts);
    return c.step();
  };
  EXPECT_EQ(run(0.0), o.initial_step_s);        // against tol · Y = 1e-5: kept
  EXPECT_EQ(run(1e-4), 2 * o.initial_step_s);   // against 2 · 1e-4 > 1e-5: doubled
}

TEST(StepControl, AStepLandingOnAStopFromLessThanTwoShortestStepsCannotBeCut) {
  StepControlOptions o;
  o.min_step_s = 1e-6;
  StepController c(o, Eigen::VectorXd::Ones(1));
  EXPECT_FALSE(c.atShortestStep(1.7e-6));
  EXPECT_TRUE(c.atShortestStep(1.7e-6, true));   // cut to 1 µs, it would leave 0.7 µs
  EXPECT_FALSE(c.atShortestStep(2.1e-6, true));  // 1 µs + 1.1 µs: can be cut
  EXPECT_THROW(c.reject(HUGE_VAL, 1.7e-6, 0.3, true), NumericalError);
}

}  // namespace
}  // namespace mastrom::fullorder
