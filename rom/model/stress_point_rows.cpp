// A point's six stress rows at a state (stress_point_rows.hpp).
#include "rom/model/stress_point_rows.hpp"

#include <cstring>

#include "common/cpu_features.hpp"
#include "rom/model/modal_stress.hpp"

namespace mastrom::rom::stress_detail {

static_assert(kStressRowsPerPoint == 6, "pointRows sums six rows");

namespace {

#if MASTROM_HAVE_AVX2_KERNELS
/// Rows 0–3 in one pack of four, rows 4–5 in a pack of two.
__attribute__((target("avx2"))) void pointRowsAvx2(const double* __restrict rows,
                                                   Eigen::Index stride, const double* __restrict x,
                                                   int inputs, double* __restrict y) {
  Pack4 y0123 = {0.0, 0.0, 0.0, 0.0};
  Pack2 y45 = {0.0, 0.0};
  for (int j = 0; j < inputs; ++j) {
    Pack4 r0123;
    Pack2 r45;
    std::memcpy(&r0123, rows + stride * j, sizeof(Pack4));
    std::memcpy(&r45, rows + stride * j + 4, sizeof(Pack2));
    y0123 += r0123 * (Pack4{} + x[j]);
    y45 += r45 * (Pack2{} + x[j]);
  }
  std::memcpy(y, &y0123, sizeof(Pack4));
  std::memcpy(y + 4, &y45, sizeof(Pack2));
}
#endif

}  // namespace

void pointRows(const double* rows, Eigen::Index column_stride, const double* x, int inputs,
               double* y) {
#if MASTROM_HAVE_AVX2_KERNELS
  if (cpuHasAvx2Fma()) return pointRowsAvx2(rows, column_stride, x, inputs, y);
#endif
  Pack2 y01 = {0.0, 0.0}, y23 = y01, y45 = y01;  // three pairs of rows
  for (int j = 0; j < inputs; ++j) {
    Pack2 r01, r23, r45;
    const double* column = rows + column_stride * j;
    std::memcpy(&r01, column, sizeof(Pack2));
    std::memcpy(&r23, column + 2, sizeof(Pack2));
    std::memcpy(&r45, column + 4, sizeof(Pack2));
    const Pack2 v = Pack2{} + x[j];
    y01 += r01 * v;
    y23 += r23 * v;
    y45 += r45 * v;
  }
  std::memcpy(y, &y01, sizeof(Pack2));
  std::memcpy(y + 2, &y23, sizeof(Pack2));
  std::memcpy(y + 4, &y45, sizeof(Pack2));
}

}  // namespace mastrom::rom::stress_detail
