// The result file of `mastrom rom eval` (docs/user_guide.md §5), written through the streamed
// writer's sinks (fullorder/streamed_result_file.hpp): the series a block at a time and the stress
// history (--stress-history: the largest von Mises of every interface) row by row, then the
// metrics, peaks and attributes. An evaluation that holds its outputs (evaluateRomDeployment) is
// written a block at a time; `rom eval -o` steps them block by block into the same sinks as it
// goes (writeStreamedRomEvaluationFile), and the file is then never held whole. SIGINT / SIGTERM
// (cli/interrupt.hpp) is seen between blocks: the file then ends with the blocks written and is
// marked incomplete (root attributes complete = 0, stopped_at_s), as an interrupted `simulate`'s;
// its metrics and stress peaks are the evaluation's, computed over the whole horizon before the
// writing began. No physics here.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>

#include "common/hdf5_file.hpp"
#include "rom/studies/rom_evaluation.hpp"

namespace mastrom::cli {

/// What writeRomEvaluationFile wrote.
struct RomEvaluationFileSummary {
  std::size_t samples = 0;             ///< output instants in the file
  std::optional<double> stopped_at_s;  ///< set when stop_requested ended the series early
};

/// Write `evaluation` to `path` atomically (temporary name, renamed when complete); `extra` adds
/// attributes before the commit. The content equals writeDeploymentFileWithStresses' of the
/// evaluation's series, metrics and stresses. `stop_requested` (may be null) is asked after every
/// block but the last: true ends the series there, and the file is marked incomplete.
RomEvaluationFileSummary writeRomEvaluationFile(
    const std::string& path, const rom::RomEvaluation& evaluation, double drive_end_time_s,
    const std::string& resolved_config_toml, double wall_time_s,
    std::optional<double> yield_strength_pa, const std::function<void(h5::File&)>& extra = {},
    const std::function<bool()>& stop_requested = {});

/// The file of an evaluation whose outputs are stepped while they are written
/// (rom::evaluateRomOutcome, then rom::streamRomOutputs into the file's sinks): the series a block
/// of fullorder::DeploymentResultStream::kBlockRows rows at a time, the stress history (with
/// input.stress_history) beside it, neither ever held whole. The content equals
/// writeRomEvaluationFile's of evaluateRomDeployment's result. `wall_time_s`: the time before the
/// outputs (their stepping is added). `stop_requested` is asked after every series block but the
/// last: true ends the file there (the rest of the series is stepped, not written; the history
/// only up to that block), marked incomplete.
RomEvaluationFileSummary writeStreamedRomEvaluationFile(
    const std::string& path, rom::RomEvaluation& evaluation, const rom::RomEvaluationInput& input,
    const std::string& resolved_config_toml, double wall_time_s,
    std::optional<double> yield_strength_pa, const std::function<void(h5::File&)>& extra = {},
    const std::function<bool()>& stop_requested = {});

}  // namespace mastrom::cli
