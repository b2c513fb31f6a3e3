// Weighted sums of the same arrays at several points at once: out_b = Σ_n w_bn a_n, the sum taken
// in the order of n for every element (the order and the operations of a loop `out += w_n a_n`
// started from zero), so a sum's bits do not depend on how many points share the call. What a
// screen interpolates the stress rows with (docs/theory.md §6.5): on a scattered database every
// design combines every sample's rows (100 samples × 65 000 entries), and one pass over the
// samples' rows for a batch of designs reads them once per batch instead of once per design.
#pragma once

#include <vector>

namespace mastrom::rom {

/// out[b][i] = Σ_n weights[b · sources + n] · a[n][i], i < size, for every b < out.size();
/// a.size() = sources. Each out[b] is written (not accumulated into).
void weightedSumBatch(const std::vector<const double*>& a, long size,
                      const std::vector<double>& weights, const std::vector<double*>& out);

}  // namespace mastrom::rom
