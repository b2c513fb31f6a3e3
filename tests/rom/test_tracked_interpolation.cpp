// Interpolation method (a) (rom/interpolation/tracked_interpolation.hpp) and the mode tracking it relies on
// (rom/offline/mode_tracking.hpp), on synthetic data with a known answer.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "common/error.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/offline/mode_tracking.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/interpolation/tracked_interpolation.hpp"
#include "rom_fixtures.hpp"

namespace mastrom::rom {
namespace {

using testing::bilinearDatabase;
using testing::randomBilinearModel;

void expectModelsNear(const ModalModel& a, const ModalModel& b, double tol) {
  ASSERT_EQ(a.modeCount(), b.modeCount());
  EXPECT_LE((a.omega_rad_s - b.omega_rad_s).cwiseAbs().maxCoeff(), tol * b.omega_rad_s.norm());
  EXPECT_LE((a.damping_ratio - b.damping_ratio).cwiseAbs().maxCoeff(), tol);
  EXPECT_LE((a.rotation_participation - b.rotation_participation).cwiseAbs().maxCoeff(), tol);
  EXPECT_LE((a.centrifugal_participation - b.centrifugal_participation).cwiseAbs().maxCoeff(), tol);
  EXPECT_LE((a.end_rotation - b.end_rotation).cwiseAbs().maxCoeff(), tol);
  EXPECT_LE((a.end_translation - b.end_translation).cwiseAbs().maxCoeff(), tol);
  EXPECT_LE((a.momentum_participation - b.momentum_participation).cwiseAbs().maxCoeff(), tol);
  EXPECT_LE((a.coriolis - b.coriolis).cwiseAbs().maxCoeff(), tol);
  EXPECT_NEAR(a.inertia_z_kg_m2, b.inertia_z_kg_m2, tol);
  EXPECT_NEAR(a.total_mass_kg, b.total_mass_kg, tol);
  EXPECT_LE((a.centroid_m - b.centroid_m).cwiseAbs().maxCoeff(), tol);
  EXPECT_LE((a.end_position_m - b.end_position_m).cwiseAbs().maxCoeff(), tol);
}

TEST(MaximumWeightAssignment, FindsTheOptimumWhereGreedyFails) {
  // Greedy takes (0,0) = 0.9 first and is left with (1,1) = 0.1: total 1.0. Optimal: 0.8 + 0.85.
  Eigen::MatrixXd w(2, 2);
  w << 0.9, 0.8, 0.85, 0.1;
  EXPECT_EQ(maximumWeightAssignment(w), (std::vector<int>{1, 0}));
  // Rectangular: 2 rows, 3 columns.
  Eigen::MatrixXd r(2, 3);
  r << 0.1, 0.2, 0.9, 0.1, 0.95, 0.3;
  EXPECT_EQ(maximumWeightAssignment(r), (std::vector<int>{2, 1}));
  EXPECT_THROW(maximumWeightAssignment(Eigen::MatrixXd::Ones(3, 2)), InputError);
}

TEST(MaximumWeightAssignment, RecoversARandomPermutation) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 12;
    std::vector<int> perm(n);
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), rng);
    Eigen::MatrixXd w = 0.3 * Eigen::MatrixXd::NullaryExpr(n, n, [&rng]() {
                          return std::uniform_real_distribution<double>(0, 1)(rng);
                        });
    for (int i = 0; i < n; ++i) w(i, perm[i]) = 0.95;
    EXPECT_EQ(maximumWeightAssignment(w), perm);
  }
}

