// The per-mode passes of the exact modal stepping (modal_stepping.hpp, stepping_detail): one step
// of the 2 × 2 maps, η̈ from the equation of motion, the forcing from its drive scalars and its
// first-order hold between two instants. With the output contraction they are most of a screen's
// deployment (perf at 2 ms, 20 modes: ≈ 25 % of it), so each is compiled twice
// (common/cpu_features.hpp): the baseline copy on packs of two doubles evaluates every element in
// the order of the Eigen array expressions it replaced (the results are bit-identical to theirs),
// the AVX2 + FMA copy on packs of four. The fused multiply-adds change the round-off (screen
// metrics within 7e-13 of the baseline's, relative to max(value, settling band)); an AVX2 copy
// without them gave the baseline's bits but measured ≈ 5 % slower on the whole deployment.
#include <cstring>

#include "common/cpu_features.hpp"
#include "rom/model/modal_stepping.hpp"

namespace mastrom::rom::stepping_detail {
namespace {

// Each body is a template over the pack (Pack2 or Pack4 and its width), inlined into a baseline
// and an AVX2 function; the last k mod width modes go through the same formulas on scalars. Packs
// are loaded before anything is stored, so outputs may be the inputs (in place).

/// One step; with an `accel` array also η̈ = f1 − 2ζω η̇ − ω² η at the new state, from the
/// registers (the same operations as accelerationBody, so the same bits).
template <typename Pack, int Width>
MASTROM_ALWAYS_INLINE void stepBody(const ModalStepping::Maps& m, const ModalStepping* ms, long k,
                                    const double* e, const double* v, const double* f0,
                                    const double* f1, double* e_out, double* v_out,
                                    double* accel) {
  const double* damping = ms != nullptr ? ms->damping.data() : nullptr;
  const double* stiffness = ms != nullptr ? ms->stiffness.data() : nullptr;
  long i = 0;
  for (; i + Width <= k; i += Width) {
    Pack a00, a01, a10, a11, b00, b01, b10, b11, pe, pv, p0, p1;
    std::memcpy(&a00, m.a00.data() + i, sizeof(Pack));
    std::memcpy(&a01, m.a01.data() + i, sizeof(Pack));
    std::memcpy(&a10, m.a10.data() + i, sizeof(Pack));
    std::memcpy(&a11, m.a11.data() + i, sizeof(Pack));
    std::memcpy(&b00, m.b00.data() + i, sizeof(Pack));
    std::memcpy(&b01, m.b01.data() + i, sizeof(Pack));
    std::memcpy(&b10, m.b10.data() + i, sizeof(Pack));
    std::memcpy(&b11, m.b11.data() + i, sizeof(Pack));
    std::memcpy(&pe, e + i, sizeof(Pack));
    std::memcpy(&pv, v + i, sizeof(Pack));
    std::memcpy(&p0, f0 + i, sizeof(Pack));
    std::memcpy(&p1, f1 + i, sizeof(Pack));
    const Pack next_e = a00 * pe + a01 * pv + b00 * p0 + b10 * p1;
    const Pack next_v = a10 * pe + a11 * pv + b01 * p0 + b11 * p1;
    std::memcpy(e_out + i, &next_e, sizeof(Pack));
    std::memcpy(v_out + i, &next_v, sizeof(Pack));
    if (accel != nullptr) {
      Pack pd, ps;
      std::memcpy(&pd, damping + i, sizeof(Pack));
      std::memcpy(&ps, stiffness + i, sizeof(Pack));
      const Pack out = p1 - pd * next_v - ps * next_e;
      std::memcpy(accel + i, &out, sizeof(Pack));
    }
  }
  for (; i < k; ++i) {
    const double next_e = m.a00[i] * e[i] + m.a01[i] * v[i] + m.b00[i] * f0[i] + m.b10[i] * f1[i];
    const double next_v = m.a10[i] * e[i] + m.a11[i] * v[i] + m.b01[i] * f0[i] + m.b11[i] * f1[i];
    e_out[i] = next_e;
    v_out[i] = next_v;
    if (accel != nullptr) accel[i] = f1[i] - damping[i] * next_v - stiffness[i] * next_e;
  }
}

template <typename Pack, int Width>
MASTROM_ALWAYS_INLINE void accelerationBody(const ModalStepping& ms, const double* f,
                                            const double* e, const double* v, double* a) {
  const long k = ms.modes;
  const double* damping = ms.damping.data();
  const double* stiffness = ms.stiffness.data();
  long i = 0;
  for (; i + Width <= k; i += Width) {
    Pack pf, pe, pv, pd, ps;
    std::memcpy(&pf, f + i, sizeof(Pack));
    std::memcpy(&pe, e + i, sizeof(Pack));
    std::memcpy(&pv, v + i, sizeof(Pack));
    std::memcpy(&pd, damping + i, sizeof(Pack));
    std::memcpy(&ps, stiffness + i, sizeof(Pack));
    const Pack out = pf - pd * pv - ps * pe;
    std::memcpy(a + i, &out, sizeof(Pack));
  }
  for (; i < k; ++i) a[i] = f[i] - damping[i] * v[i] - stiffness[i] * e[i];
}

template <typename Pack, int Width>
MASTROM_ALWAYS_INLINE void forcingBody(const ModalStepping& ms, const ForcingScalars& p,
                                       double* f) {
  const long k = ms.modes;
  const double* gamma = ms.gamma.data();
  const double* gamma_c = ms.gamma_c.data();
  const double* lx = ms.momentum_x.data();
  const double* ly = ms.momentum_y.data();
  // The Eigen expressions were −θ̈Γ − θ̇²Γ_c, then + (g_x L_x + g_y L_y) with gravity.
  const double acc = -p.acc, rate2 = p.rate2, gx = p.gx, gy = p.gy;
  Pack m_acc, m_rate2, m_gx, m_gy;
  for (int j = 0; j < Width; ++j) {
    m_acc[j] = acc;
    m_rate2[j] = rate2;
    m_gx[j] = gx;
    m_gy[j] = gy;
  }
  long i = 0;
  for (; i + Width <= k; i += Width) {
    Pack g, gc;
    std::memcpy(&g, gamma + i, sizeof(Pack));
    std::memcpy(&gc, gamma_c + i, sizeof(Pack));
    Pack out = m_acc * g - m_rate2 * gc;
    if (ms.gravity) {
      Pack px, py;
      std::memcpy(&px, lx + i, sizeof(Pack));
      std::memcpy(&py, ly + i, sizeof(Pack));
      out = out + (m_gx * px + m_gy * py);
    }
    std::memcpy(f + i, &out, sizeof(Pack));
  }
  for (; i < k; ++i) {
    double out = acc * gamma[i] - rate2 * gamma_c[i];
    if (ms.gravity) out = out + (gx * lx[i] + gy * ly[i]);
    f[i] = out;
  }
}

template <typename Pack, int Width>
MASTROM_ALWAYS_INLINE void forcingBetweenBody(long k, const double* f0, const double* f1,
                                              double sigma, double* f) {
  Pack m_sigma;
  for (int j = 0; j < Width; ++j) m_sigma[j] = sigma;
  long i = 0;
  for (; i + Width <= k; i += Width) {
    Pack p0, p1;
    std::memcpy(&p0, f0 + i, sizeof(Pack));
    std::memcpy(&p1, f1 + i, sizeof(Pack));
    const Pack out = p0 + (p1 - p0) * m_sigma;
    std::memcpy(f + i, &out, sizeof(Pack));
  }
  for (; i < k; ++i) f[i] = f0[i] + (f1[i] - f0[i]) * sigma;
}

#if MASTROM_HAVE_AVX2_KERNELS
__attribute__((target("avx2,fma"))) void stepAvx2(const ModalStepping::Maps& m,
                                                       const ModalStepping* ms, long k,
                                                       const double* e, const double* v,
                                                       const double* f0, const double* f1,
                                                       double* e_out, double* v_out,
                                                       double* accel) {
  stepBody<Pack4, 4>(m, ms, k, e, v, f0, f1, e_out, v_out, accel);
}
__attribute__((target("avx2,fma"))) void accelerationAvx2(const ModalStepping& ms, const double* f,
                                                          const double* e, const double* v,
                                                          double* a) {
  accelerationBody<Pack4, 4>(ms, f, e, v, a);
}
__attribute__((target("avx2,fma"))) void forcingAvx2(const ModalStepping& ms,
                                                     const ForcingScalars& p, double* f) {
  forcingBody<Pack4, 4>(ms, p, f);
}
__attribute__((target("avx2,fma"))) void forcingBetweenAvx2(long k, const double* f0,
                                                         const double* f1, double sigma,
                                                         double* f) {
  forcingBetweenBody<Pack4, 4>(k, f0, f1, sigma, f);
}
#endif

}  // namespace

void stepModes(const ModalStepping::Maps& maps, long k, const double* e, const double* v,
               const double* f0, const double* f1, double* e_out, double* v_out) {
#if MASTROM_HAVE_AVX2_KERNELS
  if (cpuHasAvx2Fma()) return stepAvx2(maps, nullptr, k, e, v, f0, f1, e_out, v_out, nullptr);
#endif
  stepBody<Pack2, 2>(maps, nullptr, k, e, v, f0, f1, e_out, v_out, nullptr);
}

void stepModesWithAccelerations(const ModalStepping& ms, const ModalStepping::Maps& maps,
                                const double* e, const double* v, const double* f0,
                                const double* f1, double* e_out, double* v_out, double* accel) {
#if MASTROM_HAVE_AVX2_KERNELS
  if (cpuHasAvx2Fma()) return stepAvx2(maps, &ms, ms.modes, e, v, f0, f1, e_out, v_out, accel);
#endif
  stepBody<Pack2, 2>(maps, &ms, ms.modes, e, v, f0, f1, e_out, v_out, accel);
}

void modalAccelerations(const ModalStepping& ms, const double* f, const double* e, const double* v,
                        double* a) {
#if MASTROM_HAVE_AVX2_KERNELS
  if (cpuHasAvx2Fma()) return accelerationAvx2(ms, f, e, v, a);
#endif
  accelerationBody<Pack2, 2>(ms, f, e, v, a);
}

void modalForcing(const ModalStepping& ms, const ForcingScalars& p, double* f) {
#if MASTROM_HAVE_AVX2_KERNELS
  if (cpuHasAvx2Fma()) return forcingAvx2(ms, p, f);
#endif
  forcingBody<Pack2, 2>(ms, p, f);
}

void modalForcingBetween(long k, const double* f0, const double* f1, double sigma, double* f) {
#if MASTROM_HAVE_AVX2_KERNELS
  if (cpuHasAvx2Fma()) return forcingBetweenAvx2(k, f0, f1, sigma, f);
#endif
  forcingBetweenBody<Pack2, 2>(k, f0, f1, sigma, f);
}

}  // namespace mastrom::rom::stepping_detail
