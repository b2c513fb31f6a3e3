// An interface's stress rows times a block of sample states (stress_block_product.hpp).
#include "rom/model/stress_block_product.hpp"

#include <cstring>

#include "common/cpu_features.hpp"

namespace mastrom::rom::stress_detail {
namespace {

#if MASTROM_HAVE_AVX2_KERNELS
/// Y = B X for a block of `count` samples (B: rows × inputs, X: inputs × count, Y: rows × count,
/// all column-major and contiguous; rows a multiple of 4) with AVX2 + FMA: four samples at a time,
/// one accumulator per sample, each column of B loaded once per four samples. The build's
/// baseline ISA leaves Eigen's product at SSE2 (most of a `rom eval` with stresses; measurements in
/// benchmarks/README.md).
__attribute__((target("avx2,fma"))) void blockProductAvx2(const double* __restrict b, long rows,
                                                          long inputs, const double* __restrict x,
                                                          long count, double* __restrict y) {
  long c = 0;
  for (; c + 4 <= count; c += 4) {
    const double* x0 = x + c * inputs;
    const double* x1 = x0 + inputs;
    const double* x2 = x1 + inputs;
    const double* x3 = x2 + inputs;
    for (long r = 0; r < rows; r += 4) {
      Pack4 a0 = {0.0, 0.0, 0.0, 0.0}, a1 = a0, a2 = a0, a3 = a0;
      for (long j = 0; j < inputs; ++j) {
        Pack4 column;
        std::memcpy(&column, b + j * rows + r, sizeof(Pack4));
        const double v0 = x0[j], v1 = x1[j], v2 = x2[j], v3 = x3[j];
        a0 += column * Pack4{v0, v0, v0, v0};
        a1 += column * Pack4{v1, v1, v1, v1};
        a2 += column * Pack4{v2, v2, v2, v2};
        a3 += column * Pack4{v3, v3, v3, v3};
      }
      std::memcpy(y + c * rows + r, &a0, sizeof(Pack4));
      std::memcpy(y + (c + 1) * rows + r, &a1, sizeof(Pack4));
      std::memcpy(y + (c + 2) * rows + r, &a2, sizeof(Pack4));
      std::memcpy(y + (c + 3) * rows + r, &a3, sizeof(Pack4));
    }
  }
  for (; c < count; ++c) {
    const double* xc = x + c * inputs;
    for (long r = 0; r < rows; r += 4) {
      Pack4 a = {0.0, 0.0, 0.0, 0.0};
      for (long j = 0; j < inputs; ++j) {
        Pack4 column;
        std::memcpy(&column, b + j * rows + r, sizeof(Pack4));
        const double v = xc[j];
        a += column * Pack4{v, v, v, v};
      }
      std::memcpy(y + c * rows + r, &a, sizeof(Pack4));
    }
  }
}
#endif

}  // namespace

void stressBlockProduct(const Eigen::MatrixXd& rows, const Eigen::MatrixXd& states,
                        Eigen::Index first, Eigen::Index count, Eigen::MatrixXd& y) {
#if MASTROM_HAVE_AVX2_KERNELS
  if (cpuHasAvx2Fma() && rows.rows() % 4 == 0) {
    blockProductAvx2(rows.data(), rows.rows(), rows.cols(), states.data() + first * states.rows(),
                     count, y.data());
    return;
  }
#endif
  y.leftCols(count).noalias() = rows * states.middleCols(first, count);
}

}  // namespace mastrom::rom::stress_detail
