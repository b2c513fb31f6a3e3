#include "rom/studies/screen_kernel.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "common/error.hpp"
#include "common/option_names.hpp"
#include "fullorder/interface_stress.hpp"
#include "fullorder/mast_config.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/database/stress_arrays.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/model/modal_stress_response.hpp"
#include "rom/model/stress_blocks.hpp"

namespace mastrom::rom {

namespace {

/// Whether an override sets the output interval: output.step (adaptive configurations) or
/// output.every / simulation.time_step (fixed-step ones).
bool setsOutputInterval(const std::string& override_text) {
  std::string key = override_text.substr(0, override_text.find('='));
  key.erase(std::remove_if(key.begin(), key.end(), [](unsigned char c) { return std::isspace(c); }),
            key.end());
  return key == "output.step" || key == "output.every" || key == "simulation.time_step";
}

}  // namespace

double screenStep(const std::vector<std::string>& overrides, double step_s,
                  PeakResolution peaks) {
  if (!(step_s > 0.0) || peaks != PeakResolution::Continuous) return 0.0;
  if (std::any_of(overrides.begin(), overrides.end(), setsOutputInterval)) return 0.0;
  return step_s;
}

void checkScreenStep(double step_s, const std::vector<std::string>& overrides,
                     const std::string& name) {
  MASTROM_REQUIRE(std::isfinite(step_s) && step_s > 0.0, InputError, name, " ", step_s,
                  " s; allowed: > 0");
  for (const std::string& o : overrides)
    MASTROM_REQUIRE(!setsOutputInterval(o), InputError, name, " ", step_s, " and ",
                    optionName(Option::Set), " ", o, " both set the ROM step; give one");
}

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

FreeCase freeCaseOf(const Config& c, double step_s) {
  MASTROM_REQUIRE(c.simulation.end_time_s >= c.drive.duration_s, InputError,
                  "screen: simulation.end_time = ", c.simulation.end_time_s,
                  " s ends before the drive does (drive.duration = ", c.drive.duration_s,
                  " s): the residual vibration would not be measured");
  ModalDeploymentOptions options = deploymentOptionsFromConfig(c);
  if (step_s > 0.0) options.step_s = step_s;
  return {fullorder::DriveLaw(fullorder::driveFromConfig(c)), options, c.drive.duration_s,
          c.material.yield_strength_pa};
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

ScreenStressColumns screenStressColumns(const RomDatabase& db, const Config& base,
                                        InterpolationMethod method) {
  ScreenStressColumns c;
  // An affine database recovers them from its basis's stress rows (docs/theory.md (6.9a)); one
  // written by an earlier mastrom has none.
  const bool affine_without_rows =
      method == InterpolationMethod::Affine && (!db.affine || db.affine->stress_rows.size() == 0);
  if (affine_without_rows || !databaseHasStresses(db)) return c;
  c.interfaces = db.samples.front().modal.stress.interfaceCount();
  c.margin = base.material.yield_strength_pa.has_value();
  return c;
}

MetricColumns screenColumns(const ScreenStressColumns& stress, const DesignDescriber* describer) {
  if (describer) return describer->columns(stress.interfaces, stress.margin);
  MetricColumns c;
  c.stress_interfaces = stress.interfaces;
  c.margin = stress.margin;
  return c;
}

std::vector<std::string> screenMetricNames(const ScreenStressColumns& stress,
                                           const DesignDescriber* describer) {
  return metricNames(designMetrics(screenColumns(stress, describer)));
}

std::vector<std::string> screenMetricUnits(const ScreenStressColumns& stress,
                                           const DesignDescriber* describer) {
  return metricUnits(designMetrics(screenColumns(stress, describer)));
}

void screenDesignRange(const ModalInterpolator& interpolator, const std::vector<FreeCase>& cases,
                       PeakResolution peaks, long first, long last, const DesignDecoder& decode,
                       const std::function<void(long, long)>& progress, std::vector<double>& out,
                       const ScreenStressColumns& stress, const DesignDescriber* describer) {
  const std::vector<MetricDefinition> metrics = designMetrics(screenColumns(stress, describer));
  DesignValues values;
  SampledDriveCache sampled_drives(cases);
  std::vector<double> point;
  long free_index = 0;
  std::vector<char> no_polish;  // of the free case no_polish_case
  long no_polish_case = -1;
  // With stresses the models are interpolated a batch of designs at a time: on a scattered
  // database every design's stress rows combine every sample's, and a batch reads those once
  // (ModalInterpolator::evaluateWithStressesAt; the same models bit for bit).
  std::vector<ModalModel> batch;
  std::vector<std::vector<double>> batch_points;
  long batch_first = first;
  for (long d = first; d < last; ++d) {
    if (stress.interfaces > 0 && d - batch_first >= static_cast<long>(batch.size())) {
      batch_points.clear();
      long unused_case = 0;
      for (long e = d; e < std::min(last, d + kStressInterpolationBatch); ++e) {
        decode(e, point, unused_case);
        batch_points.push_back(point);
      }
      batch = interpolator.evaluateWithStressesAt(batch_points);
      batch_first = d;
    }
    decode(d, point, free_index);
    const FreeCase& fc = cases[static_cast<std::size_t>(free_index)];
    const ModalModel model = stress.interfaces > 0
                                 ? std::move(batch[static_cast<std::size_t>(d - batch_first)])
                                 : interpolator.evaluate(point);
    const SampledDrive& sampled = sampled_drives.get(static_cast<std::size_t>(free_index));
    if (stress.interfaces == 0) {
      values.deployment =
          modalDeploymentMetrics(model, sampled, fc.options.coriolis_coupling, fc.drive_end_s,
                                 fullorder::kDefaultSettlingBandRadS2, peaks);
    } else {
      // The metrics' own pass keeps the state at the start of every block of steps and a bound
      // of the stresses over it; the peaks' search re-steps only the blocks that can hold a peak
      // (rom/model/stress_blocks.hpp: the peaks of every sample's recorded state).
      const ModalStressEvaluator evaluator(model);
      StressBlockRecord record(evaluator, model, sampled, fc.options.coriolis_coupling);
      const ModalBlockObserver observe = record.observer();
      values.deployment =
          modalDeploymentMetrics(model, sampled, fc.options.coriolis_coupling, fc.drive_end_s,
                                 fullorder::kDefaultSettlingBandRadS2, peaks, nullptr, &observe);
      if (free_index != no_polish_case) {
        no_polish = samplesNearBreakpoints(sampled);
        no_polish_case = free_index;
      }
      values.peak_von_mises_pa.clear();
      for (const ModalStressEvaluator::Peak& p : record.peaks(no_polish))
        values.peak_von_mises_pa.push_back(p.von_mises_pa);
      const std::vector<double>& vm = values.peak_von_mises_pa;
      MASTROM_REQUIRE(static_cast<int>(vm.size()) == stress.interfaces, NumericalError,
                      "screen: ", vm.size(), " interface stresses for ", stress.interfaces,
                      " interfaces");
      const double largest = *std::max_element(vm.begin(), vm.end());
      if (stress.margin) {
        // A combination without a yield strength cannot occur: the base sets it and an override
        // can only change it (config validation refuses a value <= 0).
        values.min_margin_of_safety =
            fullorder::marginOfSafety(fc.yield_strength_pa.value_or(0.0), largest);
      }
    }
    if (describer)
      describer->describe(interpolator, model, point, static_cast<std::size_t>(free_index), values);
    appendMetricValues(metrics, values, out);
    if (progress) progress(d - first + 1, last - first);
  }
}

}  // namespace mastrom::rom
