// A deployment result file fed through sinks (docs/user_guide.md §5 "Streaming"): the §5.3 series
// sample by sample (fullorder/result_stream.hpp) and, beside it, the interface stress histories
// row by row (fullorder/interface_stress_io.hpp InterfaceStressAppender), then the metrics, the
// stress peaks and fields and the root attributes at the end. Whoever produces the outputs — the
// full order's deployment loops, a ROM evaluation — hands them to the sinks as they are computed,
// so the file never needs the whole series in memory, and a run stopped early is finished with
// what was computed, marked incomplete. The content equals the whole-series writer's
// (writeDeploymentFileWithStresses) dataset for dataset.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>

#include "fullorder/interface_stress_io.hpp"
#include "fullorder/result_stream.hpp"

namespace mastrom::fullorder {

class StreamedResultFile {
public:
  /// Which stress histories the file carries.
  struct Histories {
    std::size_t interfaces = 0;   ///< 0: none
    bool edge_resultants = true;  ///< false: max von Mises only (a ROM's history)
  };
  /// Create the temporary file next to `final_path` (IoError when it cannot be written).
  StreamedResultFile(const std::string& final_path, double drive_end_time_s, Histories histories);

  /// The next output instant (time order).
  void addSample(const DeploymentSample& sample) { series_.append(sample); }
  /// The next output instants as stored in `rows` (every column as it is: a ROM's relative
  /// angular acceleration comes from its modes); a block-by-block producer's sink.
  void addSeries(const DeploymentSeries& rows) { series_.append(rows); }
  /// The stress histories at the next output instant (time order; with Histories::interfaces).
  void addStressRow(const InterfaceStressRow& row);
  /// A sink that forwards to addStressRow (borrowed: this must outlive it).
  InterfaceStressRowSink stressRowSink();

  std::size_t rows() const { return series_.rows(); }
  double lastTime() const { return series_.lastTime(); }
  /// The metrics of the samples so far (computeMetrics of them).
  DeploymentMetrics sampleMetrics() const { return series_.sampleMetrics(); }
  /// Write the buffered series rows and flush the file (before a checkpoint that refers to them).
  void flushSeries() { series_.flush(); }
  /// The name the file is written under until finish() renames it.
  const std::string& temporaryPath() const { return series_.temporaryPath(); }

  /// Close the histories (UsageError unless they have as many rows as the series), write the
  /// metrics, the stresses' peaks, fields and metrics (`stresses`, whose histories are not read),
  /// `extra`, and rename the file to its final name; incomplete with stopped_at_s.
  void finish(const DeploymentMetrics& metrics, const std::string& resolved_config_toml,
              double wall_time_s, ResultSource source, std::optional<double> stopped_at_s,
              const std::optional<InterfaceStressResult>& stresses,
              std::optional<double> yield_strength_pa,
              const std::function<void(h5::File&)>& extra = {});

private:
  DeploymentResultStream series_;
  std::optional<InterfaceStressAppender> histories_;
};

/// A streamed run restarted from its checkpoint (fullorder/checkpoint.hpp): the first `rows`
/// output instants of `source` — the file the checkpointed run was writing (its temporary name,
/// left by a killed run) or its result marked incomplete (an interrupted one) — appended to `file`
/// a block at a time, each block also handed to `each` (may be null), so the restarted run's file
/// is rebuilt with bounded memory and then continues. `last` is the checkpoint's last output
/// instant: source's row rows − 1 must equal it bit for bit. IoError naming `source` when it cannot
/// be read, holds fewer rows or another run's outputs.
void rebuildStreamedSeries(StreamedResultFile& file, const std::string& source, std::size_t rows,
                           const DeploymentSeries& last,
                           const std::function<void(const DeploymentSeries&)>& each = {});

}  // namespace mastrom::fullorder
