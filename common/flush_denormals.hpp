// A scope in which the floating-point unit flushes subnormal numbers to zero.
//
// Why: the exact modal stepping (rom/model/modal_stepping.hpp) lets every mode's free vibration
// decay as e^{−ζωt}. After the drive stops, the higher modes (ζω of hundreds per second) fall through
// the subnormal range (below 2.2e-308) within a second or two, and on x86 every arithmetic
// operation on a subnormal operand takes a microcode assist of the order of a hundred cycles. An
// 8 s deployment at a 0.1 ms output step spent 80 % of its time there (perf: 15 ms → 3 ms per
// deployment of 20 modes with the flush on; docs/theory.md §4.2). A value below 2.2e-308 of a
// quantity whose scale is one is zero for every output, so flushing changes no result beyond
// the subnormal range itself.
//
// x86-64: the MXCSR bits FTZ (results) and DAZ (operands); AArch64: FPCR.FZ. Elsewhere a no-op.
// The mode is per thread, so the guard goes where a thread does the stepping, and it restores the
// caller's mode on exit (exceptions included).
#pragma once

#if defined(__x86_64__) || defined(__SSE2__)
#include <xmmintrin.h>
#endif

namespace mastrom {

class FlushDenormalsScope {
 public:
  FlushDenormalsScope() {
#if defined(__x86_64__) || defined(__SSE2__)
    saved_ = _mm_getcsr();
    _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero);
#elif defined(__aarch64__) && defined(__GNUC__)
    saved_ = __builtin_aarch64_get_fpcr64();
    __builtin_aarch64_set_fpcr64(saved_ | kFpcrFlushToZero);
#endif
  }
  ~FlushDenormalsScope() {
#if defined(__x86_64__) || defined(__SSE2__)
    _mm_setcsr(saved_);
#elif defined(__aarch64__) && defined(__GNUC__)
    __builtin_aarch64_set_fpcr64(saved_);
#endif
  }
  FlushDenormalsScope(const FlushDenormalsScope&) = delete;
  FlushDenormalsScope& operator=(const FlushDenormalsScope&) = delete;

 private:
#if defined(__x86_64__) || defined(__SSE2__)
  static constexpr unsigned kFlushToZero = 0x8000, kDenormalsAreZero = 0x0040;
  unsigned saved_ = 0;
#elif defined(__aarch64__) && defined(__GNUC__)
  static constexpr unsigned long long kFpcrFlushToZero = 1ull << 24;
  unsigned long long saved_ = 0;
#endif
};

}  // namespace mastrom