TEST(TrackModes, UndoesPermutationSignsAndFindsTheAlignment) {
  // Reference: random M-orthonormal modes; sample: the same modes permuted, sign-flipped and
  // slightly perturbed.
  std::mt19937 rng(3);
  const int n = 30, k = 6;
  Eigen::SparseMatrix<double> mass(n, n);
  for (int i = 0; i < n; ++i) mass.insert(i, i) = 1.0 + 0.1 * i;
  Eigen::MatrixXd phi_ref = Eigen::MatrixXd::NullaryExpr(
      n, k, [&rng]() { return std::normal_distribution<double>(0, 1)(rng); });
  // M-orthonormalise (Cholesky of the Gram matrix).
  const Eigen::MatrixXd gram = phi_ref.transpose() * (mass * phi_ref);
  phi_ref = phi_ref * Eigen::MatrixXd(gram.llt().matrixU()).inverse();
  const std::vector<int> perm{2, 0, 1, 5, 3, 4};
  const std::vector<int> sign{1, -1, -1, 1, 1, -1};
  Eigen::MatrixXd phi_s(n, k);
  for (int j = 0; j < k; ++j) phi_s.col(perm[j]) = sign[j] * phi_ref.col(j);
  phi_s += 1e-3 * Eigen::MatrixXd::NullaryExpr(
                      n, k, [&rng]() { return std::normal_distribution<double>(0, 1)(rng); });
  const ModeTracking t = trackModes(phi_s, phi_ref, mass);
  EXPECT_EQ(t.tracking, perm);
  EXPECT_EQ(t.sign, sign);
  EXPECT_GT(t.mac.minCoeff(), 0.99);
  // Q is orthogonal and maps the sample's modes onto the reference's: Φ_s Q ≈ Φ_ref.
  EXPECT_LT((t.alignment.transpose() * t.alignment - Eigen::MatrixXd::Identity(k, k)).norm(),
            1e-12);
  EXPECT_LT((phi_s * t.alignment - phi_ref).norm() / phi_ref.norm(), 1e-2);
}

TEST(TrackedInterpolation, ReproducesEverySampleBitForBit) {
  const testing::BilinearModel b = randomBilinearModel(5, 11);
  const RomDatabase db = bilinearDatabase(b, {1e-3, 1.5e-3, 2e-3}, {0.4, 0.5, 0.6}, 5);
  const TrackedInterpolator interp(db);
  for (std::size_t s = 0; s < db.samples.size(); ++s) {
    const RomSample& smp = db.samples[s];
    const ModalModel m = interp.evaluate(smp.parameters);
    // The sample's modes in slot order, sign-aligned: exactly what the interpolator returns.
    for (int j = 0; j < b.modes; ++j) {
      const int i = smp.tracking[j];
      const double sg = smp.tracking_sign[j];
      // ω goes through log and exp: exact up to their round-off (a few ulp of log ω ≈ 10).
      EXPECT_NEAR(m.omega_rad_s[j], smp.modal.omega_rad_s[i], 1e-14 * smp.modal.omega_rad_s[i]);
      EXPECT_EQ(m.damping_ratio[j], smp.modal.damping_ratio[i]);
      EXPECT_EQ(m.rotation_participation[j], sg * smp.modal.rotation_participation[i]);
      EXPECT_EQ(Eigen::Vector3d(m.end_rotation.col(j)),
                Eigen::Vector3d(sg * smp.modal.end_rotation.col(i)));
    }
    EXPECT_EQ(m.inertia_z_kg_m2, smp.modal.inertia_z_kg_m2);
    EXPECT_EQ(m.centroid_m, smp.modal.centroid_m);
  }
}

TEST(TrackedInterpolation, IsExactForBilinearDataAndExtrapolatesLinearly) {
  const testing::BilinearModel b = randomBilinearModel(4, 21);
  const std::vector<double> xs{1e-3, 1.2e-3, 1.7e-3, 2e-3}, ys{0.4, 0.6};
  const RomDatabase db = bilinearDatabase(b, xs, ys, 9);
  // The plain multilinear form (linear weights, ω itself) is exact for bilinear data.
  const std::unique_ptr<ModalInterpolator> interp =
      std::make_unique<TrackedInterpolator>(db, AxisWeighting::Linear);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 10; ++trial) {
    const double x = u(rng), y = u(rng);
    const ModalModel m = interp->evaluate({1e-3 + x * 1e-3, 0.4 + y * 0.2});
    expectModelsNear(m, b.value(x, y), 1e-12);
  }
  // Outside the box (x = 1.25, y = −0.5): still the bilinear function (linear in each cell).
  expectModelsNear(interp->evaluate({2.25e-3, 0.3}), b.value(1.25, -0.5), 1e-12);
  EXPECT_THROW(interp->evaluate({1e-3}), InputError);
  EXPECT_THROW(interp->evaluate({1e-3, std::nan("")}), InputError);
}

