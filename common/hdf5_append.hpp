// Datasets that grow by rows while a long run writes them (docs/user_guide.md §5 "Streaming"): a
// chunked HDF5 dataset whose first dimension is unlimited, created empty with its `units`
// attribute and extended by each append(). `simulate` writes its time series this way
// (fullorder/result_stream.hpp), so its memory does not grow with the horizon; the file is still
// written under a temporary name and renamed at the end (common/hdf5_file.hpp), so the final name
// never holds a half-written file.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "common/hdf5_file.hpp"

namespace mastrom::h5 {

/// Element type of an appendable dataset.
enum class AppendType { Double, Int32 };

/// One [N] or [N, columns] dataset of `file`, N growing. Move-only; the file must outlive it.
class AppendableDataset {
public:
  AppendableDataset() = default;
  /// Create the empty dataset (parents created) with chunks of `chunk_rows` rows; columns = 0
  /// makes it 1-D. IoError when it exists already or HDF5 fails.
  AppendableDataset(File& file, const std::string& dataset_path, AppendType type,
                    std::size_t columns, std::size_t chunk_rows, std::string_view units);
  AppendableDataset(AppendableDataset&&) noexcept = default;
  AppendableDataset& operator=(AppendableDataset&&) noexcept = default;

  /// Append `rows` rows, row-major (rows · max(1, columns) values of the dataset's type).
  void append(const void* data, std::size_t rows);
  std::size_t rows() const { return rows_; }
  /// Close the dataset (flushes its chunk cache into the file); IoError on failure.
  void close();

private:
  DatasetHandle dataset_;
  std::string where_;
  hid_t memory_type_ = H5I_INVALID_HID;
  std::size_t columns_ = 0;
  std::size_t rows_ = 0;
};

/// Rows [first, first + count) of an [N] or [N, columns] dataset of `file` (an appendable one or
/// any other), row-major into `out` (count · max(1, columns) values of `type`): a long series read
/// back a block at a time. IoError naming the dataset when it is missing, of another rank or
/// column count, or has fewer than first + count rows.
void readRows(const File& file, const std::string& dataset_path, AppendType type,
              std::size_t columns, std::size_t first, std::size_t count, void* out);

}  // namespace mastrom::h5
