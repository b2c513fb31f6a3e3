// Radial-basis interpolation over scattered samples (rom/interpolation/rbf_weights.hpp, method
// "rbf" of rom/interpolation/tracked_interpolation.hpp), Rippa's leave-one-out (against brute
// force), and scattered databases in files (rom/database/database_io.hpp).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "rom/database/database_io.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/interpolation/rbf_weights.hpp"
#include "rom/interpolation/tracked_interpolation.hpp"
#include "rom/offline/space_filling.hpp"
#include "rom_fixtures.hpp"

namespace mastrom::rom {
namespace {

namespace fs = std::filesystem;

/// A box of two positive axes (log coordinates) and one axis through zero (linear coordinates).
std::vector<ParameterAxis> mixedBox() {
  return {{"interface.thickness", {1e-3, 2e-3}},
          {"module.mass", {0.4, 0.6}},
          {"modes.angle_deg", {-10.0, 30.0}}};
}

/// n Halton points of the box (index 1 on: 0 is a corner).
std::vector<std::vector<double>> haltonPoints(const std::vector<ParameterAxis>& axes, int n,
                                              long skip = 1) {
  std::vector<std::vector<double>> points;
  for (int i = 0; i < n; ++i)
    points.push_back(boxPoint(axes, haltonPoint(skip + i, static_cast<int>(axes.size()))));
  return points;
}

double interpolate(const RadialBasisWeights& rbf, const std::vector<double>& values,
                   const std::vector<double>& x) {
  double s = 0.0;
  for (const GridWeight& w : rbf.weights(x)) s += w.weight * values[static_cast<std::size_t>(w.sample)];
  return s;
}

TEST(BoxCoordinates, AreLogarithmicOnPositiveAxesAndRoundTrip) {
  const std::vector<ParameterAxis> axes = mixedBox();
  const Eigen::VectorXd u = boxCoordinates(axes, {std::sqrt(2.0) * 1e-3, 0.6, 10.0});
  EXPECT_NEAR(u[0], 0.5, 1e-15);  // the geometric mean of [1, 2] mm
  EXPECT_EQ(u[1], 1.0);
  EXPECT_NEAR(u[2], 0.5, 1e-15);
  const std::vector<double> back = boxPoint(axes, u);
  EXPECT_NEAR(back[0], std::sqrt(2.0) * 1e-3, 1e-18);
  EXPECT_EQ(back[1], 0.6);
  EXPECT_THROW(boxCoordinates(axes, {-1e-3, 0.5, 0.0}), InputError);
  EXPECT_THROW(boxCoordinates(axes, {1e-3, 0.5}), InputError);
}

TEST(RadialBasisWeights, AreExactAtTheSamplesAndReproduceLinearFunctions) {
  const std::vector<ParameterAxis> axes = mixedBox();
  const std::vector<std::vector<double>> points = haltonPoints(axes, 20);
  const RadialBasisWeights rbf(axes, points);
  // f linear in the box coordinates: reproduced everywhere, also outside the box.
  const auto f = [&axes](const std::vector<double>& x) {
    const Eigen::VectorXd u = boxCoordinates(axes, x);
    return 1.5 - 2.0 * u[0] + 0.7 * u[1] + 3.0 * u[2];
  };
  std::vector<double> values;
  for (const std::vector<double>& x : points) values.push_back(f(x));
  for (const std::vector<double>& x : haltonPoints(axes, 50, 1000)) {
    EXPECT_NEAR(interpolate(rbf, values, x), f(x), 1e-12);
    double sum = 0.0;
    for (const GridWeight& w : rbf.weights(x)) sum += w.weight;
    EXPECT_NEAR(sum, 1.0, 1e-12);
  }
  EXPECT_NEAR(interpolate(rbf, values, {3e-3, 0.3, 40.0}), f({3e-3, 0.3, 40.0}), 1e-12);
  // At a sample: that sample alone, and the power function vanishes.
  for (std::size_t s = 0; s < points.size(); ++s) {
    const std::vector<GridWeight> w = rbf.weights(points[s]);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0].sample, static_cast<int>(s));
    EXPECT_EQ(w[0].weight, 1.0);
    EXPECT_LT(rbf.powerFunction(points[s]), 1e-6);
  }
  // The batched power function is the pointwise one.
  const std::vector<std::vector<double>> some = haltonPoints(axes, 7, 300);
  const Eigen::VectorXd batched = rbf.powerFunctions(some);
  for (std::size_t j = 0; j < some.size(); ++j)
    EXPECT_NEAR(batched[static_cast<Eigen::Index>(j)], rbf.powerFunction(some[j]),
                1e-12 * (1.0 + rbf.powerFunction(some[j])));
  // A hair away from a sample the general weights give the same (the system is well posed).
  std::vector<double> near = points[3];
  near[1] *= 1.0 + 1e-13;
  EXPECT_NEAR(interpolate(rbf, values, near), values[3], 1e-10);
}