TEST(TrackedInterpolation, LogarithmicWeightsAreExactForPowerLawFrequencies) {
  // ω = c x^a y^b at every sample (the bilinear model's other quantities left as they are): the
  // default logarithmic form interpolates log ω linearly in (log x, log y), i.e. exactly.
  const testing::BilinearModel b = randomBilinearModel(3, 5);
  const std::vector<double> xs{1e-3, 1.5e-3, 2e-3}, ys{0.4, 0.6};
  RomDatabase db = bilinearDatabase(b, xs, ys, 2);
  const auto law = [](double x, double y, int j) {
    return (100.0 + 50.0 * j) * std::pow(x / 1e-3, 0.7 + 0.1 * j) * std::pow(y, -0.5);
  };
  for (RomSample& s : db.samples)
    for (int j = 0; j < s.modal.modeCount(); ++j)
      s.modal.omega_rad_s[s.tracking[j]] = law(s.parameters[0], s.parameters[1], j);
  const TrackedInterpolator interp(db);
  for (const auto& [x, y] : {std::pair{1.2e-3, 0.45}, std::pair{1.9e-3, 0.58}}) {
    const ModalModel m = interp.evaluate({x, y});
    std::vector<double> expected;
    for (int j = 0; j < 3; ++j) expected.push_back(law(x, y, j));
    std::sort(expected.begin(), expected.end());
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(m.omega_rad_s[j], expected[j], 1e-12 * expected[j]);
  }
}

TEST(TrackedInterpolation, RefusesAnInconsistentDatabase) {
  const testing::BilinearModel b = randomBilinearModel(3, 2);
  RomDatabase db = bilinearDatabase(b, {1e-3, 2e-3}, {0.4, 0.6}, 1);
  RomDatabase missing = db;
  missing.samples.pop_back();
  EXPECT_THROW(TrackedInterpolator{missing}, InputError);
  RomDatabase bad_tracking = db;
  bad_tracking.samples[1].tracking[0] = bad_tracking.samples[1].tracking[1];
  EXPECT_THROW(TrackedInterpolator{bad_tracking}, InputError);
}

TEST(InterpolationMethods, NamesRoundTrip) {
  for (const InterpolationMethod m : {InterpolationMethod::Tracked, InterpolationMethod::Manifold})
    EXPECT_EQ(parseInterpolationMethod(toString(m)), m);
  EXPECT_FALSE(parseInterpolationMethod("linear").has_value());
  EXPECT_TRUE(interpolationMethodAvailable(InterpolationMethod::Tracked));
}

TEST(BoxCheck, RefusesOutsideUnlessExtrapolating) {
  const testing::BilinearModel b = randomBilinearModel(3, 2);
  const RomDatabase db = bilinearDatabase(b, {1e-3, 2e-3}, {0.4, 0.6}, 1);
  EXPECT_NO_THROW(requireInsideBox(db, {2e-3, 0.4}, BoxPolicy::Refuse));
  try {
    requireInsideBox(db, {2e-3, 0.7}, BoxPolicy::Refuse);
    FAIL() << "no error outside the box";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "module.mass = 0.7 lies outside the database's range [0.4, 0.6]"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("--extrapolate"), std::string::npos);
  }
  EXPECT_NO_THROW(requireInsideBox(db, {2e-3, 0.7}, BoxPolicy::Extrapolate));
}

}  // namespace
}  // namespace mastrom::rom
