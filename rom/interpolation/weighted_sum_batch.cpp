// weightedSumBatch (weighted_sum_batch.hpp).
#include "rom/interpolation/weighted_sum_batch.hpp"

#include <algorithm>
#include <cstring>

#include "common/cpu_features.hpp"

namespace mastrom::rom {
namespace {

/// o[i] = Σ_n w[n] · a[n][first + i], i < len: every element summed over n in order, each term a
/// product rounded and then added (no fused multiply-add), from zero — the bits of the loop
/// `o += w_n a_n`. Chunks of kPacks packs of Width elements are summed over every source in
/// registers and stored once (the loop before loaded and stored o for every source: ≈ 3.5
/// instructions an element and source, most of a stress screen's interpolation).
template <typename Pack, int Width>
MASTROM_ALWAYS_INLINE void sumBody(const double* const* a, long sources, const double* w,
                                   long first, long len, double* o) {
  constexpr int kPacks = 4;
  constexpr long kChunk = Width * kPacks;
  long i = 0;
  for (; i + kChunk <= len; i += kChunk) {
    Pack acc[kPacks];
    for (int q = 0; q < kPacks; ++q) acc[q] = Pack{} + 0.0;
    for (long n = 0; n < sources; ++n) {
      const Pack wn = Pack{} + w[n];  // w_n in every lane
      const double* src = a[n] + first + i;
      for (int q = 0; q < kPacks; ++q) {
        Pack s;
        std::memcpy(&s, src + q * Width, sizeof(Pack));
        acc[q] += wn * s;
      }
    }
    std::memcpy(o + i, acc, sizeof(acc));
  }
  for (; i < len; ++i) {
    double s = 0.0;
    for (long n = 0; n < sources; ++n) s += w[n] * a[n][first + i];
    o[i] = s;
  }
}

#if MASTROM_HAVE_AVX2_KERNELS
// AVX2 without FMA: the baseline's bits.
__attribute__((target("avx2"))) void sumAvx2(const double* const* a, long sources, const double* w,
                                             long first, long len, double* o) {
  sumBody<Pack4, 4>(a, sources, w, first, len, o);
}
#endif

void sum(const double* const* a, long sources, const double* w, long first, long len, double* o) {
#if MASTROM_HAVE_AVX2_KERNELS
  if (cpuHasAvx2Fma()) return sumAvx2(a, sources, w, first, len, o);
#endif
  sumBody<Pack2, 2>(a, sources, w, first, len, o);
}

}  // namespace

void weightedSumBatch(const std::vector<const double*>& a, long size,
                      const std::vector<double>& weights, const std::vector<double*>& out) {
  const long sources = static_cast<long>(a.size());
  // Blocks of entries small enough that one block of every source (sources × 2 KB) stays in the
  // L2 cache while every point's block is summed: each source entry is read from memory once.
  constexpr long kBlock = 256;
  for (long i0 = 0; i0 < size; i0 += kBlock) {
    const long len = std::min(kBlock, size - i0);
    for (std::size_t b = 0; b < out.size(); ++b)
      sum(a.data(), sources, weights.data() + static_cast<long>(b) * sources, i0, len, out[b] + i0);
  }
}

}  // namespace mastrom::rom
