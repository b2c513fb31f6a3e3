// Tests of common/config: docs/theory.md §1, docs/user_guide.md §4 defaults, files + overrides, the
// inner-diameter mapping, the toToml round trip, the shipped scheme files, and one test per
// rejected input (each checks the exception type and that the one-line message names the key and
// the offending value).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "common/config.hpp"
#include "common/error.hpp"

namespace mastrom {
namespace {

std::string writeTempFile(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "mastrom_test_config_" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(ConfigDefaults, EmptyTextGivesDesignDefaults) {
  const Config c = parseConfigText("", "empty.toml");
  EXPECT_EQ(c, Config{});

  EXPECT_EQ(c.mast.modules, 4);
  EXPECT_EQ(c.module.side_m, 0.10);
  EXPECT_EQ(c.module.mass_kg, 0.50);
  EXPECT_FALSE(c.module.inertia_kg_m2.has_value());
  EXPECT_EQ(c.interface.length_m, 0.05);
  EXPECT_EQ(c.interface.radius_m, 0.041);
  EXPECT_EQ(c.interface.thickness_m, 0.002);
  EXPECT_FALSE(c.interface.inner_diameter_m.has_value());
  EXPECT_EQ(c.interface.elements_axial, 2);
  EXPECT_EQ(c.interface.elements_circumferential, 8);
  EXPECT_EQ(c.material.youngs_modulus_pa, 70e9);
  EXPECT_EQ(c.material.poisson_ratio, 0.33);
  EXPECT_EQ(c.material.density_kg_m3, 2700.0);
  EXPECT_EQ(c.material.damping_s, 1e-5);
  EXPECT_FALSE(c.material.yield_strength_pa.has_value());
  EXPECT_EQ(c.drive.law, DriveLawKind::Trapezoidal);
  EXPECT_EQ(c.drive.angle_deg, 90.0);
  EXPECT_EQ(c.drive.duration_s, 6.1);
  EXPECT_EQ(c.drive.ramp_s, 0.1);
  EXPECT_EQ(c.simulation.end_time_s, 8.0);
  EXPECT_EQ(c.simulation.time_step_s, 1e-5);
  EXPECT_TRUE(c.simulation.adaptive);
  EXPECT_EQ(c.simulation.tolerance, 1e-5);
  EXPECT_EQ(c.simulation.min_time_step_s, 1e-6);
  EXPECT_EQ(c.simulation.max_time_step_s, 1e-3);
  EXPECT_FALSE(c.output.step_s.has_value());  // chosen from the response by the commands
  EXPECT_EQ(outputInterval(c), kFallbackOutputStepS);
  EXPECT_EQ(c.simulation.rho_inf, 0.9);
  EXPECT_EQ(c.simulation.gravity_m_s2, (std::array<double, 3>{0.0, 0.0, 0.0}));
  EXPECT_EQ(c.simulation.accelerations, AccelerationOutputKind::Index1);
  EXPECT_EQ(c.modes.count, 10);
  EXPECT_EQ(c.modes.angle_deg, 0.0);
  EXPECT_EQ(c.modes.backend, EigenBackendKind::Slepc);
  EXPECT_EQ(c.output.file, "out.h5");
  EXPECT_EQ(c.output.every, 1);
}

TEST(ConfigDefaults, SolidCubeInertiaAndRadians) {
  const Config c;
  const double expected = 0.50 * 0.10 * 0.10 / 6.0;
  for (const double i : c.module.principalInertia()) EXPECT_DOUBLE_EQ(i, expected);
  EXPECT_DOUBLE_EQ(c.drive.angleRad(), M_PI / 2);
  EXPECT_NO_THROW(validate(c));
}

TEST(ConfigLoad, FileThenOverrides) {
  const std::string path = writeTempFile("overrides.toml", R"(
[mast]
modules = 3
[interface]
thickness = 0.001
[material]
density = 2700          # an integer where a float is expected is fine
youngs_modulus = 70000000000
[drive]
law = "cubic"
)");
  const Config c =
      loadConfig(path, {"interface.thickness=0.0015", "simulation.gravity=[0, -9.81, 0]",
                        "drive.law=quintic", "modes.backend = \"dense\"", "drive.duration=6",
                        "output.file=run 1.h5", "module.inertia=[1e-3, 1e-3, 1.5e-3]"});
  EXPECT_EQ(c.mast.modules, 3);                 // file
  EXPECT_EQ(c.interface.thickness_m, 0.0015);   // override beats file
  EXPECT_EQ(c.material.density_kg_m3, 2700.0);  // integer read as float
  EXPECT_EQ(c.material.youngs_modulus_pa, 70e9);
  EXPECT_EQ(c.simulation.gravity_m_s2, (std::array<double, 3>{0.0, -9.81, 0.0}));
  EXPECT_EQ(c.drive.law, DriveLawKind::Quintic);        // bare string
  EXPECT_EQ(c.modes.backend, EigenBackendKind::Dense);  // quoted string, spaces around '='
  EXPECT_EQ(c.drive.duration_s, 6.0);
  EXPECT_EQ(c.output.file, "run 1.h5");
  ASSERT_TRUE(c.module.inertia_kg_m2.has_value());
  EXPECT_EQ((*c.module.inertia_kg_m2)[2], 1.5e-3);
  EXPECT_EQ(c.interface.radius_m, 0.041);  // untouched default
}

TEST(ConfigLoad, OverrideAddsMissingSection) {
  const std::string path = writeTempFile("empty.toml", "");
  const Config c = loadConfig(path, {"modes.count=6"});
  EXPECT_EQ(c.modes.count, 6);
}

TEST(ConfigInnerDiameter, MapsToMidSurfaceRadius) {
  // docs/theory.md §1: R = (D_in + h)/2; the paper's D_in = 85 mm with h = 0.5 mm gives R = 42.75
  // mm.
  const Config c =
      parseConfigText("[interface]\ninner_diameter = 0.085\nthickness = 0.0005\n", "t");
  ASSERT_TRUE(c.interface.inner_diameter_m.has_value());
  EXPECT_EQ(*c.interface.inner_diameter_m, 0.085);
  EXPECT_DOUBLE_EQ(c.interface.radius_m, 0.04275);
}

TEST(ConfigInnerDiameter, RadiusMovesWithOverriddenThickness) {
  const std::string path = writeTempFile("din.toml", "[interface]\ninner_diameter = 0.09\n");
  const Config c = loadConfig(path, {"interface.thickness=0.001"});
  EXPECT_DOUBLE_EQ(c.interface.radius_m, 0.0455);
}

TEST(ConfigInnerDiameter, OverrideReplacesTheFilesChoice) {
  const std::string din = writeTempFile("din2.toml", "[interface]\ninner_diameter = 0.09\n");
  const Config a = loadConfig(din, {"interface.radius=0.05"});
  EXPECT_FALSE(a.interface.inner_diameter_m.has_value());
  EXPECT_EQ(a.interface.radius_m, 0.05);

  const std::string rad = writeTempFile("rad.toml", "[interface]\nradius = 0.05\n");
  const Config b = loadConfig(rad, {"interface.inner_diameter=0.1"});
  ASSERT_TRUE(b.interface.inner_diameter_m.has_value());
  EXPECT_DOUBLE_EQ(b.interface.radius_m, 0.051);
}

TEST(ConfigInnerDiameter, BothAsOverridesIsAnError) {
  const std::string path = writeTempFile("plain.toml", "");
  try {
    loadConfig(path, {"interface.radius=0.05", "interface.inner_diameter=0.1"});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("interface.inner_diameter = 0.1"), std::string::npos)
        << e.what();
  }
}

TEST(ConfigToml, DefaultsRoundTrip) {
  const Config c;
  const std::string text = toToml(c);
  EXPECT_EQ(parseConfigText(text, "resolved.toml"), c);
  EXPECT_EQ(toToml(parseConfigText(text, "resolved.toml")), text);
}

TEST(ConfigToml, EveryFieldNonDefaultRoundTripsExactly) {
  Config c;
  c.mast.modules = 7;
  c.module.side_m = 0.1234567890123;
  c.module.mass_kg = 1.0 / 3.0;
  c.module.inertia_kg_m2 = std::array<double, 3>{1e-3, 2e-3, 2.5e-3};
  c.interface.length_m = 0.07;
  c.interface.thickness_m = 0.0005;
  c.interface.inner_diameter_m = 0.085;
  c.interface.radius_m = 0.5 * (0.085 + 0.0005);
  c.interface.elements_axial = 4;
  c.interface.elements_circumferential = 16;
  c.material.youngs_modulus_pa = 2.5e9;
  c.material.poisson_ratio = -0.2;
  c.material.density_kg_m3 = 1200;
  c.material.damping_s = 0;
  c.material.yield_strength_pa = 2.75e8;
  c.drive.law = DriveLawKind::Cycloidal;
  c.drive.angle_deg = 360;
  c.drive.duration_s = 3.3;
  c.drive.ramp_s = 7;  // ignored by the cycloidal law, so not limited to duration/2
  c.simulation.end_time_s = 1e3;
  c.simulation.time_step_s = 1e-7;
  c.simulation.adaptive = false;  // output.every > 1 is a fixed-step setting
  c.simulation.tolerance = 3.5e-4;
  c.simulation.min_time_step_s = 2e-8;
  c.simulation.max_time_step_s = 0.25;
  c.simulation.rho_inf = 0;
  c.simulation.gravity_m_s2 = {0.1, -9.80665, 1e-300};
  c.simulation.accelerations = AccelerationOutputKind::Integrator;
  c.modes.count = 40;
  c.modes.angle_deg = 45.5;
  c.modes.backend = EigenBackendKind::Arpack;
  c.output.file = "dir with space/\"quoted\"\\x\t.h5";
  c.output.every = 100;
  c.output.step_s = 0.0125;
  ASSERT_NE(c, Config{});
  const std::string text = toToml(c);
  const Config back = parseConfigText(text, "resolved.toml");
  EXPECT_EQ(back, c) << text;
  EXPECT_EQ(toToml(back), text);
}

TEST(ConfigSchemes, ShippedFilesAreThePapersThreeLayouts) {
  const std::string dir = std::string(MASTROM_SOURCE_DIR) + "/configs/";
  for (const auto& [file, modules] : std::vector<std::pair<std::string, int>>{
           {"scheme1.toml", 2}, {"scheme2.toml", 3}, {"scheme3.toml", 4}}) {
    const Config c = loadConfig(dir + file, {});
    Config expected;  // every other value is a default of docs/theory.md §1
    expected.mast.modules = modules;
    expected.output.file = c.output.file;
    EXPECT_EQ(c, expected) << file;
  }
}

// ---------------------------------------------------------------------------------------------
// Rejections: each case is a config text (or overrides on an empty file) that must throw
// InputError whose single-line message contains every listed fragment.

struct Rejection {
  std::string name;
  std::string toml;
  std::vector<std::string> overrides;
  std::vector<std::string> fragments;
};

std::ostream& operator<<(std::ostream& os, const Rejection& r) { return os << r.name; }

class ConfigRejects : public ::testing::TestWithParam<Rejection> {};

TEST_P(ConfigRejects, WithOneLineNamingKeyAndValue) {
  const Rejection& r = GetParam();
  try {
    if (r.overrides.empty()) {
      parseConfigText(r.toml, "case.toml");
    } else {
      loadConfig(writeTempFile(r.name + ".toml", r.toml), r.overrides);
    }
    FAIL() << "accepted: " << r.toml;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_EQ(msg.rfind("config: ", 0), 0u) << msg;
    for (const std::string& f : r.fragments) EXPECT_NE(msg.find(f), std::string::npos) << msg;
  }
}

// One case per line reads better as a table.
// clang-format off
const std::vector<Rejection> kRejections{
    // structure
    {"UnknownSection", "[foo]\nx = 1\n", {}, {"[foo]", "x = 1", "allowed sections: mast, module"}},
    {"UnknownKey", "[interface]\nthicknes = 0.001\n", {},
     {"interface.thicknes", "0.001", "allowed keys of [interface]", "thickness"}},
    {"TopLevelKey", "modules = 4\n", {}, {"modules", "= 4", "allowed sections"}},
    {"SectionNotATable", "mast = 4\n", {}, {"mast = 4", "table [mast]"}},
    // types
    {"StringForInteger", "[mast]\nmodules = \"four\"\n", {},
     {"mast.modules", "\"four\"", "expected an integer"}},
    {"FloatForInteger", "[mast]\nmodules = 4.0\n", {},
     {"mast.modules", "4.0", "expected an integer"}},
    {"StringForNumber", "[interface]\nthickness = \"thin\"\n", {},
     {"interface.thickness", "\"thin\"", "expected a number"}},
    {"BoolForNumber", "[material]\ndensity = true\n", {},
     {"material.density", "true", "expected a number"}},
    {"NumberForString", "[drive]\nlaw = 3\n", {}, {"drive.law", "3", "expected a string"}},
    {"IntegerOverflow", "[mast]\nmodules = 99999999999\n", {},
     {"mast.modules", "99999999999", "at most 2147483647"}},
    // non-finite
    {"NanDamping", "[material]\ndamping = nan\n", {},
     {"material.damping", "nan", "not a finite number"}},
    {"InfModulus", "[material]\nyoungs_modulus = inf\n", {},
     {"material.youngs_modulus", "inf", "not a finite number"}},
    // interface geometry
    {"ThicknessNegative", "[interface]\nthickness = -0.001\n", {},
     {"interface.thickness = -0.001 is out of range: "
      "must satisfy 0 < thickness < radius (0.041 m)"}},
    {"ThicknessZero", "[interface]\nthickness = 0\n", {}, {"interface.thickness = 0", "0 <"}},
    {"ThicknessEqualsRadius", "[interface]\nthickness = 0.041\n", {},
     {"interface.thickness = 0.041", "< radius (0.041 m)"}},
    {"ThicknessAboveRadius", "[interface]\nradius = 0.02\nthickness = 0.03\n", {},
     {"interface.thickness = 0.03", "< radius (0.02 m)"}},
    {"RadiusZero", "[interface]\nradius = 0\n", {}, {"interface.radius = 0", "radius > 0"}},
    {"InnerDiameterNegative", "[interface]\ninner_diameter = -0.085\n", {},
     {"interface.inner_diameter = -0.085", "inner_diameter > 0"}},
    {"RadiusAndInnerDiameter", "[interface]\nradius = 0.041\ninner_diameter = 0.085\n", {},
     {"interface.radius = 0.041", "interface.inner_diameter = 0.085", "both given"}},
    {"LengthZero", "[interface]\nlength = 0\n", {}, {"interface.length = 0", "length > 0"}},
    {"ElementsAxialZero", "[interface]\nelements_axial = 0\n", {},
     {"interface.elements_axial = 0", "elements_axial >= 1"}},
    {"ElementsCircumferentialTwo", "[interface]\nelements_circumferential = 2\n", {},
     {"interface.elements_circumferential = 2", ">= 3", "periodic ring"}},
    // material
    {"PoissonMinusOne", "[material]\npoisson_ratio = -1\n", {},
     {"material.poisson_ratio = -1", "-1 < poisson_ratio < 0.5"}},
    {"PoissonHalf", "[material]\npoisson_ratio = 0.5\n", {},
     {"material.poisson_ratio = 0.5", "-1 < poisson_ratio < 0.5"}},
    {"ModulusZero", "[material]\nyoungs_modulus = 0\n", {},
     {"material.youngs_modulus = 0", "youngs_modulus > 0"}},
    {"DensityNegative", "[material]\ndensity = -2700\n", {},
     {"material.density = -2700", "density > 0"}},
    {"DampingNegative", "[material]\ndamping = -1e-5\n", {},
     {"material.damping = -1e-05", "damping >= 0"}},
    {"YieldStrengthZero", "[material]\nyield_strength = 0\n", {},
     {"material.yield_strength = 0", "yield_strength > 0 (Pa)"}},
    {"YieldStrengthNegative", "[material]\nyield_strength = -2.7e8\n", {},
     {"material.yield_strength = -2.7e+08", "yield_strength > 0"}},
    {"YieldStrengthNan", "[material]\nyield_strength = nan\n", {},
     {"material.yield_strength", "nan", "not a finite number"}},
    {"YieldStrengthString", "[material]\nyield_strength = \"high\"\n", {},
     {"material.yield_strength", "expected a number"}},
    // module and mast
    {"SideZero", "[module]\nside = 0\n", {}, {"module.side = 0", "side > 0"}},
    {"MassNegative", "[module]\nmass = -0.5\n", {}, {"module.mass = -0.5", "mass > 0"}},
    {"OneModule", "[mast]\nmodules = 1\n", {}, {"mast.modules = 1", "modules >= 2"}},
    {"InertiaTriangle", "[module]\ninertia = [1, 1, 3]\n", {},
     {"module.inertia = [1, 1, 3]", "Izz = 3 > Ixx + Iyy = 2"}},
    {"InertiaNotPositive", "[module]\ninertia = [0.001, 0, 0.001]\n", {},
     {"module.inertia = [0.001, 0, 0.001]", "Iyy = 0 <= 0"}},
    {"InertiaTwoValues", "[module]\ninertia = [0.001, 0.001]\n", {},
     {"module.inertia = [0.001, 0.001]", "3 numbers"}},
    {"InertiaNan", "[module]\ninertia = [0.001, nan, 0.001]\n", {},
     {"module.inertia = [0.001, nan, 0.001]", "finite"}},
    // drive
    {"UnknownDriveLaw", "[drive]\nlaw = \"linear\"\n", {},
     {"drive.law = \"linear\"", "trapezoidal, cubic, quintic, cycloidal"}},
    {"AngleZero", "[drive]\nangle_deg = 0\n", {}, {"drive.angle_deg = 0", "0 < angle_deg <= 360"}},
    {"AngleAbove360", "[drive]\nangle_deg = 361\n", {}, {"drive.angle_deg = 361", "<= 360"}},
    {"DurationZero", "[drive]\nduration = 0\n", {}, {"drive.duration = 0", "duration > 0"}},
    {"RampZero", "[drive]\nramp = 0\n", {}, {"drive.ramp = 0", "0 < ramp <= duration/2 (3.05 s)"}},
    {"RampAboveHalfDuration", "[drive]\nramp = 3.1\n", {}, {"drive.ramp = 3.1", "(3.05 s)"}},
    // simulation
    {"EndTimeZero", "[simulation]\nend_time = 0\n", {}, {"simulation.end_time = 0", "> 0"}},
    {"TimeStepZero", "[simulation]\ntime_step = 0\n", {},
     {"simulation.time_step = 0", "0 < time_step <= end_time (8 s)"}},
    {"TimeStepAboveEndTime", "[simulation]\ntime_step = 9\n", {},
     {"simulation.time_step = 9", "<= end_time (8 s)"}},
    {"RhoInfNegative", "[simulation]\nrho_inf = -0.1\n", {},
     {"simulation.rho_inf = -0.1", "0 <= rho_inf <= 1"}},
    {"RhoInfAboveOne", "[simulation]\nrho_inf = 1.1\n", {}, {"simulation.rho_inf = 1.1", "<= 1"}},
    {"GravityTwoValues", "[simulation]\ngravity = [0, -9.81]\n", {},
     {"simulation.gravity = [0, -9.81]", "3 numbers"}},
    {"GravityScalar", "[simulation]\ngravity = -9.81\n", {},
     {"simulation.gravity = -9.81", "3 numbers"}},
    {"GravityNotFinite", "[simulation]\ngravity = [0, inf, 0]\n", {},
     {"simulation.gravity = [0, inf, 0]", "finite"}},
    {"GravityString", "[simulation]\ngravity = [0, \"down\", 0]\n", {},
     {"simulation.gravity = [0, \"down\", 0]", "3 numbers"}},
    // modes and output
    {"CountZero", "[modes]\ncount = 0\n", {}, {"modes.count = 0", "count >= 1"}},
    {"ModesAngleNegative", "[modes]\nangle_deg = -5\n", {},
     {"modes.angle_deg = -5", "0 <= angle_deg <= 360"}},
    {"UnknownAccelerationOutput", "[simulation]\naccelerations = \"filtered\"\n", {},
     {"simulation.accelerations", "filtered", "index1, integrator"}},
    {"UnknownBackend", "[modes]\nbackend = \"lapack\"\n", {},
     {"modes.backend = \"lapack\"", "slepc, arpack, dense"}},
    {"EveryZero", "[output]\nevery = 0\n", {}, {"output.every = 0", "every >= 1"}},
    {"EmptyFile", "[output]\nfile = \"\"\n", {}, {"output.file = \"\"", "non-empty"}},
    // overrides
    {"OverrideWithoutEquals", "", {"interface.thickness"},
     {"--set \"interface.thickness\"", "malformed", "section.key=value"}},
    {"OverrideWithoutSection", "", {"thickness=0.001"}, {"\"thickness=0.001\"", "malformed"}},
    {"OverrideTooDeep", "", {"a.b.c=1"}, {"\"a.b.c=1\"", "malformed"}},
    {"OverrideUnknownKey", "", {"interface.thicknes=0.001"},
     {"interface.thicknes = 0.001", "allowed keys of [interface]"}},
    {"OverrideUnknownSection", "", {"foo.bar=1"}, {"[foo]", "bar = 1", "allowed sections"}},
    {"OverrideOutOfRange", "", {"interface.thickness=-0.001"},
     {"interface.thickness = -0.001", "0 < thickness < radius"}},
    {"OverrideBadTypeBareString", "", {"interface.thickness=0.00l"},
     {"interface.thickness = \"0.00l\"", "expected a number"}},
    {"OverrideIntoNonTable", "mast = 4\n", {"mast.modules=3"}, {"mast = 4", "table [mast]"}},
    // per-item tables
    {"ModuleItemAboveCount", "[module.5]\nmass = 1.2\n", {},
     {"[module.5] is out of range", "1 <= K <= 4", "mast.modules"}},
    {"InterfaceItemAboveCount", "[interface.4]\nthickness = 0.001\n", {},
     {"[interface.4] is out of range", "1 <= K <= 3"}},
    {"ItemAboveCountAfterOverride", "[module.3]\nmass = 1.2\n", {"mast.modules=2"},
     {"[module.3] is out of range", "1 <= K <= 2"}},
    {"ItemZero", "[module.0]\nmass = 1.2\n", {},
     {"unknown key module.0 = {mass = 1.2}", "tables [module.K] for item K"}},
    {"ItemUnknownKey", "[interface.2]\ndensity = 1200\n", {},
     {"unknown key interface.2.density = 1200", "allowed keys of [interface.2]", "thickness"}},
    {"ItemOutOfRangeValue", "[interface.1]\nthickness = 0.05\n", {},
     {"interface.1.thickness = 0.05", "< radius (0.041 m)"}},
    {"ItemBadOffset", "[module.4]\ncentroid_offset = [0, 1]\n", {},
     {"module.4.centroid_offset = [0, 1]", "array of 3 numbers"}},
    {"ItemNotATable", "[module]\n3 = 1.0\n", {}, {"module.3 = 1.0", "table [module.3]"}},
    {"ItemOverrideAboveCount", "", {"module.9.mass=1.2"},
     {"[module.9] is out of range", "1 <= K <= 4"}},
    {"ItemOverrideUnknownKey", "", {"interface.2.mass=1.2"},
     {"unknown key interface.2.mass = 1.2", "allowed keys of [interface.2]"}},
    {"ItemOverrideNotANumber", "", {"module.x.mass=1.2"}, {"\"module.x.mass=1.2\"", "malformed"}},
    // drive table
    {"TableLawWithoutTable", "[drive]\nlaw = \"table\"\n", {},
     {"drive.table = \"\"", "needs the path of a CSV file"}},
};
// clang-format on

INSTANTIATE_TEST_SUITE_P(Config, ConfigRejects, ::testing::ValuesIn(kRejections),
                         [](const ::testing::TestParamInfo<Rejection>& info) {
                           return info.param.name;
                         });

TEST(ConfigRejectsSyntax, NamesFileAndLine) {
  try {
    parseConfigText("[mast]\nmodules = = 4\n", "broken.toml");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("broken.toml:2:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("syntax error"), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST(ConfigRejectsSyntax, FileErrorNamesFileAndLine) {
  const std::string path = writeTempFile("syntax.toml", "[mast]\nmodules = 4\n[drive\n");
  try {
    loadConfig(path, {});
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ":3:"), std::string::npos) << e.what();
  }
}

TEST(ConfigRejectsFile, MissingFileIsIoErrorNamingThePath) {
  const std::string path = ::testing::TempDir() + "no/such/mastrom.toml";
  try {
    loadConfig(path, {});
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find("No such file"), std::string::npos) << msg;
  }
}

TEST(ConfigRejectsFile, DirectoryIsIoError) {
  EXPECT_THROW(loadConfig(::testing::TempDir(), {}), IoError);
}

TEST(ConfigValidate, RejectsInconsistentDerivedRadius) {
  Config c;
  c.interface.inner_diameter_m = 0.085;  // radius_m left at 0.041: not (0.085 + 0.002)/2
  EXPECT_THROW(validate(c), InputError);
}

TEST(ConfigValidate, RampIsIgnoredByNonTrapezoidalLaws) {
  EXPECT_NO_THROW(parseConfigText("[drive]\nlaw = \"cubic\"\nduration = 0.1\n", "t"));
  EXPECT_THROW(parseConfigText("[drive]\nlaw = \"cubic\"\nramp = -1\n", "t"), InputError);
}

}  // namespace
}  // namespace mastrom

