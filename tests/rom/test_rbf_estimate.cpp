// The rbf method and its estimate (rom/offline/rbf_leave_one_out.hpp) on a small real mast (Scheme 1,
// mesh 2 × 8, dense modal solves, compressed drive): on a 3 × 3 grid against the grid methods.
#include <gtest/gtest.h>

#include <random>

#include "common/error.hpp"
#include "rom/database/database_io.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/offline/database_build.hpp"
#include "rom/offline/leave_one_out.hpp"
#include "rom/offline/rbf_leave_one_out.hpp"
#include "direct_modal_solve.hpp"

namespace mastrom::rom {
namespace {

constexpr int kModes = 6;

/// NRMSE of the relative end angular acceleration of `m` against the direct modal model at `p`.
double responseErrorAt(const ModalModel& m, const RomDatabase& db, const std::vector<double>& p) {
  const Config c = testing::scheme1Config(kModes);
  const Config at = applyOverrides(c, parameterOverrides(db.axes, p));
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(c));
  const ModalDeploymentOptions deploy = deploymentOptionsFromConfig(c);
  return responseNrmse(
      relativeAccelerationSeries(testing::directModalSolve(at, kModes).modal, drive, deploy),
      relativeAccelerationSeries(m, drive, deploy));
}

/// Uniform random points of the box (seeded).
std::vector<std::vector<double>> randomPoints(const RomDatabase& db, int count) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<std::vector<double>> points(static_cast<std::size_t>(count));
  for (std::vector<double>& p : points)
    for (const ParameterAxis& a : db.axes)
      p.push_back(a.values.front() + unit(rng) * (a.values.back() - a.values.front()));
  return points;
}

TEST(RbfOnAGrid, IsAsAccurateAsTheGridMethodsBetweenSamples) {
  // 3 × 3 grid of thickness × module mass: the rbf takes the 9 samples as scattered points. At
  // random points, against the ROM of a direct modal solve, it must stay within the multilinear
  // method's error (both are second order on this grid; the spline's r³ term does better where
  // the data are smooth), and it lists the rbf estimate in the build report.
  const Config c = testing::scheme1Config(kModes);
  DatabaseBuildOptions o;
  o.axes = {parseParameterAxis("interface.thickness=0.001:0.002:3", c),
            parseParameterAxis("module.mass=0.4:0.6:3", c)};
  o.stresses = false;
  BuildReport report;
  const RomDatabase db = buildDatabase(c, o, &report);
  const auto rbf_entry =
      std::find_if(report.leave_one_out.begin(), report.leave_one_out.end(),
                   [](const LeaveOneOutResult& l) { return l.method == InterpolationMethod::Rbf; });
  ASSERT_NE(rbf_entry, report.leave_one_out.end());
  EXPECT_GT(rbf_entry->response_estimate, 0.0);
  const std::unique_ptr<ModalInterpolator> rbf = makeInterpolator(db, InterpolationMethod::Rbf);
  const std::unique_ptr<ModalInterpolator> tracked =
      makeInterpolator(db, InterpolationMethod::Tracked);
  const std::unique_ptr<ModalInterpolator> cubic = makeInterpolator(db, InterpolationMethod::Cubic);
  double worst_rbf = 0.0, worst_tracked = 0.0, worst_cubic = 0.0;
  for (const std::vector<double>& p : randomPoints(db, 4)) {
    worst_rbf = std::max(worst_rbf, responseErrorAt(rbf->evaluate(p), db, p));
    worst_tracked = std::max(worst_tracked, responseErrorAt(tracked->evaluate(p), db, p));
    worst_cubic = std::max(worst_cubic, responseErrorAt(cubic->evaluate(p), db, p));
  }
  std::printf("[ measured ] 3 x 3 grid, 4 random points: NRMSE rbf %.3g %% (estimate %.3g %%), "
              "tracked %.3g %%, cubic %.3g %%\n",
              100 * worst_rbf, 100 * rbf_entry->response_estimate, 100 * worst_tracked,
              100 * worst_cubic);
  EXPECT_LT(worst_rbf, worst_tracked);
}

}  // namespace
}  // namespace mastrom::rom
