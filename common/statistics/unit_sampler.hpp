// Points of the unit hypercube (0, 1)^d for sampling uncertain inputs (docs/theory.md §7.2):
//  * Sobol: GSL's Sobol sequence (gsl_qrng_sobol, Bratley & Fox's directions, d ≤ 40), randomised
//    by one uniform random shift per dimension taken modulo 1 (Cranley–Patterson rotation). The
//    shift keeps the sequence's low discrepancy, makes every estimate unbiased and independent
//    shifts (seeds) give independent replicates; it also moves the sequence's first point off the
//    origin, where an inverse CDF is infinite.
//  * MonteCarlo: independent uniforms (GSL's MT19937).
// Both are deterministic in the seed. next() continues the sequence, so a sample can be extended
// (an adaptive sample size) with the points that a larger sample would have had.
#pragma once

#include <gsl/gsl_qrng.h>
#include <gsl/gsl_rng.h>

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mastrom::stats {

enum class SamplingKind { Sobol, MonteCarlo };
std::optional<SamplingKind> parseSamplingKind(std::string_view name);
std::string toString(SamplingKind kind);

/// The largest dimension GSL's Sobol sequence offers.
inline constexpr int kMaxSobolDimension = 40;

class UnitSampler {
public:
  /// UsageError for dimension < 1 or, with Sobol, > kMaxSobolDimension.
  UnitSampler(SamplingKind kind, int dimension, unsigned long seed);
  int dimension() const { return dimension_; }
  /// The next point, written to x[0 … dimension), each coordinate in (0, 1).
  void next(double* x);

private:
  struct QrngFree {
    void operator()(gsl_qrng* q) const { gsl_qrng_free(q); }
  };
  struct RngFree {
    void operator()(gsl_rng* r) const { gsl_rng_free(r); }
  };
  SamplingKind kind_;
  int dimension_;
  std::unique_ptr<gsl_qrng, QrngFree> qrng_;
  std::unique_ptr<gsl_rng, RngFree> rng_;
  std::vector<double> shift_;
};

}  // namespace mastrom::stats
