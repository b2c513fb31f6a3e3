// Summary statistics of a sample with confidence intervals from its size (docs/theory.md §7.3):
// mean, standard deviation, quantiles and exceedance probabilities, each with an interval at a
// given confidence level. The intervals are those of independent samples (plain Monte Carlo):
//  * mean: x̄ ± z s/√n;
//  * standard deviation: s ± z √((m₄ − s⁴)/(4 s² n)) (the delta method on the sample variance,
//    m₄ the fourth central moment: no normality assumed);
//  * quantile q_p: the order statistics x_(l), x_(u) with l, u = n p ∓ z √(n p (1 − p)) (the
//    binomial count of values below q_p; distribution-free);
//  * probability k/n: Wilson's score interval (correct near 0 and 1, where k/n ± z√(p(1−p)/n)
//    collapses to a point).
// z = Φ⁻¹((1 + confidence)/2). For a randomised Sobol sample the estimates' errors are smaller than
// those of independent samples of the same size, so these intervals are conservative there.
// Moments and quantiles come from GSL (gsl_stats_*).
#pragma once

#include <cstddef>
#include <vector>

namespace mastrom::stats {

struct Interval {
  double estimate = 0.0;
  double lower = 0.0;
  double upper = 0.0;
  bool contains(double v) const { return lower <= v && v <= upper; }
  double width() const { return upper - lower; }
};

/// The quantile levels reported by default: 1, 5, 50, 95 and 99 %.
inline const std::vector<double> kDefaultQuantileLevels{0.01, 0.05, 0.50, 0.95, 0.99};

struct SampleSummary {
  std::size_t count = 0;
  Interval mean;
  Interval std_dev;
  std::vector<double> quantile_levels;
  std::vector<Interval> quantiles;  ///< one per level
};

/// z of a two-sided interval at `confidence` ∈ (0, 1).
double normalCriticalValue(double confidence);

/// Mean, standard deviation and quantiles of `values` (at least 2; non-finite values are a
/// UsageError: the caller decides what a failed sample means).
SampleSummary summarize(std::vector<double> values, const std::vector<double>& quantile_levels,
                        double confidence);

/// Wilson's interval of a probability from `hits` of `count` trials.
Interval proportionInterval(std::size_t hits, std::size_t count, double confidence);

}  // namespace mastrom::stats
