#include "common/statistics/unit_sampler.hpp"

#include <cmath>
#include <limits>

#include "common/error.hpp"

namespace mastrom::stats {

std::optional<SamplingKind> parseSamplingKind(std::string_view name) {
  if (name == "sobol") return SamplingKind::Sobol;
  if (name == "mc") return SamplingKind::MonteCarlo;
  return std::nullopt;
}

std::string toString(SamplingKind kind) { return kind == SamplingKind::Sobol ? "sobol" : "mc"; }

UnitSampler::UnitSampler(SamplingKind kind, int dimension, unsigned long seed)
    : kind_(kind), dimension_(dimension), rng_(gsl_rng_alloc(gsl_rng_mt19937)) {
  MASTROM_REQUIRE(
      dimension >= 1 && (kind == SamplingKind::MonteCarlo || dimension <= kMaxSobolDimension),
      UsageError, "UnitSampler: dimension ", dimension, " outside 1 … ", kMaxSobolDimension,
      " (GSL's Sobol sequence)");
  gsl_rng_set(rng_.get(), seed);
  if (kind == SamplingKind::Sobol) {
    qrng_.reset(gsl_qrng_alloc(gsl_qrng_sobol, static_cast<unsigned>(dimension)));
    shift_.resize(static_cast<std::size_t>(dimension));
    for (double& s : shift_) s = gsl_rng_uniform(rng_.get());
  }
}

void UnitSampler::next(double* x) {
  if (kind_ == SamplingKind::MonteCarlo) {
    for (int i = 0; i < dimension_; ++i) x[i] = gsl_rng_uniform_pos(rng_.get());
    return;
  }
  gsl_qrng_get(qrng_.get(), x);
  constexpr double tiny = std::numeric_limits<double>::min();
  for (int i = 0; i < dimension_; ++i) {
    double v = x[i] + shift_[static_cast<std::size_t>(i)];
    v -= std::floor(v);
    x[i] = v > 0.0 ? v : tiny;  // (0, 1): the inverse CDFs are infinite at 0
  }
}

}  // namespace mastrom::stats
