// Method (c) wired into the database (rom/interpolation/affine_interpolation.hpp, rom/offline/database_build.hpp,
// rom/database/database_io.hpp): a database over thickness × Young's modulus at a fixed radius carries the
// exact affine terms and evaluates them by default; they survive the file bit for bit; between the
// samples they beat interpolation against a direct modal solve; databases over other parameters
// carry none.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "common/error.hpp"
#include "rom/database/database_io.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/interpolation/affine_interpolation.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/offline/database_build.hpp"
#include "tests/rom/direct_modal_solve.hpp"

namespace mastrom::rom {
namespace {

constexpr int kModes = 6;

Config affineConfig() { return testing::scheme1Config(kModes); }

const RomDatabase& affineDatabase() {
  static const RomDatabase db = [] {
    const Config c = affineConfig();
    DatabaseBuildOptions o;
    o.axes = {parseParameterAxis("interface.thickness=0.001:0.002:3", c),
              parseParameterAxis("material.youngs_modulus=60e9:80e9:3", c)};
    return buildDatabase(c, o);
  }();
  return db;
}

TEST(DatabaseAffine, ApplicabilityFollowsTheAffineStructure) {
  Config c = affineConfig();
  const std::vector<ParameterAxis> affine = {
      parseParameterAxis("interface.thickness=0.001:0.002:3", c),
      parseParameterAxis("material.density=2000:3000:3", c)};
  EXPECT_TRUE(affineApplicable(c, affine));
  std::string why;
  EXPECT_FALSE(affineApplicable(c, {parseParameterAxis("module.mass=0.4:0.6:3", c)}, &why));
  EXPECT_NE(why.find("module.mass"), std::string::npos) << why;
  Config by_diameter = applyOverrides(c, {"interface.inner_diameter=0.08"});
  EXPECT_FALSE(affineApplicable(by_diameter, affine, &why));
  EXPECT_NE(why.find("inner diameter"), std::string::npos) << why;
  c.simulation.gravity_m_s2 = {0.0, -9.81, 0.0};
  EXPECT_FALSE(affineApplicable(c, affine, &why));
  EXPECT_NE(why.find("gravity"), std::string::npos) << why;
}

TEST(DatabaseAffine, CarriesTheTermsAndEvaluatesThemByDefault) {
  const RomDatabase& db = affineDatabase();
  ASSERT_TRUE(db.affine.has_value());
  EXPECT_EQ(db.default_method, InterpolationMethod::Affine);
  EXPECT_EQ(db.affine->thickness_min_m, 0.001);
  EXPECT_EQ(db.affine->thickness_max_m, 0.002);
  EXPECT_EQ(db.affine->youngs_modulus_min_pa, 60e9);
  EXPECT_EQ(db.affine->density_min_kg_m3, db.affine->density_max_kg_m3);  // fixed at the base's

  // Between samples: the affine model against a direct modal solve, next to the interpolants.
  // Affine errors come from the truncation to the snapshot basis alone (Rayleigh–Ritz: the
  // frequency error is quadratic in the small angle between the true modes and span V), the
  // interpolants' from the O(Δp²) interpolation error, so affine must be the most accurate — and
  // it must stay far inside the 5 % response target.
  const std::unique_ptr<ModalInterpolator> affine =
      makeInterpolator(db, InterpolationMethod::Affine);
  const std::unique_ptr<ModalInterpolator> spd =
      makeInterpolator(db, InterpolationMethod::Manifold);
  const Config base = affineConfig();
  for (const std::vector<double>& p :
       {std::vector<double>{0.00125, 65e9}, std::vector<double>{0.0018, 77e9}}) {
    const Config at = applyOverrides(base, parameterOverrides(db.axes, p));
    const ModalModel truth = testing::directModalSolve(at, kModes).modal;
    const ModalModel a = affine->evaluate(p), b = spd->evaluate(p);
    const double fa = testing::frequencyError(truth, a, kModes);
    const double fb = testing::frequencyError(truth, b, kModes);
    const double ea = testing::compareRoms(truth, a, at).nrmse_relative_acceleration;
    const double eb = testing::compareRoms(truth, b, at).nrmse_relative_acceleration;
    std::printf("[ measured ] h = %.3g mm, E = %.3g GPa: frequencies affine %.2e manifold %.2e; "
                "NRMSE affine %.2e manifold %.2e\n",
                p[0] * 1e3, p[1] * 1e-9, fa, fb, ea, eb);
    EXPECT_LE(fa, fb);
    EXPECT_LE(ea, eb);
    EXPECT_LT(ea, 0.05);
  }
  // No extrapolation: the terms are exact inside their box only.
  EXPECT_THROW(affine->evaluate({0.0025, 70e9}), InputError);
}

TEST(DatabaseAffine, TermsSurviveTheFileBitForBit) {
  const RomDatabase& db = affineDatabase();
  // The process id in the name: two runs of the suite on one machine must not share the file.
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("mastrom_test_database_affine_" + std::to_string(::getpid()) + ".h5"))
                               .string();
  writeDatabase(path, db);
  const RomDatabase back = readDatabase(path);
  std::filesystem::remove(path);
  ASSERT_TRUE(back.affine.has_value());
  EXPECT_EQ(back.default_method, InterpolationMethod::Affine);
  EXPECT_EQ(databaseChecksum(back), databaseChecksum(db));
  const std::vector<double> p = {0.0014, 72e9};
  const ModalModel a = makeInterpolator(db, InterpolationMethod::Affine)->evaluate(p);
  const ModalModel b = makeInterpolator(back, InterpolationMethod::Affine)->evaluate(p);
  for (int k = 0; k < kModes; ++k) EXPECT_EQ(a.omega_rad_s[k], b.omega_rad_s[k]);
  EXPECT_EQ(a.rotation_participation, b.rotation_participation);
}

TEST(DatabaseAffine, OtherParametersCarryNoTerms) {
  Config c = affineConfig();
  c.interface.elements_axial = 1;
  c.interface.elements_circumferential = 6;
  DatabaseBuildOptions o;
  o.axes = {parseParameterAxis("module.mass=0.4:0.6:2", c)};
  const RomDatabase db = buildDatabase(c, o);
  EXPECT_FALSE(db.affine.has_value());
  EXPECT_EQ(db.default_method, InterpolationMethod::Manifold);
  try {
    makeInterpolator(db, InterpolationMethod::Affine);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    // The refusal lists every method that works here and the option: the grid methods, not rbf
    // (2 samples of 1 parameter; its linear tail needs p + 2 = 3).
    EXPECT_NE(std::string(e.what()).find("carries no affine terms"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("methods that work for it: tracked, manifold, cubic; "
                                         "choose one with --method"),
              std::string::npos)
        << e.what();
  }
  // The list is what the factory builds: every listed method builds, every other one is refused.
  const std::vector<InterpolationMethod> listed = interpolationMethodsFor(db);
  for (const InterpolationMethod m : allInterpolationMethods()) {
    const bool is_listed = std::find(listed.begin(), listed.end(), m) != listed.end();
    if (is_listed)
      EXPECT_NO_THROW(makeInterpolator(db, m)) << toString(m);
    else
      EXPECT_THROW(makeInterpolator(db, m), InputError) << toString(m);
  }
}

}  // namespace
}  // namespace mastrom::rom
