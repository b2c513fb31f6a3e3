// The inverse CDFs of the [uncertainty] distributions: F(F⁻¹(u)) = u, and the moments of the
// samples they produce against the closed-form moments (the truncated normal's by quadrature of
// its density, an independent check of the formulas in distributions.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/error.hpp"
#include "common/statistics/distributions.hpp"
#include "common/statistics/sample_statistics.hpp"
#include "common/statistics/unit_sampler.hpp"

namespace mastrom::stats {
namespace {

UncertainInput make(DistributionKind kind, std::optional<double> mean, std::optional<double> sd,
                    std::optional<double> lower, std::optional<double> upper) {
  UncertainInput in;
  in.distribution = kind;
  in.mean = mean;
  in.std_dev = sd;
  in.lower = lower;
  in.upper = upper;
  return in;
}

std::vector<UncertainInput> cases() {
  return {make(DistributionKind::Normal, 70e9, 2e9, {}, {}),
          make(DistributionKind::Lognormal, 2e-3, 3e-4, {}, {}),
          make(DistributionKind::Uniform, {}, {}, 0.4, 0.6),
          make(DistributionKind::TruncatedNormal, 1.0, 0.5, 0.8, 2.0),
          // Far in the upper tail: the mirrored branch.
          make(DistributionKind::TruncatedNormal, 0.0, 1.0, 4.0, 6.0)};
}

TEST(Distributions, CdfInvertsInverseCdf) {
  for (const UncertainInput& in : cases())
    for (const double u : {1e-6, 0.01, 0.3, 0.5, 0.9, 0.999})
      EXPECT_NEAR(cdf(in, inverseCdf(in, u)), u, 1e-9 * std::max(1.0, 1 / u))
          << toString(in.distribution) << " u = " << u;
}

TEST(Distributions, SampleMomentsMatchClosedForms) {
  for (const UncertainInput& in : cases()) {
    UnitSampler sampler(SamplingKind::Sobol, 1, 3);
    std::vector<double> x;
    for (int j = 0; j < 1 << 15; ++j) {
      double u = 0;
      sampler.next(&u);
      x.push_back(inverseCdf(in, u));
    }
    const SampleSummary s = summarize(x, {0.5}, 0.999);
    EXPECT_TRUE(s.mean.contains(distributionMean(in))) << toString(in.distribution);
    EXPECT_TRUE(s.std_dev.contains(distributionStdDev(in))) << toString(in.distribution);
    if (in.lower) {
      for (const double v : x) ASSERT_TRUE(v >= *in.lower && v <= *in.upper);
    }
  }
}

TEST(Distributions, TruncatedNormalMomentsByQuadrature) {
  const UncertainInput in = make(DistributionKind::TruncatedNormal, 1.0, 0.5, 0.8, 2.0);
  // Midpoint rule on the density ∝ exp(−(x − μ)²/(2σ²)) over [lower, upper].
  const int n = 200000;
  double z = 0, m1 = 0, m2 = 0;
  const double h = (*in.upper - *in.lower) / n;
  for (int i = 0; i < n; ++i) {
    const double x = *in.lower + (i + 0.5) * h;
    const double w = std::exp(-0.5 * std::pow((x - *in.mean) / *in.std_dev, 2));
    z += w;
    m1 += w * x;
    m2 += w * x * x;
  }
  const double mean = m1 / z, sd = std::sqrt(m2 / z - mean * mean);
  EXPECT_NEAR(distributionMean(in), mean, 1e-9);
  EXPECT_NEAR(distributionStdDev(in), sd, 1e-9);
}

TEST(Distributions, LognormalIsParametrisedByTheValuesMoments) {
  const UncertainInput in = make(DistributionKind::Lognormal, 2e-3, 3e-4, {}, {});
  // The median of a lognormal with mean m and cv c is m / √(1 + c²).
  const double cv = 0.15;
  EXPECT_NEAR(inverseCdf(in, 0.5), 2e-3 / std::sqrt(1 + cv * cv), 1e-15);
}

TEST(UnitSampler, SobolPointsAreShiftedAndInsideTheOpenCube) {
  UnitSampler a(SamplingKind::Sobol, 5, 1), b(SamplingKind::Sobol, 5, 2);
  std::vector<double> x(5), y(5);
  a.next(x.data());
  b.next(y.data());
  EXPECT_NE(x, y);  // different shifts
  for (int j = 0; j < 1000; ++j) {
    a.next(x.data());
    for (const double v : x) ASSERT_TRUE(v > 0.0 && v < 1.0);
  }
  EXPECT_THROW(UnitSampler(SamplingKind::Sobol, kMaxSobolDimension + 1, 1), UsageError);
}

}  // namespace
}  // namespace mastrom::stats
