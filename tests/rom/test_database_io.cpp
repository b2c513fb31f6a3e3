// The ROM database file (rom/database/database_io.hpp): a bit-exact round trip, and every way a file is
// refused — missing, not HDF5, foreign, other version, missing dataset, inconsistent sizes, and a
// single changed value (the checksum).
#include <cmath>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "fullorder/results_io.hpp"
#include "rom/database/database_io.hpp"
#include "rom_fixtures.hpp"

namespace mastrom::rom {
namespace {

namespace fs = std::filesystem;

class DatabaseFile : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("mastrom_rom_io_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    db_ = testing::bilinearDatabase(testing::randomBilinearModel(4, 17), {1e-3, 1.5e-3, 2e-3},
                                    {0.4, 0.6}, 23);
    path_ = (dir_ / "db.h5").string();
    writeDatabase(path_, db_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// The IoError message of readDatabase(path), or "" when it succeeds.
  static std::string refusal(const std::string& path) {
    try {
      readDatabase(path);
    } catch (const IoError& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
  std::string path_;
  RomDatabase db_;
};

void expectSameBits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const char* what) {
  ASSERT_EQ(a.rows(), b.rows()) << what;
  ASSERT_EQ(a.cols(), b.cols()) << what;
  EXPECT_EQ(0, std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())))
      << what;
}

TEST_F(DatabaseFile, RoundTripIsBitExact) {
  const RomDatabase r = readDatabase(path_);
  EXPECT_EQ(r.base_config_toml, db_.base_config_toml);
  EXPECT_EQ(r.mastrom_version, db_.mastrom_version);
  EXPECT_EQ(r.default_method, db_.default_method);
  EXPECT_EQ(r.reference_sample, db_.reference_sample);
  EXPECT_EQ(r.modes_per_sample, db_.modes_per_sample);
  ASSERT_EQ(r.axes.size(), db_.axes.size());
  for (std::size_t a = 0; a < r.axes.size(); ++a) {
    EXPECT_EQ(r.axes[a].key, db_.axes[a].key);
    EXPECT_EQ(r.axes[a].values, db_.axes[a].values);
  }
  ASSERT_EQ(r.samples.size(), db_.samples.size());
  for (std::size_t s = 0; s < r.samples.size(); ++s) {
    const RomSample &x = r.samples[s], &y = db_.samples[s];
    const ModalModel &m = x.modal, &n = y.modal;
    EXPECT_EQ(x.parameters, y.parameters);
    expectSameBits(m.omega_rad_s, n.omega_rad_s, "omega");
    expectSameBits(m.damping_ratio, n.damping_ratio, "zeta");
    expectSameBits(m.rotation_participation, n.rotation_participation, "gamma");
    expectSameBits(m.centrifugal_participation, n.centrifugal_participation, "gamma_c");
    expectSameBits(m.end_rotation, n.end_rotation, "psi");
    expectSameBits(m.end_translation, n.end_translation, "translation");
    expectSameBits(m.momentum_participation, n.momentum_participation, "L");
    expectSameBits(m.coriolis, n.coriolis, "coriolis");
    expectSameBits(x.alignment, y.alignment, "alignment");
    EXPECT_EQ(m.inertia_z_kg_m2, n.inertia_z_kg_m2);
    EXPECT_EQ(m.total_mass_kg, n.total_mass_kg);
    EXPECT_EQ(m.centroid_m, n.centroid_m);
    EXPECT_EQ(m.end_position_m, n.end_position_m);
    EXPECT_EQ(m.reference_angle_rad, n.reference_angle_rad);
    EXPECT_EQ(m.gravity_m_s2, n.gravity_m_s2);
    EXPECT_EQ(x.tracking, y.tracking);
    EXPECT_EQ(x.tracking_sign, y.tracking_sign);
    EXPECT_EQ(x.loo_frequency_error, y.loo_frequency_error);
    EXPECT_EQ(x.loo_response_error, y.loo_response_error);
  }
  EXPECT_EQ(databaseChecksum(r), databaseChecksum(db_));
  // Self-describing: format, version, units on every dataset.
  const h5::File f = h5::File::open(path_, h5::OpenMode::ReadOnly);
  EXPECT_EQ(f.readStringAttribute("/", "format"), kDatabaseFormat);
  EXPECT_EQ(f.readIntAttribute("/", "format_version"), kDatabaseFormatVersion);
  EXPECT_EQ(f.readUnits("/samples/omega"), "rad/s");
  EXPECT_EQ(f.readUnits("/axes/0/values"), "m");
  EXPECT_EQ(f.datasetShape("/samples/end_rotation"), (std::vector<std::size_t>{6, 3, 4}));
  // The estimate: the largest leave-one-out error scaled to the full grid (the fixture's largest,
  // 0.02, sits at x index 1 of the axis {1, 1.5, 2} mm: ρ = log(4/3)/(4 log 1.5) in the log
  // coordinate, rom/offline/database_build.hpp).
  EXPECT_DOUBLE_EQ(f.readDoubleAttribute("/", "loo_frequency_error"),
                   databaseErrorEstimate(db_).first);
  EXPECT_NEAR(databaseErrorEstimate(db_).first,
              0.02 * std::log(1.5) * std::log(1.5) / (4 * std::log(1.5) * std::log(4.0 / 3.0)),
              1e-15);
}

TEST_F(DatabaseFile, ChangedValueIsReportedAsCorrupted) {
  {
    // Flip one byte of one double in /samples/omega, rewriting the dataset in place.
    h5::File f = h5::File::open(path_, h5::OpenMode::ReadWrite);
    const hid_t d = H5Dopen2(f.id(), "/samples/omega", H5P_DEFAULT);
    ASSERT_GE(d, 0);
    std::vector<double> values(24);
    ASSERT_GE(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
    unsigned char* bytes = reinterpret_cast<unsigned char*>(&values[7]);
    bytes[3] ^= 0x10;
    ASSERT_GE(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), 0);
    H5Dclose(d);
    f.close();
  }
  const std::string why = refusal(path_);
  EXPECT_NE(why.find("ROM database '" + path_ + "' is corrupted"), std::string::npos) << why;
}

TEST_F(DatabaseFile, ChangedConfigIsReportedAsCorrupted) {
  {
    h5::File f = h5::File::open(path_, h5::OpenMode::ReadWrite);
    f.setStringAttribute("/", "config", db_.base_config_toml + "\n");
    f.close();
  }
  EXPECT_NE(refusal(path_).find("is corrupted"), std::string::npos);
}

TEST_F(DatabaseFile, MissingNonHdf5AndForeignFilesAreRefused) {
  EXPECT_NE(refusal((dir_ / "absent.h5").string()).find("no such file"), std::string::npos);
  const std::string text = (dir_ / "text.h5").string();
  std::ofstream(text) << "[mast]\nmodules = 2\n";
  EXPECT_NE(refusal(text).find("not an HDF5 file"), std::string::npos) << refusal(text);
  // A deployment result: HDF5, but not a database.
  fullorder::DeploymentSeries series;
  fullorder::DeploymentSample sample;
  series.append(sample);
  sample.time_s = 1.0;
  series.append(sample);
  const std::string deployment = (dir_ / "run.h5").string();
  fullorder::writeDeploymentFile(deployment, series, fullorder::computeMetrics(series, 0.5), "",
                                 0.0, fullorder::ResultSource::Rom);
  const std::string why = refusal(deployment);
  EXPECT_NE(
      why.find("is not a mastrom ROM database (no root attribute 'format'; it is a 'rom' file)"),
      std::string::npos)
      << why;
  // Another format name.
  {
    h5::File f = h5::File::open(path_, h5::OpenMode::ReadWrite);
    f.setStringAttribute("/", "format", "someone-else");
    f.close();
  }
  EXPECT_NE(refusal(path_).find("format = 'someone-else'"), std::string::npos);
}

TEST_F(DatabaseFile, OtherVersionIsRefused) {
  {
    h5::File f = h5::File::open(path_, h5::OpenMode::ReadWrite);
    f.setIntAttribute("/", "format_version", 1);  // the previous version
    f.close();
  }
  const std::string why = refusal(path_);
  EXPECT_NE(why.find("has format_version 1, which this mastrom does not read"), std::string::npos)
      << why;
}

TEST_F(DatabaseFile, MissingDatasetIsNamed) {
  {
    h5::File f = h5::File::open(path_, h5::OpenMode::ReadWrite);
    ASSERT_GE(H5Ldelete(f.id(), "/samples/coriolis", H5P_DEFAULT), 0);
    f.close();
  }
  const std::string why = refusal(path_);
  EXPECT_NE(why.find("is incomplete: missing dataset /samples/coriolis"), std::string::npos) << why;
}

TEST_F(DatabaseFile, InconsistentSizesAreNamed) {
  {
    h5::File f = h5::File::open(path_, h5::OpenMode::ReadWrite);
    ASSERT_GE(H5Ldelete(f.id(), "/samples/omega", H5P_DEFAULT), 0);
    f.writeMatrix("/samples/omega", Eigen::MatrixXd::Ones(6, 3), "rad/s");
    f.close();
  }
  const std::string why = refusal(path_);
  EXPECT_NE(why.find("is inconsistent: /samples/omega has shape [6, 3], expected [6, 4]"),
            std::string::npos)
      << why;
}

TEST_F(DatabaseFile, WriterRefusesAnInconsistentDatabaseBeforeCreatingTheFile) {
  RomDatabase bad = db_;
  bad.samples[2].tracking.pop_back();
  const std::string out = (dir_ / "bad.h5").string();
  EXPECT_THROW(writeDatabase(out, bad), InputError);
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace mastrom::rom
