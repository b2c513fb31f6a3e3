#include "common/hdf5_file.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <mutex>

#include <fcntl.h>
#include <unistd.h>

namespace mastrom::h5 {
namespace fs = std::filesystem;

// --- errors ------------------------------------------------------------------------------------------
namespace detail {

void initializeLibrary() {
  static std::once_flag once;
  std::call_once(once, [] {
    H5open();
    // Failures are reported through exceptions carrying the innermost message (throwError below);
    // HDF5's default handler would print a multi-line stack trace to stderr for every one, including
    // failures mastrom expects and handles.
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  });
}

namespace {
struct ErrorMessages {
  std::string innermost;  ///< the most specific description (first in an upward walk)
  std::string api;        ///< the API-level description (last in an upward walk)
};

herr_t collectError(unsigned n, const H5E_error2_t* error, void* data) {
  auto* messages = static_cast<ErrorMessages*>(data);
  const std::string text = (error != nullptr && error->desc != nullptr) ? error->desc : "";
  if (n == 0) messages->innermost = text;
  messages->api = text;
  return 0;
}
}  // namespace

void throwError(std::string_view operation, std::string_view context) {
  ErrorMessages messages;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, collectError, &messages);
  H5Eclear2(H5E_DEFAULT);
  std::string detail = messages.api;
  if (!messages.innermost.empty() && messages.innermost != messages.api) {
    detail += detail.empty() ? messages.innermost : " (" + messages.innermost + ")";
  }
  if (detail.empty()) detail = "no further detail from HDF5";
  throw IoError(::mastrom::detail::concat("HDF5 ", operation, " failed for ", context, ": ", detail));
}

}  // namespace detail

namespace {

/// "/a/b" → {"a", "b"}; empty components ("//", trailing "/") are dropped.
std::vector<std::string> splitPath(const std::string& path) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t slash = path.find('/', start);
    const std::size_t end = slash == std::string::npos ? path.size() : slash;
    if (end > start) parts.push_back(path.substr(start, end - start));
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  return parts;
}

/// Absolute, canonical object path: "end//position/" → "/end/position", "" → "/".
std::string normalizePath(const std::string& path) {
  std::string out;
  for (const std::string& part : splitPath(path)) out += "/" + part;
  return out.empty() ? "/" : out;
}

/// File-access properties shared by create and open.
PropertyListHandle fileAccessProperties(const std::string& path) {
  PropertyListHandle fapl(checked(H5Pcreate(H5P_FILE_ACCESS), "H5Pcreate", "'" + path + "'"));
  // The 1.8 object-header format stores large attributes densely: the resolved config text of a
  // large model could otherwise exceed the 64 KB limit of the original format.
  checked(H5Pset_libver_bounds(fapl.get(), H5F_LIBVER_V18, H5F_LIBVER_V110),
          "H5Pset_libver_bounds", "'" + path + "'");
  // Closing the file closes every object still open in it, so the data is flushed before the
  // atomic rename even if a caller leaked an identifier.
  checked(H5Pset_fclose_degree(fapl.get(), H5F_CLOSE_STRONG), "H5Pset_fclose_degree",
          "'" + path + "'");
#if H5_VERSION_GE(1, 10, 7)
  // Keep HDF5's file locking, but do not fail on file systems that do not support it (NFS, Lustre).
  checked(H5Pset_file_locking(fapl.get(), true, true), "H5Pset_file_locking", "'" + path + "'");
#endif
  return fapl;
}

hsize_t elementCount(const std::vector<hsize_t>& dims) {
  hsize_t n = 1;
  for (hsize_t d : dims) n *= d;
  return n;
}

/// Flush a closed file's data to stable storage before it is renamed (a crash of the machine, not
/// only of the process, must not leave a renamed-but-empty file).
void syncPath(const std::string& path, int flags) {
  const int fd = ::open(path.c_str(), flags);
  if (fd < 0) return;  // best effort: the rename still protects against process crashes
  ::fsync(fd);
  ::close(fd);
}

