// The natural frequencies of a design from the ROM (rom/studies/design_description.hpp,
// docs/theory.md §1.7 and (4.15)): against `mastrom modes` at the same point
// (modes::solveMastModes, the function the command runs) within the database's estimate; at the
// deployed angle, not the database's θ₀, when gravity makes the modes depend on the angle; refused,
// with the reason, where the database holds no modes at the deployed angle. And the design's mass
// against the full order's assembled mass matrix.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "common/error.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/mast_model.hpp"
#include "modes/mast_modes.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/offline/database_build.hpp"
#include "rom/studies/design_screen.hpp"
#include "rom_fixtures.hpp"
#include "tests/rom/direct_modal_solve.hpp"

namespace mastrom::rom {
namespace {

constexpr int kModes = 6;

/// The column of `name` in a design screen's table.
std::size_t column(const DesignScreenTable& t, const std::string& name) {
  for (std::size_t i = 0; i < t.metric_names.size(); ++i)
    if (t.metric_names[i] == name) return i;
  ADD_FAILURE() << name << " is not a column";
  return 0;
}

/// `mastrom modes` of the configuration: its frequencies [Hz].
Eigen::VectorXd modesFrequencies(Config c) {
  c.modes.count = kModes;
  c.modes.backend = EigenBackendKind::Dense;
  return modes::solveMastModes(c).data.frequency_hz;
}

TEST(DesignFrequencies, EqualModesAtThePointWithinTheEstimate) {
  // Scheme 1 (2 × 8 mesh) over thickness × module mass, 3 × 3 samples (the default cubic method).
  const Config c = testing::scheme1Config(kModes);
  DatabaseBuildOptions o;
  o.axes = {parseParameterAxis("interface.thickness=0.001:0.002:3", c),
            parseParameterAxis("module.mass=0.4:0.6:3", c)};
  o.stresses = false;
  const RomDatabase db = buildDatabase(c, o);
  const std::unique_ptr<ModalInterpolator> interpolator = makeInterpolator(db, db.default_method);
  // Three points inside cells and one sample (1.5 mm, 0.5 kg), where every method is exact.
  const std::vector<double> h{0.00113, 0.00171, 0.00137, 0.0015};
  const std::vector<double> m{0.43, 0.47, 0.58, 0.5};
  DesignScreenOptions so;
  so.frequencies = {4, true, "--frequencies"};
  const DesignScreenTable t = screenDesigns(
      db, *interpolator, {{"interface.thickness", h, {}}, {"module.mass", m, {}}}, so);
  const std::size_t q = t.metric_names.size();
  for (std::size_t d = 0; d < h.size(); ++d) {
    const Config at = evaluationConfig(
        db, {formatOverride("interface.thickness", h[d]), formatOverride("module.mass", m[d])});
    const Eigen::VectorXd f = modesFrequencies(at);
    for (int k = 1; k <= 4; ++k) {
      const double rom = t.metrics[d * q + column(t, "frequency_" + std::to_string(k))];
      const double estimate =
          t.metrics[d * q + column(t, "frequency_" + std::to_string(k) + "_error")];
      const double error = std::abs(rom - f[k - 1]) / f[k - 1];
      std::printf(
          "[ measured ] design %zu, f%d = %.6f Hz (modes %.6f): error %.2e, estimate "
          "%.2e\n",
          d, k, rom, f[k - 1], error, estimate);
      if (d == 3) {
        // At a sample the interpolant is the sample and the power function vanishes.
        EXPECT_LT(error, 1e-10) << "f" << k;
        EXPECT_LT(estimate, 1e-10) << "f" << k;
      } else {
        EXPECT_GT(estimate, 0.0) << "design " << d << ", f" << k;
        EXPECT_LE(error, estimate) << "design " << d << ", f" << k;
      }
    }
    // The mass: (1.12) of the configuration at the point, bit for bit; the full order's assembled
    // mass matrix holds it up to the ring's geometric discretisation, which at 8 elements per ring
    // leaves the shells 5e-4 light (tests/fullorder/test_mast_mass.cpp: falls like N_circ⁻⁴).
    const double mass = t.metrics[d * q + column(t, "mass")];
    const fullorder::MastMass by_items = configuredMass(at);
    EXPECT_EQ(mass, by_items.total_kg);
    const double shells = by_items.interface_kg[0];
    const double assembled =
        fullorder::buildMast(fullorder::mastParametersFromConfig(at)).totalMass();
    EXPECT_NEAR(mass, assembled, 1e-3 * shells);
  }
}

TEST(DesignFrequencies, AreTakenAtTheDeployedAngleWhenGravityTurnsWithTheMast) {
  // Gravity in the plane of the deployment: the preload, hence the modes, depend on the angle
  // (test_angle_parameter.cpp). The database spans θ₀ = 0 … 90°; the designs stand at θ₀ = 0 and
  // deploy to Θ = 60° (drive.angle_deg, a free key), so their frequencies must be those at 60°.
  Config c = testing::scheme1Config(kModes);
  c.simulation.gravity_m_s2 = {0.0, -9.81, 0.0};
  c.interface.thickness_m = 0.0005;  // a thin wall, so that the preload shows in the frequencies
  DatabaseBuildOptions o;
  o.axes = {parseParameterAxis("modes.angle_deg=0:90:5", c)};
  o.stresses = false;
  const RomDatabase db = buildDatabase(c, o);
  const std::unique_ptr<ModalInterpolator> interpolator = makeInterpolator(db, db.default_method);
  DesignScreenOptions so;
  so.overrides = {"drive.angle_deg=60", "drive.duration=0.04", "simulation.end_time=0.05"};
  so.frequencies = {3, true, "--frequencies"};
  const DesignScreenTable t =
      screenDesigns(db, *interpolator, {{"modes.angle_deg", {0.0}, {}}}, so);
  const Eigen::VectorXd at_60 = modesFrequencies(evaluationConfig(db, {"modes.angle_deg=60.0"}));
  const Eigen::VectorXd at_0 = modesFrequencies(evaluationConfig(db, {"modes.angle_deg=0.0"}));
  for (int k = 1; k <= 3; ++k) {
    const double rom = t.metrics[column(t, "frequency_" + std::to_string(k))];
    const double estimate = t.metrics[column(t, "frequency_" + std::to_string(k) + "_error")];
    const double error = std::abs(rom - at_60[k - 1]) / at_60[k - 1];
    const double turn = std::abs(at_0[k - 1] - at_60[k - 1]) / at_60[k - 1];
    std::printf(
        "[ measured ] f%d at 60 deg = %.6f Hz (modes %.6f, at 0 deg %.6f): error %.2e, "
        "estimate %.2e, change 0 -> 60 deg %.2e\n",
        k, rom, at_60[k - 1], at_0[k - 1], error, estimate, turn);
    EXPECT_LE(error, estimate) << "f" << k;
  }
  // The test tells the angles apart: the first frequency moves by more than its estimate.
  const double turn = std::abs(at_0[0] - at_60[0]) / at_60[0];
  EXPECT_GT(turn, t.metrics[column(t, "frequency_1_error")]);
}

TEST(DesignFrequencies, RefusedWhereTheDatabaseHoldsNoModesAtTheDeployedAngle) {
  // A database at θ₀ = 0 with gravity in the plane of the deployment, deployed to 90°.
  RomDatabase db = testing::bilinearDatabase(testing::randomBilinearModel(4, 31),
                                             {1e-3, 1.5e-3, 2e-3}, {0.4, 0.6}, 3);
  Config base = parseConfigText(db.base_config_toml, "test");
  base.simulation.gravity_m_s2 = {0.0, -3.71, 0.0};
  db.base_config_toml = toToml(base);
  const std::unique_ptr<ModalInterpolator> interpolator =
      makeInterpolator(db, InterpolationMethod::Tracked);
  const std::vector<DesignColumn> columns{{"module.mass", {0.5}, {}}};
  DesignScreenOptions so;
  so.frequencies = {2, true, "--frequencies"};
  try {
    screenDesigns(db, *interpolator, columns, so);
    FAIL() << "no refusal";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("--frequencies 2: simulation.gravity has a component in the plane of the "
                        "deployment"),
              std::string::npos)
        << what;
    EXPECT_NE(what.find("only at modes.angle_deg = 0 deg, not at the deployed angle "
                        "drive.angle_deg = 90 deg"),
              std::string::npos)
        << what;
  }
  // By default the frequency columns are left out, and asking for one by name says why.
  so.frequencies = FrequencyRequest{};
  const DesignScreenTable t = screenDesigns(db, *interpolator, columns, so);
  EXPECT_EQ(t.columns.frequencies, 0);
  EXPECT_NE(t.columns.no_frequency_reason.find("in the plane of the deployment"),
            std::string::npos);
  EXPECT_THROW(metricIndex(t.columns, "frequency_1", "--pareto"), InputError);
  EXPECT_EQ(column(t, "mass"), 10u);
  // Deployed to θ₀ itself, or with gravity along the joint axis, the database's modes are those of
  // the deployed angle.
  so.frequencies = {2, true, "--frequencies"};
  so.overrides = {"drive.angle_deg=0.0001"};
  EXPECT_THROW(screenDesigns(db, *interpolator, columns, so), InputError);
  base.modes.angle_deg = 90.0;
  db.base_config_toml = toToml(base);
  so.overrides = {};
  EXPECT_EQ(screenDesigns(db, *interpolator, columns, so).columns.frequencies, 2);
  base.modes.angle_deg = 0.0;
  base.simulation.gravity_m_s2 = {0.0, 0.0, -3.71};
  db.base_config_toml = toToml(base);
  EXPECT_EQ(screenDesigns(db, *interpolator, columns, so).columns.frequencies, 2);
  // More frequencies than the database holds.
  so.frequencies = {5, true, "--frequencies"};
  EXPECT_THROW(screenDesigns(db, *interpolator, columns, so), InputError);
}

}  // namespace
}  // namespace mastrom::rom
