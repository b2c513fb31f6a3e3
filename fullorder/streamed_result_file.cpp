// A deployment result file fed through sinks (see streamed_result_file.hpp).
#include "fullorder/streamed_result_file.hpp"

#include <algorithm>

#include "common/error.hpp"

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

}  // namespace mastrom::fullorder
