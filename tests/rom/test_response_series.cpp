// The estimate's signal r (the relative end angular acceleration) of many models at once
// (rom/offline/leave_one_out.hpp): the modes r cannot see are not stepped, and the models are
// stepped side by side. Both must give the series of every model stepped alone with all its modes.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "common/error.hpp"
#include "fullorder/drive_law.hpp"
#include "rom/model/modal_stepping.hpp"
#include "rom/offline/leave_one_out.hpp"
#include "rom_fixtures.hpp"

namespace mastrom::rom {
namespace {

/// Six random modes (100–600 Hz, ζ ≈ 1 %) at (x, y), with modes 1 and 4 made invisible to r the
/// way a symmetric mesh makes them: ψ_z and Γ at round-off (1e-28 of the others' product).
ModalModel modelWithHiddenModes(double x, double y, bool gravity) {
  ModalModel m = testing::randomBilinearModel(6, 23).value(x, y);
  for (const int hidden : {1, 4}) {
    m.end_rotation(2, hidden) = 1e-14;
    m.rotation_participation[hidden] = 1e-14;
    m.centrifugal_participation[hidden] = 1e-14;
    m.momentum_participation.col(hidden).setConstant(1e-14);
  }
  if (gravity) m.gravity_m_s2 = Eigen::Vector3d(0.5, -9.81, 0.2);
  return m;
}

fullorder::DriveLaw quickDrive() {
  fullorder::DriveLawParameters dp;
  dp.duration_s = 0.3;
  dp.ramp_s = 0.0173;  // breakpoints between samples: split steps
  dp.total_angle_rad = 1.2;
  return fullorder::DriveLaw(dp);
}

double largest(const std::vector<double>& v) {
  double m = 0.0;
  for (const double x : v) m = std::max(m, std::abs(x));
  return m;
}

TEST(ResponseSeries, TheModesRCannotSeeAreLeftOutAndChangeNothing) {
  ModalDeploymentOptions o;
  o.end_time_s = 0.5;
  o.step_s = 1e-3;
  const SampledDrive drive = sampleDrive(quickDrive(), o);
  for (const bool gravity : {false, true}) {
    SCOPED_TRACE(gravity ? "with gravity" : "without gravity");
    const ModalModel m = modelWithHiddenModes(0.3, 0.6, gravity);
    EXPECT_EQ(modesInRelativeAcceleration(m, drive), (std::vector<int>{0, 2, 3, 5}));
    const std::vector<double> all = relativeAccelerationSeriesOfAll(m, drive, o);
    const std::vector<double> seen = relativeAccelerationSeries(m, drive, o);
    ASSERT_EQ(all.size(), seen.size());
    // The hidden modes' share is ψ_z·η̈ ~ 1e-14 × 1e-14 × forcing: far below round-off of r.
    const double scale = largest(all);
    for (std::size_t n = 0; n < all.size(); ++n) ASSERT_NEAR(seen[n], all[n], 1e-14 * scale) << n;
  }
  // A mode r sees, however weakly above the share, is kept; so is one with a non-finite bound.
  ModalModel weak = modelWithHiddenModes(0.3, 0.6, false);
  weak.end_rotation(2, 1) = 1e-4;
  weak.rotation_participation[1] = 1e-4;  // |ψ_z Γ| ~ 1e-8 of the others': above the share
  EXPECT_EQ(modesInRelativeAcceleration(weak, drive), (std::vector<int>{0, 1, 2, 3, 5}));
  weak.damping_ratio[4] = 0.0;  // undamped: no finite gain bound
  weak.end_rotation(2, 4) = 1e-300;
  EXPECT_EQ(modesInRelativeAcceleration(weak, drive).size(), 6u);
}

TEST(ResponseSeries, ModelsSteppedTogetherGiveEachModelsOwnSeries) {
  ModalDeploymentOptions o;
  o.end_time_s = 0.5;
  o.step_s = 1e-3;
  const SampledDrive drive = sampleDrive(quickDrive(), o);
  std::vector<ModalModel> models;
  for (int i = 0; i < 70; ++i)  // more than one pass of 64
    models.push_back(modelWithHiddenModes(0.01 * i, 1.0 - 0.013 * i, false));
  std::vector<const ModalModel*> pointers;
  for (const ModalModel& m : models) pointers.push_back(&m);
  const std::vector<std::vector<double>> together =
      relativeAccelerationSeriesTogether(pointers, drive, o);
  ASSERT_EQ(together.size(), models.size());
  std::vector<std::vector<double>> alone;
  for (const ModalModel& m : models) alone.push_back(relativeAccelerationSeries(m, drive, o));
  for (std::size_t j = 0; j < models.size(); ++j) {
    ASSERT_EQ(together[j].size(), alone[j].size());
    // Each mode's arithmetic does not depend on its neighbours; only the lane of its pack may.
    const double scale = largest(alone[j]);
    for (std::size_t n = 0; n < alone[j].size(); ++n)
      ASSERT_NEAR(together[j][n], alone[j][n], 1e-14 * scale) << "model " << j << " sample " << n;
  }
  // The NRMSE against references, without forming the series: each against its neighbour's.
  std::vector<const std::vector<double>*> references;
  for (std::size_t j = 0; j < models.size(); ++j) references.push_back(&alone[(j + 1) % models.size()]);
  const std::vector<double> nrmse = responseNrmseTogether(pointers, references, drive, o);
  for (std::size_t j = 0; j < models.size(); ++j) {
    const double expected = responseNrmse(*references[j], alone[j]);
    EXPECT_GT(expected, 1e-4);
    EXPECT_NEAR(nrmse[j], expected, 1e-12 * expected) << j;
  }
}

TEST(ResponseSeries, ModelsThatCannotShareAPassAreDeployedAlone) {
  // Different θ₀ with gravity (the forcing's rotation differs), and the Coriolis coupling (modes
  // coupled): one by one, the same values.
  ModalDeploymentOptions o;
  o.end_time_s = 0.4;
  o.step_s = 1e-3;
  const SampledDrive drive = sampleDrive(quickDrive(), o);
  ModalModel a = modelWithHiddenModes(0.2, 0.2, true), b = modelWithHiddenModes(0.7, 0.4, true);
  b.reference_angle_rad = 0.3;
  const std::vector<std::vector<double>> together =
      relativeAccelerationSeriesTogether({&a, &b}, drive, o);
  EXPECT_EQ(together[0], relativeAccelerationSeries(a, drive, o));
  EXPECT_EQ(together[1], relativeAccelerationSeries(b, drive, o));
  o.coriolis_coupling = true;
  const std::vector<std::vector<double>> coupled =
      relativeAccelerationSeriesTogether({&a, &a}, drive, o);
  EXPECT_EQ(coupled[0], relativeAccelerationSeriesOfAll(a, drive, o));
  EXPECT_EQ(coupled[1], coupled[0]);
  EXPECT_THROW(responseNrmseTogether({&a}, {}, drive, o), InputError);
}

TEST(ResponseSeries, SelectModesSlicesEveryPerModeField) {
  const ModalModel m = testing::randomBilinearModel(5, 7).value(0.4, 0.9);
  const ModalModel s = selectModes(m, {3, 1});
  ASSERT_EQ(s.modeCount(), 2);
  EXPECT_NO_THROW(s.validate());
  EXPECT_EQ(s.omega_rad_s[0], m.omega_rad_s[3]);
  EXPECT_EQ(s.damping_ratio[1], m.damping_ratio[1]);
  EXPECT_EQ(s.rotation_participation[0], m.rotation_participation[3]);
  EXPECT_EQ(s.centrifugal_participation[1], m.centrifugal_participation[1]);
  EXPECT_EQ(s.end_rotation.col(0), m.end_rotation.col(3));
  EXPECT_EQ(s.end_translation.col(1), m.end_translation.col(1));
  EXPECT_EQ(s.momentum_participation.col(0), m.momentum_participation.col(3));
  EXPECT_EQ(s.coriolis(0, 1), m.coriolis(3, 1));
  EXPECT_EQ(s.coriolis(1, 0), m.coriolis(1, 3));
  EXPECT_EQ(s.inertia_z_kg_m2, m.inertia_z_kg_m2);
  EXPECT_EQ(s.end_position_m, m.end_position_m);
  EXPECT_THROW(selectModes(m, {5}), InputError);
}

}  // namespace
}  // namespace mastrom::rom
