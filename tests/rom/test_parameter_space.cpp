// The ROM's parameter space (rom/database/parameter_space.hpp): --param parsing and its errors, overrides
// applied like the command line's, key roles, and the evaluation configuration.
#include <gtest/gtest.h>

#include "common/error.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom_fixtures.hpp"

namespace mastrom::rom {
namespace {

/// The InputError message of parseParameterAxis, or "" when it succeeds.
std::string paramError(const std::string& text, const Config& base = Config{}) {
  try {
    parseParameterAxis(text, base);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ParameterAxis, ParsesEvenlySpacedValuesWithExactEnds) {
  const ParameterAxis a = parseParameterAxis("interface.thickness=0.0005:0.0015:3", Config{});
  EXPECT_EQ(a.key, "interface.thickness");
  ASSERT_EQ(a.values.size(), 3u);
  EXPECT_EQ(a.values[0], 0.0005);
  EXPECT_DOUBLE_EQ(a.values[1], 0.001);
  EXPECT_EQ(a.values[2], 0.0015);
  const ParameterAxis e = parseParameterAxis(" material.youngs_modulus = 60e9:80e9:7 ", Config{});
  EXPECT_EQ(e.key, "material.youngs_modulus");
  EXPECT_EQ(e.values.back(), 80e9);
  EXPECT_EQ(parseParameterAxis("module.mass=0.4:0.6:2", Config{}).values,
            (std::vector<double>{0.4, 0.6}));
}

TEST(ParameterAxis, RejectsMalformedAndOutOfRangeInputWithOneLine) {
  const auto has = [](const std::string& message, const std::string& part) {
    return message.find(part) != std::string::npos && message.find('\n') == std::string::npos;
  };
  EXPECT_TRUE(has(paramError("interface.thickness"), "is malformed: expected KEY=LO:HI:N"));
  EXPECT_TRUE(has(paramError("interface.thickness=0.001:0.002"), "is malformed"));
  EXPECT_TRUE(has(paramError("interface.thickness=a:0.002:3"), "LO and HI must be finite numbers"));
  EXPECT_TRUE(has(paramError("interface.thickness=0.001:inf:3"), "finite"));
  EXPECT_TRUE(has(paramError("interface.thickness=0.001:0.002:1"), "N must be an integer in [2"));
  EXPECT_TRUE(has(paramError("interface.thickness=0.001:0.002:2.5"), "N must be an integer"));
  EXPECT_TRUE(has(paramError("interface.thickness=0.002:0.001:3"),
                  "LO = 0.002 must be less than HI = 0.001"));
  // The configuration's own range check decides (h < R).
  EXPECT_TRUE(has(paramError("interface.thickness=0.001:0.05:3"), "interface.thickness = 0.05"));
  EXPECT_TRUE(
      has(paramError("interface.thicknes=0.001:0.002:3"), "unknown key interface.thicknes"));
  EXPECT_TRUE(has(paramError("drive.duration=4:8:3"),
                  "drive keys are not database parameters; they are free"));
  EXPECT_TRUE(has(paramError("simulation.time_step=1e-4:1e-3:3"), "simulation keys are not"));
  EXPECT_TRUE(has(paramError("interface.elements_axial=1:4:4"), "changes the model's size"));
  EXPECT_TRUE(
      has(paramError("modes.angle_deg=0:90:3"), "only when simulation.gravity is non-zero"));
  Config gravity;
  gravity.simulation.gravity_m_s2 = {0.0, -9.81, 0.0};
  EXPECT_EQ(paramError("modes.angle_deg=0:90:3", gravity), "");
}

TEST(Overrides, BehaveLikeTheCommandLine) {
  Config base;
  const Config c = applyOverrides(
      base, {"interface.thickness=0.001", "drive.law=cubic", "interface.inner_diameter=0.09"});
  EXPECT_EQ(c.interface.thickness_m, 0.001);
  EXPECT_EQ(c.drive.law, DriveLawKind::Cubic);
  ASSERT_TRUE(c.interface.inner_diameter_m.has_value());
  EXPECT_DOUBLE_EQ(c.interface.radius_m, (0.09 + 0.001) / 2);
  EXPECT_EQ(configValue(c, "interface.inner_diameter"), 0.09);
  EXPECT_THROW(configValue(base, "interface.inner_diameter"), InputError);  // radius given
  EXPECT_THROW(configValue(base, "mast.modules"), InputError);              // integer
  EXPECT_THROW(applyOverrides(base, {"interface.thickness=-1"}), InputError);
  // Bit-exact values through formatOverride.
  const double v = 0.1 + 0.2;
  EXPECT_EQ(configValue(applyOverrides(base, {formatOverride("module.mass", v)}), "module.mass"),
            v);
}

TEST(DatabaseBaseConfig, SwitchesToTheAxisParametrisation) {
  Config base;  // radius 0.041, thickness 0.002
  const Config c = databaseBaseConfig(base, {{"interface.inner_diameter", {0.08, 0.09}}});
  ASSERT_TRUE(c.interface.inner_diameter_m.has_value());
  EXPECT_DOUBLE_EQ(*c.interface.inner_diameter_m, 0.08);
  EXPECT_DOUBLE_EQ(c.interface.radius_m, 0.041);
  EXPECT_THROW(databaseBaseConfig(base, {{"module.mass", {0.4, 0.6}}, {"module.mass", {0.4, 0.5}}}),
               InputError);
}

TEST(EvaluationConfig, AcceptsParametersAndFreeKeysOnly) {
  const RomDatabase db =
      testing::bilinearDatabase(testing::randomBilinearModel(3, 1), {1e-3, 2e-3}, {0.4, 0.6}, 1);
  const Config c = evaluationConfig(
      db, {"module.mass=0.5", "drive.law=quintic", "simulation.end_time=7", "output.step=1e-3"});
  EXPECT_EQ(parameterPoint(db, c), (std::vector<double>{1e-3, 0.5}));
  EXPECT_EQ(c.drive.law, DriveLawKind::Quintic);
  try {
    evaluationConfig(db, {"material.density=3000"});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("material.density is not a parameter of this database "
                                         "(parameters: interface.thickness, module.mass"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(evaluationConfig(db, {"simulation.gravity=[0,-9.81,0]"}), InputError);
  EXPECT_THROW(evaluationConfig(db, {"drive.law=sideways"}), InputError);
}

TEST(ItemParameters, AreDatabaseParametersReadLikeTheirSectionsKeys) {
  const ParameterAxis a = parseParameterAxis("interface.2.thickness=0.001:0.003:3", Config{});
  EXPECT_EQ(a.key, "interface.2.thickness");
  EXPECT_EQ(a.values.back(), 0.003);
  EXPECT_EQ(keyRole("module.4.mass", Config{}), KeyRole::DatabaseParameter);
  EXPECT_EQ(keyRole("module.4.centroid_offset", Config{}), KeyRole::Fixed);
  EXPECT_EQ(configKeyUnits("module.4.mass"), "kg");
  // Absent from its item's table: the value of [section]; present: the item's own.
  Config c;
  c.module.mass_kg = 0.6;
  EXPECT_EQ(configValue(c, "module.4.mass"), 0.6);
  c = applyOverrides(c, {formatOverride("module.4.mass", 1.2)});
  EXPECT_EQ(configValue(c, "module.4.mass"), 1.2);
  EXPECT_EQ(c.moduleItem(4).mass_kg, 1.2);
  EXPECT_EQ(c.moduleItem(3).mass_kg, 0.6);
  // Item numbers and keys are checked by the configuration's own rules.
  EXPECT_NE(paramError("module.5.mass=1:2:2").find("[module.5] is out of range"), std::string::npos)
      << paramError("module.5.mass=1:2:2");
  EXPECT_NE(paramError("interface.2.mass=1:2:2").find("unknown key interface.2.mass"),
            std::string::npos);
  EXPECT_NE(paramError("module.4.inertia=1:2:2").find("cannot be a database parameter"),
            std::string::npos);
}

}  // namespace
}  // namespace mastrom::rom
