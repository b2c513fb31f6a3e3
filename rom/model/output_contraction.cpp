// The metrics' output contractions, compiled for the baseline ISA and for AVX2 + FMA
// (output_contraction.hpp).
#include "rom/model/output_contraction.hpp"

#include <cstring>

#include "common/cpu_features.hpp"
#include "rom/model/state_contraction.hpp"

namespace mastrom::rom::metrics_detail {
namespace {

/// SSE2: the 14 used rows as seven packs of two (η: packs 0–1, η̇: 2–3, η̈: 4–6), the modes in
/// order — per row the same sequence of products and sums as the Eigen column updates it
/// replaced, so the results are bit-identical to theirs.
void contractBaseline(long modes, const double* __restrict rows, const double* __restrict eta,
                      const double* __restrict eta_dot, const double* __restrict eta_ddot,
                      double* __restrict y) {
  contraction_detail::contractInOrder<7, 2, 2>(modes, OutputContraction::kRows, rows, eta, eta_dot,
                                               eta_ddot, y);
  y[14] = y[15] = 0.0;
}

#if MASTROM_HAVE_AVX2_KERNELS
/// AVX2 + FMA: four packs of four rows (η, η̇, η̈ twice), even and odd modes in separate
/// accumulators: a chain of dependent fused multiply-adds is half as long (20 modes: 10 × 4
/// cycles instead of 20 × 4), and the eight chains fill both FMA ports.
__attribute__((target("avx2,fma"))) void contractAvx2(long modes, const double* __restrict rows,
                                                      const double* __restrict eta,
                                                      const double* __restrict eta_dot,
                                                      const double* __restrict eta_ddot,
                                                      double* __restrict y) {
  constexpr int kRows = OutputContraction::kRows;
  // Named accumulators, not an array: an array was cleared with `rep stos` in memory (≈ 10 % of
  // the kernel) instead of living in registers.
  Pack4 e0 = {0.0, 0.0, 0.0, 0.0}, e1 = e0, e2 = e0, e3 = e0;  // even modes
  Pack4 o0 = e0, o1 = e0, o2 = e0, o3 = e0;                    // odd modes
  long i = 0;
  for (; i + 2 <= modes; i += 2) {
    const double* col = rows + kRows * i;
    Pack4 c0, c1, c2, c3, d0, d1, d2, d3;
    std::memcpy(&c0, col, sizeof(Pack4));
    std::memcpy(&c1, col + 4, sizeof(Pack4));
    std::memcpy(&c2, col + 8, sizeof(Pack4));
    std::memcpy(&c3, col + 12, sizeof(Pack4));
    std::memcpy(&d0, col + 16, sizeof(Pack4));
    std::memcpy(&d1, col + 20, sizeof(Pack4));
    std::memcpy(&d2, col + 24, sizeof(Pack4));
    std::memcpy(&d3, col + 28, sizeof(Pack4));
    const double ea = eta[i], va = eta_dot[i], aa = eta_ddot[i];
    const double eb = eta[i + 1], vb = eta_dot[i + 1], ab = eta_ddot[i + 1];
    e0 += c0 * Pack4{ea, ea, ea, ea};
    e1 += c1 * Pack4{va, va, va, va};
    e2 += c2 * Pack4{aa, aa, aa, aa};
    e3 += c3 * Pack4{aa, aa, aa, aa};
    o0 += d0 * Pack4{eb, eb, eb, eb};
    o1 += d1 * Pack4{vb, vb, vb, vb};
    o2 += d2 * Pack4{ab, ab, ab, ab};
    o3 += d3 * Pack4{ab, ab, ab, ab};
  }
  if (i < modes) {  // the last mode of an odd count
    const double* col = rows + kRows * i;
    Pack4 c0, c1, c2, c3;
    std::memcpy(&c0, col, sizeof(Pack4));
    std::memcpy(&c1, col + 4, sizeof(Pack4));
    std::memcpy(&c2, col + 8, sizeof(Pack4));
    std::memcpy(&c3, col + 12, sizeof(Pack4));
    const double ea = eta[i], va = eta_dot[i], aa = eta_ddot[i];
    e0 += c0 * Pack4{ea, ea, ea, ea};
    e1 += c1 * Pack4{va, va, va, va};
    e2 += c2 * Pack4{aa, aa, aa, aa};
    e3 += c3 * Pack4{aa, aa, aa, aa};
  }
  e0 += o0;
  e1 += o1;
  e2 += o2;
  e3 += o3;
  std::memcpy(y, &e0, sizeof(Pack4));
  std::memcpy(y + 4, &e1, sizeof(Pack4));
  std::memcpy(y + 8, &e2, sizeof(Pack4));
  std::memcpy(y + 12, &e3, sizeof(Pack4));
}
#endif

}  // namespace

OutputContraction::OutputContraction(const ModalModel& m)
    : modes_(m.modeCount()), rows_(static_cast<std::size_t>(kRows * m.modeCount()), 0.0) {
  for (long i = 0; i < modes_; ++i) {
    double* col = rows_.data() + kRows * i;
    col[kEta + 0] = col[kRate + 0] = m.momentum_participation(0, i);
    col[kEta + 1] = col[kRate + 1] = m.momentum_participation(1, i);
    col[kEta + 2] = col[kRate + 2] = m.centrifugal_participation[i];
    col[kAcc + 0] = m.end_rotation(2, i);
    for (int r = 0; r < 3; ++r) col[kAcc + 1 + r] = m.momentum_participation(r, i);
    col[kAcc + 4] = m.rotation_participation[i];
  }
}

void OutputContraction::apply(const double* eta, const double* eta_dot, const double* eta_ddot,
                              double* y) const {
#if MASTROM_HAVE_AVX2_KERNELS
  if (cpuHasAvx2Fma()) return contractAvx2(modes_, rows_.data(), eta, eta_dot, eta_ddot, y);
#endif
  contractBaseline(modes_, rows_.data(), eta, eta_dot, eta_ddot, y);
}

}  // namespace mastrom::rom::metrics_detail
