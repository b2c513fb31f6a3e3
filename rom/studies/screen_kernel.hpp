// The per-design loop shared by both kinds of ROM screen: a tensor grid of designs (`mastrom
// screen`, rom/studies/screening.hpp) and an explicit list of designs (rom/studies/design_screen.hpp, what the
// Python module's RomDatabase.screen runs). Both reduce each design to the same metrics through the
// same calls, so a design screened either way gives the same numbers bit for bit.
//
// A design is a point of the database's parameter space plus a "free case": one combination of the
// free keys' values (drive law, timing), i.e. one deployment to run. Free cases are few and shared
// by many designs; each is validated once and its drive sampled once (SampledDriveCache).
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common/config.hpp"
#include "fullorder/deployment_result.hpp"
#include "fullorder/drive_law.hpp"
#include "rom/database/interpolation_method.hpp"
#include "rom/database/rom_database.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/model/modal_stepping.hpp"
#include "rom/studies/design_description.hpp"
#include "rom/studies/design_metrics.hpp"

namespace mastrom::rom {

/// One combination of the free keys' values: the deployment it asks for.
struct FreeCase {
  fullorder::DriveLaw drive;
  ModalDeploymentOptions options;
  double drive_end_s;
  std::optional<double> yield_strength_pa;  ///< material.yield_strength of the combination
};

/// The strength columns of a screen (docs/theory.md §6.5): the peak von Mises stress of every
/// interface and their max when the database carries stress modes (and the method recovers them),
/// the smallest margin of safety when the configuration sets material.yield_strength.
struct ScreenStressColumns {
  int interfaces = 0;
  bool margin = false;
};
ScreenStressColumns screenStressColumns(const RomDatabase& db, const Config& base,
                                        InterpolationMethod method);

/// base with one combination of free-key overrides; InputError "<context>the combination a=1, b=2
/// is invalid: <reason>" when the configuration refuses it.
/// The ROM step of a screen [s], when the user does not set output.step: with the continuous
/// metrics (PeakResolution::Continuous: peaks refined between the samples, the RMS integrated
/// exactly, the settling time the last exit from the band; docs/theory.md §4.2–4.2b) the step sets
/// the cost, not the answer. What is left is the first-order hold of the smooth forcing (θ̇²,
/// gravity, a smooth law's θ̈): O(Δ²), and where a kink train of the hold meets a mode near a
/// multiple of 1/Δ, a small artificial ringing. Measured at 2 ms against 10 µs screens (192
/// five-parameter designs × 4 laws; 108 Scheme 3 designs × 3 laws with stresses): every metric of
/// r within 2.1e-4 of max(value, settling band), the settling time within 7e-8 s, force and torque
/// within 1e-5, the interface stress peaks within 8e-5 (at 1 ms they read up to 0.23 % high:
/// the samples' parabola polish before the refinement, docs/theory.md §6.5). A smooth law's RMS of
/// r, far below the band, can be a few per cent off relative to itself (3 % of 5e-6 rad/s²).
inline constexpr double kDefaultScreenStepS = 2e-3;
/// Designs whose models (with stress rows) a screen interpolates at once: their rows summed block
/// by block while one block of every sample's rows stays in cache, so every sample's rows are read
/// from memory once a batch (64 designs × 0.5 MB of rows on the five-parameter Scheme 3 database:
/// 32 MB a rank; 64 instead of 16 measured 10 % less CPU time for the whole stress screen, the same
/// models bit for bit).
inline constexpr long kStressInterpolationBatch = 64;

/// The ROM step [s] of a screen's deployments: step_s, unless it is ≤ 0, the peaks are the
/// samples' (sample metrics need the configuration's own output step) or `overrides` set the
/// output interval themselves (output.step, output.every or simulation.time_step); 0 then, for
/// the configuration's output interval. Independent of the full order's adaptive or fixed steps.
double screenStep(const std::vector<std::string>& overrides, double step_s, PeakResolution peaks);

/// A user's explicit screen step (option `name`, e.g. "--step"): finite, > 0, and not given
/// together with an override of the output interval (InputError, one line).
void checkScreenStep(double step_s, const std::vector<std::string>& overrides,
                     const std::string& name);

Config applyCombination(const Config& base, const std::vector<std::string>& overrides,
                        const std::string& context);

/// The free case of a configuration carrying that combination, its deployments stepped at step_s
/// when > 0 (else the configuration's output interval). InputError when the record ends before
/// the drive does (the residual vibration would not be measured).
FreeCase freeCaseOf(const Config& config, double step_s = 0.0);

/// The sampled drive of each free case (rom/model/modal_stepping.hpp), computed when a design first needs
/// it and shared by all the designs that use it. All are kept while they fit in kKeepAllBytes;
/// beyond that only the most recent one (designs of one case are usually contiguous).
class SampledDriveCache {
public:
  explicit SampledDriveCache(const std::vector<FreeCase>& cases);
  const SampledDrive& get(std::size_t i);

private:
  static constexpr double kKeepAllBytes = 256.0 * 1024 * 1024;
  const std::vector<FreeCase>& cases_;
  std::vector<std::unique_ptr<SampledDrive>> slots_;
  bool keep_all_ = true;
  std::size_t last_ = static_cast<std::size_t>(-1);
};

/// The columns of a screen table (rom/studies/design_metrics.hpp): the deployment's metrics, the
/// strength columns, and the mass and frequencies when `describer` is given.
MetricColumns screenColumns(const ScreenStressColumns& stress,
                            const DesignDescriber* describer = nullptr);

/// Metric names of a screen table, in DeploymentMetrics order then the strength columns, and their
/// SI units (designMetrics of screenColumns(stress, describer)).
std::vector<std::string> screenMetricNames(const ScreenStressColumns& stress = {},
                                           const DesignDescriber* describer = nullptr);
std::vector<std::string> screenMetricUnits(const ScreenStressColumns& stress = {},
                                           const DesignDescriber* describer = nullptr);

/// Where design d sits: its parameter point (one value per database axis) and its free case.
using DesignDecoder = std::function<void(long design, std::vector<double>& point, long& free_case)>;

/// The metrics of designs [first, last), appended to `out` in design order (screenMetricNames()
/// per design). `progress`, if set, gets (done, last − first) after every design. `describer`, if
/// set, adds each design's mass and frequencies (its free case index = the decoder's).
void screenDesignRange(const ModalInterpolator& interpolator, const std::vector<FreeCase>& cases,
                       PeakResolution peaks, long first, long last, const DesignDecoder& decode,
                       const std::function<void(long, long)>& progress, std::vector<double>& out,
                       const ScreenStressColumns& stress = {},
                       const DesignDescriber* describer = nullptr);

}  // namespace mastrom::rom
