// A deployment result file fed through sinks (see streamed_result_file.hpp).
#include "fullorder/streamed_result_file.hpp"

#include <algorithm>
#include <cstring>

#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "fullorder/results_io.hpp"

namespace mastrom::fullorder {

StreamedResultFile::StreamedResultFile(const std::string& final_path, double drive_end_time_s,
                                       Histories histories)
    : series_(final_path, drive_end_time_s) {
  if (histories.interfaces > 0) {
    // About one series block of rows in all, at least 256 rows a block.
    const std::size_t rows =
        std::max<std::size_t>(256, DeploymentResultStream::kBlockRows / histories.interfaces);
    histories_.emplace(series_.file(), histories.interfaces, rows, histories.edge_resultants);
  }
}

void StreamedResultFile::addStressRow(const InterfaceStressRow& row) {
  MASTROM_REQUIRE(histories_.has_value(), UsageError,
                  "StreamedResultFile: a stress row for a file without stress histories");
  histories_->append(row);
}

InterfaceStressRowSink StreamedResultFile::stressRowSink() {
  return [this](const InterfaceStressRow& row) { addStressRow(row); };
}

void StreamedResultFile::finish(const DeploymentMetrics& metrics,
                                const std::string& resolved_config_toml, double wall_time_s,
                                ResultSource source, std::optional<double> stopped_at_s,
                                const std::optional<InterfaceStressResult>& stresses,
                                std::optional<double> yield_strength_pa,
                                const std::function<void(h5::File&)>& extra) {
  if (histories_) {
    histories_->close();
    MASTROM_REQUIRE(histories_->rows() == series_.rows(), UsageError,
                    "the interface stress histories have ", histories_->rows(),
                    " rows, the outputs ", series_.rows());
  }
  series_.finish(metrics, resolved_config_toml, wall_time_s, source, stopped_at_s,
                 [&](h5::File& file) {
                   if (stresses) writeInterfaceStressResults(file, *stresses, yield_strength_pa);
                   if (extra) extra(file);
                 });
}

void rebuildStreamedSeries(StreamedResultFile& file, const std::string& source, std::size_t rows,
                           const DeploymentSeries& last,
                           const std::function<void(const DeploymentSeries&)>& each) {
  MASTROM_REQUIRE(rows > 0 && last.size() == 1, UsageError, "rebuildStreamedSeries: ", rows,
                  " rows, ", last.size(), " last instants");
  const h5::File in = h5::File::open(source, h5::OpenMode::ReadOnly);
  const std::vector<std::size_t> shape =
      in.exists("/time") ? in.datasetShape("/time") : std::vector<std::size_t>{};
  MASTROM_REQUIRE(shape.size() == 1 && shape[0] >= rows, IoError, "'", source, "' holds ",
                  shape.empty() ? 0 : shape[0], " output instants; the checkpoint needs its first ",
                  rows);
  // The checkpoint's last output instant, bit for bit: the file is this run's, up to it.
  const DeploymentSeries at = readDeploymentSeriesRows(in, rows - 1, 1);
  MASTROM_REQUIRE(
      std::memcmp(&at.time_s[0], &last.time_s[0], sizeof(double)) == 0 &&
          std::memcmp(at.end_angular_acceleration_rad_s2[0].data(),
                      last.end_angular_acceleration_rad_s2[0].data(), 3 * sizeof(double)) == 0,
      IoError, "'", source, "' is not the result of the checkpointed run: its output ", rows - 1,
      " is at t = ", at.time_s[0], " s, the checkpoint's at ", last.time_s[0],
      " s (or differs there)");
  for (std::size_t first = 0; first < rows; first += DeploymentResultStream::kBlockRows) {
    const std::size_t count = std::min(DeploymentResultStream::kBlockRows, rows - first);
    const DeploymentSeries block = readDeploymentSeriesRows(in, first, count);
    file.addSeries(block);
    if (each) each(block);
  }
}

}  // namespace mastrom::fullorder
