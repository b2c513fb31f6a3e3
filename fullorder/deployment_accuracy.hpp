// The metrics of a full-order run with what it knows of its own accuracy (docs/theory.md §5.5):
// the peaks of its continuous response, and an a-posteriori estimate of its discretisation error.
//
// Estimate. With the local error controlled per step (fullorder/step_control.hpp), the global
// error of a second-order scheme falls like tol^(2/3) (the steps like tol^(1/3)). A second run of
// the same case at 8·tol therefore has about 4 times the error, mostly of the same shape (the phase
// lag of the same ringing), so the error of the run at tol is estimated as a third of the
// difference of the two: e(tol) ≈ (r_{8 tol} − r_tol)/3 — the NRMSE of the relative end angular
// acceleration and the relative errors of the peaks. The second run costs about half the first.
// The steps the controller does not judge — the first ones after the start and after every
// breakpoint take simulation.time_step (step_control.hpp), and the largest step is a cap, not a
// judgement — are coarsened with it, by 8^(1/3) = 2:
// a local error ∝ h³ makes 8·tol and 2·h the same coarsening. Without that, the error of a first
// step too long for the ringing it starts is the same in both runs and the estimate misses it (on
// coarse Scheme 1 with a 1 ms first step: peak r 82 % high, estimated 4 %).
// (Summing the local error estimates instead was tried and overestimated the measured NRMSE by a
// factor ≈ 22 on Scheme 1: local errors of quiet stretches do not add to the error of the ringing.)
#pragma once

#include <vector>

#include "fullorder/deployment.hpp"
#include "fullorder/deployment_result.hpp"

namespace mastrom::fullorder {

/// computeMetrics() of the output series, with the continuous peaks and the error estimates of an
/// adaptive run (statistics from simulateDeployment; a fixed-step run reports its sample peaks and
/// no estimate).
DeploymentMetrics fullOrderMetrics(const DeploymentSeries& series,
                                   const DeploymentStatistics& statistics,
                                   double drive_end_time_s);
/// The same from the metrics of the output samples (a streamed run's MetricsAccumulator).
DeploymentMetrics fullOrderMetrics(DeploymentMetrics sample_metrics,
                                   const DeploymentStatistics& statistics);

/// The factor of the estimate's second run on the steps no estimate judges (the first steps, the
/// largest step): the controlled steps' own, (looser_tolerance / tolerance)^(1/3) (see above).
double looserStepFactor(double tolerance, double looser_tolerance);

/// Fill the estimated_* fields of `metrics` (of `series`, an adaptive run of `model` with
/// `options`) from a second run at 8 times the tolerance (see above). InputError for a fixed-step
/// run. `progress` reports the second run.
void estimateDiscretisationError(MastModel& model, const DeploymentOptions& options,
                                 const DeploymentSeries& series, DeploymentMetrics& metrics,
                                 const DeploymentProgress& progress = {});
/// The same from the first run's relative end angular acceleration alone (one value per output
/// instant), for a run whose outputs went to a file as they were computed. The second run keeps
/// no series either, so the estimate's memory is 8 bytes per output instant.
void estimateDiscretisationError(MastModel& model, const DeploymentOptions& options,
                                 const std::vector<double>& relative_rad_s2,
                                 DeploymentMetrics& metrics,
                                 const DeploymentProgress& progress = {});

}  // namespace mastrom::fullorder
