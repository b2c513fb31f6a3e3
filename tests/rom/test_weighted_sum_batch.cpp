// weightedSumBatch (rom/interpolation/weighted_sum_batch.hpp): the weighted sums of a batch equal
// the loop `out += w_n a_n` from zero (what an interpolation at one point computes) bit for bit,
// whatever the batch, and equal the exact sums to round-off.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "rom/interpolation/weighted_sum_batch.hpp"

namespace mastrom::rom {
namespace {

TEST(WeightedSumBatch, EqualsTheSequentialSumBitForBitWhateverTheBatch) {
  constexpr int kSources = 7, kPoints = 5;
  constexpr long kSize = 1000;  // not a multiple of the kernel's block
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  std::vector<std::vector<double>> a(kSources, std::vector<double>(kSize));
  for (auto& v : a)
    for (double& x : v) x = normal(rng);
  std::vector<double> weights(kPoints * kSources);
  for (double& w : weights) w = normal(rng);
  std::vector<const double*> sources;
  for (const auto& v : a) sources.push_back(v.data());

  std::vector<std::vector<double>> batch(kPoints, std::vector<double>(kSize, -1.0));
  std::vector<double*> out;
  for (auto& v : batch) out.push_back(v.data());
  weightedSumBatch(sources, kSize, weights, out);
  double worst = 0.0;
  for (int b = 0; b < kPoints; ++b) {
    // The same point alone, and the loop an interpolation at one point runs.
    std::vector<double> alone(kSize, 7.0);
    const std::vector<double> w(weights.begin() + b * kSources,
                                weights.begin() + (b + 1) * kSources);
    weightedSumBatch(sources, kSize, w, {alone.data()});
    for (long i = 0; i < kSize; ++i) {
      double sequential = 0.0;
      long double exact = 0.0L;
      for (int n = 0; n < kSources; ++n) {
        sequential += w[static_cast<std::size_t>(n)] * a[static_cast<std::size_t>(n)][i];
        exact += static_cast<long double>(w[static_cast<std::size_t>(n)]) *
                 a[static_cast<std::size_t>(n)][i];
      }
      ASSERT_EQ(batch[b][i], alone[i]) << "point " << b << ", entry " << i;
      ASSERT_EQ(batch[b][i], sequential) << "point " << b << ", entry " << i;
      worst = std::max(worst, std::abs(static_cast<double>(batch[b][i] - exact)));
    }
  }
  // Seven products of O(1) terms: a few units of round-off of the largest partial sum.
  EXPECT_LT(worst, 1e-14);
}

}  // namespace
}  // namespace mastrom::rom