namespace mastrom {
namespace {

// ---------------------------------------------------------------------------------------------
// Per-item tables [module.K], [interface.K].

TEST(ConfigItems, OverrideSingleKeysOfTheirItem) {
  const Config c = parseConfigText(
      "[module]\nmass = 0.6\n"
      "[module.4]\nmass = 1.2\ninertia = [2e-3, 3e-3, 3e-3]\ncentroid_offset = [0.0, 0.02, 0.0]\n"
      "[interface.1]\nthickness = 0.0015\n",
      "items.toml");
  EXPECT_EQ(c.moduleItem(1).mass_kg, 0.6);  // no table: the defaults
  EXPECT_EQ(c.moduleItem(4).mass_kg, 1.2);
  EXPECT_EQ(c.moduleItem(4).side_m, 0.10);  // not given: [module]'s
  EXPECT_EQ(c.moduleItem(4).centroid_offset_m, (std::array<double, 3>{0.0, 0.02, 0.0}));
  EXPECT_EQ(c.moduleItem(4).principalInertia(), (std::array<double, 3>{2e-3, 3e-3, 3e-3}));
  EXPECT_EQ(c.interfaceItem(1).thickness_m, 0.0015);
  EXPECT_EQ(c.interfaceItem(2).thickness_m, 0.002);
}

TEST(ConfigItems, SetOverridesTheSameKeys) {
  const std::string path = writeTempFile("items_set.toml", "[module.4]\nmass = 1.0\n");
  const Config c =
      loadConfig(path, {"module.4.mass=1.2", "interface.1.thickness=0.0015", "module.mass=0.7"});
  EXPECT_EQ(c.moduleItem(4).mass_kg, 1.2);
  EXPECT_EQ(c.moduleItem(3).mass_kg, 0.7);  // the default moved, item 4 keeps its own
  EXPECT_EQ(c.interfaceItem(1).thickness_m, 0.0015);
  EXPECT_EQ(c, parseConfigText("[module]\nmass = 0.7\n[module.4]\nmass = 1.2\n"
                               "[interface.1]\nthickness = 0.0015\n",
                               "same.toml"));
}

TEST(ConfigItems, InnerDiameterOfAnItemMovesItsRadiusWithItsThickness) {
  const Config c = parseConfigText(
      "[interface]\ninner_diameter = 0.08\n[interface.2]\nthickness = 0.004\n", "id.toml");
  EXPECT_EQ(c.interfaceItem(1).radius_m, 0.5 * (0.08 + 0.002));
  EXPECT_EQ(c.interfaceItem(2).radius_m, 0.5 * (0.08 + 0.004));
  // An item's radius replaces the inner diameter for that item only.
  const Config d = applyConfigOverrides(c, {"interface.3.radius=0.05"});
  EXPECT_EQ(d.interfaceItem(3).radius_m, 0.05);
  EXPECT_FALSE(d.interfaceItem(3).inner_diameter_m.has_value());
  EXPECT_TRUE(d.interfaceItem(2).inner_diameter_m.has_value());
}

TEST(ConfigItems, ShippedCameraMastHasAHeavyOffAxisHeadAndAStifferBaseInterface) {
  const Config c = loadConfig(std::string(MASTROM_SOURCE_DIR) + "/configs/camera_mast.toml", {});
  EXPECT_EQ(c.mast.modules, 4);
  EXPECT_EQ(c.moduleItem(4).mass_kg, 1.2);
  EXPECT_EQ(c.moduleItem(4).centroid_offset_m, (std::array<double, 3>{0.0, 0.02, 0.0}));
  EXPECT_EQ(c.moduleItem(3).mass_kg, 0.5);
  EXPECT_EQ(c.interfaceItem(1).thickness_m, 0.003);
  EXPECT_EQ(c.interfaceItem(2).thickness_m, 0.002);
  // Its drive as the shipped motor profile, found next to the config file.
  const Config t = loadConfig(std::string(MASTROM_SOURCE_DIR) + "/configs/camera_mast.toml",
                              {"drive.law=table", "drive.table=motor_profile.csv"});
  EXPECT_EQ(t.drive.table_time_s.size(), 123u);
  EXPECT_EQ(t.drive.duration_s, 6.1);
  EXPECT_NEAR(t.drive.angle_deg, 90.0, 1e-12);
}

TEST(ConfigItems, ResolvedTomlListsEveryItemAndRoundTrips) {
  const Config c = parseConfigText(
      "[module.4]\nmass = 1.2\ncentroid_offset = [0.0, 0.02, 0.0]\n"
      "[module.1]\nside = 0.12\n[interface.1]\nthickness = 0.003\nelements_axial = 3\n",
      "items.toml");
  const std::string text = toToml(c);
  EXPECT_NE(text.find("[module.1]"), std::string::npos) << text;
  EXPECT_NE(text.find("[module.4]"), std::string::npos) << text;
  EXPECT_NE(text.find("[interface.1]"), std::string::npos) << text;
  EXPECT_EQ(text.find("[module.2]"), std::string::npos) << text;
  EXPECT_EQ(parseConfigText(text, "resolved.toml"), c);
}

// ---------------------------------------------------------------------------------------------
// Drive tables (common/drive_table.hpp).

std::string cubicProfile(int rows, double duration_s, double angle_deg) {
  std::string csv = "time_s, angle_deg\n";
  for (int i = 0; i < rows; ++i) {
    const double t = duration_s * i / (rows - 1), tau = t / duration_s;
    char line[96];
    std::snprintf(line, sizeof line, "%.17g, %.17g\n", t, angle_deg * tau * tau * (3 - 2 * tau));
    csv += line;
  }
  return csv;
}

TEST(ConfigDriveTable, RelativePathResolvesAgainstTheConfigFileAndGivesDurationAndAngle) {
  writeTempFile("profile.csv", cubicProfile(11, 2.0, 45.0));
  const std::string path =
      writeTempFile("table.toml", "[drive]\nlaw = \"table\"\ntable = \"mastrom_test_config_profile.csv\"\n");
  const Config c = loadConfig(path, {});
  EXPECT_EQ(c.drive.law, DriveLawKind::Table);
  EXPECT_EQ(c.drive.table, ::testing::TempDir() + "mastrom_test_config_profile.csv");
  EXPECT_EQ(c.drive.duration_s, 2.0);
  EXPECT_NEAR(c.drive.angle_deg, 45.0, 1e-12);
  ASSERT_EQ(c.drive.table_time_s.size(), 11u);
  EXPECT_EQ(parseConfigText(toToml(c), "resolved.toml"), c);
}

struct BadTable {
  std::string name;
  std::string csv;
  std::vector<std::string> fragments;
};
std::ostream& operator<<(std::ostream& os, const BadTable& b) { return os << b.name; }
class ConfigRejectsDriveTable : public ::testing::TestWithParam<BadTable> {};

TEST_P(ConfigRejectsDriveTable, WithOneLineNamingTheFileAndTheRule) {
  const BadTable& b = GetParam();
  const std::string csv = writeTempFile(b.name + ".csv", b.csv);
  try {
    parseConfigText("[drive]\nlaw = \"table\"\ntable = \"" + csv + "\"\n", "case.toml");
    FAIL() << "accepted: " << b.csv;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    EXPECT_NE(msg.find("drive.table = \"" + csv + "\""), std::string::npos) << msg;
    for (const std::string& f : b.fragments) EXPECT_NE(msg.find(f), std::string::npos) << msg;
  }
}

// clang-format off
const std::vector<BadTable> kBadTables{
    {"TooShort", "0, 0\n1, 45\n2, 90\n", {"has 3 rows", "at least 4"}},
    {"NotMonotonic", "0, 0\n1, 0.1\n3, 45\n2, 89.9\n4, 90\n5, 90\n",
     {"row 4: time 2 s does not exceed the previous row's 3 s", "increase strictly"}},
    {"RepeatedTime", "0, 0\n1, 0.1\n1, 45\n2, 89.9\n3, 90\n", {"row 3", "increase strictly"}},
    {"NotStartingAtZeroTime", "0.5, 0\n1, 0.1\n2, 45\n3, 90\n4, 90\n", {"first time is 0.5 s"}},
    {"NotStartingStowed", "0, 5\n1, 5.1\n2, 45\n3, 90\n4, 90\n", {"first angle is 5 deg"}},
    {"NotStartingAtRest", "0, 0\n1, 20\n2, 40\n3, 60\n4, 80\n5, 90\n5.5, 90\n6, 90\n",
     {"does not start at rest", "rate at t = 0", "25 % of its peak rate"}},
    {"NotEndingAtRest", "0, 0\n1, 0\n2, 0.1\n3, 30\n4, 60\n5, 90\n", {"does not end at rest"}},
    {"NotARow", "0, 0\n1, zero\n", {"line 2", "is not a row"}},
    {"NoDeployment", "0, 0\n1, 0\n2, 0\n3, 0\n", {"last angle is 0 deg", "0 < angle <= 360"}},
};
// clang-format on

INSTANTIATE_TEST_SUITE_P(Config, ConfigRejectsDriveTable, ::testing::ValuesIn(kBadTables),
                         [](const ::testing::TestParamInfo<BadTable>& info) {
                           return info.param.name;
                         });

TEST(ConfigDriveTable, MissingFileIsIoErrorNamingThePath) {
  EXPECT_THROW(parseConfigText("[drive]\nlaw = \"table\"\ntable = \"/nonexistent/p.csv\"\n", "x"),
               IoError);
}

}  // namespace
}  // namespace mastrom