herr_t collectAttributeName(hid_t, const char* name, const H5A_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->emplace_back(name);
  return 0;
}

}  // namespace

// --- File --------------------------------------------------------------------------------------------
File File::create(const std::string& path, CreateMode mode) {
  detail::initializeLibrary();
  MASTROM_REQUIRE(!path.empty(), IoError, "cannot create an HDF5 file with an empty name");
  const PropertyListHandle fapl = fileAccessProperties(path);
  const unsigned flags = mode == CreateMode::Truncate ? H5F_ACC_TRUNC : H5F_ACC_EXCL;
  FileHandle handle(checked(H5Fcreate(path.c_str(), flags, H5P_DEFAULT, fapl.get()), "H5Fcreate",
                            "'" + path + "'"));
  return File(std::move(handle), path);
}

File File::open(const std::string& path, OpenMode mode) {
  detail::initializeLibrary();
  std::error_code ec;
  MASTROM_REQUIRE(fs::is_regular_file(path, ec), IoError, "cannot open '", path,
                  "': no such file");
  const htri_t is_hdf5 = H5Fis_hdf5(path.c_str());
  H5Eclear2(H5E_DEFAULT);
  MASTROM_REQUIRE(is_hdf5 > 0, IoError, "cannot open '", path, "': not an HDF5 file");
  const PropertyListHandle fapl = fileAccessProperties(path);
  const unsigned flags = mode == OpenMode::ReadOnly ? H5F_ACC_RDONLY : H5F_ACC_RDWR;
  FileHandle handle(
      checked(H5Fopen(path.c_str(), flags, fapl.get()), "H5Fopen", "'" + path + "'"));
  return File(std::move(handle), path);
}

void File::close() { handle_.close("H5Fclose", "'" + path_ + "'"); }

std::string File::where(const std::string& object_path) const {
  return normalizePath(object_path) + " in '" + path_ + "'";
}

void File::requireOpen() const {
  MASTROM_REQUIRE(isOpen(), IoError, "HDF5 file '", path_, "' is not open");
}

bool File::exists(const std::string& object_path) const {
  requireOpen();
  const std::vector<std::string> parts = splitPath(object_path);
  std::string prefix;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    prefix += "/" + parts[i];
    const htri_t link = checked(H5Lexists(id(), prefix.c_str(), H5P_DEFAULT), "H5Lexists",
                                where(prefix));
    if (link == 0) return false;
    const htri_t object = checked(H5Oexists_by_name(id(), prefix.c_str(), H5P_DEFAULT),
                                  "H5Oexists_by_name", where(prefix));
    if (object == 0) return false;  // a dangling soft link
    if (i + 1 < parts.size()) {     // an intermediate component must be a group to descend into
      const ObjectHandle parent = openObject(prefix);
      if (H5Iget_type(parent.get()) != H5I_GROUP) return false;
    }
  }
  return true;
}

void File::createGroup(const std::string& group_path) {
  requireOpen();
  const std::string path = normalizePath(group_path);
  if (exists(path)) {
    const ObjectHandle object = openObject(path);
    MASTROM_REQUIRE(H5Iget_type(object.get()) == H5I_GROUP, IoError, "cannot create group ",
                    where(path), ": a dataset of that name exists");
    return;
  }
  PropertyListHandle lcpl(checked(H5Pcreate(H5P_LINK_CREATE), "H5Pcreate", where(path)));
  checked(H5Pset_create_intermediate_group(lcpl.get(), 1), "H5Pset_create_intermediate_group",
          where(path));
  GroupHandle group(checked(H5Gcreate2(id(), path.c_str(), lcpl.get(), H5P_DEFAULT, H5P_DEFAULT),
                            "H5Gcreate2", where(path)));
}

ObjectHandle File::openObject(const std::string& object_path) const {
  requireOpen();
  const std::string path = normalizePath(object_path);
  return ObjectHandle(checked(H5Oopen(id(), path.c_str(), H5P_DEFAULT), "H5Oopen", where(path)));
}

