// String and int-matrix datasets (see h5_datasets.hpp).
#include "modes/h5_datasets.hpp"

#include <cstring>

namespace mastrom::modes::detail {
namespace {

std::string where(const h5::File& file, const std::string& path) {
  return ::mastrom::detail::concat(path, " in '", file.path(), "'");
}

/// Create (with parents) and write one dataset of `dims` from `data` in memory type `memory_type`.
void createAndWrite(h5::File& file, const std::string& path, hid_t file_type, hid_t memory_type,
                    const std::vector<hsize_t>& dims, const void* data, std::string_view units) {
  const std::string context = where(file, path);
  MASTROM_REQUIRE(!file.exists(path), IoError, "dataset ", context, " exists already");
  h5::PropertyListHandle lcpl(h5::checked(H5Pcreate(H5P_LINK_CREATE), "H5Pcreate", context));
  h5::checked(H5Pset_create_intermediate_group(lcpl.get(), 1), "H5Pset_create_intermediate_group",
              context);
  const h5::DataspaceHandle space(
      h5::checked(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr),
                  "H5Screate_simple", context));
  h5::DatasetHandle dataset(h5::checked(H5Dcreate2(file.id(), path.c_str(), file_type, space.get(),
                                                   lcpl.get(), H5P_DEFAULT, H5P_DEFAULT),
                                        "H5Dcreate2", context));
  bool empty = false;
  for (hsize_t d : dims) empty = empty || d == 0;
  if (!empty)
    h5::checked(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
                "H5Dwrite", context);
  dataset.close("H5Dclose", context);
  file.setUnits(path, units);
}

}  // namespace

void writeStrings(h5::File& file, const std::string& dataset_path,
                  const std::vector<std::string>& values, std::string_view units) {
  const std::string context = where(file, dataset_path);
  h5::TypeHandle type(h5::checked(H5Tcopy(H5T_C_S1), "H5Tcopy", context));
  h5::checked(H5Tset_size(type.get(), H5T_VARIABLE), "H5Tset_size", context);
  h5::checked(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset", context);
  std::vector<const char*> pointers;
  pointers.reserve(values.size());
  for (const std::string& v : values) pointers.push_back(v.c_str());
  createAndWrite(file, dataset_path, type.get(), type.get(), {values.size()}, pointers.data(),
                 units);
}

std::vector<std::string> readStrings(const h5::File& file, const std::string& dataset_path) {
  const std::string context = where(file, dataset_path);
  MASTROM_REQUIRE(file.exists(dataset_path), IoError, "dataset ", context, " does not exist");
  const h5::DatasetHandle dataset(
      h5::checked(H5Dopen2(file.id(), dataset_path.c_str(), H5P_DEFAULT), "H5Dopen2", context));
  const h5::TypeHandle type(h5::checked(H5Dget_type(dataset.get()), "H5Dget_type", context));
  MASTROM_REQUIRE(H5Tget_class(type.get()) == H5T_STRING, IoError, "dataset ", context,
                  " does not hold strings");
  const h5::DataspaceHandle space(
      h5::checked(H5Dget_space(dataset.get()), "H5Dget_space", context));
  MASTROM_REQUIRE(H5Sget_simple_extent_ndims(space.get()) == 1, IoError, "dataset ", context,
                  " is not 1-D");
  hsize_t n = 0;
  h5::checked(H5Sget_simple_extent_dims(space.get(), &n, nullptr), "H5Sget_simple_extent_dims",
              context);
  std::vector<std::string> out;
  out.reserve(n);
  if (n == 0) return out;
  if (h5::checked(H5Tis_variable_str(type.get()), "H5Tis_variable_str", context) > 0) {
    h5::TypeHandle memory(h5::checked(H5Tcopy(H5T_C_S1), "H5Tcopy", context));
    h5::checked(H5Tset_size(memory.get(), H5T_VARIABLE), "H5Tset_size", context);
    h5::checked(H5Tset_cset(memory.get(), H5Tget_cset(type.get())), "H5Tset_cset", context);
    std::vector<char*> buffer(n, nullptr);
    h5::checked(H5Dread(dataset.get(), memory.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()),
                "H5Dread", context);
    for (char* s : buffer) out.emplace_back(s != nullptr ? s : "");
    H5Dvlen_reclaim(memory.get(), space.get(), H5P_DEFAULT, buffer.data());
    return out;
  }
  const std::size_t size = H5Tget_size(type.get());
  std::vector<char> buffer(size * n, '\0');
  h5::checked(H5Dread(dataset.get(), type.get(), H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()),
              "H5Dread", context);
  for (hsize_t i = 0; i < n; ++i) {
    const char* s = buffer.data() + i * size;
    out.emplace_back(s, ::strnlen(s, size));
  }
  return out;
}

void writeIntMatrix(h5::File& file, const std::string& dataset_path,
                    const std::vector<int>& row_major, std::size_t rows, std::size_t cols,
                    std::string_view units) {
  MASTROM_REQUIRE(row_major.size() == rows * cols, IoError, "dataset ", where(file, dataset_path),
                  ": ", row_major.size(), " values do not fill ", rows, " x ", cols);
  createAndWrite(file, dataset_path, H5T_STD_I32LE, H5T_NATIVE_INT, {rows, cols}, row_major.data(),
                 units);
}

}  // namespace mastrom::modes::detail
