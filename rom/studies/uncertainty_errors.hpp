// The ROM's error at each sample of an uncertainty study, per metric, and the exceedance
// probabilities with and without it (docs/theory.md §7.3).
//
// The database estimates, at any point, the relative error of ω₁ and the NRMSE of the relative end
// angular acceleration r (the upper values e⁺ of (4.13)/(4.14), rom/interpolation/
// point_error_estimate.hpp). A metric's absolute error bound at the sample is taken from them:
//  * the peaks, RMS and residual of r, the joint force, the drive torque and the interfaces' peak
//    von Mises stresses (all linear in the modal response): e⁺ · |value|;
//  * the margin of safety M = Y/σ − 1, with σ within a factor 1 ± e⁺: (1 + M) e⁺ / (1 − e⁺);
//  * a frequency [Hz]: e_ω₁ · |value|;
//  * the settling time and flag, the drive's end, the settling band, masses (exact or not a
//    response): no bound (0), and the metric is marked as having none.
// A sample counts towards the conservative probability of "METRIC > V" when value + bound > V,
// of "METRIC < V" when value − bound < V: the probability that the event cannot be excluded.
#pragma once

#include "rom/studies/uncertainty_study.hpp"

namespace mastrom::rom {

/// Fill r.metric_error and r.metric_has_error from r.rom_error (rank 0's result).
void metricErrorBounds(UqResult& r);

/// The probability of `limit` over r.statistic_rows, plain and conservative, with Wilson
/// intervals at `confidence`, and the critical sample.
LimitProbability limitProbability(const UqResult& r, const ColumnCondition& limit,
                                  double confidence);

/// Whether `value` satisfies the limit's condition (NaN never does).
bool limitHolds(const ColumnCondition& limit, double value);

}  // namespace mastrom::rom
