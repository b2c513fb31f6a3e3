// The default output step of a run (see default_output_step.hpp; docs/theory.md §5.4a).
#include "rom/studies/default_output_step.hpp"

#include <cmath>

#include "fullorder/drive_law.hpp"
#include "fullorder/mast_config.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/model/modal_stepping.hpp"
#include "rom/offline/direct_modal_model.hpp"

namespace mastrom::rom {

OutputStepChoice outputStepForModel(const Config& config, const ModalModel& model,
                                    double bytes_per_sample) {
  // The drive's largest θ̈ and θ̇ with their one-sided limits at the breakpoints (sampled at the
  // fallback step: the maxima of the forcing bound, not of any output).
  const fullorder::DriveLaw drive(fullorder::driveFromConfig(config));
  // After T the drive holds still, so [0, T] has them; a horizon of 10⁹ s costs nothing here.
  ModalDeploymentOptions options;
  options.end_time_s = std::min(config.simulation.end_time_s, drive.parameters().duration_s);
  options.step_s = std::min(kFallbackOutputStepS, options.end_time_s);
  const SampledDrive sampled = sampleDrive(drive, options);
  const ExcitedMode mode =
      highestExcitedMode(model, sampled.max_abs_acceleration_rad_s2, sampled.max_abs_rate_rad_s);
  return chooseOutputStep(mode, config.simulation.end_time_s, bytes_per_sample);
}

OutputStepChoice fullOrderOutputStep(const Config& config, double bytes_per_sample) {
  // The mast at the start configuration (docs/theory.md §5.4a): without gravity the locked mast's
  // modes do not depend on the angle at all (they turn with it), with gravity the preload at θ(0)
  // is the one the run starts from.
  Config locked = config;
  const double start_deg =
      fullorder::DriveLaw(fullorder::driveFromConfig(config)).at(0.0).angle_rad * 180.0 /
      3.14159265358979323846;
  locked.modes.angle_deg = std::fmod(std::fmod(start_deg, 360.0) + 360.0, 360.0);
  const ModalModel model = directModalModel(locked, kOutputStepModes);
  return outputStepForModel(config, model, bytes_per_sample);
}

std::optional<OutputStepChoice> resolveFullOrderOutputStep(Config& config,
                                                           double bytes_per_sample) {
  if (config.output.step_s || !config.simulation.adaptive) return std::nullopt;
  const OutputStepChoice choice = fullOrderOutputStep(config, bytes_per_sample);
  config.output.step_s = choice.step_s;
  return choice;
}

std::optional<OutputStepChoice> resolveRomOutputStep(Config& config, const ModalModel& model,
                                                     double bytes_per_sample) {
  if (config.output.step_s || !config.simulation.adaptive) return std::nullopt;
  const OutputStepChoice choice = outputStepForModel(config, model, bytes_per_sample);
  config.output.step_s = choice.step_s;
  return choice;
}

}  // namespace mastrom::rom
