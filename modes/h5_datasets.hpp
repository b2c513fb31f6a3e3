// Internal to modes/: the two HDF5 dataset kinds common/hdf5_file.hpp does not offer — a 1-D
// variable-length UTF-8 string dataset (mode labels) and a 2-D int32 dataset (cell connectivity for
// XDMF) — written through File::id() with the same checked-call and RAII helpers, each with the
// mandatory `units` attribute (docs/user_guide.md §5).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "common/hdf5_file.hpp"

namespace mastrom::modes::detail {

/// 1-D dataset of variable-length UTF-8 strings; parents are created. IoError on failure.
void writeStrings(h5::File& file, const std::string& dataset_path,
                  const std::vector<std::string>& values, std::string_view units);
/// Read a 1-D string dataset (variable or fixed length). IoError if missing or not strings.
std::vector<std::string> readStrings(const h5::File& file, const std::string& dataset_path);

/// 2-D int32 dataset [rows, cols] from row-major data; parents are created.
void writeIntMatrix(h5::File& file, const std::string& dataset_path,
                    const std::vector<int>& row_major, std::size_t rows, std::size_t cols,
                    std::string_view units);

}  // namespace mastrom::modes::detail