DatasetHandle File::openDataset(const std::string& dataset_path) const {
  MASTROM_REQUIRE(exists(dataset_path), IoError, "no dataset ", where(dataset_path));
  const std::string path = normalizePath(dataset_path);
  return DatasetHandle(
      checked(H5Dopen2(id(), path.c_str(), H5P_DEFAULT), "H5Dopen2", where(path)));
}

std::vector<std::size_t> File::datasetShape(const std::string& dataset_path) const {
  const DatasetHandle dataset = openDataset(dataset_path);
  const std::vector<hsize_t> dims = readShape(dataset, dataset_path, -1);
  return std::vector<std::size_t>(dims.begin(), dims.end());
}

std::vector<hsize_t> File::readShape(const DatasetHandle& dataset, const std::string& dataset_path,
                                     int expected_rank) const {
  const DataspaceHandle space(
      checked(H5Dget_space(dataset.get()), "H5Dget_space", where(dataset_path)));
  const int rank = checked(H5Sget_simple_extent_ndims(space.get()), "H5Sget_simple_extent_ndims",
                           where(dataset_path));
  MASTROM_REQUIRE(expected_rank < 0 || rank == expected_rank, IoError, "dataset ",
                  where(dataset_path), " has rank ", rank, ", expected ", expected_rank);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (rank > 0) {
    checked(H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr),
            "H5Sget_simple_extent_dims", where(dataset_path));
  }
  return dims;
}

void File::writeDataset(const std::string& dataset_path, hid_t file_type, hid_t memory_type,
                        const std::vector<hsize_t>& dims, const void* data, std::string_view units) {
  requireOpen();
  const std::string path = normalizePath(dataset_path);
  MASTROM_REQUIRE(path != "/", IoError, "cannot write a dataset at the root of '", path_, "'");
  MASTROM_REQUIRE(!units.empty(), IoError, "dataset ", where(path),
                  " needs a units attribute (use \"1\" for dimensionless)");
  MASTROM_REQUIRE(!exists(path), IoError, "dataset ", where(path), " exists already");
  PropertyListHandle lcpl(checked(H5Pcreate(H5P_LINK_CREATE), "H5Pcreate", where(path)));
  checked(H5Pset_create_intermediate_group(lcpl.get(), 1), "H5Pset_create_intermediate_group",
          where(path));
  const DataspaceHandle space(
      checked(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
              "H5Screate_simple", where(path)));
  DatasetHandle dataset(checked(H5Dcreate2(id(), path.c_str(), file_type, space.get(), lcpl.get(),
                                           H5P_DEFAULT, H5P_DEFAULT),
                                "H5Dcreate2", where(path)));
  if (elementCount(dims) > 0) {
    checked(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "H5Dwrite",
            where(path));
  }
  dataset.close("H5Dclose", where(path));
  setUnits(path, units);
}

void File::writeDoubles(const std::string& dataset_path, const std::vector<double>& values,
                        std::string_view units) {
  writeDataset(dataset_path, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {values.size()}, values.data(),
               units);
}

void File::writeMatrix(const std::string& dataset_path, const std::vector<double>& row_major,
                       std::size_t rows, std::size_t cols, std::string_view units) {
  MASTROM_REQUIRE(row_major.size() == rows * cols, IoError, "dataset ", where(dataset_path), ": ",
                  row_major.size(), " values do not fill ", rows, " x ", cols);
  writeDataset(dataset_path, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, {rows, cols}, row_major.data(),
               units);
}

void File::writeMatrix(const std::string& dataset_path,
                       const Eigen::Ref<const Eigen::MatrixXd>& matrix, std::string_view units) {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  const RowMajor row_major = matrix;
  const std::vector<hsize_t> dims{static_cast<hsize_t>(matrix.rows()),
                                  static_cast<hsize_t>(matrix.cols())};
  writeDataset(dataset_path, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, dims, row_major.data(), units);
}

void File::writeMatrix(const std::string& dataset_path, const std::vector<Eigen::Vector3d>& rows,
                       std::string_view units) {
  std::vector<double> row_major;
  row_major.reserve(3 * rows.size());
  for (const Eigen::Vector3d& r : rows) row_major.insert(row_major.end(), r.data(), r.data() + 3);
  writeMatrix(dataset_path, row_major, rows.size(), 3, units);
}

