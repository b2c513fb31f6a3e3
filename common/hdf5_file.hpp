// A small RAII wrapper over the HDF5 C API, and the atomic-write rule of docs/user_guide.md §5.
//
// HDF5 is wrapped once here: `checked()` turns a negative HDF5 return into
// an IoError that names the operation, the file and the object, plus the innermost message of HDF5's
// error stack; HDF5's own automatic stack printing is switched off, so a failure is one clear line.
// `Handle<Close>` owns one HDF5 identifier and closes it in its destructor. `File` offers the few
// operations mastrom needs: groups by path, 1-D / 2-D double and 1-D int datasets (row-major on disk,
// each with a mandatory `units` attribute — docs/user_guide.md §5), string / double / int
// attributes on any object, listing and existence checks.
//
// `AtomicH5Writer` writes to "<final>.tmp.<pid>" in the same directory and renames on commit(), so a
// crash or an exception never leaves a truncated file under the final name. `checkWritable()` lets a
// long run fail before it starts when its output cannot be written.
//
// The C++ HDF5 API is not linked; the library is Debian's Open MPI build (scripts/setup.sh), used
// here serially through the default (sec2) driver.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <hdf5.h>

#include "common/error.hpp"

namespace mastrom::h5 {

namespace detail {
/// Switch off HDF5's automatic error printing and initialise the library (idempotent, cheap).
void initializeLibrary();
/// Throw IoError for a failed HDF5 call, with the innermost message of the HDF5 error stack.
[[noreturn]] void throwError(std::string_view operation, std::string_view context);
}  // namespace detail

/// Checked HDF5 call: returns `result` when it is ≥ 0 (an id, herr_t or htri_t), otherwise throws
/// IoError "HDF5 <operation> failed for <context>: <HDF5's message>".
/// Example: `hid_t d = checked(H5Dopen2(f, "/time", H5P_DEFAULT), "H5Dopen2", "/time in 'a.h5'");`
template <typename T>
T checked(T result, std::string_view operation, std::string_view context) {
  if (result < 0) detail::throwError(operation, context);
  return result;
}

/// Owns one HDF5 identifier; `Close` is the matching H5?close function. Move-only.
template <herr_t (*Close)(hid_t)>
class Handle {
public:
  Handle() = default;
  /// Takes ownership of `id` (which may be invalid, < 0).
  explicit Handle(hid_t id) : id_(id) {}
  ~Handle() { reset(); }
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, H5I_INVALID_HID)) {}
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  /// Close now, ignoring failure (destructors, error paths).
  void reset() noexcept {
    if (id_ >= 0) Close(id_);
    id_ = H5I_INVALID_HID;
  }
  /// Close now and throw IoError on failure (matters for files: closing flushes).
  void close(std::string_view operation, std::string_view context) {
    if (id_ < 0) return;
    const herr_t status = Close(std::exchange(id_, H5I_INVALID_HID));
    checked(status, operation, context);
  }

private:
  hid_t id_ = H5I_INVALID_HID;
};

using FileHandle = Handle<H5Fclose>;
using GroupHandle = Handle<H5Gclose>;
using DatasetHandle = Handle<H5Dclose>;
using DataspaceHandle = Handle<H5Sclose>;
using AttributeHandle = Handle<H5Aclose>;
using TypeHandle = Handle<H5Tclose>;
using PropertyListHandle = Handle<H5Pclose>;
using ObjectHandle = Handle<H5Oclose>;  ///< group, dataset or named type opened with H5Oopen

/// What File::create does when the file exists already.
enum class CreateMode {
  Truncate,  ///< replace it
  Exclusive  ///< fail with IoError
};

/// How File::open opens an existing file.
enum class OpenMode { ReadOnly, ReadWrite };

/// One open HDF5 file. Object paths are absolute ("/end/position"); a path without the leading "/" is
/// taken relative to the root. Every failure throws IoError naming the file and the object.
class File {
public:
  /// A closed file (isOpen() is false); assign a created or opened one to it.
  File() = default;
  /// Create a file (1.8-or-later format, so attributes may exceed 64 KB).
  static File create(const std::string& path, CreateMode mode);
  /// Open an existing HDF5 file; IoError when it does not exist or is not HDF5.
  static File open(const std::string& path, OpenMode mode);

  File(File&&) noexcept = default;
  File& operator=(File&&) noexcept = default;
  /// Closes without checking; call close() to see a flush failure.
  ~File() = default;

  /// Flush and close; throws IoError on failure. Closing a closed file does nothing.
  void close();
  bool isOpen() const { return handle_.valid(); }
  const std::string& path() const { return path_; }
  /// The raw identifier, borrowed, for operations this wrapper does not offer.
  hid_t id() const { return handle_.get(); }

  // --- structure ---------------------------------------------------------------------------------
  /// True when `object_path` names an existing group, dataset or named type ("/" always exists).
  bool exists(const std::string& object_path) const;
  /// Create a group and any missing parents; does nothing when the group exists already.
  void createGroup(const std::string& group_path);
  /// Dimensions of a dataset (empty for a scalar dataset).
  std::vector<std::size_t> datasetShape(const std::string& dataset_path) const;

