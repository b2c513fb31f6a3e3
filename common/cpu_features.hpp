// Run-time CPU feature check for the few kernels compiled twice — for the baseline ISA and, with
// __attribute__((target("avx2,fma"))), for AVX2 + FMA (fullorder/supernodal_cholesky.cpp,
// fullorder/schur_complement.cpp, rom/model/modal_deployment.cpp, output_contraction.cpp,
// and modal_step_kernels.cpp;
// fullorder/shell_force_batch.cpp compiles its kernel's AVX2 copy inside a target region, so that
// its helpers are AVX2 code too).
// The choice is an ordinary branch on a flag computed once, not an ifunc, so it behaves the same
// under sanitizers and with either compiler. MASTROM_BASELINE_ISA=1 in the environment forces the
// baseline copies, so that the suite can check them on a machine that has AVX2
// (scripts/run_tests.sh documents it).
#pragma once

#include <cstdlib>
#include <cstring>

#if defined(__GNUC__)
/// For the bodies of the kernels compiled twice: inlined into each compiled copy, so every copy is
/// compiled for its own instruction set.
#define MASTROM_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define MASTROM_ALWAYS_INLINE inline
#endif

#if defined(__GNUC__)
namespace mastrom {
/// Two and four doubles as one GNU vector — one SSE2 / one AVX register — for the arithmetic of
/// the kernels compiled twice (element-wise operators; memcpy loads and stores them unaligned).
typedef double Pack2 __attribute__((vector_size(2 * sizeof(double))));
typedef double Pack4 __attribute__((vector_size(4 * sizeof(double))));
}  // namespace mastrom
#endif

namespace mastrom {

#if defined(__GNUC__) && defined(__x86_64__)
#define MASTROM_HAVE_AVX2_KERNELS 1
/// True when the CPU executes AVX2 and FMA instructions and MASTROM_BASELINE_ISA is not set to 1.
inline bool cpuHasAvx2Fma() {
  static const bool has = [] {
    const char* baseline = std::getenv("MASTROM_BASELINE_ISA");
    if (baseline != nullptr && std::strcmp(baseline, "1") == 0) return false;
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  }();
  return has;
}
#else
#define MASTROM_HAVE_AVX2_KERNELS 0
inline bool cpuHasAvx2Fma() { return false; }
#endif

}  // namespace mastrom