void File::writeInts(const std::string& dataset_path, const std::vector<int>& values,
                     std::string_view units) {
  writeDataset(dataset_path, H5T_STD_I32LE, H5T_NATIVE_INT, {values.size()}, values.data(), units);
}

namespace {
/// IoError unless the stored type is one of the accepted classes (conversion is left to HDF5).
void requireTypeClass(hid_t object_type, bool allow_float, const std::string& what) {
  const H5T_class_t type_class = H5Tget_class(object_type);
  const bool ok = type_class == H5T_INTEGER || (allow_float && type_class == H5T_FLOAT);
  MASTROM_REQUIRE(ok, IoError, what, " is not ", allow_float ? "numeric" : "of integer type");
}
}  // namespace

std::vector<double> File::readDoubles(const std::string& dataset_path) const {
  const DatasetHandle dataset = openDataset(dataset_path);
  const TypeHandle type(checked(H5Dget_type(dataset.get()), "H5Dget_type", where(dataset_path)));
  requireTypeClass(type.get(), true, "dataset " + where(dataset_path));
  const std::vector<hsize_t> dims = readShape(dataset, dataset_path, 1);
  std::vector<double> values(dims[0]);
  if (!values.empty()) {
    checked(H5Dread(dataset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
            "H5Dread", where(dataset_path));
  }
  return values;
}

Eigen::MatrixXd File::readMatrix(const std::string& dataset_path) const {
  const DatasetHandle dataset = openDataset(dataset_path);
  const TypeHandle type(checked(H5Dget_type(dataset.get()), "H5Dget_type", where(dataset_path)));
  requireTypeClass(type.get(), true, "dataset " + where(dataset_path));
  const std::vector<hsize_t> dims = readShape(dataset, dataset_path, 2);
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> row_major(
      static_cast<Eigen::Index>(dims[0]), static_cast<Eigen::Index>(dims[1]));
  if (row_major.size() > 0) {
    checked(
        H5Dread(dataset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, row_major.data()),
        "H5Dread", where(dataset_path));
  }
  return Eigen::MatrixXd(row_major);
}

std::vector<int> File::readInts(const std::string& dataset_path) const {
  const DatasetHandle dataset = openDataset(dataset_path);
  const TypeHandle type(checked(H5Dget_type(dataset.get()), "H5Dget_type", where(dataset_path)));
  requireTypeClass(type.get(), false, "dataset " + where(dataset_path));
  const std::vector<hsize_t> dims = readShape(dataset, dataset_path, 1);
  std::vector<int> values(dims[0]);
  if (!values.empty()) {
    checked(H5Dread(dataset.get(), H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
            "H5Dread", where(dataset_path));
  }
  return values;
}

// --- attributes --------------------------------------------------------------------------------------
bool File::hasAttribute(const std::string& object_path, const std::string& name) const {
  if (!exists(object_path)) return false;
  const std::string path = normalizePath(object_path);
  return checked(H5Aexists_by_name(id(), path.c_str(), name.c_str(), H5P_DEFAULT),
                 "H5Aexists_by_name", where(path) + " attribute '" + name + "'") > 0;
}

std::vector<std::string> File::attributeNames(const std::string& object_path) const {
  const ObjectHandle object = openObject(object_path);
  std::vector<std::string> names;
  hsize_t index = 0;
  checked(H5Aiterate2(object.get(), H5_INDEX_NAME, H5_ITER_INC, &index, collectAttributeName, &names),
          "H5Aiterate2", where(object_path));
  return names;
}

AttributeHandle File::openAttribute(const std::string& object_path, const std::string& name) const {
  MASTROM_REQUIRE(hasAttribute(object_path, name), IoError, "no attribute '", name, "' on ",
                  where(object_path));
  const std::string path = normalizePath(object_path);
  return AttributeHandle(
      checked(H5Aopen_by_name(id(), path.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
              "H5Aopen_by_name", where(path) + " attribute '" + name + "'"));
}

void File::writeAttribute(const std::string& object_path, const std::string& name, hid_t file_type,
                          hid_t memory_type, const void* value) {
  const std::string context = where(object_path) + " attribute '" + name + "'";
  MASTROM_REQUIRE(!name.empty(), IoError, "empty attribute name on ", where(object_path));
  const ObjectHandle object = openObject(object_path);
  if (checked(H5Aexists(object.get(), name.c_str()), "H5Aexists", context) > 0) {
    checked(H5Adelete(object.get(), name.c_str()), "H5Adelete", context);
  }
  const DataspaceHandle space(checked(H5Screate(H5S_SCALAR), "H5Screate", context));
  AttributeHandle attribute(checked(
      H5Acreate2(object.get(), name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
      "H5Acreate2", context));
  checked(H5Awrite(attribute.get(), memory_type, value), "H5Awrite", context);
  attribute.close("H5Aclose", context);
}

void File::setStringAttribute(const std::string& object_path, const std::string& name,
                              std::string_view value) {
  const std::string context = where(object_path) + " attribute '" + name + "'";
  // Fixed-length, NUL-terminated UTF-8: what h5dump prints plainly and h5py reads as bytes.
  const std::string text(value);
  TypeHandle type(checked(H5Tcopy(H5T_C_S1), "H5Tcopy", context));
  checked(H5Tset_size(type.get(), text.size() + 1), "H5Tset_size", context);
  checked(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), "H5Tset_strpad", context);
  checked(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset", context);
  writeAttribute(object_path, name, type.get(), type.get(), text.c_str());
}

void File::setDoubleAttribute(const std::string& object_path, const std::string& name,
                              double value) {
  writeAttribute(object_path, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void File::setIntAttribute(const std::string& object_path, const std::string& name, int value) {
  writeAttribute(object_path, name, H5T_STD_I32LE, H5T_NATIVE_INT, &value);
}

namespace {
/// IoError unless the attribute holds exactly one element (scalar or [1]).
void requireSingleElement(hid_t attribute, const std::string& context) {
  const DataspaceHandle space(checked(H5Aget_space(attribute), "H5Aget_space", context));
  const hssize_t n =
      checked(H5Sget_simple_extent_npoints(space.get()), "H5Sget_simple_extent_npoints", context);
  MASTROM_REQUIRE(n == 1, IoError, context, " holds ", n, " values, expected one");
}
}  // namespace

std::string File::readStringAttribute(const std::string& object_path,
                                      const std::string& name) const {
  const std::string context = where(object_path) + " attribute '" + name + "'";
  const AttributeHandle attribute = openAttribute(object_path, name);
  const TypeHandle type(checked(H5Aget_type(attribute.get()), "H5Aget_type", context));
  MASTROM_REQUIRE(H5Tget_class(type.get()) == H5T_STRING, IoError, context, " is not a string");
  requireSingleElement(attribute.get(), context);

  if (checked(H5Tis_variable_str(type.get()), "H5Tis_variable_str", context) > 0) {
    TypeHandle memory(checked(H5Tcopy(H5T_C_S1), "H5Tcopy", context));
    checked(H5Tset_size(memory.get(), H5T_VARIABLE), "H5Tset_size", context);
    checked(H5Tset_cset(memory.get(), H5Tget_cset(type.get())), "H5Tset_cset", context);
    char* buffer = nullptr;
    checked(H5Aread(attribute.get(), memory.get(), &buffer), "H5Aread", context);
    std::string text = buffer != nullptr ? buffer : "";
    H5free_memory(buffer);
    return text;
  }
  const std::size_t size = H5Tget_size(type.get());
  MASTROM_REQUIRE(size > 0, IoError, context, " has a zero-size string type");
  std::vector<char> buffer(size + 1, '\0');
  checked(H5Aread(attribute.get(), type.get(), buffer.data()), "H5Aread", context);
  std::string text(buffer.data(), ::strnlen(buffer.data(), size));
  if (H5Tget_strpad(type.get()) == H5T_STR_SPACEPAD) {
    text.erase(text.find_last_not_of(' ') + 1);
  }
  return text;
}

double File::readDoubleAttribute(const std::string& object_path, const std::string& name) const {
  const std::string context = where(object_path) + " attribute '" + name + "'";
  const AttributeHandle attribute = openAttribute(object_path, name);
  const TypeHandle type(checked(H5Aget_type(attribute.get()), "H5Aget_type", context));
  requireTypeClass(type.get(), true, context);
  requireSingleElement(attribute.get(), context);
  double value = 0.0;
  checked(H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value), "H5Aread", context);
  return value;
}

int File::readIntAttribute(const std::string& object_path, const std::string& name) const {
  const std::string context = where(object_path) + " attribute '" + name + "'";
  const AttributeHandle attribute = openAttribute(object_path, name);
  const TypeHandle type(checked(H5Aget_type(attribute.get()), "H5Aget_type", context));
  requireTypeClass(type.get(), false, context);
  requireSingleElement(attribute.get(), context);
  int value = 0;
  checked(H5Aread(attribute.get(), H5T_NATIVE_INT, &value), "H5Aread", context);
  return value;
}

void File::setUnits(const std::string& object_path, std::string_view units) {
  setStringAttribute(object_path, "units", units);
}

std::string File::readUnits(const std::string& object_path) const {
  return readStringAttribute(object_path, "units");
}

// --- atomic writing ----------------------------------------------------------------------------------
std::string temporaryPathFor(const std::string& final_path) {
  return final_path + ".tmp." + std::to_string(static_cast<long>(::getpid()));
}

void checkWritable(const std::string& path) {
  MASTROM_REQUIRE(!path.empty(), IoError, "output file name is empty");
  const fs::path file(path);
  MASTROM_REQUIRE(file.has_filename(), IoError, "output '", path, "' names a directory, not a file");
  const fs::path directory = file.has_parent_path() ? file.parent_path() : fs::path(".");
  std::error_code ec;
  const fs::file_status status = fs::status(directory, ec);
  MASTROM_REQUIRE(fs::exists(status), IoError, "cannot write '", path, "': directory '",
                  directory.string(), "' does not exist");
  MASTROM_REQUIRE(fs::is_directory(status), IoError, "cannot write '", path, "': '",
                  directory.string(), "' is not a directory");
  MASTROM_REQUIRE(!fs::is_directory(fs::status(file, ec)), IoError, "cannot write '", path,
                  "': it is a directory");
  // Creating the temporary file and renaming it need write and search permission on the directory.
  if (::access(directory.c_str(), W_OK | X_OK) != 0) {
    const int error = errno;
    throw IoError(::mastrom::detail::concat("cannot write '", path, "': directory '",
                                            directory.string(), "' is not writable (",
                                            std::strerror(error), ")"));
  }
}

AtomicH5Writer::AtomicH5Writer(std::string final_path)
    : final_path_(std::move(final_path)), temporary_path_(temporaryPathFor(final_path_)) {
  checkWritable(final_path_);
  // Truncate: a temporary file of this name can only be a leftover of a crashed process that had
  // the same pid.
  file_ = File::create(temporary_path_, CreateMode::Truncate);
}

AtomicH5Writer::~AtomicH5Writer() {
  if (committed_) return;
  file_ = File();  // close, ignoring errors
  std::error_code ec;
  fs::remove(temporary_path_, ec);
}

void AtomicH5Writer::commit() {
  MASTROM_REQUIRE(!committed_, IoError, "'", final_path_, "' is committed already");
  file_.close();
  syncPath(temporary_path_, O_RDONLY);
  std::error_code ec;
  fs::rename(temporary_path_, final_path_, ec);
  MASTROM_REQUIRE(!ec, IoError, "cannot rename '", temporary_path_, "' to '", final_path_,
                  "': ", ec.message());
  committed_ = true;
  const fs::path parent = fs::path(final_path_).parent_path();
  syncPath(parent.empty() ? std::string(".") : parent.string(), O_RDONLY | O_DIRECTORY);
}

}  // namespace mastrom::h5
