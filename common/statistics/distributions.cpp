#include "common/statistics/distributions.hpp"

#include <gsl/gsl_cdf.h>
#include <gsl/gsl_randist.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace mastrom::stats {
namespace {

/// A lognormal X with mean m and standard deviation s: ln X ~ N(ζ, σ²) with
/// σ² = ln(1 + s²/m²), ζ = ln m − σ²/2 (docs/theory.md (7.1)).
void lognormalParameters(const UncertainInput& in, double& zeta, double& sigma) {
  const double cv = *in.std_dev / *in.mean;
  sigma = std::sqrt(std::log1p(cv * cv));
  zeta = std::log(*in.mean) - 0.5 * sigma * sigma;
}

/// Standardised truncation bounds a = (lower − μ)/σ, b = (upper − μ)/σ.
void truncationBounds(const UncertainInput& in, double& a, double& b) {
  a = (*in.lower - *in.mean) / *in.std_dev;
  b = (*in.upper - *in.mean) / *in.std_dev;
}

/// The standard normal truncated to [a, b] at probability u: Φ⁻¹(Φ(a) + u (Φ(b) − Φ(a))). Taken
/// in the lower tail (mirrored when the interval lies mostly above 0) so that Φ never rounds to 1.
double truncatedStandardNormal(double a, double b, double u) {
  if (a + b > 0.0) return -truncatedStandardNormal(-b, -a, 1.0 - u);
  const double pa = gsl_cdf_ugaussian_P(a), pb = gsl_cdf_ugaussian_P(b);
  const double z = gsl_cdf_ugaussian_Pinv(pa + u * (pb - pa));
  return std::clamp(z, a, b);
}

/// Mean and standard deviation of the truncated normal, with Z = Φ(b) − Φ(a):
/// μ + σ (φ(a) − φ(b))/Z and σ √(1 + (a φ(a) − b φ(b))/Z − ((φ(a) − φ(b))/Z)²).
std::pair<double, double> truncatedNormalMoments(const UncertainInput& in) {
  double a = 0.0, b = 0.0;
  truncationBounds(in, a, b);
  const double z = gsl_cdf_ugaussian_P(b) - gsl_cdf_ugaussian_P(a);
  const double pa = gsl_ran_ugaussian_pdf(a), pb = gsl_ran_ugaussian_pdf(b);
  const double shift = (pa - pb) / z;
  return {*in.mean + *in.std_dev * shift,
          *in.std_dev * std::sqrt(1.0 + (a * pa - b * pb) / z - shift * shift)};
}

}  // namespace

double inverseCdf(const UncertainInput& in, double u) {
  constexpr double tiny = std::numeric_limits<double>::epsilon();
  u = std::clamp(u, tiny, 1.0 - tiny);
  switch (in.distribution) {
    case DistributionKind::Normal:
      return *in.mean + gsl_cdf_gaussian_Pinv(u, *in.std_dev);
    case DistributionKind::Lognormal: {
      double zeta = 0.0, sigma = 0.0;
      lognormalParameters(in, zeta, sigma);
      return gsl_cdf_lognormal_Pinv(u, zeta, sigma);
    }
    case DistributionKind::Uniform:
      return gsl_cdf_flat_Pinv(u, *in.lower, *in.upper);
    case DistributionKind::TruncatedNormal: {
      double a = 0.0, b = 0.0;
      truncationBounds(in, a, b);
      return std::clamp(*in.mean + *in.std_dev * truncatedStandardNormal(a, b, u), *in.lower,
                        *in.upper);
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double cdf(const UncertainInput& in, double x) {
  switch (in.distribution) {
    case DistributionKind::Normal:
      return gsl_cdf_gaussian_P(x - *in.mean, *in.std_dev);
    case DistributionKind::Lognormal: {
      double zeta = 0.0, sigma = 0.0;
      lognormalParameters(in, zeta, sigma);
      return x <= 0.0 ? 0.0 : gsl_cdf_lognormal_P(x, zeta, sigma);
    }
    case DistributionKind::Uniform:
      return gsl_cdf_flat_P(x, *in.lower, *in.upper);
    case DistributionKind::TruncatedNormal: {
      double a = 0.0, b = 0.0;
      truncationBounds(in, a, b);
      const double z = std::clamp((x - *in.mean) / *in.std_dev, a, b);
      const double pa = gsl_cdf_ugaussian_P(a), pb = gsl_cdf_ugaussian_P(b);
      return (gsl_cdf_ugaussian_P(z) - pa) / (pb - pa);
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double distributionMean(const UncertainInput& in) {
  switch (in.distribution) {
    case DistributionKind::Normal:
    case DistributionKind::Lognormal:
      return *in.mean;
    case DistributionKind::Uniform:
      return 0.5 * (*in.lower + *in.upper);
    case DistributionKind::TruncatedNormal:
      return truncatedNormalMoments(in).first;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

double distributionStdDev(const UncertainInput& in) {
  switch (in.distribution) {
    case DistributionKind::Normal:
    case DistributionKind::Lognormal:
      return *in.std_dev;
    case DistributionKind::Uniform:
      return (*in.upper - *in.lower) / std::sqrt(12.0);
    case DistributionKind::TruncatedNormal:
      return truncatedNormalMoments(in).second;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace mastrom::stats
