// The local error estimate and the step controller of adaptive generalized-α
// (fullorder/step_control.hpp): the error constant against its closed form, the third-difference
// estimate against the exact local error of a sinusoid, the ladder of step sizes, and the
// acceptance at the estimate's noise floor.
#include <cmath>

#include <gtest/gtest.h>

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
  // y = sin(ωt) at four equally spaced points: 6 c h³ y[t0..t3] → c h³ y‴(t) = −c h³ ω³ cos(ωt)
  // to O(h) relative (the divided difference is centred between the points).
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
  c.accept(h, y(h), 0.0, h);
  c.accept(2 * h, y(2 * h), 0.0, h);
  ASSERT_TRUE(c.canEstimate());
  const double err = c.estimate(3 * h, y(3 * h), e);
  const double expected = -0.1 * h * h * h * w * w * w * std::cos(w * 1.5 * h);
  EXPECT_NEAR(e[0], expected, 5e-3 * std::abs(expected));
  // Scaled by tolerance · the peak seen so far (|y| ≤ sin(3ωh) here).
  EXPECT_NEAR(err, std::abs(e[0]) / std::abs(std::sin(w * 3 * h)), 1e-12);
}

TEST(StepControl, StepsStayOnTheLadderAndGrowOnlyByWholeLevels) {
  StepControlOptions o;
  o.max_step_s = 1e-3;
  o.min_step_s = 1e-7;
  o.initial_step_s = 3e-5;  // not on the ladder: starts at 1e-3 · 2⁻⁶ = 15.6 µs
  StepController c(o, Eigen::VectorXd::Ones(1));
  EXPECT_DOUBLE_EQ(c.step(), 1e-3 / 64.0);
  c.restart(0.0, Eigen::VectorXd::Ones(1));
  double t = 0.0;
  for (int k = 0; k < 3; ++k) {  // tiny errors: the step doubles once the estimate exists
    t += c.step();
    c.accept(t, Eigen::VectorXd::Ones(1), k < 2 ? 0.0 : 1e-6, c.step());
  }
  EXPECT_DOUBLE_EQ(c.step(), 1e-3 / 32.0);
  // A rejection lands at least one level lower.
  c.reject(2.0, c.step(), t);
  EXPECT_DOUBLE_EQ(c.step(), 1e-3 / 64.0);
  EXPECT_EQ(c.state().rejected, 1);
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
  // A Newton failure at the smallest step is an error, with the instant.
  EXPECT_THROW(c.reject(HUGE_VAL, 1e-7, 0.7), NumericalError);
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

}  // namespace
}  // namespace mastrom::fullorder
