// Jansen's Sobol indices on Saltelli's design against the closed-form indices of the Ishigami
// function [Ishigami & Homma 1990; Saltelli et al. 2010, §4]: f = sin x₁ + a sin² x₂ + b x₃⁴ sin
// x₁, x_i ~ U(−π, π), a = 7, b = 0.1.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/statistics/distributions.hpp"
#include "common/statistics/sobol_indices.hpp"
#include "common/statistics/unit_sampler.hpp"

namespace mastrom::stats {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kA = 7.0, kB = 0.1;

double ishigami(const double* x) {
  return std::sin(x[0]) + kA * std::sin(x[1]) * std::sin(x[1]) +
         kB * std::pow(x[2], 4) * std::sin(x[0]);
}

struct Exact {
  double first[3];
  double total[3];
};

/// V = a²/8 + bπ⁴/5 + b²π⁸/18 + ½; V₁ = ½(1 + bπ⁴/5)², V₂ = a²/8, V₃ = 0, V₁₃ = 8b²π⁸/225.
Exact ishigamiIndices() {
  const double pi4 = std::pow(kPi, 4), pi8 = pi4 * pi4;
  const double v = kA * kA / 8 + kB * pi4 / 5 + kB * kB * pi8 / 18 + 0.5;
  const double v1 = 0.5 * std::pow(1 + kB * pi4 / 5, 2), v2 = kA * kA / 8;
  const double v13 = 8 * kB * kB * pi8 / 225;
  return {{v1 / v, v2 / v, 0.0}, {(v1 + v13) / v, v2 / v, v13 / v}};
}

std::vector<double> ishigamiValues(SamplingKind kind, int base_samples, unsigned long seed) {
  const int k = 3;
  UncertainInput in;
  in.distribution = DistributionKind::Uniform;
  in.lower = -kPi;
  in.upper = kPi;
  UnitSampler sampler(kind, 2 * k, seed);
  std::vector<double> u(2 * k), rows((k + 2) * k), f;
  for (int j = 0; j < base_samples; ++j) {
    sampler.next(u.data());
    for (double& x : u) x = inverseCdf(in, x);
    saltelliRows(u.data(), k, rows.data());
    for (int r = 0; r < k + 2; ++r) f.push_back(ishigami(&rows[static_cast<std::size_t>(r * k)]));
  }
  return f;
}

// The six indices within their bootstrap intervals. 99 % intervals: six of them at 95 % would
// all hold only about three times in four even when each is right.
void expectIndicesCovered(SamplingKind kind, int base_samples, double widest) {
  const Exact exact = ishigamiIndices();
  BootstrapOptions bootstrap;
  bootstrap.confidence = 0.99;
  const SobolIndices s = jansenIndices(ishigamiValues(kind, base_samples, 7), 3, bootstrap);
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(s.first[i].contains(exact.first[i]))
        << "S" << i + 1 << " = " << exact.first[i] << " outside [" << s.first[i].lower << ", "
        << s.first[i].upper << "], estimate " << s.first[i].estimate;
    EXPECT_TRUE(s.total[i].contains(exact.total[i]))
        << "ST" << i + 1 << " = " << exact.total[i] << " outside [" << s.total[i].lower << ", "
        << s.total[i].upper << "], estimate " << s.total[i].estimate;
  }
  // Intervals that are informative: otherwise containing the exact value proves nothing. At
  // N = 4096 the widest 99 % interval measured 0.112 (Sobol) and 0.120 (Monte Carlo), the total
  // index of x₁, whose Jansen estimator carries the x₃⁴ interaction's heavy tail; the exact
  // indices range over [0, 0.56].
  EXPECT_LT(s.widestInterval(), widest);
}

TEST(SobolIndices, IshigamiWithinBootstrapIntervalsSobolSampling) {
  expectIndicesCovered(SamplingKind::Sobol, 4096, 0.15);
}

TEST(SobolIndices, IshigamiWithinBootstrapIntervalsMonteCarlo) {
  expectIndicesCovered(SamplingKind::MonteCarlo, 4096, 0.15);
}

// The interval shrinks like 1/√N with the base sample: 4 times the samples, about half the width.
TEST(SobolIndices, IntervalsShrinkWithSampleSize) {
  BootstrapOptions bootstrap;
  const double w1 = jansenIndices(ishigamiValues(SamplingKind::MonteCarlo, 1000, 3), 3, bootstrap)
                        .widestInterval();
  const double w4 = jansenIndices(ishigamiValues(SamplingKind::MonteCarlo, 4000, 3), 3, bootstrap)
                        .widestInterval();
  EXPECT_GT(w1 / w4, 1.5);
  EXPECT_LT(w1 / w4, 2.7);
}

TEST(SobolIndices, AdditiveFunctionHasEqualFirstAndTotal) {
  // f = x₁ + 2 x₂ with x ~ U(0, 1): S = ST = (1/5, 4/5) exactly (no interaction).
  UnitSampler sampler(SamplingKind::Sobol, 4, 11);
  std::vector<double> u(4), rows(8), f;
  for (int j = 0; j < 2048; ++j) {
    sampler.next(u.data());
    saltelliRows(u.data(), 2, rows.data());
    for (int r = 0; r < 4; ++r) f.push_back(rows[2 * r] + 2 * rows[2 * r + 1]);
  }
  const SobolIndices s = jansenIndices(f, 2, {});
  EXPECT_NEAR(s.first[0].estimate, 0.2, 0.01);
  EXPECT_NEAR(s.first[1].estimate, 0.8, 0.01);
  EXPECT_NEAR(s.total[0].estimate, 0.2, 0.01);
  EXPECT_NEAR(s.total[1].estimate, 0.8, 0.01);
}

TEST(SobolIndices, SaltelliRowsTakeOneColumnFromB) {
  const double u[4] = {0.1, 0.2, 0.3, 0.4};  // A = (0.1, 0.2), B = (0.3, 0.4)
  double rows[8];
  saltelliRows(u, 2, rows);
  const double expected[8] = {0.1, 0.2, 0.3, 0.4, 0.3, 0.2, 0.1, 0.4};
  for (int i = 0; i < 8; ++i) EXPECT_EQ(rows[i], expected[i]) << i;
}

}  // namespace
}  // namespace mastrom::stats