  // --- datasets: parents are created; writing over an existing dataset is an IoError -------------
  /// 1-D double dataset [N].
  void writeDoubles(const std::string& dataset_path, const std::vector<double>& values,
                    std::string_view units);
  /// 2-D double dataset [rows, cols] from row-major data (values.size() == rows · cols).
  void writeMatrix(const std::string& dataset_path, const std::vector<double>& row_major,
                   std::size_t rows, std::size_t cols, std::string_view units);
  /// 2-D double dataset with the shape of `matrix` (stored row-major, as HDF5 and numpy expect).
  void writeMatrix(const std::string& dataset_path, const Eigen::Ref<const Eigen::MatrixXd>& matrix,
                   std::string_view units);
  /// 2-D double dataset [N, 3], row i = rows[i].
  void writeMatrix(const std::string& dataset_path, const std::vector<Eigen::Vector3d>& rows,
                   std::string_view units);
  /// 1-D int dataset [N] (stored as 32-bit little-endian integers).
  void writeInts(const std::string& dataset_path, const std::vector<int>& values,
                 std::string_view units);

  /// Read a 1-D numeric dataset as doubles; IoError if it is missing or not rank 1.
  std::vector<double> readDoubles(const std::string& dataset_path) const;
  /// Read a 2-D numeric dataset; IoError if it is missing or not rank 2.
  Eigen::MatrixXd readMatrix(const std::string& dataset_path) const;
  /// Read a 1-D integer dataset; IoError if it is missing, not rank 1 or not of integer type.
  std::vector<int> readInts(const std::string& dataset_path) const;

  // --- attributes on any object ("/" for the root); writing replaces an existing attribute -------
  void setStringAttribute(const std::string& object_path, const std::string& name,
                          std::string_view value);
  void setDoubleAttribute(const std::string& object_path, const std::string& name, double value);
  void setIntAttribute(const std::string& object_path, const std::string& name, int value);
  /// Reads fixed- and variable-length strings (the latter as h5py writes them).
  std::string readStringAttribute(const std::string& object_path, const std::string& name) const;
  double readDoubleAttribute(const std::string& object_path, const std::string& name) const;
  int readIntAttribute(const std::string& object_path, const std::string& name) const;
  bool hasAttribute(const std::string& object_path, const std::string& name) const;
  /// Attribute names of an object, in name order.
  std::vector<std::string> attributeNames(const std::string& object_path) const;

  /// The `units` attribute every dataset carries (docs/user_guide.md §5): "s", "rad/s^2", "N*m",
  /// "1", …
  void setUnits(const std::string& object_path, std::string_view units);
  std::string readUnits(const std::string& object_path) const;

private:
  File(FileHandle handle, std::string path) : handle_(std::move(handle)), path_(std::move(path)) {}
  /// "<object> in '<file>'", for error messages.
  std::string where(const std::string& object_path) const;
  void requireOpen() const;
  ObjectHandle openObject(const std::string& object_path) const;
  DatasetHandle openDataset(const std::string& dataset_path) const;
  AttributeHandle openAttribute(const std::string& object_path, const std::string& name) const;
  void writeDataset(const std::string& dataset_path, hid_t file_type, hid_t memory_type,
                    const std::vector<hsize_t>& dims, const void* data, std::string_view units);
  /// Open a dataset, check its rank, return its dims.
  std::vector<hsize_t> readShape(const DatasetHandle& dataset, const std::string& dataset_path,
                                 int expected_rank) const;
  void writeAttribute(const std::string& object_path, const std::string& name, hid_t file_type,
                      hid_t memory_type, const void* value);

  FileHandle handle_;
  std::string path_;
};

/// The temporary name AtomicH5Writer uses for `final_path`: "<final_path>.tmp.<pid>".
std::string temporaryPathFor(const std::string& final_path);

/// Fail early, before a long run, when `path` could not be written: IoError naming the path when its
/// directory does not exist, is not a directory or is not writable, or when `path` is a directory.
void checkWritable(const std::string& path);

/// Writes an HDF5 file under a temporary name in the target directory; commit() closes it and renames
/// it to the final name (atomic on POSIX). Destroyed without commit() — an exception, an early return —
/// it deletes the temporary file, so the final name holds either a complete file or what it held before.
class AtomicH5Writer {
public:
  /// Checks that `final_path` is writable, then creates the temporary file.
  explicit AtomicH5Writer(std::string final_path);
  ~AtomicH5Writer();
  AtomicH5Writer(const AtomicH5Writer&) = delete;
  AtomicH5Writer& operator=(const AtomicH5Writer&) = delete;

  /// The file being written (under its temporary name).
  File& file() { return file_; }
  /// Close, flush to disk and rename to the final name; IoError on failure (the temporary file is then
  /// removed by the destructor). Calling it twice is an IoError.
  void commit();
  bool committed() const { return committed_; }
  const std::string& temporaryPath() const { return temporary_path_; }

private:
  std::string final_path_;
  std::string temporary_path_;
  File file_;
  bool committed_ = false;
};

}  // namespace mastrom::h5
