// The distributions of uncertain inputs ([uncertainty], common/config.hpp UncertainInput;
// docs/theory.md §7.1) as inverse cumulative distribution functions: a point u ∈ (0, 1) of a
// uniform (quasi-)random sequence becomes a sample x = F⁻¹(u), so one unit hypercube sequence
// serves every input whatever its law. GSL's gsl_cdf_* inverses do the work.
#pragma once

#include "common/config.hpp"

namespace mastrom::stats {

/// x = F⁻¹(u) of the input's distribution, u ∈ (0, 1) (values at or beyond the ends are clamped to
/// the representable open interval).
double inverseCdf(const UncertainInput& input, double u);

/// F(x): the probability that the input is ≤ x.
double cdf(const UncertainInput& input, double x);

/// The distribution's mean and standard deviation (of the value, in the key's unit).
double distributionMean(const UncertainInput& input);
double distributionStdDev(const UncertainInput& input);

}  // namespace mastrom::stats
