// A deployment result file written while the run goes (docs/user_guide.md §5 "Streaming"): the
// output instants are buffered a block at a time and appended to chunked, extendible datasets
// (fullorder/results_io.hpp SeriesAppender), so a run of any horizon holds one block in memory.
// The file is written under a temporary name and renamed when the run ends (common/hdf5_file.hpp
// AtomicH5Writer): a complete run carries the root attribute complete = 1; a run stopped before
// its end time (SIGINT, SIGTERM: cli/interrupt.hpp) is finished the same way with what was
// computed and complete = 0, stopped_at_s. A process killed outright (SIGKILL, the machine) never
// renames: the final name keeps what it held before, and only the temporary file
// "<file>.tmp.<pid>" remains, which no reader takes for a result.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>

#include "common/hdf5_file.hpp"
#include "fullorder/deployment_result.hpp"
#include "fullorder/metrics_accumulator.hpp"
#include "fullorder/results_io.hpp"

namespace mastrom::fullorder {

class DeploymentResultStream {
public:
  /// Rows per block (and per HDF5 chunk): 4096 rows of the §5.3 datasets are about 0.8 MB.
  static constexpr std::size_t kBlockRows = 4096;

  /// Create the temporary file next to `final_path` (IoError when it cannot be written).
  /// drive_end_time_s and the band: for the metrics gathered on the way (MetricsAccumulator).
  DeploymentResultStream(const std::string& final_path, double drive_end_time_s,
                         std::size_t block_rows = kBlockRows);

  /// The next output instant (time order). NumericalError for a non-finite value (nothing of its
  /// block is written).
  void append(const DeploymentSample& sample);
  /// The rows of `rows` as they are stored (its relative angular acceleration column too, which
  /// a ROM computes from its modes, not as α_z − θ̈ again), after the instants so far.
  void append(const DeploymentSeries& rows);
  /// Output instants so far (written and buffered).
  std::size_t rows() const { return appender_.rows() + buffer_.size(); }
  /// The last output instant appended [s] (NaN before the first).
  double lastTime() const { return last_time_s_; }
  /// The file being written, for datasets streamed beside the series (the interface stresses'
  /// histories, fullorder/interface_stress_io.hpp InterfaceStressAppender).
  h5::File& file() { return writer_.file(); }
  /// The metrics of the output instants so far, from the samples (computeMetrics of them).
  DeploymentMetrics sampleMetrics() const { return metrics_.metrics(); }
  /// Write the buffered rows and flush the file, so that it holds every instant appended so far
  /// (a checkpoint refers to them: fullorder/checkpoint.hpp).
  void flush();
  /// The name the file is written under until finish() renames it.
  const std::string& temporaryPath() const { return writer_.temporaryPath(); }

  /// Write the buffered block, the metrics and the root attributes; `extra` may add groups (the
  /// interface stresses) before the file is closed; then rename it to its final name. With
  /// stopped_at_s the file is marked incomplete (fullorder/results_io.hpp markIncomplete).
  void finish(const DeploymentMetrics& metrics, const std::string& resolved_config_toml,
              double wall_time_s, ResultSource source, std::optional<double> stopped_at_s,
              const std::function<void(h5::File&)>& extra = {});

private:
  void writeBlock();

  h5::AtomicH5Writer writer_;
  SeriesAppender appender_;
  MetricsAccumulator metrics_;
  DeploymentSeries buffer_;
  std::size_t block_rows_;
  double last_time_s_;
};

}  // namespace mastrom::fullorder
