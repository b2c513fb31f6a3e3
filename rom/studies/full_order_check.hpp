// The nonlinear full order at one design, reduced to the metrics of a screen (docs/theory.md §4.5):
// what `mastrom optimize` holds its ROM optimum against, with the full order's own estimate of its
// discretisation error beside every value.
//
// The run is fullorder/configured_deployment.hpp (the one `simulate` makes: adaptive steps,
// continuous peaks of r, the interface stresses at the output instants). Its error estimate is the
// rule of docs/theory.md §5.5 applied to every metric: a second run at 8 × simulation.tolerance,
// e ≈ |m(8 tol) − m(tol)| / 3 — the same estimate as the full order's NRMSE in `validate`, here for
// the stresses and loads too. A fixed-step configuration has none (NaN).
#pragma once

#include <string>
#include <vector>

#include "common/config.hpp"
#include "fullorder/configured_deployment.hpp"

namespace mastrom::rom {

struct FullOrderCheck {
  std::vector<double> values;           ///< per requested metric; NaN where the full order has none
  std::vector<double> estimated_error;  ///< per metric, absolute; NaN without an estimate
  double wall_s = 0.0;                  ///< the run at the configuration's tolerance
  double estimate_wall_s = 0.0;         ///< the second run, at 8 × the tolerance
};

/// The metrics `names` (screen names, rom/studies/screen_kernel.hpp) of a full-order run: the
/// deployment metrics, the interfaces' peak von Mises stresses, their max and, when the
/// configuration sets material.yield_strength, the smallest margin of safety. A name the full
/// order does not give is NaN.
std::vector<double> fullOrderMetricValues(const fullorder::ConfiguredDeployment& run,
                                          const Config& config,
                                          const std::vector<std::string>& names);

/// Run the full order of `config` (one design: the database's configuration at the point) and, for
/// adaptive steps, the second run of its estimate. `progress` as for the run (both runs report).
FullOrderCheck checkWithFullOrder(const Config& config, const std::vector<std::string>& names,
                                  const fullorder::DeploymentProgress& progress = {});

}  // namespace mastrom::rom
