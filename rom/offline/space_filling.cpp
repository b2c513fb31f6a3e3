// Halton points and box corners (see space_filling.hpp).
#include "rom/offline/space_filling.hpp"

#include "common/error.hpp"

namespace mastrom::rom {

Eigen::VectorXd haltonPoint(long index, int p) {
  static constexpr int kPrimes[] = {2,  3,  5,  7,  11, 13, 17, 19, 23, 29,
                                    31, 37, 41, 43, 47, 53, 59, 61, 67, 71};
  MASTROM_REQUIRE(p >= 1 && p <= 20 && index >= 0, InputError, "rom: Halton point ", index,
                  " in ", p, " dimensions (1 to 20)");
  Eigen::VectorXd u(p);
  for (int a = 0; a < p; ++a) {
    const int base = kPrimes[a];
    double f = 1.0, r = 0.0;
    for (long i = index; i > 0; i /= base) {
      f /= base;
      r += f * static_cast<double>(i % base);
    }
    u[a] = r;
  }
  return u;
}

std::vector<Eigen::VectorXd> unitBoxCorners(int p) {
  std::vector<Eigen::VectorXd> corners;
  if (p > 16) return corners;
  for (long c = 0; c < (1L << p); ++c) {
    Eigen::VectorXd u(p);
    for (int a = 0; a < p; ++a) u[a] = static_cast<double>((c >> a) & 1);
    corners.push_back(std::move(u));
  }
  return corners;
}

}  // namespace mastrom::rom
