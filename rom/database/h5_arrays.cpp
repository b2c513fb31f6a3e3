#include "rom/database/h5_arrays.hpp"

#include <algorithm>
#include <cstring>

namespace mastrom::rom::h5x {
namespace {

using h5::checked;

std::string where(const h5::File& file, const std::string& path) {
  return path + " in '" + file.path() + "'";
}

void writeRaw(h5::File& file, const std::string& path, const std::vector<std::size_t>& dims,
              hid_t file_type, hid_t memory_type, const void* data, std::string_view units) {
  const std::string context = where(file, path);
  MASTROM_REQUIRE(!file.exists(path), IoError, "dataset ", context, " exists already");
  std::vector<hsize_t> d(dims.begin(), dims.end());
  h5::PropertyListHandle lcpl(checked(H5Pcreate(H5P_LINK_CREATE), "H5Pcreate", context));
  checked(H5Pset_create_intermediate_group(lcpl.get(), 1), "H5Pset_create_intermediate_group",
          context);
  const h5::DataspaceHandle space(
      checked(H5Screate_simple(static_cast<int>(d.size()), d.data(), nullptr), "H5Screate_simple",
              context));
  h5::DatasetHandle dataset(checked(H5Dcreate2(file.id(), path.c_str(), file_type, space.get(),
                                               lcpl.get(), H5P_DEFAULT, H5P_DEFAULT),
                                    "H5Dcreate2", context));
  std::size_t n = 1;
  for (const std::size_t x : dims) n *= x;
  if (n > 0) {
    checked(H5Dwrite(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "H5Dwrite",
            context);
  }
  dataset.close("H5Dclose", context);
  file.setUnits(path, units);
}

h5::DatasetHandle openDataset(const h5::File& file, const std::string& path) {
  MASTROM_REQUIRE(file.exists(path), IoError, "no dataset ", where(file, path));
  return h5::DatasetHandle(
      checked(H5Dopen2(file.id(), path.c_str(), H5P_DEFAULT), "H5Dopen2", where(file, path)));
}

std::vector<std::size_t> shapeOf(const h5::File& file, const std::string& path,
                                 const h5::DatasetHandle& dataset) {
  const std::string context = where(file, path);
  const h5::DataspaceHandle space(checked(H5Dget_space(dataset.get()), "H5Dget_space", context));
  const int rank =
      checked(H5Sget_simple_extent_ndims(space.get()), "H5Sget_simple_extent_ndims", context);
  std::vector<hsize_t> d(static_cast<std::size_t>(rank));
  if (rank > 0) {
    checked(H5Sget_simple_extent_dims(space.get(), d.data(), nullptr), "H5Sget_simple_extent_dims",
            context);
  }
  return std::vector<std::size_t>(d.begin(), d.end());
}

template <typename T>
std::vector<T> readRaw(const h5::File& file, const std::string& path,
                       std::vector<std::size_t>& dims, hid_t memory_type, bool allow_float) {
  const h5::DatasetHandle dataset = openDataset(file, path);
  const std::string context = where(file, path);
  const h5::TypeHandle type(checked(H5Dget_type(dataset.get()), "H5Dget_type", context));
  const H5T_class_t c = H5Tget_class(type.get());
  MASTROM_REQUIRE(c == H5T_INTEGER || (allow_float && c == H5T_FLOAT), IoError, "dataset ", context,
                  " is not ", allow_float ? "numeric" : "of integer type");
  dims = shapeOf(file, path, dataset);
  std::size_t n = 1;
  for (const std::size_t x : dims) n *= x;
  std::vector<T> values(n);
  if (n > 0) {
    checked(H5Dread(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
            "H5Dread", context);
  }
  return values;
}

/// Fixed-length NUL-terminated UTF-8 string type wide enough for every value.
h5::TypeHandle stringType(const std::vector<std::string>& values, const std::string& context) {
  std::size_t width = 1;
  for (const std::string& v : values) width = std::max(width, v.size() + 1);
  h5::TypeHandle type(checked(H5Tcopy(H5T_C_S1), "H5Tcopy", context));
  checked(H5Tset_size(type.get(), width), "H5Tset_size", context);
  checked(H5Tset_strpad(type.get(), H5T_STR_NULLTERM), "H5Tset_strpad", context);
  checked(H5Tset_cset(type.get(), H5T_CSET_UTF8), "H5Tset_cset", context);
  return type;
}

std::vector<char> packStrings(const std::vector<std::string>& values, std::size_t width) {
  std::vector<char> buffer(values.size() * width, '\0');
  for (std::size_t i = 0; i < values.size(); ++i)
    std::memcpy(buffer.data() + i * width, values[i].data(), values[i].size());
  return buffer;
}

}  // namespace

void writeDoubles(h5::File& file, const std::string& path, const std::vector<std::size_t>& dims,
                  const double* data, std::string_view units) {
  writeRaw(file, path, dims, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, data, units);
}

void writeInts(h5::File& file, const std::string& path, const std::vector<std::size_t>& dims,
               const int* data, std::string_view units) {
  writeRaw(file, path, dims, H5T_STD_I32LE, H5T_NATIVE_INT, data, units);
}

std::vector<double> readDoubles(const h5::File& file, const std::string& path,
                                std::vector<std::size_t>& dims) {
  return readRaw<double>(file, path, dims, H5T_NATIVE_DOUBLE, true);
}

std::vector<int> readInts(const h5::File& file, const std::string& path,
                          std::vector<std::size_t>& dims) {
  return readRaw<int>(file, path, dims, H5T_NATIVE_INT, false);
}

void writeStrings(h5::File& file, const std::string& path, const std::vector<std::string>& values) {
  const std::string context = where(file, path);
  const h5::TypeHandle type = stringType(values, context);
  const std::size_t width = H5Tget_size(type.get());
  const std::vector<char> buffer = packStrings(values, width);
  writeRaw(file, path, {values.size()}, type.get(), type.get(), buffer.data(), "1");
}

void setStringArrayAttribute(h5::File& file, const std::string& object_path,
                             const std::string& name, const std::vector<std::string>& values) {
  const std::string context = where(file, object_path) + " attribute '" + name + "'";
  const h5::ObjectHandle object(
      checked(H5Oopen(file.id(), object_path.c_str(), H5P_DEFAULT), "H5Oopen", context));
  if (checked(H5Aexists(object.get(), name.c_str()), "H5Aexists", context) > 0)
    checked(H5Adelete(object.get(), name.c_str()), "H5Adelete", context);
  const h5::TypeHandle type = stringType(values, context);
  const std::size_t width = H5Tget_size(type.get());
  const std::vector<char> buffer = packStrings(values, width);
  const hsize_t n = values.size();
  const h5::DataspaceHandle space(
      checked(H5Screate_simple(1, &n, nullptr), "H5Screate_simple", context));
  h5::AttributeHandle attribute(checked(
      H5Acreate2(object.get(), name.c_str(), type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
      "H5Acreate2", context));
  checked(H5Awrite(attribute.get(), type.get(), buffer.data()), "H5Awrite", context);
  attribute.close("H5Aclose", context);
}

}  // namespace mastrom::rom::h5x
