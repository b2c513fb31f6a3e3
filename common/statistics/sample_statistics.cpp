#include "common/statistics/sample_statistics.hpp"

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>

#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace mastrom::stats {

double normalCriticalValue(double confidence) {
  MASTROM_REQUIRE(confidence > 0.0 && confidence < 1.0, UsageError, "confidence ", confidence,
                  " outside (0, 1)");
  return gsl_cdf_ugaussian_Pinv(0.5 * (1.0 + confidence));
}

SampleSummary summarize(std::vector<double> values, const std::vector<double>& levels,
                        double confidence) {
  const std::size_t n = values.size();
  MASTROM_REQUIRE(n >= 2, UsageError, "summarize: ", n, " values (at least 2)");
  for (const double v : values)
    MASTROM_REQUIRE(std::isfinite(v), UsageError, "summarize: a value is not finite");
  const double z = normalCriticalValue(confidence);
  const double nd = static_cast<double>(n);
  SampleSummary s;
  s.count = n;
  const double mean = gsl_stats_mean(values.data(), 1, n);
  const double sd = gsl_stats_sd_m(values.data(), 1, n, mean);
  const double half_mean = z * sd / std::sqrt(nd);
  s.mean = {mean, mean - half_mean, mean + half_mean};
  // Var(s) ≈ (m₄ − σ⁴) / (4 σ² n); m₄ = (kurtosis + 3) σ⁴ with GSL's excess kurtosis.
  double half_sd = 0.0;
  if (sd > 0.0) {
    const double excess = gsl_stats_kurtosis_m_sd(values.data(), 1, n, mean, sd);
    const double m4_over_s4 = std::max(excess + 3.0, 1.0);
    half_sd = z * sd * std::sqrt((m4_over_s4 - 1.0) / (4.0 * nd));
  }
  s.std_dev = {sd, std::max(0.0, sd - half_sd), sd + half_sd};

  gsl_sort(values.data(), 1, n);
  s.quantile_levels = levels;
  for (const double p : levels) {
    MASTROM_REQUIRE(p > 0.0 && p < 1.0, UsageError, "quantile level ", p, " outside (0, 1)");
    const double q = gsl_stats_quantile_from_sorted_data(values.data(), 1, n, p);
    // Ranks (1-based) of the order statistics that bracket q_p with the binomial's normal bounds.
    const double spread = z * std::sqrt(nd * p * (1.0 - p));
    const auto rank = [n](double r) {
      return static_cast<std::size_t>(std::clamp(r, 1.0, static_cast<double>(n))) - 1;
    };
    const std::size_t lo = rank(std::floor(nd * p - spread));
    const std::size_t hi = rank(std::ceil(nd * p + spread) + 1.0);
    s.quantiles.push_back({q, std::min(values[lo], q), std::max(values[hi], q)});
  }
  return s;
}

Interval proportionInterval(std::size_t hits, std::size_t count, double confidence) {
  MASTROM_REQUIRE(count >= 1 && hits <= count, UsageError, "proportionInterval: ", hits, " of ",
                  count);
  const double z = normalCriticalValue(confidence);
  const double n = static_cast<double>(count), p = static_cast<double>(hits) / n;
  const double z2n = z * z / n;
  const double centre = (p + 0.5 * z2n) / (1.0 + z2n);
  const double half = z / (1.0 + z2n) * std::sqrt(p * (1.0 - p) / n + 0.25 * z2n / n);
  // At no hits (all hits) the lower (upper) end is 0 (1) exactly, not a rounding of centre ∓ half.
  return {p, hits == 0 ? 0.0 : std::max(0.0, centre - half),
          hits == count ? 1.0 : std::min(1.0, centre + half)};
}

}  // namespace mastrom::stats
