#include "fullorder/result_stream.hpp"

#include <limits>

namespace mastrom::fullorder {

DeploymentResultStream::DeploymentResultStream(const std::string& final_path,
                                               double drive_end_time_s, std::size_t block_rows)
    : writer_(final_path),
      appender_(writer_.file(), block_rows),
      metrics_(drive_end_time_s),
      block_rows_(block_rows),
      last_time_s_(std::numeric_limits<double>::quiet_NaN()) {
  buffer_.reserve(block_rows_);
}

void DeploymentResultStream::append(const DeploymentSample& sample) {
  metrics_.add(sample);  // checks finiteness and time order before the sample is kept
  buffer_.append(sample);
  last_time_s_ = sample.time_s;
  if (buffer_.size() >= block_rows_) writeBlock();
}

void DeploymentResultStream::append(const DeploymentSeries& rows) {
  rows.checkConsistent();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const DeploymentSample sample = rows.sample(i);
    metrics_.add(sample);
    buffer_.append(sample);
    buffer_.end_relative_angular_acceleration_rad_s2.back() =
        rows.end_relative_angular_acceleration_rad_s2[i];
    last_time_s_ = sample.time_s;
    if (buffer_.size() >= block_rows_) writeBlock();
  }
}

void DeploymentResultStream::writeBlock() {
  appender_.append(buffer_);
  buffer_ = DeploymentSeries{};
  buffer_.reserve(block_rows_);
  // The file's metadata on disk follows the data block by block.
  h5::checked(H5Fflush(writer_.file().id(), H5F_SCOPE_LOCAL), "H5Fflush",
              "'" + writer_.file().path() + "'");
}

void DeploymentResultStream::flush() {
  if (!buffer_.empty()) writeBlock();
}

void DeploymentResultStream::finish(const DeploymentMetrics& metrics,
                                    const std::string& resolved_config_toml, double wall_time_s,
                                    ResultSource source, std::optional<double> stopped_at_s,
                                    const std::function<void(h5::File&)>& extra) {
  if (!buffer_.empty()) writeBlock();
  appender_.close();
  h5::File& file = writer_.file();
  writeDeploymentMetadata(file, metrics, resolved_config_toml, wall_time_s, source);
  if (extra) extra(file);
  if (stopped_at_s) markIncomplete(file, *stopped_at_s);
  writer_.commit();
}

}  // namespace mastrom::fullorder
