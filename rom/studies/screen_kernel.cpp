#include "rom/studies/screen_kernel.hpp"

#include "common/error.hpp"
#include "fullorder/mast_config.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/database/parameter_space.hpp"

namespace mastrom::rom {

Config applyCombination(const Config& base, const std::vector<std::string>& overrides,
                        const std::string& context) {
  try {
    return applyOverrides(base, overrides);
  } catch (const InputError& e) {
    std::string which;
    for (const std::string& o : overrides) which += (which.empty() ? "" : ", ") + o;
    throw InputError(detail::concat(context, "the combination ", which, " is invalid: ", e.what()));
  }
}

FreeCase freeCaseOf(const Config& c) {
  MASTROM_REQUIRE(c.simulation.end_time_s >= c.drive.duration_s, InputError,
                  "screen: simulation.end_time = ", c.simulation.end_time_s,
                  " s ends before the drive does (drive.duration = ", c.drive.duration_s,
                  " s): the residual vibration would not be measured");
  return {fullorder::DriveLaw(fullorder::driveFromConfig(c)), deploymentOptionsFromConfig(c),
          c.drive.duration_s};
}

SampledDriveCache::SampledDriveCache(const std::vector<FreeCase>& cases)
    : cases_(cases), slots_(cases.size()) {
  double bytes = 0.0;
  for (const FreeCase& c : cases)
    bytes += (c.options.end_time_s / c.options.step_s + 2.0) * sizeof(SampledDrive::Sample);
  keep_all_ = bytes <= kKeepAllBytes;
}

const SampledDrive& SampledDriveCache::get(std::size_t i) {
  if (!slots_[i]) {
    if (!keep_all_ && last_ < slots_.size()) slots_[last_].reset();
    slots_[i] = std::make_unique<SampledDrive>(sampleDrive(cases_[i].drive, cases_[i].options));
  }
  last_ = i;
  return *slots_[i];
}

std::vector<std::string> screenMetricNames() {
  return {"peak_abs_end_angular_acceleration",
          "peak_rel_end_angular_acceleration",
          "rms_rel_end_angular_acceleration",
          "residual_rel_end_angular_acceleration",
          "settling_time",
          "settled",
          "peak_joint_force",
          "peak_drive_torque",
          "drive_end_time",
          "settling_band"};
}

const std::vector<std::string>& screenMetricUnits() {
  static const std::vector<std::string> units{
      "rad/s^2", "rad/s^2", "rad/s^2", "rad/s^2", "s", "flag", "N", "N*m", "s", "rad/s^2"};
  return units;
}

void appendMetricValues(const fullorder::DeploymentMetrics& m, std::vector<double>& out) {
  out.push_back(m.peak_abs_end_angular_acceleration);
  out.push_back(m.peak_rel_end_angular_acceleration);
  out.push_back(m.rms_rel_end_angular_acceleration);
  out.push_back(m.residual_rel_end_angular_acceleration);
  out.push_back(m.settling_time);
  out.push_back(m.settled ? 1.0 : 0.0);
  out.push_back(m.peak_joint_force);
  out.push_back(m.peak_drive_torque);
  out.push_back(m.drive_end_time);
  out.push_back(m.settling_band);
}

void screenDesignRange(const ModalInterpolator& interpolator, const std::vector<FreeCase>& cases,
                       PeakResolution peaks, long first, long last, const DesignDecoder& decode,
                       const std::function<void(long, long)>& progress, std::vector<double>& out) {
  SampledDriveCache sampled_drives(cases);
  std::vector<double> point;
  long free_index = 0;
  for (long d = first; d < last; ++d) {
    decode(d, point, free_index);
    const FreeCase& fc = cases[static_cast<std::size_t>(free_index)];
    const ModalModel model = interpolator.evaluate(point);
    const SampledDrive& sampled = sampled_drives.get(static_cast<std::size_t>(free_index));
    appendMetricValues(
        modalDeploymentMetrics(model, sampled, fc.options.coriolis_coupling, fc.drive_end_s,
                               fullorder::kDefaultSettlingBandRadS2, peaks),
        out);
    if (progress) progress(d - first + 1, last - first);
  }
}

}  // namespace mastrom::rom
