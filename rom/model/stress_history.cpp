// ModalStressEvaluator::History (modal_stress_response.hpp): an interface's largest von Mises
// stress at every sample, computing only the points that can hold it (docs/theory.md §6.5,
// "Histories").
//
// Why: the history of `rom eval --stress-history` needs the largest of every station at every
// output sample. One product of the interface's 6P × (k + 5) rows per sample (the previous way,
// blocked) costs 6P(k + 5) multiply-adds, ~20× the rest of the evaluation on Scheme 3. Between
// two samples close in time most points change little: (6.6) is a norm of the stress vector, so a
// point whose stations were computed at x_p is bounded at x by
//     max_s σ_vM,s(x) ≤ m_p + Σ_j c_pj |x_j − x_p,j|, (6.12)
// (m_p its largest value at x_p, c_pj as in (6.10)), and a cluster of points likewise with c_gj and
// a value M_g that bounds its points at x_g. The previous sample's largest point is computed first:
// its value is reached at x, so every point and cluster whose bound is below it is left out and
// the result is still the exact largest value.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "common/cpu_features.hpp"
#include "rom/model/modal_stress_response.hpp"
#include "rom/model/stress_point_rows.hpp"
#include "rom/model/stress_stations.hpp"

namespace mastrom::rom {

namespace {

/// The drift of (6.12) for `count` points or clusters at once: out[k] = Σ_j c_kj |x_j − x0_kj|,
/// c and x0 column-major with leading dimension ld (k contiguous for each j). The loop runs along
/// k in packs of the vector width, so it needs no chain of dependent additions. A bound's sum may
/// be rounded in any order (kBoundMargin covers it), so the AVX2 copy may fuse its multiply-adds.
template <typename Pack, int Width>
MASTROM_ALWAYS_INLINE void driftBoundsBody(const double* __restrict c, const double* __restrict x0,
                                           Eigen::Index ld, int count, const double* __restrict x,
                                           int inputs, double* __restrict out) {
  int k = 0;
  for (; k + 2 * Width <= count; k += 2 * Width) {  // two packs of points at a time
    Pack a0 = Pack{}, a1 = Pack{};
    for (int j = 0; j < inputs; ++j) {
      const Pack xj = Pack{} + x[j];
      Pack c0, c1, y0, y1;
      std::memcpy(&c0, c + j * ld + k, sizeof(Pack));
      std::memcpy(&c1, c + j * ld + k + Width, sizeof(Pack));
      std::memcpy(&y0, x0 + j * ld + k, sizeof(Pack));
      std::memcpy(&y1, x0 + j * ld + k + Width, sizeof(Pack));
      Pack d0 = xj - y0, d1 = xj - y1;
      d0 = d0 < 0.0 ? -d0 : d0;  // |d|, lane by lane
      d1 = d1 < 0.0 ? -d1 : d1;
      a0 += c0 * d0;
      a1 += c1 * d1;
    }
    std::memcpy(out + k, &a0, sizeof(Pack));
    std::memcpy(out + k + Width, &a1, sizeof(Pack));
  }
  for (; k < count; ++k) {
    double a = 0.0;
    for (int j = 0; j < inputs; ++j) a += c[j * ld + k] * std::abs(x[j] - x0[j * ld + k]);
    out[k] = a;
  }
}

#if MASTROM_HAVE_AVX2_KERNELS
__attribute__((target("avx2,fma"))) void driftBoundsAvx2(const double* c, const double* x0,
                                                         Eigen::Index ld, int count,
                                                         const double* x, int inputs, double* out) {
  driftBoundsBody<Pack4, 4>(c, x0, ld, count, x, inputs, out);
}
#endif

void driftBounds(const double* c, const double* x0, Eigen::Index ld, int count, const double* x,
                 int inputs, double* out) {
#if MASTROM_HAVE_AVX2_KERNELS
  if (cpuHasAvx2Fma()) return driftBoundsAvx2(c, x0, ld, count, x, inputs, out);
#endif
  driftBoundsBody<Pack2, 2>(c, x0, ld, count, x, inputs, out);
}

/// A bound that rounding in its own sum cannot put below a value it must reach: (6.12) is summed
/// in k + 5 terms of relative rounding ε each.
constexpr double kBoundMargin = 1.0 + 1e-12;

}  // namespace

ModalStressEvaluator::History::History(const ModalStressEvaluator& evaluator, int interface_index)
    : evaluator_(evaluator), interface_(interface_index) {
  const Interface& itf = evaluator_.interfaces_[static_cast<std::size_t>(interface_)];
  const int inputs = evaluator_.inputs_;
  point_value_ = Eigen::VectorXd::Constant(itf.points, std::numeric_limits<double>::infinity());
  point_state_ = Eigen::MatrixXd::Zero(itf.points, inputs);
  const Eigen::Index clusters = itf.cluster_bound.rows();
  cluster_value_ = Eigen::VectorXd::Constant(clusters, std::numeric_limits<double>::infinity());
  cluster_state_ = Eigen::MatrixXd::Zero(clusters, inputs);
  // A point's six rows contiguous: a sample computes a few points.
  point_rows_.resize(kStressRowsPerPoint * inputs, itf.points);
  for (int p = 0; p < itf.points; ++p)
    for (int j = 0; j < inputs; ++j)
      for (int r = 0; r < kStressRowsPerPoint; ++r)
        point_rows_(kStressRowsPerPoint * j + r, p) = itf.rows(kStressRowsPerPoint * p + r, j);
}

double ModalStressEvaluator::History::computePoint(int p,
                                                   const Eigen::Ref<const Eigen::VectorXd>& x) {
  const int inputs = evaluator_.inputs_;
  double y[kStressRowsPerPoint];
  stress_detail::pointRows(point_rows_.col(p).data(), kStressRowsPerPoint, x.data(), inputs, y);
  double vm2[fullorder::kShellSurfaces];
  stress_detail::stationsOf(y, vm2);
  const double value = std::sqrt(std::max({vm2[0], vm2[1], vm2[2], 0.0}));
  point_value_[p] = value;
  point_state_.row(p) = x.transpose();
  ++computed_;
  return value;
}

double ModalStressEvaluator::History::next(const Eigen::Ref<const Eigen::VectorXd>& x) {
  const Interface& itf = evaluator_.interfaces_[static_cast<std::size_t>(interface_)];
  const int inputs = evaluator_.inputs_;
  const int cluster_points = ModalStressEvaluator::kClusterPoints;
  const Eigen::Index clusters = itf.cluster_bound.rows();
  ++samples_;
  // The floor: the previous sample's largest point, at this sample.
  const int floor_point = largest_point_;
  double best = floor_point >= 0 ? computePoint(floor_point, x) : -1.0;
  int best_point = floor_point;
  double drift[ModalStressEvaluator::kClusterPoints];
  cluster_drift_.resize(clusters);
  driftBounds(itf.cluster_bound.data(), cluster_state_.data(), clusters, static_cast<int>(clusters),
              x.data(), inputs, cluster_drift_.data());
  for (Eigen::Index g = 0; g < clusters; ++g) {
    if (kBoundMargin * (cluster_value_[g] + cluster_drift_[g]) < best) continue;  // all below
    // The points of g: computed where their own bound reaches the largest value so far. After
    // the visit each point is bounded at x by its value (computed) or its bound (left out): the
    // largest of those bounds the cluster at x from now on.
    const int first = static_cast<int>(g) * cluster_points;
    const int count = std::min(itf.points - first, cluster_points);
    driftBounds(itf.point_bound.data() + first, point_state_.data() + first, itf.points, count,
                x.data(), inputs, drift);
    double cluster_value = 0.0;
    for (int k = 0; k < count; ++k) {
      const int p = first + k;
      double value;
      if (p == floor_point) {
        value = point_value_[p];  // computed at x above
      } else {
        const double bound = kBoundMargin * (point_value_[p] + drift[k]);
        if (bound < best) {
          value = bound;
        } else {
          value = computePoint(p, x);
          if (value > best) best = value, best_point = p;
        }
      }
      cluster_value = std::max(cluster_value, value);
    }
    cluster_value_[g] = cluster_value;
    cluster_state_.row(g) = x.transpose();
  }
  largest_point_ = best_point;
  return std::max(best, 0.0);
}

void ModalStressEvaluator::largestHistory(int i, const Eigen::MatrixXd& states,
                                          std::vector<double>& out) const {
  History history(*this, i);
  out.resize(static_cast<std::size_t>(states.cols()));
  for (Eigen::Index n = 0; n < states.cols(); ++n)
    out[static_cast<std::size_t>(n)] = history.next(states.col(n));
}

}  // namespace mastrom::rom
