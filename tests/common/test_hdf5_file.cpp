// Tests of common/hdf5_file.hpp: round trips of datasets and attributes, the error path of the
// checked-call helper, atomic writing and checkWritable, and common/version.hpp against CMake.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "common/hdf5_file.hpp"
#include "common/version.hpp"

namespace fs = std::filesystem;
using mastrom::IoError;
using namespace mastrom::h5;

namespace {

/// A fresh directory under the system temp dir, removed with everything in it at the end.
class TempDir {
public:
  TempDir() {
    const std::string name = "mastrom_test_h5_" + std::to_string(::getpid()) + "_" +
                             ::testing::UnitTest::GetInstance()->current_test_info()->name();
    path_ = fs::temp_directory_path() / name;
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  const fs::path& path() const { return path_; }

private:
  fs::path path_;
};

/// Expect `statement` to throw ExceptionType whose what() contains every one of `parts`.
template <typename ExceptionType, typename Statement>
void expectThrowContaining(Statement statement, const std::vector<std::string>& parts) {
  try {
    statement();
    ADD_FAILURE() << "no exception thrown";
  } catch (const ExceptionType& e) {
    const std::string message = e.what();
    for (const std::string& part : parts) {
      EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
    }
  }
}

/// Files in `dir` whose names start with `prefix`.
std::vector<std::string> filesStartingWith(const fs::path& dir, const std::string& prefix) {
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) == 0) names.push_back(name);
  }
  return names;
}

}  // namespace

TEST(Hdf5File, DatasetsRoundTripWithUnits) {
  TempDir dir;
  const std::string path = dir.file("datasets.h5");
  const std::vector<double> time{0.0, 0.5, 1.0, 1.5};
  std::vector<Eigen::Vector3d> rows{{1.0, 2.0, 3.0}, {4.0, 5.0, 6.0}};
  Eigen::MatrixXd matrix(2, 3);
  matrix << 1.5, -2.5, 3.5, 4.5, 5.5, -6.5;
  const std::vector<double> row_major{1, 2, 3, 4, 5, 6, 7, 8};  // [4, 2]
  const std::vector<int> ints{3, 1, -4, 1, 5};
  {
    File file = File::create(path, CreateMode::Exclusive);
    file.writeDoubles("/time", time, "s");
    file.writeMatrix("/end/position", rows, "m");  // creates /end on the way
    file.writeMatrix("/a/b/c/matrix", matrix, "N");
    file.writeMatrix("flat", row_major, 4, 2, "1");  // relative to the root
    file.writeInts("/solver/newton_iterations", ints, "1");
    file.writeDoubles("/empty", {}, "1");
    file.close();
  }
  const File file = File::open(path, OpenMode::ReadOnly);
  EXPECT_EQ(file.readDoubles("/time"), time);
  EXPECT_EQ(file.readUnits("/time"), "s");

  const Eigen::MatrixXd position = file.readMatrix("/end/position");
  ASSERT_EQ(position.rows(), 2);
  ASSERT_EQ(position.cols(), 3);
  EXPECT_EQ(position(0, 2), 3.0);  // row-major on disk: row i = rows[i]
  EXPECT_EQ(position(1, 0), 4.0);
  EXPECT_EQ(file.readUnits("/end/position"), "m");

  EXPECT_EQ(file.readMatrix("/a/b/c/matrix"), matrix);
  EXPECT_EQ(file.datasetShape("/flat"), (std::vector<std::size_t>{4, 2}));
  EXPECT_EQ(file.readMatrix("/flat")(3, 1), 8.0);
  EXPECT_EQ(file.readMatrix("/flat")(1, 0), 3.0);
  EXPECT_EQ(file.readInts("/solver/newton_iterations"), ints);
  EXPECT_TRUE(file.readDoubles("/empty").empty());
  // Integers read as doubles convert; doubles are refused as ints.
  EXPECT_EQ(file.readDoubles("/solver/newton_iterations")[2], -4.0);
  expectThrowContaining<IoError>([&] { file.readInts("/time"); }, {"/time", "integer"});
}

