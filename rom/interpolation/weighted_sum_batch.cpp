// weightedSumBatch (weighted_sum_batch.hpp).
#include "rom/interpolation/weighted_sum_batch.hpp"

#include <algorithm>

namespace mastrom::rom {

void weightedSumBatch(const std::vector<const double*>& a, long size,
                      const std::vector<double>& weights, const std::vector<double*>& out) {
  const long sources = static_cast<long>(a.size());
  // Blocks of entries small enough that one block of every source (sources × 2 KB) stays in the
  // L2 cache while every point's block is summed: each source entry is read from memory once.
  constexpr long kBlock = 256;
  for (long i0 = 0; i0 < size; i0 += kBlock) {
    const long len = std::min(kBlock, size - i0);
    for (std::size_t b = 0; b < out.size(); ++b) {
      double* o = out[b] + i0;
      const double* w = weights.data() + static_cast<long>(b) * sources;
      std::fill(o, o + len, 0.0);
      for (long n = 0; n < sources; ++n) {
        const double wn = w[n];
        const double* src = a[static_cast<std::size_t>(n)] + i0;
        for (long i = 0; i < len; ++i) o[i] += wn * src[i];
      }
    }
  }
}

}  // namespace mastrom::rom
