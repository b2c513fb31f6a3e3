// ModalStressEvaluator (modal_stress_response.hpp): an interface's stress rows [S | S_res | σ̄] and
// bounds c_j, c_gj of (6.10) from a ModalModel, and the von Mises stresses of a state — at one
// instant, at one station, as a field, and as the history over every sample (docs/theory.md §6.5).
// The best-first search that uses the bounds is in stress_peak_search.cpp.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "common/cpu_features.hpp"
#include "common/error.hpp"
#include "rom/model/modal_stress_response.hpp"
#include "rom/model/stress_stations.hpp"

namespace mastrom::rom {

using stress_detail::stationsOf;

namespace {

/// out = e + μ v, element by element (a multiply, then an add).
template <typename Pack, int Width>
MASTROM_ALWAYS_INLINE void etaPlusDampedRateBody(int k, const double* __restrict e,
                                                 const double* __restrict v, double mu,
                                                 double* __restrict out) {
  const Pack m = Pack{} + mu;  // μ in every lane
  int i = 0;
  for (; i + Width <= k; i += Width) {
    Pack rate, sum;
    std::memcpy(&sum, e + i, sizeof(Pack));
    std::memcpy(&rate, v + i, sizeof(Pack));
    sum += m * rate;  // the product rounded first: no fused multiply-add without FMA enabled
    std::memcpy(out + i, &sum, sizeof(Pack));
  }
  for (; i < k; ++i) out[i] = e[i] + mu * v[i];
}

#if MASTROM_HAVE_AVX2_KERNELS
__attribute__((target("avx2"))) void etaPlusDampedRateAvx2(int k, const double* e, const double* v,
                                                           double mu, double* out) {
  etaPlusDampedRateBody<Pack4, 4>(k, e, v, mu, out);
}
#endif

void etaPlusDampedRate(int k, const double* e, const double* v, double mu, double* out) {
#if MASTROM_HAVE_AVX2_KERNELS
  if (cpuHasAvx2Fma()) return etaPlusDampedRateAvx2(k, e, v, mu, out);
#endif
  etaPlusDampedRateBody<Pack2, 2>(k, e, v, mu, out);
}

/// vonMises2 (stress_stations.hpp) on packs: the same operations in the same order.
template <typename Pack>
MASTROM_ALWAYS_INLINE void vonMises2Pack(const Pack& a, const Pack& b, const Pack& c, Pack& out) {
  out = a * a - a * b + b * b + 3.0 * c * c;
}

/// out[p] = the largest von Mises over the three stations of point p of one stress column (its 6P
/// rows, stress_stations.hpp): Width points at a time, each lane the scalar formula's operations
/// in its order (no fused multiply-adds: the same bits). Runs for every column of every
/// interface of every design of a screen (≈ 10⁴ points × columns a design).
template <typename Pack, int Width>
MASTROM_ALWAYS_INLINE void pointStationMaximaBody(const double* __restrict column, int points,
                                                  double* __restrict out) {
  int p = 0;
  for (; p + Width <= points; p += Width) {
    // Row r of the Width points, transposed into pack r.
    double lanes[kStressRowsPerPoint][Width];
    for (int r = 0; r < kStressRowsPerPoint; ++r)
      for (int l = 0; l < Width; ++l) lanes[r][l] = column[kStressRowsPerPoint * (p + l) + r];
    Pack y[kStressRowsPerPoint];
    std::memcpy(y, lanes, sizeof(y));
    Pack s0, s1, s2;
    vonMises2Pack<Pack>(y[0] - y[3], y[1] - y[4], y[2] - y[5], s0);
    vonMises2Pack<Pack>(y[0], y[1], y[2], s1);
    vonMises2Pack<Pack>(y[0] + y[3], y[1] + y[4], y[2] + y[5], s2);
    const Pack m01 = s0 > s1 ? s0 : s1;
    const Pack m = m01 > s2 ? m01 : s2;
    for (int l = 0; l < Width; ++l) out[p + l] = std::sqrt(m[l]);
  }
  for (; p < points; ++p) {
    double vm2[fullorder::kShellSurfaces];
    stationsOf(column + kStressRowsPerPoint * p, vm2);
    out[p] = std::sqrt(std::max({vm2[0], vm2[1], vm2[2]}));
  }
}

#if MASTROM_HAVE_AVX2_KERNELS
// AVX2 without FMA: the baseline's bits (the bounds prune the exact evaluations; equal bounds keep
// every decision the same).
__attribute__((target("avx2"))) void pointStationMaximaAvx2(const double* column, int points,
                                                            double* out) {
  pointStationMaximaBody<Pack4, 4>(column, points, out);
}
#endif

void pointStationMaxima(const double* column, int points, double* out) {
#if MASTROM_HAVE_AVX2_KERNELS
  if (cpuHasAvx2Fma()) return pointStationMaximaAvx2(column, points, out);
#endif
  pointStationMaximaBody<Pack2, 2>(column, points, out);
}

}  // namespace

ModalStressEvaluator::ModalStressEvaluator(const ModalModel& model) {
  const ModalStress& s = model.stress;
  MASTROM_REQUIRE(!s.empty(), InputError,
                  "rom stresses: the modal model carries no stress modes (a database built "
                  "with --no-stresses or by an earlier mastrom, or the affine method)");
  s.validate(model.modeCount(), /*check_values=*/false);
  modes_ = model.modeCount();
  inputs_ = modes_ + kStressLoadCount + 1;
  damping_s_ = s.damping_s;
  for (int i = 0; i < s.interfaceCount(); ++i) {
    Interface itf;
    itf.points = s.interface_offsets[i + 1] - s.interface_offsets[i];
    const Eigen::Index first = kStressRowsPerPoint * s.interface_offsets[i];
    const Eigen::Index rows = kStressRowsPerPoint * itf.points;
    itf.rows.resize(rows, inputs_);
    itf.rows.leftCols(modes_) = s.modes.middleRows(first, rows);
    itf.rows.middleCols(modes_, kStressLoadCount) = s.loads.middleRows(first, rows);
    itf.rows.col(inputs_ - 1) = s.preload.segment(first, rows);
    // c_pj: the largest von Mises of column j alone over the stations of point p; c_gj the same
    // over cluster g, and c_j over all of them (the bound b of (6.10)).
    const int clusters = (itf.points + kClusterPoints - 1) / kClusterPoints;
    itf.cluster_bound.resize(clusters, inputs_);
    itf.point_bound.resize(itf.points, inputs_);
    // (√ is monotone and correctly rounded: the largest root is the root of the largest square.)
    for (int j = 0; j < inputs_; ++j) {
      pointStationMaxima(itf.rows.col(j).data(), itf.points, itf.point_bound.col(j).data());
      for (int g = 0; g < clusters; ++g) {
        const int first = g * kClusterPoints;
        itf.cluster_bound(g, j) = itf.point_bound.col(j)
                                      .segment(first, std::min(itf.points - first, kClusterPoints))
                                      .maxCoeff();
      }
    }
    itf.bound = itf.cluster_bound.colwise().maxCoeff().transpose();
    interfaces_.push_back(std::move(itf));
  }
}

void ModalStressEvaluator::input(const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
                                 const stepping_detail::ForcingScalars& f,
                                 Eigen::Ref<Eigen::VectorXd> x) const {
  // x = η + μη̇ runs at every output sample of rom eval: the Eigen expression through Ref cost
  // ≈ 140 instructions for 20 modes, the plain loop ≈ 120 (SSE2), the AVX2 copy (multiply, then
  // add: no fused multiply-add, so the same bits) ≈ 30.
  etaPlusDampedRate(modes_, eta.data(), eta_dot.data(), damping_s_, x.data());
  x[modes_] = f.acc;
  x[modes_ + 1] = f.rate2;
  x[modes_ + 2] = f.gx;
  x[modes_ + 3] = f.gy;
  x[modes_ + 4] = 1.0;
}

double ModalStressEvaluator::largest(int i, const Eigen::Ref<const Eigen::VectorXd>& x,
                                     int* station) const {
  return largestAbove(i, x, -std::numeric_limits<double>::infinity(), station);
}

void ModalStressEvaluator::field(int i, const Eigen::Ref<const Eigen::VectorXd>& x,
                                 std::vector<double>& vm) const {
  const Interface& itf = interfaces_[static_cast<std::size_t>(i)];
  const Eigen::VectorXd y = itf.rows * x;
  vm.resize(static_cast<std::size_t>(fullorder::kShellSurfaces * itf.points));
  for (int p = 0; p < itf.points; ++p) {
    double vm2[fullorder::kShellSurfaces];
    stationsOf(y.segment<kStressRowsPerPoint>(kStressRowsPerPoint * p), vm2);
    for (int z = 0; z < fullorder::kShellSurfaces; ++z)
      vm[static_cast<std::size_t>(fullorder::kShellSurfaces * p + z)] = std::sqrt(vm2[z]);
  }
}

double ModalStressEvaluator::station(int i, int station,
                                     const Eigen::Ref<const Eigen::VectorXd>& x) const {
  const Interface& itf = interfaces_[static_cast<std::size_t>(i)];
  const int p = station / fullorder::kShellSurfaces, z = station % fullorder::kShellSurfaces;
  const Eigen::Matrix<double, kStressRowsPerPoint, 1> y =
      itf.rows.middleRows<kStressRowsPerPoint>(kStressRowsPerPoint * p) * x;
  double vm2[fullorder::kShellSurfaces];
  stationsOf(y, vm2);
  return std::sqrt(vm2[z]);
}

}  // namespace mastrom::rom
