// The baseline-ISA kernel of the modal output contractions y = W_η η + W_η̇ η̇ + W_η̈ η̈ (a few
// rows each; rom/model/modal_deployment.cpp for the series, output_contraction.cpp for the
// metrics): each compiles it for its own row layout and pairs it with an AVX2 + FMA copy of its
// own (common/cpu_features.hpp). Not part of the library's interface.
#pragma once

#include <cstring>

#include "common/cpu_features.hpp"

namespace mastrom::rom::contraction_detail {

/// y[0 … 2·Packs) = Σ_i rows_i ⊙ s_i with rows_i the i-th column of `rows` (stride doubles apart)
/// and s_i = η_i for the first EtaPacks packs of two rows, η̇_i for the next RatePacks and η̈_i for
/// the rest. One independent accumulator per pack (the additions do not wait on each other) and
/// the modes in order, so every row is the plain sequence of products and sums of a column-by-
/// column product. The states are read once per mode as scalars and broadcast in registers: a
/// variant broadcasting straight from memory measured ≈ 8 % slower overall (the series, 20 modes),
/// presumably because η, η̇, η̈ were just stored by the stepping and broadcast loads miss store
/// forwarding. Columns need only 16-byte alignment: memcpy loads them.
template <int Packs, int EtaPacks, int RatePacks>
MASTROM_ALWAYS_INLINE void contractInOrder(long modes, long stride, const double* __restrict rows,
                                           const double* __restrict eta,
                                           const double* __restrict eta_dot,
                                           const double* __restrict eta_ddot,
                                           double* __restrict y) {
  static_assert(EtaPacks + RatePacks <= Packs, "more state packs than packs");
  Pack2 acc[Packs];
  for (int p = 0; p < Packs; ++p) acc[p] = Pack2{0.0, 0.0};
  for (long i = 0; i < modes; ++i) {
    const double e = eta[i], v = eta_dot[i], a = eta_ddot[i];
    const Pack2 m_e = {e, e}, m_v = {v, v}, m_a = {a, a};
    const double* col = rows + stride * i;
#pragma GCC unroll 16
    for (int p = 0; p < Packs; ++p) {
      Pack2 column;
      std::memcpy(&column, col + 2 * p, sizeof(Pack2));
      // Known at compile time once unrolled.
      acc[p] += column * (p < EtaPacks ? m_e : (p < EtaPacks + RatePacks ? m_v : m_a));
    }
  }
#pragma GCC unroll 16
  for (int p = 0; p < Packs; ++p) std::memcpy(y + 2 * p, &acc[p], sizeof(Pack2));
}

}  // namespace mastrom::rom::contraction_detail
