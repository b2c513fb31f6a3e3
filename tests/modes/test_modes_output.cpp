// Output of the modal analysis: the /modes HDF5 layout (modes/modes_file.hpp; docs/user_guide.md
// §5) written and read back, refused when non-finite, and the XDMF + HDF5 pair for ParaView
// (modes/xdmf_writer.hpp) checked for well-formed XML whose every referenced dataset exists with
// the declared dimensions.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/error.hpp"
#include "common/version.hpp"
#include "modes/modal_analysis.hpp"
#include "modes/modes_file.hpp"
#include "modes/xdmf_writer.hpp"
#include "tests/modes/mast_fixtures.hpp"
#include "tests/modes/xdmf_check.hpp"

namespace mastrom::modes {
namespace {

namespace fs = std::filesystem;

/// A fresh directory per test under the build tree.
fs::path scratchDirectory(const std::string& name) {
  const fs::path dir = fs::path(MASTROM_BINARY_DIR) / "test_scratch" / "modes" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

struct SmallMastModes {
  fullorder::MastModel model;
  Linearization lin;
  ModalAnalysis analysis;
};

SmallMastModes smallMastModes(double angle_rad) {
  SmallMastModes out{buildLockedMast(fixtures::mastParameters(3, 1, 6), angle_rad), {}, {}};
  out.lin = linearizeMast(out.model);
  EigenSolverOptions o;
  o.backend = EigenBackendKind::Dense;
  o.count = 7;
  out.analysis = analyzeMast(out.model, out.lin, o);
  return out;
}

TEST(ModesFile, WritesTheDesignLayoutAndReadsItBack) {
  const SmallMastModes m = smallMastModes(0.25);
  ASSERT_TRUE(m.analysis.eigen.ok());
  const ModesData data = modesData(m.analysis, m.lin, 0.25);
  const std::string path = (scratchDirectory("roundtrip") / "modes.h5").string();
  writeModesFile(path, data, "[modes]\ncount = 7\n", 1.5);

  const ModesFile back = readModesFile(path);
  EXPECT_EQ(back.source, "modes");
  EXPECT_EQ(back.mastrom_version, std::string(kVersion));
  EXPECT_EQ(back.config_toml, "[modes]\ncount = 7\n");
  EXPECT_EQ(back.wall_time_s, 1.5);
  const ModesData& d = back.modes;
  EXPECT_EQ(d.angle_rad, 0.25);
  EXPECT_EQ(d.backend, "dense");
  EXPECT_EQ(d.status, "converged");
  EXPECT_EQ(d.requested, 7);
  EXPECT_EQ(d.frequency_hz, m.analysis.eigen.frequencies_hz);
  EXPECT_EQ(d.damping_ratio, m.analysis.damping_ratio);
  EXPECT_EQ(d.participation, m.analysis.participation);
  EXPECT_EQ(d.effective_mass_fraction, m.analysis.effective_mass_fraction);
  EXPECT_EQ(d.shapes, Eigen::MatrixXd(m.analysis.eigen.modes.transpose()));
  EXPECT_EQ(d.end_rotation, m.analysis.end_rotation);
  EXPECT_EQ(d.coriolis, m.analysis.coriolis);
  EXPECT_EQ(d.reference, m.lin.q);
  EXPECT_EQ(d.labels, m.analysis.labels);
  EXPECT_EQ(d.rotational_inertia_kg_m2, m.analysis.rotational_inertia_kg_m2);
  for (int k = 1; k < d.modeCount(); ++k) EXPECT_LE(d.frequency_hz(k - 1), d.frequency_hz(k));

  // docs/user_guide.md §5: every dataset carries units.
  const h5::File file = h5::File::open(path, h5::OpenMode::ReadOnly);
  for (const char* dataset :
       {"/modes/frequency_hz", "/modes/damping_ratio", "/modes/participation",
        "/modes/effective_mass_fraction", "/modes/shapes", "/modes/end_rotation",
        "/modes/angle_rad", "/modes/labels", "/modes/coriolis", "/modes/reference"})
    EXPECT_FALSE(file.readUnits(dataset).empty()) << dataset;
  EXPECT_EQ(file.readUnits("/modes/frequency_hz"), "Hz");
  EXPECT_EQ(file.readUnits("/modes/angle_rad"), "rad");
  EXPECT_EQ(file.datasetShape("/modes/shapes"),
            (std::vector<std::size_t>{7, static_cast<std::size_t>(m.model.dofCount())}));
  EXPECT_EQ(file.datasetShape("/modes/end_rotation"), (std::vector<std::size_t>{7, 3}));
}

TEST(ModesFile, NonFiniteDataAndForeignFilesAreRefused) {
  const SmallMastModes m = smallMastModes(0.0);
  ModesData data = modesData(m.analysis, m.lin, 0.0);
  data.participation(3) = std::nan("");
  const fs::path dir = scratchDirectory("refused");
  const std::string path = (dir / "modes.h5").string();
  EXPECT_THROW(writeModesFile(path, data, "", 0.0), NumericalError);
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::is_empty(dir)) << "no temporary file left behind";

  // A deployment-like file is not a modes file: the message names what is missing.
  const std::string other = (dir / "other.h5").string();
  {
    h5::File f = h5::File::create(other, h5::CreateMode::Truncate);
    f.writeDoubles("/time", {0.0, 1.0}, "s");
    f.close();
  }
  try {
    readModesFile(other);
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("/modes/frequency_hz"), std::string::npos) << e.what();
  }
}

TEST(Xdmf, ParaViewPairIsWellFormedAndReferencesExistingDatasets) {
  const SmallMastModes m = smallMastModes(0.6);
  ASSERT_TRUE(m.analysis.eigen.ok());
  const fs::path dir = scratchDirectory("xdmf");
  const std::string h5_path = (dir / "mast.h5").string();
  h5::AtomicH5Writer writer(h5_path);
  writeModes(writer.file(), modesData(m.analysis, m.lin, 0.6), "", 0.0);
  const VisualizationLayout layout =
      writeModeVisualization(writer.file(), m.model.system(), m.lin.q, m.analysis.eigen.modes, 0.1);
  writer.commit();
  const std::string xdmf = xdmfPathFor(h5_path);
  EXPECT_EQ(xdmf, (dir / "mast.xdmf").string());
  writeXdmf(xdmf, "mast.h5", layout, m.analysis.eigen.frequencies_hz, m.analysis.labels);

  EXPECT_EQ(layout.shell_cells, m.model.system().elementCount());
  EXPECT_EQ(layout.module_cells, 3);
  EXPECT_EQ(layout.module_points, 24);
  int grids = 0;
  const std::vector<std::string> problems = testing_xdmf::checkXdmf(xdmf, &grids);
  for (const std::string& p : problems) ADD_FAILURE() << p;
  EXPECT_EQ(grids, 2 * m.analysis.eigen.converged) << "shell + modules per mode";

  // Geometry: the module boxes are cubes of side d around the centroids; the largest displayed
  // displacement of every mode is 10 % of the model's bounding-box diagonal.
  const h5::File file = h5::File::open(h5_path, h5::OpenMode::ReadOnly);
  const Eigen::MatrixXd corners = file.readMatrix("/visualization/modules/points");
  const double d = m.model.parameters().module_side_m;
  for (int b = 0; b < 3; ++b) {
    const Eigen::Vector3d c0 = corners.row(8 * b).transpose(),
                          c6 = corners.row(8 * b + 6).transpose();
    EXPECT_NEAR((c6 - c0).norm(), std::sqrt(3.0) * d, 1e-12);  // space diagonal
    const Eigen::Vector3d centroid = m.lin.q.segment<3>(m.model.moduleDofOffset(b));
    EXPECT_LT((0.5 * (c0 + c6) - centroid).norm(), 1e-12);
  }
  const Eigen::MatrixXd shell = file.readMatrix("/visualization/shell/points");
  Eigen::Vector3d low =
      shell.colwise().minCoeff().transpose().cwiseMin(corners.colwise().minCoeff().transpose());
  Eigen::Vector3d high =
      shell.colwise().maxCoeff().transpose().cwiseMax(corners.colwise().maxCoeff().transpose());
  const double size = (high - low).norm();
  for (int k = 0; k < m.analysis.eigen.converged; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "mode_%03d", k + 1);
    const Eigen::MatrixXd u_shell = file.readMatrix(std::string("/visualization/shell/") + name);
    const Eigen::MatrixXd u_modules =
        file.readMatrix(std::string("/visualization/modules/") + name);
    const double largest =
        std::max(u_shell.rowwise().norm().maxCoeff(), u_modules.rowwise().norm().maxCoeff());
    EXPECT_NEAR(largest, 0.1 * size, 1e-12 * size) << name;
  }

  // A broken reference is caught by the checker (it is not vacuous).
  std::ifstream in(xdmf);
  std::stringstream text;
  text << in.rdbuf();
  std::string broken = text.str();
  broken.replace(broken.find("mode_002"), 8, "mode_999");
  const std::string broken_path = (dir / "broken.xdmf").string();
  std::ofstream(broken_path) << broken;
  EXPECT_FALSE(testing_xdmf::checkXdmf(broken_path).empty());
  std::ofstream(broken_path) << text.str().substr(0, text.str().size() / 2);
  EXPECT_FALSE(testing_xdmf::checkXdmf(broken_path).empty());
}

}  // namespace
}  // namespace mastrom::modes