TEST(RadialBasisWeights, AQuadraticTailReproducesQuadratics) {
  const std::vector<ParameterAxis> axes = mixedBox();
  const std::vector<std::vector<double>> points = haltonPoints(axes, 25);  // ≥ 10 + 1 needed
  const RadialBasisWeights rbf(axes, points, 2);
  const auto f = [&axes](const std::vector<double>& x) {
    const Eigen::VectorXd u = boxCoordinates(axes, x);
    return 1.0 + u[0] - 2.0 * u[1] * u[2] + 0.5 * u[0] * u[0] + 3.0 * u[2] * u[2];
  };
  std::vector<double> values;
  for (const std::vector<double>& x : points) values.push_back(f(x));
  for (const std::vector<double>& x : haltonPoints(axes, 20, 700))
    EXPECT_NEAR(interpolate(rbf, values, x), f(x), 1e-11);
  // The linear tail does not reproduce them; too few samples for the quadratic one are refused.
  const RadialBasisWeights linear(axes, points);
  double worst = 0.0;
  for (const std::vector<double>& x : haltonPoints(axes, 20, 700))
    worst = std::max(worst, std::abs(interpolate(linear, values, x) - f(x)));
  EXPECT_GT(worst, 1e-4);
  EXPECT_THROW(RadialBasisWeights(axes, haltonPoints(axes, 10), 2), InputError);
}

TEST(RadialBasisWeights, ConvergeOnASmoothFunctionAsPointsAreAdded) {
  // f smooth (not in the spline's span) on two log axes; the largest error over 400 test points
  // for 16, 64 and 256 Halton samples (fill distance halving each time). The polyharmonic spline
  // r³ converges like h^{3/2} in its native space and faster for smooth f away from the boundary
  // [Wen05, §11]; we require at least order 1.5 per halving, i.e. a ratio ≤ 2^{−1.5} ≈ 0.35.
  const std::vector<ParameterAxis> axes{{"interface.thickness", {1e-3, 2e-3}},
                                        {"module.mass", {0.4, 0.6}}};
  const auto f = [&axes](const std::vector<double>& x) {
    const Eigen::VectorXd u = boxCoordinates(axes, x);
    return std::exp(u[0]) * std::sin(2.0 * u[1]) + u[0] * u[0];
  };
  const std::vector<std::vector<double>> test = haltonPoints(axes, 400, 5000);
  std::vector<double> errors;
  for (const int n : {16, 64, 256}) {
    const std::vector<std::vector<double>> points = haltonPoints(axes, n);
    const RadialBasisWeights rbf(axes, points);
    std::vector<double> values;
    for (const std::vector<double>& x : points) values.push_back(f(x));
    double e = 0.0;
    for (const std::vector<double>& x : test)
      e = std::max(e, std::abs(interpolate(rbf, values, x) - f(x)));
    errors.push_back(e);
  }
  std::printf("[ measured ] rbf max error, 16 / 64 / 256 samples: %.3g / %.3g / %.3g\n",
              errors[0], errors[1], errors[2]);
  EXPECT_LT(errors[1], 0.35 * errors[0]);
  EXPECT_LT(errors[2], 0.35 * errors[1]);
}

