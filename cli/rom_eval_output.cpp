// The result file of `mastrom rom eval` (see rom_eval_output.hpp).
#include "cli/rom_eval_output.hpp"

#include "fullorder/streamed_result_file.hpp"

namespace mastrom::cli {

void writeRomEvaluationFile(const std::string& path, const rom::RomEvaluation& evaluation,
                            double drive_end_time_s, const std::string& resolved_config_toml,
                            double wall_time_s, std::optional<double> yield_strength_pa,
                            const std::function<void(h5::File&)>& extra) {
  const std::optional<fullorder::InterfaceStressResult>& stresses = evaluation.stresses;
  // The history is there only when asked (--stress-history), one per interface, on the samples.
  const bool history =
      stresses && !stresses->history.empty() && !stresses->history.front().max_von_mises_pa.empty();
  const std::size_t interfaces = history ? stresses->history.size() : 0;
  fullorder::StreamedResultFile file(path, drive_end_time_s, {interfaces, false});
  file.addSeries(evaluation.series);
  if (history) {
    const fullorder::InterfaceStressRowSink put_row = file.stressRowSink();
    fullorder::InterfaceStressRow row;
    row.resize(interfaces);
    for (std::size_t i = 0; i < stresses->time_s.size(); ++i) {
      row.time_s = stresses->time_s[i];
      for (std::size_t k = 0; k < interfaces; ++k)
        row.max_von_mises_pa[k] = stresses->history[k].max_von_mises_pa[i];
      put_row(row);
    }
  }
  file.finish(evaluation.metrics, resolved_config_toml, wall_time_s, fullorder::ResultSource::Rom,
              std::nullopt, stresses, yield_strength_pa, extra);
}

}  // namespace mastrom::cli
