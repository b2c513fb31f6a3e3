// The nonlinear full order at one design, reduced to the metrics of a screen (docs/theory.md §4.5):
// what `mastrom optimize` holds its ROM optimum against, with the full order's own estimate of its
// error beside every value.
//
// The deployment metrics and stresses come from the run `simulate` makes (adaptive steps,
// continuous peaks of r), with two settings matched to what the ROM reports:
//  * the interface stresses at every accepted step, not only at the output instants — the ROM's
//    stress peaks are those of its continuous response, and the interfaces ring within a fraction
//    of a millisecond of each jump of θ̈, between the outputs (as the tail runs of `mastrom uq`);
//  * the first step after the start and after every breakpoint (simulation.time_step, the steps
//    the error control cannot judge: docs/theory.md §5.3) cut to 1/20 of the period of the
//    highest mode the drive excites where it is longer than 1/10 of it (the rule of the default
//    output step, §5.4a, on the modes of the mast locked at the start angle). A database's base
//    configuration may carry any time_step — its build never integrates — and a first step of 1 ms
//    on coarse Scheme 1 made the full order's peak r 82 % high.
// Its error estimate is the rule of §5.5 applied to every metric: a second run at
// 8 × simulation.tolerance with the unjudged steps twice as long
// (fullorder/deployment_accuracy.hpp), e ≈ |m(8 tol) − m(tol)| / 3. A fixed-step configuration has
// none (NaN).
//
// The natural frequencies frequency_K are the full order's modal solve (what `mastrom modes`
// computes: the mast locked at the deployed angle drive.angle_deg, its static equilibrium,
// linearisation and constrained eigenproblem with the configuration's backend), made only when a
// frequency is asked for. Their error estimate is the eigen-solver's: a pair with relative
// projected residual ρ has |Δω²| ≤ ρ ω² (symmetric pencil), so |Δf| ≤ ρ f / 2.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/config.hpp"
#include "fullorder/deployment.hpp"
#include "fullorder/deployment_result.hpp"
#include "fullorder/interface_stress.hpp"
#include "fullorder/mast_model.hpp"
#include "rom/model/output_resolution.hpp"

namespace mastrom::rom {

struct FullOrderCheck {
  std::vector<double> values;           ///< per requested metric; NaN where the full order has none
  std::vector<double> estimated_error;  ///< per metric, absolute; NaN without an estimate
  double wall_s = 0.0;                  ///< the run at the configuration's tolerance
  double estimate_wall_s = 0.0;         ///< the second run, at 8 × the tolerance
  double modes_wall_s = 0.0;            ///< the modal solves: the first step's and the frequencies'
  double first_step_s = 0.0;  ///< the first step after each breakpoint the run took (0: fixed)
  /// Why first_step_s is shorter than simulation.time_step (empty when it is not).
  std::string first_step_note;
};

/// The full order at a design: `config` (the database's configuration at the point) and the
/// metric names asked for. A function type so that the rounds of `mastrom optimize` can be run
/// against another truth (tests inject one that disagrees by a known amount).
using FullOrderTruth =
    std::function<FullOrderCheck(const Config& config, const std::vector<std::string>& names)>;

/// The screen's names of a full-order run's values: the deployment metrics, the interfaces' peak
/// von Mises stresses, their max and, when the configuration sets material.yield_strength, the
/// smallest margin of safety; the mass of the configuration (exact).
std::map<std::string, double> fullOrderValuesByName(
    const fullorder::DeploymentMetrics& metrics,
    const std::optional<fullorder::InterfaceStressResult>& stresses, const Config& config);

/// One full-order run with the interface stresses at every accepted step (see the header), as the
/// check and the tail runs of `mastrom uq` make it.
struct FullOrderStressRun {
  fullorder::DeploymentSeries series;
  fullorder::DeploymentStatistics statistics;
  fullorder::DeploymentMetrics metrics;
  fullorder::InterfaceStressResult stresses;  ///< at the output instants of `series`
};
/// Run `options` (deploymentFromConfig of `config`, its step control possibly changed; any state
/// observer is replaced) on `model`, the mast of `config`.
FullOrderStressRun runWithStressesAtEveryStep(fullorder::MastModel& model,
                                              fullorder::DeploymentOptions options,
                                              const Config& config,
                                              const fullorder::DeploymentProgress& progress = {});
/// The natural frequency index K of a metric named frequency_K; 0 for any other name.
int frequencyMetricIndex(const std::string& name);

/// The first step for a run of `config`: simulation.time_step, cut to 1/20 of the period of the
/// highest mode the drive excites where it is longer than 1/10 of it (see the header); `note`
/// says why when it is cut. With the
/// SLEPc backend a modes::SlepcSession must be alive.
double resolvedFirstStep(const Config& config, std::string& note);
/// The same from the output-step choice of `config` already made (its excited mode): no modal
/// solve.
double resolvedFirstStep(const Config& config, const OutputStepChoice& choice, std::string& note);

/// Run the full order of `config` and, for adaptive steps, the second run of its estimate; the
/// modal solve when `names` holds a frequency. `progress` as for the run (both runs report).
FullOrderCheck checkWithFullOrder(const Config& config, const std::vector<std::string>& names,
                                  const fullorder::DeploymentProgress& progress = {});

}  // namespace mastrom::rom
