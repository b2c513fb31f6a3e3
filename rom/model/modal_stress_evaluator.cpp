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
    for (int j = 0; j < inputs_; ++j) {
      for (int g = 0; g < clusters; ++g) {
        double c2 = 0.0;
        for (int p = g * kClusterPoints; p < std::min(itf.points, (g + 1) * kClusterPoints); ++p) {
          double vm2[fullorder::kShellSurfaces];
          stationsOf(itf.rows.col(j).segment<kStressRowsPerPoint>(kStressRowsPerPoint * p), vm2);
          const double p2 = std::max({vm2[0], vm2[1], vm2[2]});
          itf.point_bound(p, j) = std::sqrt(p2);
          c2 = std::max(c2, p2);
        }
        itf.cluster_bound(g, j) = std::sqrt(c2);
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
