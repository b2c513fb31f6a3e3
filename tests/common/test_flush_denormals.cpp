// The flush-to-zero scope of the modal stepping (common/flush_denormals.hpp): inside it a product
// that would be subnormal is zero, outside it is not, and the caller's mode comes back on exit.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>

#include "common/flush_denormals.hpp"

namespace mastrom {
namespace {

/// DBL_MIN × 2⁻¹⁰, computed at run time (volatile operands: no constant folding).
double subnormalProduct() {
  volatile double tiny = DBL_MIN, scale = std::ldexp(1.0, -10);
  return tiny * scale;
}

TEST(FlushDenormals, FlushesInsideTheScopeAndRestoresTheModeOutside) {
#if defined(__x86_64__) || defined(__SSE2__) || defined(__aarch64__)
  ASSERT_EQ(std::fpclassify(subnormalProduct()), FP_SUBNORMAL) << "default mode keeps subnormals";
  {
    const FlushDenormalsScope flush;
    EXPECT_EQ(subnormalProduct(), 0.0);
    {
      const FlushDenormalsScope nested;  // nesting keeps the flush on at the inner exit
    }
    EXPECT_EQ(subnormalProduct(), 0.0);
    volatile double normal = 3.0 * DBL_MIN;  // normal numbers are untouched
    EXPECT_EQ(normal * 0.5, 1.5 * DBL_MIN);
  }
  EXPECT_EQ(std::fpclassify(subnormalProduct()), FP_SUBNORMAL);
#else
  GTEST_SKIP() << "no flush-to-zero control on this architecture";
#endif
}

}  // namespace
}  // namespace mastrom
