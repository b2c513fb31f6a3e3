// Local Lagrange weights on a tensor grid (rom/interpolation/grid_weights.hpp) and the cubic
// tracked interpolation built on them: polynomial reproduction, exactness at the nodes, agreement
// with the multilinear weights at degree 1, and a database whose log ω is a cubic in log h.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "common/error.hpp"
#include "rom/interpolation/grid_weights.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/interpolation/tracked_interpolation.hpp"
#include "rom_fixtures.hpp"

namespace mastrom::rom {
namespace {

const std::vector<ParameterAxis> kAxes = {{"x", {1.0, 1.3, 2.0, 2.2, 3.5}}, {"y", {0.5, 0.8, 1.0}}};

/// Σ c_ab u^a v^b with a ≤ 3, b ≤ 2: what cubic weights on a 5 × 3 grid reproduce exactly.
double polynomial(double u, double v) {
  double p = 0.0;
  for (int a = 0; a <= 3; ++a)
    for (int b = 0; b <= 2; ++b) p += (1.0 + a - 0.5 * b) * std::pow(u, a) * std::pow(v, b);
  return p;
}

double interpolate(const std::vector<GridWeight>& weights, bool logarithmic) {
  double sum = 0.0;
  for (const GridWeight& w : weights) {
    const double x = kAxes[0].values[static_cast<std::size_t>(w.sample % 5)];
    const double y = kAxes[1].values[static_cast<std::size_t>(w.sample / 5)];
    sum += w.weight * (logarithmic ? polynomial(std::log(x), std::log(y)) : polynomial(x, y));
  }
  return sum;
}

TEST(LagrangeWeights, ReproduceCubicsInXAndQuadraticsInYExactly) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(0.9, 3.7), uy(0.45, 1.05);  // a little outside too
  for (const AxisWeighting weighting : {AxisWeighting::Linear, AxisWeighting::Logarithmic}) {
    const bool logarithmic = weighting == AxisWeighting::Logarithmic;
    for (int trial = 0; trial < 50; ++trial) {
      const double x = ux(rng), y = uy(rng);
      const std::vector<GridWeight> w = lagrangeWeights(kAxes, {x, y}, 3, weighting);
      EXPECT_LE(w.size(), 12u);  // 4 × 3 stencil
      double sum = 0.0;
      for (const GridWeight& g : w) sum += g.weight;
      EXPECT_NEAR(sum, 1.0, 1e-13);
      const double exact = logarithmic ? polynomial(std::log(x), std::log(y)) : polynomial(x, y);
      EXPECT_NEAR(interpolate(w, logarithmic), exact, 1e-12 * std::abs(exact))
          << "at (" << x << ", " << y << ")";
    }
  }
}

TEST(LagrangeWeights, AreOneSampleAtANodeAndMultilinearAtDegreeOne) {
  for (int s = 0; s < 15; ++s) {
    const double x = kAxes[0].values[static_cast<std::size_t>(s % 5)];
    const double y = kAxes[1].values[static_cast<std::size_t>(s / 5)];
    const std::vector<GridWeight> w = lagrangeWeights(kAxes, {x, y}, 3);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0].sample, s);
    EXPECT_EQ(w[0].weight, 1.0);
  }
  for (const std::vector<double>& p : {std::vector<double>{1.7, 0.6}, {3.1, 0.95}, {4.0, 0.3}}) {
    std::vector<GridWeight> a = lagrangeWeights(kAxes, p, 1), b = multilinearWeights(kAxes, p);
    ASSERT_EQ(a.size(), b.size());
    const auto by_sample = [](const GridWeight& l, const GridWeight& r) {
      return l.sample < r.sample;
    };
    std::sort(a.begin(), a.end(), by_sample);
    std::sort(b.begin(), b.end(), by_sample);
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].sample, b[i].sample);
      EXPECT_NEAR(a[i].weight, b[i].weight, 1e-14);
    }
  }
  EXPECT_THROW(lagrangeWeights(kAxes, {1.0}, 3), InputError);
  EXPECT_THROW(lagrangeWeights(kAxes, {1.0, 0.5}, 0), InputError);
  EXPECT_THROW(lagrangeWeights(kAxes, {std::nan(""), 0.5}, 3), InputError);
}

TEST(CubicInterpolation, IsExactWhereLogOmegaIsACubicInLogThickness) {
  // log ω = cubic in log h (4 thickness nodes) and linear in log m (2 mass nodes): the cubic method
  // reproduces it to round-off; the multilinear one (tracked) is off between the nodes.
  const testing::BilinearModel b = testing::randomBilinearModel(3, 17);
  const std::vector<double> hs{1e-3, 1.3e-3, 1.6e-3, 2e-3}, ms{0.4, 0.6};
  RomDatabase db = testing::bilinearDatabase(b, hs, ms, 4);
  const auto law = [](double h, double m, int j) {
    const double u = std::log(h / 1e-3);
    return (150.0 + 40.0 * j) * std::exp(0.9 * u + 0.4 * u * u - 0.3 * u * u * u) *
           std::pow(m, -0.5);
  };
  for (RomSample& s : db.samples)
    for (int j = 0; j < s.modal.modeCount(); ++j)
      s.modal.omega_rad_s[s.tracking[j]] = law(s.parameters[0], s.parameters[1], j);
  const std::unique_ptr<ModalInterpolator> cubic = makeInterpolator(db, InterpolationMethod::Cubic);
  const std::unique_ptr<ModalInterpolator> linear =
      makeInterpolator(db, InterpolationMethod::Tracked);
  double linear_error = 0.0;
  for (const auto& [h, m] :
       {std::pair{1.15e-3, 0.45}, std::pair{1.45e-3, 0.5}, std::pair{1.8e-3, 0.57}}) {
    std::vector<double> expected;
    for (int j = 0; j < 3; ++j) expected.push_back(law(h, m, j));
    std::sort(expected.begin(), expected.end());
    const ModalModel c = cubic->evaluate({h, m}), l = linear->evaluate({h, m});
    for (int j = 0; j < 3; ++j) {
      EXPECT_NEAR(c.omega_rad_s[j], expected[j], 1e-12 * expected[j]);
      linear_error = std::max(linear_error, std::abs(l.omega_rad_s[j] / expected[j] - 1.0));
    }
  }
  EXPECT_GT(linear_error, 1e-4);  // the test would not tell the two apart otherwise
}

}  // namespace
}  // namespace mastrom::rom