TEST(RadialBasisWeights, RippaLeaveOneOutMatchesBruteForce) {
  const std::vector<ParameterAxis> axes = mixedBox();
  const std::vector<std::vector<double>> points = haltonPoints(axes, 15);
  const RadialBasisWeights rbf(axes, points);
  std::mt19937 rng(5);
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::MatrixXd data =
      Eigen::MatrixXd::NullaryExpr(15, 3, [&]() { return normal(rng); });
  const Eigen::MatrixXd errors = rbf.leaveOneOutErrors(data);
  for (int k = 0; k < 15; ++k) {
    std::vector<std::vector<double>> others;
    std::vector<int> index;
    for (int s = 0; s < 15; ++s)
      if (s != k) {
        others.push_back(points[static_cast<std::size_t>(s)]);
        index.push_back(s);
      }
    const RadialBasisWeights without(axes, others);
    for (int c = 0; c < 3; ++c) {
      double s = 0.0;
      for (const GridWeight& w : without.weights(points[static_cast<std::size_t>(k)]))
        s += w.weight * data(index[static_cast<std::size_t>(w.sample)], c);
      EXPECT_NEAR(errors(k, c), data(k, c) - s, 1e-9 * (1.0 + std::abs(data(k, c))));
    }
    // P₋ₖ(x_k) = 1/√(M⁻¹)_kk.
    EXPECT_NEAR(rbf.leaveOneOutPower(k), without.powerFunction(points[static_cast<std::size_t>(k)]),
                1e-7 * rbf.leaveOneOutPower(k));
  }
}

TEST(RadialBasisWeights, RefuseSamplesThatDoNotDetermineThem) {
  const std::vector<ParameterAxis> axes{{"interface.thickness", {1e-3, 2e-3}},
                                        {"module.mass", {0.4, 0.6}}};
  // Too few (p + 2 = 4 needed), coincident, and all on one line.
  EXPECT_THROW(RadialBasisWeights(axes, {{1e-3, 0.4}, {2e-3, 0.6}, {1.5e-3, 0.4}}), InputError);
  EXPECT_THROW(
      RadialBasisWeights(axes, {{1e-3, 0.4}, {2e-3, 0.6}, {1.5e-3, 0.4}, {1e-3, 0.4}}),
      InputError);
  EXPECT_THROW(
      RadialBasisWeights(axes, {{1e-3, 0.5}, {1.2e-3, 0.5}, {1.5e-3, 0.5}, {2e-3, 0.5}}),
      InputError);
}

/// A scattered database whose features are linear in the box coordinates (log ω too), every
/// sample's modes scrambled as a real build would leave them.
RomDatabase linearScatteredDatabase(int samples) {
  const testing::BilinearModel b = [] {
    testing::BilinearModel m = testing::randomBilinearModel(4, 11);
    m.coefficients.col(3).setZero();  // no x·y term
    return m;
  }();
  RomDatabase db = testing::bilinearDatabase(b, {1e-3, 2e-3}, {0.4, 0.6}, 3);
  db.layout = SampleLayout::Scattered;
  db.samples.clear();
  std::mt19937 rng(9);
  for (const std::vector<double>& x : haltonPoints(db.axes, samples)) {
    const Eigen::VectorXd u = boxCoordinates(db.axes, x);
    ModalModel m = b.value(u[0], u[1]);
    for (int j = 0; j < b.modes; ++j)
      m.omega_rad_s[j] = 100.0 * (j + 1) * std::exp(0.3 * u[0] - 0.1 * u[1]);
    std::vector<int> perm{0, 1, 2, 3};
    std::shuffle(perm.begin(), perm.end(), rng);
    std::vector<int> sign;
    for (int j = 0; j < b.modes; ++j) sign.push_back(rng() % 2 ? 1 : -1);
    RomSample s = testing::scrambledSample(m, perm, sign);
    s.parameters = x;
    db.samples.push_back(std::move(s));
  }
  db.reference_sample = 0;
  db.default_method = InterpolationMethod::Rbf;
  return db;
}

