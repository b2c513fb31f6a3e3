#include "cli/output_step_note.hpp"

#include <cstdio>

namespace mastrom::cli {

std::string outputStepNote(const std::optional<rom::OutputStepChoice>& choice,
                           const Config& config) {
  if (choice) return rom::describeOutputStep(*choice);
  char line[200];
  if (config.simulation.adaptive)
    std::snprintf(line, sizeof line, "output step %.3g s (output.step)", outputInterval(config));
  else
    std::snprintf(line, sizeof line,
                  "output step %.3g s (fixed steps: simulation.time_step x output.every = %d)",
                  outputInterval(config), config.output.every);
  return line;
}

void writeOutputStepAttributes(h5::File& file, const std::optional<rom::OutputStepChoice>& choice,
                               const Config& config) {
  file.setDoubleAttribute("/", "output_step_s", outputInterval(config));
  file.setStringAttribute("/", "output_step_rule", outputStepNote(choice, config));
  if (!choice) return;
  file.setDoubleAttribute("/", "resolved_frequency_hz", choice->mode.frequency_hz);
  file.setDoubleAttribute("/", "samples_per_period", choice->samplesPerPeriod());
  file.setIntAttribute("/", "output_step_capped", choice->capped ? 1 : 0);
}

}  // namespace mastrom::cli
