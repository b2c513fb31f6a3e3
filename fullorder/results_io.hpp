// Deployment result files: the HDF5 layout of docs/user_guide.md §5, written atomically.
//
//   /time [N]                                          s
//   /drive/angle, /drive/rate, /drive/acceleration [N] rad, rad/s, rad/s^2
//   /end/angular_acceleration [N,3]                    rad/s^2
//   /end/relative_angular_acceleration [N]             rad/s^2
//   /end/position [N,3], /end/acceleration [N,3]       m, m/s^2
//   /joint/force [N,3], /joint/torque [N]              N, N*m
//   /solver/newton_iterations [N] (int32)              1
//   /solver/constraint_residual [N]                    1
//   /metrics   double attributes named as the fields of DeploymentMetrics (SI), settled as int 0/1
//   /          attributes config (resolved TOML text), mastrom_version, source, wall_time_s,
//              complete (int: 1, or 0 for a run stopped before its end time, which then also has
//              stopped_at_s, the last instant computed)
//
// Every dataset carries a `units` attribute. A file never holds a NaN or an infinity: the data are
// checked before the file is created, and a failure leaves no file under the final name.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/hdf5_append.hpp"
#include "common/hdf5_file.hpp"
#include "fullorder/deployment_result.hpp"

namespace mastrom::fullorder {

/// Which model produced a result (root attribute `source`).
enum class ResultSource { FullOrder, Rom };
/// "full-order" / "rom".
std::string toString(ResultSource source);
std::optional<ResultSource> parseResultSource(std::string_view name);

/// Everything a deployment file holds.
struct DeploymentFile {
  DeploymentSeries series;
  DeploymentMetrics metrics;
  std::string config_toml;      ///< the resolved configuration the run used
  std::string mastrom_version;  ///< of the program that wrote the file
  ResultSource source = ResultSource::FullOrder;
  double wall_time_s = 0.0;
  /// False for a run stopped before its end time (interrupted): the file holds what was computed.
  /// Files without the attribute (older ones) are complete.
  bool complete = true;
};

/// Write the §5.3 deployment layout into an open file (for callers that add more, e.g. /modes, before
/// committing an AtomicH5Writer). Throws NumericalError naming the dataset and index of the first
/// non-finite value before writing anything; UsageError for an inconsistent series.
void writeDeployment(h5::File& file, const DeploymentSeries& series,
                     const DeploymentMetrics& metrics, const std::string& resolved_config_toml,
                     double wall_time_s, ResultSource source);

/// The /metrics group and the root attributes of the §5.3 layout (writeDeployment's part after
/// the series). NumericalError naming the attribute for a non-finite metric or wall time.
void writeDeploymentMetadata(h5::File& file, const DeploymentMetrics& metrics,
                             const std::string& resolved_config_toml, double wall_time_s,
                             ResultSource source);

/// The §5.3 time series as chunked datasets that grow by rows (common/hdf5_append.hpp): a run
/// that streams its outputs appends them a block at a time (fullorder/result_stream.hpp).
class SeriesAppender {
public:
  /// Create the empty datasets in `file` (which must outlive this).
  SeriesAppender(h5::File& file, std::size_t chunk_rows);
  /// Append the rows of `rows`; NumericalError naming the dataset and the time of the first
  /// non-finite value, before anything of the block is written.
  void append(const DeploymentSeries& rows);
  std::size_t rows() const { return rows_; }
  /// Close the datasets; IoError on failure.
  void close();

private:
  std::string file_path_;
  std::vector<h5::AppendableDataset> scalars_, vectors_;
  h5::AppendableDataset iterations_, tangential_;
  std::size_t rows_ = 0;
};

/// Mark a file written by writeDeployment as the result of a run stopped at stopped_at_s, before
/// its end time: root attributes complete = 0 and stopped_at_s.
void markIncomplete(h5::File& file, double stopped_at_s);

/// Only the time series of the §5.3 layout, under `group` ("" for the root, "/series" puts /time at
/// /series/time): checkpoints (fullorder/checkpoint.hpp) store the series recorded so far this way.
/// Same checks as writeDeployment for the series.
void writeDeploymentSeries(h5::File& file, const std::string& group,
                           const DeploymentSeries& series);
/// Read what writeDeploymentSeries wrote; IoError naming the first missing or inconsistent dataset.
DeploymentSeries readDeploymentSeries(const h5::File& file, const std::string& group);
/// Rows [first, first + count) of the root series of a deployment file (written whole or streamed),
/// every column as stored: a long series read back a block at a time. IoError naming the first
/// missing dataset or one with fewer rows.
DeploymentSeries readDeploymentSeriesRows(const h5::File& file, std::size_t first,
                                          std::size_t count);

/// Write a complete deployment file atomically (temporary name, renamed when complete). All checks
/// — finiteness (NumericalError), consistency, writable directory (IoError) — happen before any file
/// is created; on any failure the final name is left untouched.
void writeDeploymentFile(const std::string& path, const DeploymentSeries& series,
                         const DeploymentMetrics& metrics, const std::string& resolved_config_toml,
                         double wall_time_s, ResultSource source);

/// Read a file written by writeDeploymentFile. IoError when the file is missing, not HDF5, or not a
/// mastrom deployment file (the message lists every missing dataset and attribute), or when the
/// datasets disagree in length.
DeploymentFile readDeploymentFile(const std::string& path);

}  // namespace mastrom::fullorder
