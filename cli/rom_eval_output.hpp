// The result file of `mastrom rom eval` (docs/user_guide.md §5), written through the streamed
// writer's sinks (fullorder/streamed_result_file.hpp): the series sample by sample and the stress
// history (--stress-history: the largest von Mises of every interface) row by row, then the
// metrics, peaks and attributes. The evaluation (rom/studies/rom_evaluation.hpp) hands its outputs
// over here once it has them all; one that steps its series block by block can hand each block to
// the same sinks as it goes, and the file is then never held whole. No physics here.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "common/hdf5_file.hpp"
#include "rom/studies/rom_evaluation.hpp"

namespace mastrom::cli {

/// Write `evaluation` to `path` atomically (temporary name, renamed when complete); `extra` adds
/// attributes before the commit. The content equals writeDeploymentFileWithStresses' of the
/// evaluation's series, metrics and stresses.
void writeRomEvaluationFile(const std::string& path, const rom::RomEvaluation& evaluation,
                            double drive_end_time_s, const std::string& resolved_config_toml,
                            double wall_time_s, std::optional<double> yield_strength_pa,
                            const std::function<void(h5::File&)>& extra = {});

}  // namespace mastrom::cli