TEST(Hdf5File, ExistenceAndGroups) {
  TempDir dir;
  File file = File::create(dir.file("groups.h5"), CreateMode::Exclusive);
  EXPECT_TRUE(file.exists("/"));
  EXPECT_FALSE(file.exists("/end"));
  file.createGroup("/end");
  file.createGroup("/end");  // idempotent
  file.createGroup("/x/y/z");
  EXPECT_TRUE(file.exists("/end"));
  EXPECT_TRUE(file.exists("/x/y"));
  EXPECT_TRUE(file.exists("x/y/z/"));
  EXPECT_FALSE(file.exists("/x/q"));
  file.writeDoubles("/end/time", {1.0}, "s");
  EXPECT_TRUE(file.exists("/end/time"));
  EXPECT_FALSE(file.exists("/end/time/below"));  // a dataset has no children
  expectThrowContaining<IoError>([&] { file.createGroup("/end/time"); }, {"/end/time", "dataset"});
  expectThrowContaining<IoError>([&] { file.writeDoubles("/end/time", {2.0}, "s"); },
                                 {"/end/time", "exists already"});
  expectThrowContaining<IoError>([&] { file.writeDoubles("/no_units", {2.0}, ""); },
                                 {"/no_units", "units"});
}

TEST(Hdf5File, AttributesRoundTrip) {
  TempDir dir;
  const std::string path = dir.file("attributes.h5");
  // Longer than the 64 KB limit of HDF5's original object-header format, with UTF-8 text.
  std::string config = "[drive]\nangle_deg = 90.0  # 90°\n";
  while (config.size() < 100000) config += "# padding line of a large resolved config\n";
  {
    File file = File::create(path, CreateMode::Exclusive);
    file.writeDoubles("/time", {0.0, 1.0}, "s");
    file.createGroup("/metrics");
    file.setStringAttribute("/", "config", config);
    file.setStringAttribute("/", "empty", "");
    file.setDoubleAttribute("/metrics", "settling_time", 6.25);
    file.setDoubleAttribute("/metrics", "settling_time", 6.5);  // replaces
    file.setIntAttribute("/metrics", "settled", 1);
    file.setDoubleAttribute("/time", "scale", -1e-300);
    {
      // A variable-length string, as h5py writes str attributes, through the raw C API and handles.
      TypeHandle type(H5Tcopy(H5T_C_S1));
      ASSERT_GE(H5Tset_size(type.get(), H5T_VARIABLE), 0);
      DataspaceHandle space(H5Screate(H5S_SCALAR));
      AttributeHandle attribute(
          H5Acreate2(file.id(), "vlen", type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT));
      ASSERT_TRUE(attribute.valid());
      const char* text = "written by another tool";
      ASSERT_GE(H5Awrite(attribute.get(), type.get(), &text), 0);
    }
    file.close();
  }
  const File file = File::open(path, OpenMode::ReadOnly);
  EXPECT_EQ(file.readStringAttribute("/", "config"), config);
  EXPECT_EQ(file.readStringAttribute("/", "empty"), "");
  EXPECT_EQ(file.readStringAttribute("/", "vlen"), "written by another tool");
  EXPECT_EQ(file.readDoubleAttribute("/metrics", "settling_time"), 6.5);
  EXPECT_EQ(file.readIntAttribute("/metrics", "settled"), 1);
  EXPECT_EQ(file.readDoubleAttribute("/metrics", "settled"), 1.0);
  EXPECT_EQ(file.readDoubleAttribute("/time", "scale"), -1e-300);
  EXPECT_EQ(file.attributeNames("/metrics"),
            (std::vector<std::string>{"settled", "settling_time"}));
  EXPECT_EQ(file.attributeNames("/time"), (std::vector<std::string>{"scale", "units"}));
  EXPECT_TRUE(file.hasAttribute("/metrics", "settled"));
  EXPECT_FALSE(file.hasAttribute("/metrics", "absent"));
  EXPECT_FALSE(file.hasAttribute("/nowhere", "settled"));
  expectThrowContaining<IoError>([&] { file.readDoubleAttribute("/metrics", "absent"); },
                                 {"absent", "/metrics", "attributes.h5"});
  expectThrowContaining<IoError>([&] { file.readDoubleAttribute("/", "config"); },
                                 {"config", "numeric"});
  expectThrowContaining<IoError>([&] { file.readStringAttribute("/metrics", "settled"); },
                                 {"settled", "not a string"});
}