TEST(RbfInterpolation, UndoesTheTrackingAndIsExactForLinearFeatures) {
  const RomDatabase db = linearScatteredDatabase(12);
  const std::unique_ptr<ModalInterpolator> rbf = makeInterpolator(db, InterpolationMethod::Rbf);
  const std::vector<double> x{1.37e-3, 0.47};
  const Eigen::VectorXd u = boxCoordinates(db.axes, x);
  const ModalModel m = rbf->evaluate(x);
  for (int j = 0; j < 4; ++j)
    EXPECT_NEAR(m.omega_rad_s[j], 100.0 * (j + 1) * std::exp(0.3 * u[0] - 0.1 * u[1]),
                1e-10 * m.omega_rad_s[j]);
  testing::BilinearModel b = testing::randomBilinearModel(4, 11);
  b.coefficients.col(3).setZero();
  const ModalModel expected = b.value(u[0], u[1]);
  EXPECT_LE((m.rotation_participation - expected.rotation_participation).cwiseAbs().maxCoeff(),
            1e-10);
  EXPECT_LE((m.end_rotation - expected.end_rotation).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_LE((m.coriolis - expected.coriolis).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_NEAR(m.inertia_z_kg_m2, expected.inertia_z_kg_m2, 1e-12);
  // The grid methods refuse scattered samples, naming the way out.
  try {
    makeInterpolator(db, InterpolationMethod::Cubic);
    ADD_FAILURE() << "cubic accepted scattered samples";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("methods that work for it: rbf; choose one with --method"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(makeInterpolator(db, InterpolationMethod::Manifold), InputError);
  EXPECT_THROW(makeInterpolator(db, InterpolationMethod::Tracked), InputError);
}

TEST(RbfInterpolation, ReproducesEveryGridSampleAsTheGridMethodDoes) {
  // On a 3 × 3 grid the rbf method takes the grid's samples as scattered points: at each one the
  // sample itself, tracking undone, exactly as the multilinear method gives it.
  const testing::BilinearModel b = testing::randomBilinearModel(3, 4);
  const RomDatabase db =
      testing::bilinearDatabase(b, {1e-3, 1.5e-3, 2e-3}, {0.4, 0.5, 0.6}, 8);
  const std::unique_ptr<ModalInterpolator> rbf = makeInterpolator(db, InterpolationMethod::Rbf);
  const std::unique_ptr<ModalInterpolator> tracked =
      makeInterpolator(db, InterpolationMethod::Tracked);
  for (const RomSample& s : db.samples) {
    const ModalModel a = rbf->evaluate(s.parameters), c = tracked->evaluate(s.parameters);
    EXPECT_LE((a.omega_rad_s - c.omega_rad_s).cwiseAbs().maxCoeff(), 1e-12 * c.omega_rad_s.norm());
    EXPECT_LE((a.end_rotation - c.end_rotation).cwiseAbs().maxCoeff(), 1e-14);
  }
}

class ScatteredDatabaseFile : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("mastrom_rom_scattered_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    path_ = (dir_ / "db.h5").string();
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
  std::string path_;
};

TEST_F(ScatteredDatabaseFile, RoundTripsItsLayoutAndPoints) {
  const RomDatabase db = linearScatteredDatabase(9);
  writeDatabase(path_, db);
  const RomDatabase back = readDatabase(path_);
  EXPECT_EQ(back.layout, SampleLayout::Scattered);
  ASSERT_EQ(back.samples.size(), 9u);
  for (std::size_t s = 0; s < 9; ++s) EXPECT_EQ(back.samples[s].parameters, db.samples[s].parameters);
  EXPECT_EQ(databaseChecksum(back), databaseChecksum(db));
  EXPECT_EQ(back.default_method, InterpolationMethod::Rbf);
  // The layout is part of the content: the same data as a "grid" would be another checksum.
  RomDatabase relabelled = db;
  relabelled.layout = SampleLayout::Grid;
  relabelled.axes = {{"interface.thickness", {1e-3, 1.1e-3, 1.2e-3}},
                     {"module.mass", {0.4, 0.5, 0.6}}};
  EXPECT_NE(databaseChecksum(relabelled), databaseChecksum(db));
}

TEST_F(ScatteredDatabaseFile, AGridFileWithoutALayoutIsAGrid) {
  // Files written before scattered layouts carry no layout attribute and the same checksum.
  const RomDatabase grid = testing::bilinearDatabase(testing::randomBilinearModel(3, 2),
                                                     {1e-3, 2e-3}, {0.4, 0.6}, 1);
  writeDatabase(path_, grid);
  {
    h5::File f = h5::File::open(path_, h5::OpenMode::ReadWrite);
    ASSERT_GE(H5Adelete(f.id(), "layout"), 0);
    f.close();
  }
  const RomDatabase back = readDatabase(path_);
  EXPECT_EQ(back.layout, SampleLayout::Grid);
  EXPECT_EQ(databaseChecksum(back), databaseChecksum(grid));
}

TEST_F(ScatteredDatabaseFile, WriterRefusesAScatteredAxisWithoutARange) {
  RomDatabase db = linearScatteredDatabase(9);
  db.axes[0].values = {1e-3, 1.5e-3, 2e-3};
  EXPECT_THROW(writeDatabase(path_, db), InputError);
  EXPECT_FALSE(fs::exists(path_));
}

}  // namespace
}  // namespace mastrom::rom
