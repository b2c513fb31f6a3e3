// The result file of `mastrom rom eval` (see rom_eval_output.hpp).
#include "cli/rom_eval_output.hpp"

#include <algorithm>

#include "fullorder/result_stream.hpp"
#include "fullorder/streamed_result_file.hpp"

namespace mastrom::cli {
namespace {

/// Rows [first, first + count) of `series`, every column as stored (a ROM's relative angular
/// acceleration comes from its modes, not as α_z − θ̈ again).
fullorder::DeploymentSeries rowsOf(const fullorder::DeploymentSeries& series, std::size_t first,
                                   std::size_t count) {
  fullorder::DeploymentSeries rows;
  rows.reserve(count);
  for (std::size_t i = first; i < first + count; ++i) {
    rows.append(series.sample(i));
    rows.end_relative_angular_acceleration_rad_s2.back() =
        series.end_relative_angular_acceleration_rad_s2[i];
  }
  return rows;
}

}  // namespace

RomEvaluationFileSummary writeRomEvaluationFile(
    const std::string& path, const rom::RomEvaluation& evaluation, double drive_end_time_s,
    const std::string& resolved_config_toml, double wall_time_s,
    std::optional<double> yield_strength_pa, const std::function<void(h5::File&)>& extra,
    const std::function<bool()>& stop_requested) {
  const std::optional<fullorder::InterfaceStressResult>& stresses = evaluation.stresses;
  // The history is there only when asked (--stress-history), one per interface, on the samples.
  const bool history =
      stresses && !stresses->history.empty() && !stresses->history.front().max_von_mises_pa.empty();
  const std::size_t interfaces = history ? stresses->history.size() : 0;
  fullorder::StreamedResultFile file(path, drive_end_time_s, {interfaces, false});
  const fullorder::InterfaceStressRowSink put_row =
      history ? file.stressRowSink() : fullorder::InterfaceStressRowSink{};
  fullorder::InterfaceStressRow row;
  row.resize(interfaces);
  const fullorder::DeploymentSeries& series = evaluation.series;
  const std::size_t n = series.size();
  RomEvaluationFileSummary summary;
  // A block of the series (and of the history) at a time; a signal is seen between blocks, and
  // the file then ends with the last block written, marked incomplete (cli/interrupt.hpp).
  for (std::size_t first = 0; first < n;) {
    const std::size_t count = std::min(fullorder::DeploymentResultStream::kBlockRows, n - first);
    file.addSeries(rowsOf(series, first, count));
    for (std::size_t i = first; history && i < first + count; ++i) {
      row.time_s = stresses->time_s[i];
      for (std::size_t k = 0; k < interfaces; ++k)
        row.max_von_mises_pa[k] = stresses->history[k].max_von_mises_pa[i];
      put_row(row);
    }
    first += count;
    if (first < n && stop_requested && stop_requested()) {
      summary.stopped_at_s = file.lastTime();
      break;
    }
  }
  summary.samples = file.rows();
  file.finish(evaluation.metrics, resolved_config_toml, wall_time_s, fullorder::ResultSource::Rom,
              summary.stopped_at_s, stresses, yield_strength_pa, extra);
  return summary;
}

RomEvaluationFileSummary writeStreamedRomEvaluationFile(
    const std::string& path, rom::RomEvaluation& evaluation, const rom::RomEvaluationInput& input,
    const std::string& resolved_config_toml, double wall_time_s,
    std::optional<double> yield_strength_pa, const std::function<void(h5::File&)>& extra,
    const std::function<bool()>& stop_requested) {
  std::optional<fullorder::InterfaceStressResult>& stresses = evaluation.stresses;
  const bool history = stresses && input.stress_history;
  const std::size_t interfaces = history ? stresses->history.size() : 0;
  fullorder::StreamedResultFile file(path, input.config.drive.duration_s, {interfaces, false});
  const fullorder::InterfaceStressRowSink put_row =
      history ? file.stressRowSink() : fullorder::InterfaceStressRowSink{};
  fullorder::InterfaceStressRow row;
  row.resize(interfaces);
  const std::size_t n = evaluation.output_samples;
  const double step_s = evaluation.options.step_s;
  RomEvaluationFileSummary summary;
  std::size_t written = 0;  // series rows in the file; the history follows up to them
  rom::streamRomOutputs(
      evaluation, input, fullorder::DeploymentResultStream::kBlockRows,
      [&](const fullorder::DeploymentSeries& block) {
        if (summary.stopped_at_s) return;  // stopped: the rest is stepped, not written
        file.addSeries(block);
        written += block.size();
        if (written < n && stop_requested && stop_requested())
          summary.stopped_at_s = file.lastTime();
      },
      [&](long first, const std::vector<std::vector<double>>& values) {
        const std::size_t count = values.empty() ? 0 : values.front().size();
        for (std::size_t j = 0; j < count && static_cast<std::size_t>(first) + j < written; ++j) {
          // The instants of rom::setStressOutputInstants.
          row.time_s = static_cast<double>(first + static_cast<long>(j)) * step_s;
          for (std::size_t k = 0; k < interfaces; ++k) row.max_von_mises_pa[k] = values[k][j];
          put_row(row);
        }
      });
  summary.samples = file.rows();
  file.finish(evaluation.metrics, resolved_config_toml,
              wall_time_s + evaluation.deployment_s + evaluation.stress_history_s,
              fullorder::ResultSource::Rom, summary.stopped_at_s, stresses, yield_strength_pa,
              extra);
  return summary;
}

}  // namespace mastrom::cli
