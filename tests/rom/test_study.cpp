// Study files (rom/studies/study_definition.hpp) and the direct modal model of a study case
// (rom/offline/direct_modal_model.hpp): every shipped study loads with the cases the paper names, bad study
// files fail with one message naming the file, case and key, and the direct modal model's
// frequencies equal the modal analysis of `mastrom modes` (modes/modal_analysis.hpp, an independent
// path: its own solve and canonicalisation).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/error.hpp"
#include "fullorder/mast_config.hpp"
#include "modes/linearize.hpp"
#include "modes/modal_analysis.hpp"
#include "rom/offline/direct_modal_model.hpp"
#include "rom/studies/study_definition.hpp"

namespace mastrom::rom {
namespace {

namespace fs = std::filesystem;

std::string studiesDir() { return std::string(MASTROM_SOURCE_DIR) + "/configs/studies"; }

/// A study file in a fresh directory next to a copy-free base (absolute path to scheme1.toml).
std::string writeStudy(const std::string& name, const std::string& text) {
  const fs::path dir = fs::path(MASTROM_BINARY_DIR) / "test_study_files";
  fs::create_directories(dir);
  const fs::path p = dir / (name + ".toml");
  std::ofstream(p) << text;
  return p.string();
}

std::string base() { return std::string(MASTROM_SOURCE_DIR) + "/configs/scheme1.toml"; }

TEST(StudyDefinition, ShippedStudiesHaveThePapersCases) {
  const std::vector<std::string> names = availableStudies({studiesDir()});
  EXPECT_EQ(names, (std::vector<std::string>{"drive_laws", "inner_diameter", "materials", "schemes",
                                             "shell_thickness"}));
  const Study schemes = loadStudy(studiesDir() + "/schemes.toml", {});
  ASSERT_EQ(schemes.cases.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(schemes.cases[i].config.mast.modules, i + 2);

  const Study thickness = loadStudy(studiesDir() + "/shell_thickness.toml", {});
  ASSERT_EQ(thickness.cases.size(), 3u);
  EXPECT_DOUBLE_EQ(thickness.cases[0].config.interface.thickness_m, 0.0005);
  EXPECT_DOUBLE_EQ(thickness.cases[2].config.interface.thickness_m, 0.0015);
  EXPECT_DOUBLE_EQ(thickness.cases[1].config.interface.radius_m, 0.041);  // R kept

  // Inner diameter D at h = 2 mm: mid-surface radius R = (D + h)/2 (docs/theory.md §1).
  const Study diameter = loadStudy(studiesDir() + "/inner_diameter.toml", {});
  ASSERT_EQ(diameter.cases.size(), 3u);
  EXPECT_NEAR(diameter.cases[0].config.interface.radius_m, 0.0435, 1e-15);
  EXPECT_NEAR(diameter.cases[2].config.interface.radius_m, 0.051, 1e-15);

  const Study laws = loadStudy(studiesDir() + "/drive_laws.toml", {});
  ASSERT_EQ(laws.cases.size(), 4u);
  EXPECT_EQ(laws.cases[0].config.drive.law, DriveLawKind::Cubic);
  EXPECT_EQ(laws.cases[2].config.drive.law, DriveLawKind::Cycloidal);

  const Study materials = loadStudy(studiesDir() + "/materials.toml", {});
  ASSERT_EQ(materials.cases.size(), 2u);
  EXPECT_DOUBLE_EQ(materials.cases[1].config.material.youngs_modulus_pa, 2.5e9);
  EXPECT_DOUBLE_EQ(materials.cases[1].config.material.poisson_ratio, 0.38);
  EXPECT_DOUBLE_EQ(materials.cases[1].config.material.density_kg_m3, 1200.0);
}

TEST(StudyDefinition, CommandLineOverridesComeLast) {
  const Study s = loadStudy(studiesDir() + "/shell_thickness.toml",
                            {"simulation.end_time=1", "interface.thickness=0.003"});
  for (const StudyCase& c : s.cases) {
    EXPECT_DOUBLE_EQ(c.config.simulation.end_time_s, 1.0);
    EXPECT_DOUBLE_EQ(c.config.interface.thickness_m, 0.003);  // after the case's own set
  }
}

TEST(StudyDefinition, BadFilesFailNamingFileCaseAndKey) {
  const auto message = [](const std::string& path) -> std::string {
    try {
      loadStudy(path, {});
    } catch (const InputError& e) {
      return e.what();
    }
    return "(no error)";
  };
  const std::string b = "[study]\nbase = \"" + base() + "\"\n";
  EXPECT_NE(message(writeStudy("unknown_key", b + "[[case]]\nname = \"a\"\nsett = []\n"))
                .find("unknown key 'sett'"),
            std::string::npos);
  EXPECT_NE(message(writeStudy("duplicate", b + "[[case]]\nname = \"a\"\n[[case]]\nname = \"a\"\n"))
                .find("name 'a' is used twice"),
            std::string::npos);
  EXPECT_NE(message(writeStudy("no_cases", b)).find("no [[case]]"), std::string::npos);
  EXPECT_NE(message(writeStudy("bad_name", b + "[[case]]\nname = \"a b\"\n")).find("name = 'a b'"),
            std::string::npos);
  const std::string bad_value =
      message(writeStudy("bad_value", b + "[[case]]\nname = \"thin\"\n"
                                          "set = [\"interface.thickness=-1\"]\n"));
  EXPECT_NE(bad_value.find("case 'thin'"), std::string::npos) << bad_value;
  EXPECT_NE(bad_value.find("interface.thickness = -1"), std::string::npos) << bad_value;
  EXPECT_NE(
      message(writeStudy("no_base", "[study]\n[[case]]\nname = \"a\"\n")).find("no configuration"),
      std::string::npos);
  EXPECT_THROW(resolveStudyPath("no_such_study", {studiesDir()}), InputError);
}

// The direct modal model against `mastrom modes`' analysis of the same configuration: the same
// eigenproblem solved twice, so the frequencies agree to the eigen-solver's tolerance (1e-10
// relative residual → ω² to ≈ 1e-9). Coarse Scheme 1 mesh, dense backend (milliseconds).
TEST(DirectModalModel, FrequenciesEqualTheModalAnalysisAndPairsStayWhole) {
  Config c;
  c.mast.modules = 2;
  c.interface.elements_axial = 1;
  c.interface.elements_circumferential = 6;
  c.modes.backend = EigenBackendKind::Dense;
  const fullorder::MastModel locked =
      modes::buildLockedMast(fullorder::mastParametersFromConfig(c), c.modes.angleRad());
  const modes::Linearization lin = modes::linearizeMast(locked);
  modes::EigenSolverOptions eo;
  eo.count = 8;
  eo.backend = EigenBackendKind::Dense;
  const modes::ModalAnalysis reference = modes::analyzeMast(locked, lin, eo);
  ASSERT_TRUE(reference.eigen.ok());

  const ModalModel model = directModalModel(c, 8);
  ASSERT_GE(model.modeCount(), 8);
  for (int k = 0; k < 8; ++k)
    EXPECT_NEAR(model.omega_rad_s[k] / (2 * M_PI), reference.eigen.frequencies_hz[k],
                1e-8 * reference.eigen.frequencies_hz[k])
        << "mode " << k;

  // Asking for one mode more than a degenerate pair's first member returns the whole pair.
  // (The square modules and round shells make the y and z bending modes an exact pair.)
  const Eigen::VectorXd w2 = reference.eigen.eigenvalues_rad2_s2;
  int pair = -1;
  for (int k = 0; k + 1 < 8 && pair < 0; ++k)
    if (std::abs(w2[k + 1] - w2[k]) <= modes::kClusterTolerance * w2[k + 1]) pair = k;
  ASSERT_GE(pair, 0) << "no degenerate pair among the lowest 8 modes";
  EXPECT_EQ(directModalModel(c, pair + 1).modeCount(), pair + 2);
  // The first drive-excited mode is the first in-plane bending mode: it carries rotation about Z.
  const int b = firstExcitedMode(model);
  ASSERT_GE(b, 0);
  EXPECT_NE(model.rotation_participation[b], 0.0);
}

}  // namespace
}  // namespace mastrom::rom
