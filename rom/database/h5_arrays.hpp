// HDF5 pieces the ROM files need beyond common/hdf5_file.hpp's 1-D / 2-D datasets: datasets of any
// rank (double and int32), 1-D string datasets, and string-array attributes (one unit per column).
// They use the raw identifier File::id() and the same checked() / handle wrappers, so failures are
// the same one-line IoErrors.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "common/hdf5_file.hpp"

namespace mastrom::rom::h5x {

/// Dataset of any rank from row-major data (product of dims values), with a `units` attribute.
void writeDoubles(h5::File& file, const std::string& path, const std::vector<std::size_t>& dims,
                  const double* data, std::string_view units);
void writeInts(h5::File& file, const std::string& path, const std::vector<std::size_t>& dims,
               const int* data, std::string_view units);

/// Read a numeric dataset of any rank (row-major); dims receives its shape. IoError when missing
/// or not numeric (integers only for readInts).
std::vector<double> readDoubles(const h5::File& file, const std::string& path,
                                std::vector<std::size_t>& dims);
std::vector<int> readInts(const h5::File& file, const std::string& path,
                          std::vector<std::size_t>& dims);

/// 1-D dataset of fixed-length UTF-8 strings (h5py reads them as bytes), units "1".
void writeStrings(h5::File& file, const std::string& path, const std::vector<std::string>& values);

/// Replace attribute `name` of an object by a 1-D array of strings.
void setStringArrayAttribute(h5::File& file, const std::string& object_path,
                             const std::string& name, const std::vector<std::string>& values);

}  // namespace mastrom::rom::h5x