TEST(Hdf5File, ReadErrorsNameTheFileAndObject) {
  TempDir dir;
  const std::string path = dir.file("errors.h5");
  {
    File file = File::create(path, CreateMode::Exclusive);
    file.writeDoubles("/time", {0.0}, "s");
    file.writeMatrix("/m", std::vector<double>{1, 2}, 1, 2, "1");
    expectThrowContaining<IoError>(
        [&] { file.writeMatrix("/bad", std::vector<double>{1, 2, 3}, 2, 2, "1"); },
        {"/bad", "2 x 2"});
    file.close();
    file.close();  // closing twice is harmless
  }
  // Creating over an existing file is refused in Exclusive mode; the HDF5 message is carried along.
  expectThrowContaining<IoError>([&] { File::create(path, CreateMode::Exclusive); },
                                 {"H5Fcreate", path});
  const File file = File::open(path, OpenMode::ReadOnly);
  expectThrowContaining<IoError>([&] { file.readDoubles("/missing"); }, {"/missing", path});
  expectThrowContaining<IoError>([&] { file.readDoubles("/m"); }, {"/m", "rank 2", "expected 1"});
  expectThrowContaining<IoError>([&] { file.readMatrix("/time"); }, {"/time", "rank 1"});

  expectThrowContaining<IoError>([&] { File::open(dir.file("absent.h5"), OpenMode::ReadOnly); },
                                 {"absent.h5", "no such file"});
  const std::string text = dir.file("text.h5");
  std::ofstream(text) << "not hdf5\n";
  expectThrowContaining<IoError>([&] { File::open(text, OpenMode::ReadOnly); },
                                 {"text.h5", "not an HDF5 file"});
}

TEST(Hdf5File, CheckedTurnsNegativeReturnIntoIoError) {
  detail::initializeLibrary();
  EXPECT_EQ(checked(herr_t{0}, "H5Xnothing", "ctx"), 0);
  // A real failing call: closing an invalid identifier.
  expectThrowContaining<IoError>([] { checked(H5Dclose(H5I_INVALID_HID), "H5Dclose", "/x in 'y'"); },
                                 {"HDF5 H5Dclose failed for /x in 'y'"});
}

TEST(Hdf5File, HandlesAreMoveOnlyAndClose) {
  detail::initializeLibrary();
  DataspaceHandle a(H5Screate(H5S_SCALAR));
  ASSERT_TRUE(a.valid());
  const hid_t id = a.get();
  DataspaceHandle b(std::move(a));
  EXPECT_FALSE(a.valid());  // NOLINT(bugprone-use-after-move): checking the moved-from state
  EXPECT_EQ(b.get(), id);
  EXPECT_GT(H5Iis_valid(id), 0);
  b.reset();
  EXPECT_EQ(H5Iis_valid(id), 0);
}

TEST(AtomicH5Writer, CommitRenamesAndLeavesNoTemporaryFile) {
  TempDir dir;
  const std::string path = dir.file("result.h5");
  {
    AtomicH5Writer writer(path);
    EXPECT_EQ(writer.temporaryPath(), path + ".tmp." + std::to_string(::getpid()));
    EXPECT_TRUE(fs::exists(writer.temporaryPath()));
    EXPECT_FALSE(fs::exists(path));  // nothing under the final name while writing
    writer.file().writeDoubles("/time", {0.0, 1.0}, "s");
    writer.commit();
    EXPECT_TRUE(writer.committed());
    expectThrowContaining<IoError>([&] { writer.commit(); }, {"committed already"});
  }
  EXPECT_TRUE(fs::exists(path));
  EXPECT_EQ(filesStartingWith(dir.path(), "result.h5.tmp"), std::vector<std::string>{});
  EXPECT_EQ(File::open(path, OpenMode::ReadOnly).readDoubles("/time").size(), 2u);
}

