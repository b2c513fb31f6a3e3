// What a run's output step is and why (docs/theory.md §5.4a): the line `simulate` and `rom eval`
// print first, and the root attributes of their result files.
#pragma once

#include <optional>
#include <string>

#include "common/config.hpp"
#include "common/hdf5_file.hpp"
#include "rom/model/output_resolution.hpp"

namespace mastrom::cli {

/// "output step 2.5e-05 s (default: …)" for a chosen step, "output step … s (output.step)" for a
/// set one, "outputs every N steps …" for fixed steps.
std::string outputStepNote(const std::optional<rom::OutputStepChoice>& choice,
                           const Config& config);

/// Root attributes output_step_s (the spacing of the outputs [s]) and output_step_rule (the
/// note), and for a chosen step resolved_frequency_hz, samples_per_period and output_step_capped.
void writeOutputStepAttributes(h5::File& file, const std::optional<rom::OutputStepChoice>& choice,
                               const Config& config);

}  // namespace mastrom::cli