TEST(AtomicH5Writer, DestroyedWithoutCommitLeavesNoFile) {
  TempDir dir;
  const std::string path = dir.file("aborted.h5");
  try {
    AtomicH5Writer writer(path);
    writer.file().writeDoubles("/time", {0.0, 1.0}, "s");
    throw std::runtime_error("simulated failure mid-write");
  } catch (const std::runtime_error&) {
  }
  EXPECT_FALSE(fs::exists(path));
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(AtomicH5Writer, AbortedRewriteKeepsThePreviousFile) {
  TempDir dir;
  const std::string path = dir.file("kept.h5");
  {
    AtomicH5Writer writer(path);
    writer.file().writeDoubles("/time", {1.0, 2.0, 3.0}, "s");
    writer.commit();
  }
  {
    AtomicH5Writer writer(path);  // a second run that fails before commit
    writer.file().writeDoubles("/time", {9.0}, "s");
  }
  EXPECT_EQ(File::open(path, OpenMode::ReadOnly).readDoubles("/time"),
            (std::vector<double>{1.0, 2.0, 3.0}));
  EXPECT_EQ(filesStartingWith(dir.path(), "kept.h5.tmp"), std::vector<std::string>{});
}

TEST(CheckWritable, AcceptsAWritableDirectory) {
  TempDir dir;
  EXPECT_NO_THROW(checkWritable(dir.file("out.h5")));
  EXPECT_TRUE(fs::is_empty(dir.path()));  // checking creates nothing
}

TEST(CheckWritable, RejectsMissingDirectoryAndDirectoryTargets) {
  TempDir dir;
  const std::string missing = dir.file("no/such/dir/out.h5");
  expectThrowContaining<IoError>([&] { checkWritable(missing); }, {missing, "does not exist"});
  expectThrowContaining<IoError>([&] { AtomicH5Writer writer(missing); }, {"does not exist"});
  expectThrowContaining<IoError>([&] { checkWritable(dir.path().string()); }, {"is a directory"});
  expectThrowContaining<IoError>([&] { checkWritable(dir.file("sub/")); }, {"names a directory"});
  std::ofstream(dir.file("plain")) << "x";
  expectThrowContaining<IoError>([&] { checkWritable(dir.file("plain/out.h5")); },
                                 {"is not a directory"});
  expectThrowContaining<IoError>([&] { checkWritable(""); }, {"empty"});
}

TEST(CheckWritable, RejectsAReadOnlyDirectory) {
  if (::geteuid() == 0) GTEST_SKIP() << "root may write anywhere";
  TempDir dir;
  const fs::path locked = dir.path() / "locked";
  fs::create_directory(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
  const std::string path = (locked / "out.h5").string();
  expectThrowContaining<IoError>([&] { checkWritable(path); }, {path, "not writable"});
  fs::permissions(locked, fs::perms::owner_all);
}

TEST(Version, MatchesTheCMakeProjectVersion) {
  std::ifstream cmake(std::string(MASTROM_SOURCE_DIR) + "/CMakeLists.txt");
  ASSERT_TRUE(cmake.good());
  std::stringstream text;
  text << cmake.rdbuf();
  // Parsed by hand: "project(mastrom VERSION x.y.z …" (std::regex trips GCC 12 warnings).
  const std::string content = text.str();
  const std::size_t project = content.find("project(mastrom");
  ASSERT_NE(project, std::string::npos);
  const std::size_t keyword = content.find("VERSION", project);
  ASSERT_NE(keyword, std::string::npos);
  const std::size_t begin = content.find_first_of("0123456789", keyword);
  const std::size_t end = content.find_first_not_of("0123456789.", begin);
  EXPECT_EQ(content.substr(begin, end - begin), std::string(mastrom::kVersion));
}
