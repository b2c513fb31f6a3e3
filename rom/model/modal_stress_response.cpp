// ROM interface stresses (see modal_stress_response.hpp).
#include "rom/model/modal_stress_response.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <cmath>
#include <numeric>
#include <tuple>
#include <vector>

#include "common/cpu_features.hpp"
#include "common/error.hpp"
#include "fullorder/shell_stress.hpp"

namespace mastrom::rom {
namespace {

/// Four doubles as one GNU vector: one AVX register.
typedef double Pack4 __attribute__((vector_size(4 * sizeof(double))));

#if MASTROM_HAVE_AVX2_KERNELS
/// Y = B X for a block of `count` samples (B: rows × inputs, X: inputs × count, Y: rows × count,
/// all column-major and contiguous; rows a multiple of 4) with AVX2 + FMA: four samples at a time,
/// one accumulator per sample, each column of B loaded once per four samples. The build's
/// baseline ISA leaves Eigen's product at SSE2 (61 % of a `rom eval` with stresses, perf).
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

/// The parabola polish's error on a sinusoid sampled at phase steps x = ωh, relative to its
/// amplitude: 0.0234 x⁴ (rom/model/deployment_metrics.hpp), at most 2 when the samples miss it.
inline double polishError(double x) { return std::min(2.0, 0.0234 * x * x * x * x); }

/// The vertex of the parabola through (−1, v_minus), (0, v0), (1, v_plus) when it is a maximum
/// within [−1, 1]: its value and abscissa; false otherwise.
bool parabolaMaximum(double v_minus, double v0, double v_plus, double& value, double& offset) {
  const double curvature = v_plus + v_minus - 2.0 * v0, slope = 0.5 * (v_plus - v_minus);
  if (!(curvature < 0.0)) return false;
  offset = -slope / curvature;
  if (std::abs(offset) > 1.0) return false;
  value = v0 - 0.5 * slope * slope / curvature;
  return true;
}

thread_local long t_peak_evaluations = 0;
thread_local StressRefinementStats t_refine_stats;

/// Squared plane-stress von Mises of [a, b, c] (tensor shear c; fullorder/shell_stress.hpp).
inline double vonMises2(double a, double b, double c) { return a * a - a * b + b * b + 3.0 * c * c; }

/// The three ζ stations of a point from its rows [σ_m; σ_b] (modal_stress.hpp).
template <class Rows>
void stationsOf(const Rows& y, double vm2[fullorder::kShellSurfaces]) {
  vm2[0] = vonMises2(y[0] - y[3], y[1] - y[4], y[2] - y[5]);
  vm2[1] = vonMises2(y[0], y[1], y[2]);
  vm2[2] = vonMises2(y[0] + y[3], y[1] + y[4], y[2] + y[5]);
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
    // c_gj: the largest von Mises of column j alone over the stations of cluster g, and c_j over
    // all of them (the bound b of the header).
    const int clusters = (itf.points + kClusterPoints - 1) / kClusterPoints;
    itf.cluster_bound.resize(clusters, inputs_);
    for (int j = 0; j < inputs_; ++j) {
      for (int g = 0; g < clusters; ++g) {
        double c2 = 0.0;
        for (int p = g * kClusterPoints; p < std::min(itf.points, (g + 1) * kClusterPoints); ++p) {
          double vm2[fullorder::kShellSurfaces];
          stationsOf(itf.rows.col(j).segment<kStressRowsPerPoint>(kStressRowsPerPoint * p), vm2);
          c2 = std::max({c2, vm2[0], vm2[1], vm2[2]});
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
  x.head(modes_) = eta + damping_s_ * eta_dot;
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

double ModalStressEvaluator::largestAbove(int i, const Eigen::Ref<const Eigen::VectorXd>& x,
                                          double floor, int* station) const {
  const Interface& itf = interfaces_[static_cast<std::size_t>(i)];
  const Eigen::Index all_rows = itf.rows.rows();
  thread_local std::vector<double> abs_x, y;
  abs_x.resize(static_cast<std::size_t>(inputs_));
  y.resize(static_cast<std::size_t>(kStressRowsPerPoint * kClusterPoints));
  for (int j = 0; j < inputs_; ++j) abs_x[static_cast<std::size_t>(j)] = std::abs(x[j]);
  double best = -1.0;
  int where = -1;
  for (Eigen::Index g = 0; g < itf.cluster_bound.rows(); ++g) {
    double b = 0.0;
    for (int j = 0; j < inputs_; ++j) b += itf.cluster_bound(g, j) * abs_x[static_cast<std::size_t>(j)];
    if (b < floor) continue;
    // y = the cluster's rows times x, row by row summed over j in order (the same arithmetic
    // whichever clusters are computed).
    const int first_point = static_cast<int>(g) * kClusterPoints;
    const int points = std::min(itf.points - first_point, kClusterPoints);
    const Eigen::Index first_row = kStressRowsPerPoint * first_point;
    const int rows = kStressRowsPerPoint * points;
    std::fill(y.begin(), y.begin() + rows, 0.0);
    for (int j = 0; j < inputs_; ++j) {
      const double* column = itf.rows.data() + j * all_rows + first_row;
      const double v = x[j];
      for (int r = 0; r < rows; ++r) y[static_cast<std::size_t>(r)] += column[r] * v;
    }
    for (int p = 0; p < points; ++p) {
      double vm2[fullorder::kShellSurfaces];
      stationsOf(y.data() + kStressRowsPerPoint * p, vm2);
      for (int z = 0; z < fullorder::kShellSurfaces; ++z)
        if (vm2[z] > best) best = vm2[z], where = fullorder::kShellSurfaces * (first_point + p) + z;
    }
  }
  if (where < 0) return -1.0;
  if (station) *station = where;
  return std::sqrt(std::max(best, 0.0));
}

void ModalStressEvaluator::largestHistory(int i, const Eigen::MatrixXd& states,
                                          std::vector<double>& out) const {
  const Interface& itf = interfaces_[static_cast<std::size_t>(i)];
  const Eigen::Index samples = states.cols();
  out.resize(static_cast<std::size_t>(samples));
  constexpr Eigen::Index kBlock = 128;  // columns per product: Y stays in the L2 cache
  Eigen::MatrixXd y(itf.rows.rows(), kBlock);
  for (Eigen::Index first = 0; first < samples; first += kBlock) {
    const Eigen::Index count = std::min(kBlock, samples - first);
#if MASTROM_HAVE_AVX2_KERNELS
    if (cpuHasAvx2Fma() && itf.rows.rows() % 4 == 0) {
      blockProductAvx2(itf.rows.data(), itf.rows.rows(), itf.rows.cols(),
                       states.data() + first * states.rows(), count, y.data());
    } else
#endif
    {
      y.leftCols(count).noalias() = itf.rows * states.middleCols(first, count);
    }
    for (Eigen::Index c = 0; c < count; ++c) {
      double best = 0.0;
      for (int p = 0; p < itf.points; ++p) {
        double vm2[fullorder::kShellSurfaces];
        stationsOf(y.col(c).segment<kStressRowsPerPoint>(kStressRowsPerPoint * p), vm2);
        best = std::max({best, vm2[0], vm2[1], vm2[2]});
      }
      out[static_cast<std::size_t>(first + c)] = std::sqrt(best);
    }
  }
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

Eigen::MatrixXd ModalStressEvaluator::blockMaxima(const Eigen::MatrixXd& states) const {
  const Eigen::Index samples = states.cols();
  const Eigen::Index blocks = (samples + kBoundBlock - 1) / kBoundBlock;
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(states.rows(), blocks);
  for (Eigen::Index n = 0; n < samples; ++n) {
    auto m = out.col(n / kBoundBlock);
    m = m.cwiseMax(states.col(n).cwiseAbs());
  }
  return out;
}

ModalStressEvaluator::Peak ModalStressEvaluator::peak(int i, const Eigen::MatrixXd& states,
                                                      const std::vector<char>& no_polish,
                                                      const Eigen::MatrixXd* block_maxima) const {
  const Interface& itf = interfaces_[static_cast<std::size_t>(i)];
  const long samples = static_cast<long>(states.cols());
  MASTROM_REQUIRE(states.rows() == inputs_ && samples >= 1, InputError, "rom stresses: ",
                  states.rows(), " × ", samples, " states for inputs of size ", inputs_);
  Eigen::MatrixXd own;
  if (!block_maxima) {
    own = blockMaxima(states);
    block_maxima = &own;
  }
  const long blocks = (samples + kBoundBlock - 1) / kBoundBlock;
  MASTROM_REQUIRE(block_maxima->rows() == inputs_ && block_maxima->cols() == blocks, InputError,
                  "rom stresses: block maxima of the wrong size");
  // Best-first over the blocks, then over the samples of each block that can still hold more
  // than the largest value found (header comment). Ties keep the earliest sample.
  const Eigen::VectorXd block_bound = block_maxima->transpose() * itf.bound;
  std::vector<long> block_order(static_cast<std::size_t>(blocks));
  for (long k = 0; k < blocks; ++k) block_order[static_cast<std::size_t>(k)] = k;
  std::sort(block_order.begin(), block_order.end(), [&block_bound](long a, long b) {
    return block_bound[a] > block_bound[b] || (block_bound[a] == block_bound[b] && a < b);
  });
  Peak out;
  out.von_mises_pa = -1.0;
  long evaluations = 0;
  std::vector<std::pair<double, long>> candidates;
  for (const long k : block_order) {
    if (block_bound[k] < out.von_mises_pa) break;
    candidates.clear();
    const long end = std::min(samples, (k + 1) * kBoundBlock);
    for (long n = k * kBoundBlock; n < end; ++n) {
      const double* x = states.col(n).data();
      double b = 0.0;
      for (int j = 0; j < inputs_; ++j) b += itf.bound[j] * std::abs(x[j]);
      if (b >= out.von_mises_pa) candidates.emplace_back(b, n);
    }
    std::sort(candidates.begin(), candidates.end(),
              [](const std::pair<double, long>& a, const std::pair<double, long>& b) {
                return a.first > b.first || (a.first == b.first && a.second < b.second);
              });
    for (const auto& [b, n] : candidates) {
      if (b < out.von_mises_pa) break;
      int where = 0;
      const double v = largestAbove(i, states.col(n), out.von_mises_pa, &where);
      ++evaluations;
      if (v > out.von_mises_pa || (v == out.von_mises_pa && n < out.nearest_sample))
        out.von_mises_pa = v, out.station = where, out.nearest_sample = n;
    }
  }
  t_peak_evaluations = evaluations;

  // The parabola through the peak sample and its neighbours at the same station.
  const long n = out.nearest_sample;
  out.sample = static_cast<double>(n);
  const auto near_breakpoint = [&no_polish](long m) {
    return m >= 0 && static_cast<std::size_t>(m) < no_polish.size() && no_polish[static_cast<std::size_t>(m)];
  };
  if (n > 0 && n + 1 < samples && !near_breakpoint(n - 1) && !near_breakpoint(n) &&
      !near_breakpoint(n + 1)) {
    double value = 0.0, offset = 0.0;
    if (parabolaMaximum(station(i, out.station, states.col(n - 1)),
                        station(i, out.station, states.col(n)),
                        station(i, out.station, states.col(n + 1)), value, offset)) {
      out.von_mises_pa = std::max(out.von_mises_pa, value);
      out.sample = static_cast<double>(n) + offset;
    }
  }
  return out;
}

long ModalStressEvaluator::lastPeakEvaluations() { return t_peak_evaluations; }

ModalSampleObserver modalStressRecorder(const ModalStressEvaluator& evaluator,
                                        Eigen::MatrixXd& states) {
  return [&evaluator, &states](long n, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
                               const stepping_detail::ForcingScalars& f) {
    evaluator.input(eta, eta_dot, f, states.col(n));
  };
}

ModalSampleObserver modalStressRecorder(const ModalStressEvaluator& evaluator,
                                        Eigen::MatrixXd& states, Eigen::MatrixXd& eta,
                                        Eigen::MatrixXd& eta_dot) {
  return [&evaluator, &states, &eta, &eta_dot](long n, const Eigen::VectorXd& e,
                                               const Eigen::VectorXd& v,
                                               const stepping_detail::ForcingScalars& f) {
    evaluator.input(e, v, f, states.col(n));
    eta.col(n) = e;
    eta_dot.col(n) = v;
  };
}

bool stressPeaksNeedRefinement(const ModalStressEvaluator& evaluator, const ModalModel& model,
                               double step_s) {
  // Each mode's share of the stress, c_k|Γ_k|/ω_k² (its static deflection per unit θ̈, also the
  // scale of its ringing after a jump of θ̈), weighted by the polish error e(ω_k Δ) of its peaks.
  const int k = model.modeCount();
  for (int i = 0; i < evaluator.interfaceCount(); ++i) {
    double largest = 0.0, error = 0.0;
    for (int j = 0; j < k; ++j) {
      const double w = model.omega_rad_s[j];
      if (!(w > 0.0)) continue;
      const double share = evaluator.bound(i)[j] * std::abs(model.rotation_participation[j]) / (w * w);
      const double x = w * step_s;
      largest = std::max(largest, share);
      error += share * polishError(x);
    }
    if (error > kStressPolishTolerance * largest) return true;
  }
  return false;
}

namespace {

/// The refinement's target: a peak within this share of itself (the sample polish's own order).
constexpr double kStressPeakTolerance = 1e-4;
constexpr int kMaxStressSubSteps = 256;

/// Re-steps one interval (a step or a piece of a split step) where its bound allows a higher peak
/// (modal_stress_response.hpp, "Between samples"). prepare() bounds the modal state over the
/// interval once; refine() then serves each interface. Buffers are members: no allocation per
/// interval.
class IntervalRefiner {
public:
  IntervalRefiner(const ModalStressEvaluator& ev, const ModalModel& m, const ModalStepping& ms)
      : ev_(ev), m_(m), ms_(ms), k_(m.modeCount()), w_(m.omega_rad_s.array()),
        zeta_(m.damping_ratio.array()) {
    inv_w_ = 1.0 / w_.max(1e-300);
    inv_w2_ = inv_w_.square();
    two_zeta_ = 2.0 * zeta_;
    for (Eigen::ArrayXd* a : {&f0_, &f1_, &ringing_, &bound_modes_, &e0_, &v0_, &p0_, &p1_, &tmp_})
      a->resize(k_);
  }

  /// Bound the interval from the state (η, η̇) at its start.
  void prepare(const Eigen::Ref<const Eigen::VectorXd>& eta,
               const Eigen::Ref<const Eigen::VectorXd>& eta_dot, const DriveInstant& d0,
               const DriveInstant& d1, double duration_s) {
    d0_ = d0;
    d1_ = d1;
    duration_s_ = duration_s;
    s0_ = stepping_detail::forcingScalars(ms_, d0);
    s1_ = stepping_detail::forcingScalars(ms_, d1);
    const double mu = ev_.damping(), inv_d = 1.0 / duration_s;
    // Whole-array passes over the modes into member buffers (vectorised, no allocation); the
    // forcing at the start is the previous interval's end whenever the drive is continuous there.
    const bool continued = have_end_ && d0.rate_rad_s == last_d1_.rate_rad_s &&
                           d0.acceleration_rad_s2 == last_d1_.acceleration_rad_s2 &&
                           d0.sin_angle == last_d1_.sin_angle && d0.cos_angle == last_d1_.cos_angle;
    if (continued) {
      f0_.swap(f1_);
    } else {
      modalForcing(s0_, f0_);
    }
    modalForcing(s1_, f1_);
    last_d1_ = d1;
    have_end_ = true;
    tmp_ = (f1_ - f0_) * (inv_d * inv_w2_);                          // η̇_p
    p0_ = f0_ * inv_w2_ - two_zeta_ * tmp_ * inv_w_;                  // η_p(t_start)
    p1_ = f1_ * inv_w2_ - two_zeta_ * tmp_ * inv_w_;                  // η_p(t_end)
    // The free oscillation's amplitude a; ringing = a (1 + μω) bounds its share of η + μη̇.
    ringing_ = ((eta.array() - p0_).square() + ((eta_dot.array() - tmp_) * inv_w_).square())
                   .sqrt() *
               (1.0 + mu * w_);
    bound_modes_ = p0_.abs().max(p1_.abs()) + mu * tmp_.abs() + ringing_;
    loads_ << std::max(std::abs(s0_.acc), std::abs(s1_.acc)), std::max(s0_.rate2, s1_.rate2),
        std::max(std::abs(s0_.gx), std::abs(s1_.gx)), std::max(std::abs(s0_.gy), std::abs(s1_.gy));
    e0_ = eta.array();
    v0_ = eta_dot.array();
  }

  /// Σ_j c_j r_j of interface i for the prepared interval: its ringing bound at the start.
  double ringingBound(int i) const { return ev_.bound(i).head(k_).dot(ringing_.matrix()); }

  /// Raise interface i's peak if the prepared interval holds a higher value; start_sample is the
  /// interval's start as a (fractional) sample index.
  void refine(int i, double start_sample, double step_s, ModalStressEvaluator::Peak& peak) {
    const Eigen::VectorXd& c = ev_.bound(i);
    ++t_refine_stats.intervals;
    const double upper = c.head(k_).dot(bound_modes_.matrix()) +
                         c.segment<kStressLoadCount>(k_).dot(loads_) + c[k_ + kStressLoadCount];
    if (upper <= peak.von_mises_pa) return;
    // Sub-steps: the coarsest h = duration/sub whose estimated polish error over the ringing
    // modes, Σ_j c_j r_j e(ω_j h) with e(x) = min(2, 0.0234 x⁴) (the parabola's error on a
    // sinusoid, rom/model/deployment_metrics.hpp), is at most kStressPeakTolerance of the peak.
    const auto errorAt = [&](int sub) {
      const double h = duration_s_ / sub;
      double e = 0.0;
      for (int j = 0; j < k_; ++j) {
        const double x = w_[j] * h;
        e += c[j] * ringing_[j] * polishError(x);
      }
      return e;
    };
    int sub = 1;
    while (sub < kMaxStressSubSteps && errorAt(sub) > kStressPeakTolerance * peak.von_mises_pa)
      sub *= 2;
    if (sub == 1) return;  // the samples and their polish resolve it
    ++t_refine_stats.refined;
    t_refine_stats.sub_steps += sub;
    const ModalStepping::Maps& h = maps(duration_s_, sub);
    x_.resize(ev_.inputSize(), sub + 1);
    const auto load = [&](double t) {
      stepping_detail::ForcingScalars f;
      f.acc = s0_.acc + t * (s1_.acc - s0_.acc);
      const double rate = d0_.rate_rad_s + t * (d1_.rate_rad_s - d0_.rate_rad_s);
      f.rate2 = rate * rate;
      f.gx = s0_.gx + t * (s1_.gx - s0_.gx);
      f.gy = s0_.gy + t * (s1_.gy - s0_.gy);
      return f;
    };
    eta_ = e0_.matrix();
    eta_dot_ = v0_.matrix();
    ev_.input(eta_, eta_dot_, load(0.0), x_.col(0));
    for (int j = 1; j <= sub; ++j) {
      const double ta = static_cast<double>(j - 1) / sub, tb = static_cast<double>(j) / sub;
      fa_ = f0_ + ta * (f1_ - f0_);
      fb_ = f0_ + tb * (f1_ - f0_);
      advance(h);
      ev_.input(eta_, eta_dot_, load(tb), x_.col(j));
    }
    int best = -1, station = 0;
    for (int j = 1; j < sub; ++j) {
      if (c.dot(x_.col(j).cwiseAbs()) <= peak.von_mises_pa) continue;
      int where = 0;
      const double v = ev_.largestAbove(i, x_.col(j), peak.von_mises_pa, &where);
      if (v > peak.von_mises_pa) peak.von_mises_pa = v, best = j, station = where;
    }
    if (best < 0) return;
    peak.station = station;
    peak.sample = start_sample + duration_s_ / step_s * best / sub;
    // The parabola through the best sub-sample and its neighbours at the same station.
    double value = 0.0, offset = 0.0;
    if (parabolaMaximum(ev_.station(i, station, x_.col(best - 1)),
                        ev_.station(i, station, x_.col(best)),
                        ev_.station(i, station, x_.col(best + 1)), value, offset)) {
      peak.von_mises_pa = std::max(peak.von_mises_pa, value);
      peak.sample += duration_s_ / step_s * offset / sub;
    }
    peak.nearest_sample = static_cast<long>(std::lround(peak.sample));
  }

  /// The state at the prepared interval's end (for the next piece of a split step).
  void end(Eigen::VectorXd& eta, Eigen::VectorXd& eta_dot) {
    eta_ = e0_.matrix();
    eta_dot_ = v0_.matrix();
    fa_ = f0_;
    fb_ = f1_;
    advance(maps(duration_s_, 1));
    eta = eta_;
    eta_dot = eta_dot_;
  }

private:
  void modalForcing(const stepping_detail::ForcingScalars& f, Eigen::ArrayXd& out) const {
    // The stepping's own forcing arrays (rom/model/modal_stepping.hpp), without the Coriolis term.
    out = -f.acc * ms_.gamma - f.rate2 * ms_.gamma_c;
    if (f.gx != 0.0 || f.gy != 0.0) out += f.gx * ms_.momentum_x + f.gy * ms_.momentum_y;
  }
  const ModalStepping::Maps& maps(double duration_s, int sub) {
    for (const auto& [d, n, m] : cache_)
      if (d == duration_s && n == sub) return m;
    cache_.push_back({duration_s, sub, modalStepMaps(m_, duration_s / sub)});
    return std::get<2>(cache_.back());
  }
  void advance(const ModalStepping::Maps& h) {
    next_ = h.a00 * eta_.array() + h.a01 * eta_dot_.array() + h.b00 * fa_ + h.b10 * fb_;
    eta_dot_.array() = h.a10 * eta_.array() + h.a11 * eta_dot_.array() + h.b01 * fa_ + h.b11 * fb_;
    eta_ = next_.matrix();
  }

  const ModalStressEvaluator& ev_;
  const ModalModel& m_;
  const ModalStepping& ms_;
  int k_;
  Eigen::ArrayXd w_, zeta_, inv_w_, inv_w2_, two_zeta_;
  // The prepared interval.
  DriveInstant d0_, d1_;
  double duration_s_ = 0.0;
  stepping_detail::ForcingScalars s0_, s1_;
  Eigen::ArrayXd f0_, f1_, ringing_, bound_modes_, e0_, v0_, p0_, p1_, tmp_;
  DriveInstant last_d1_;
  bool have_end_ = false;
  Eigen::Matrix<double, kStressLoadCount, 1> loads_;
  // Sub-stepping.
  Eigen::VectorXd eta_, eta_dot_;
  Eigen::ArrayXd fa_, fb_, next_;
  Eigen::MatrixXd x_;
  std::vector<std::tuple<double, int, ModalStepping::Maps>> cache_;
};

}  // namespace

StressRefinementStats lastStressRefinementStats() { return t_refine_stats; }

void refineStressPeaks(const ModalStressEvaluator& evaluator, const ModalModel& model,
                       const SampledDrive& drive, const Eigen::MatrixXd& eta,
                       const Eigen::MatrixXd& eta_dot,
                       std::vector<ModalStressEvaluator::Peak>& peaks) {
  t_refine_stats = {};
  MASTROM_REQUIRE(eta.cols() == drive.steps + 1 && eta_dot.cols() == drive.steps + 1 &&
                      eta.rows() == model.modeCount() &&
                      static_cast<int>(peaks.size()) == evaluator.interfaceCount(),
                  InputError, "rom stresses: refinement inputs do not match the deployment");
  const ModalStepping ms = prepareModalStepping(model, drive, false);
  IntervalRefiner refiner(evaluator, model, ms);
  const int interfaces = evaluator.interfaceCount();
  const int k = model.modeCount();

  // An O(1) screening bound per step and interface (most steps need no O(modes) prepare()): with
  // the load scalars s ∈ {θ̈, θ̇², g_x, g_y} and the modes' coefficients γ_sj (−Γ, −Γ_c, L_x, L_y),
  //   quasi-static part ≤ Σ_s max|s| Q_s + Σ_s |ṡ| Qd_s,
  //     Q_s = Σ_j c_j|γ_sj|/ω_j²,  Qd_s = Σ_j c_j|γ_sj|(2ζ_j/ω_j + μ)/ω_j²,
  //   ringing part R: exact after a prepare(), then raised at each step boundary by the change of
  //     the particular solution, ≤ Σ_s |Δs| P_s + Σ_s |Δṡ| Pd_s,
  //     P_s = Σ_j c_j(1 + μω_j)|γ_sj|/ω_j²,  Pd_s = Σ_j c_j(1 + μω_j)|γ_sj|(1 + 2ζ_j)/ω_j³
  // (the free amplitude never grows inside a step). Only a step whose screening bound exceeds a
  // peak is prepared exactly.
  struct Sums {
    Eigen::Vector4d q, qd, p, pd;
  };
  std::vector<Sums> sums(static_cast<std::size_t>(interfaces));
  const double mu = evaluator.damping();
  for (int i = 0; i < interfaces; ++i) {
    Sums& su = sums[static_cast<std::size_t>(i)];
    su.q.setZero();
    su.qd.setZero();
    su.p.setZero();
    su.pd.setZero();
    const Eigen::VectorXd& c = evaluator.bound(i);
    for (int j = 0; j < k; ++j) {
      const double w = std::max(model.omega_rad_s[j], 1e-300), z = model.damping_ratio[j];
      const double coef[4] = {std::abs(model.rotation_participation[j]),
                              std::abs(model.centrifugal_participation[j]),
                              std::abs(model.momentum_participation(0, j)),
                              std::abs(model.momentum_participation(1, j))};
      for (int q = 0; q < 4; ++q) {
        su.q[q] += c[j] * coef[q] / (w * w);
        su.qd[q] += c[j] * coef[q] * (2.0 * z / w + mu) / (w * w);
        su.p[q] += c[j] * (1.0 + mu * w) * coef[q] / (w * w);
        su.pd[q] += c[j] * (1.0 + mu * w) * coef[q] * (1.0 + 2.0 * z) / (w * w * w);
      }
    }
  }
  const auto scalars = [](const stepping_detail::ForcingScalars& f) {
    return Eigen::Vector4d(f.acc, f.rate2, f.gx, f.gy);
  };
  std::vector<double> ringing(static_cast<std::size_t>(interfaces), 0.0);
  bool ringing_known = false;                     // R valid at the start of step n
  Eigen::Vector4d previous_end, previous_rate;    // s at the end of step n − 1, and its ṡ
  DriveInstant previous_d1;                       // the drive there
  bool have_previous = false;
  Eigen::VectorXd e, v;
  std::size_t next_split = 0;
  for (long n = 0; n < drive.steps; ++n) {
    if (next_split < drive.splits.size() && drive.splits[next_split].step == n) {
      e = eta.col(n);
      v = eta_dot.col(n);
      double start = static_cast<double>(n);
      for (const SampledDrive::Piece& piece : drive.splits[next_split].pieces) {
        refiner.prepare(e, v, piece.start, piece.end, piece.duration_s);
        for (int i = 0; i < interfaces; ++i)
          refiner.refine(i, start, drive.step_s, peaks[static_cast<std::size_t>(i)]);
        refiner.end(e, v);
        start += piece.duration_s / drive.step_s;
      }
      ++next_split;
      ringing_known = false;  // re-derived exactly at the next step
      continue;
    }
    const DriveInstant d0 = drive.startOf(n), d1 = drive.endAt(n + 1);
    // The scalars are a function of the drive instant: where the drive is continuous at t_n, those
    // of the step's start are the previous step's end.
    const bool continued = have_previous && d0.rate_rad_s == previous_d1.rate_rad_s &&
                           d0.acceleration_rad_s2 == previous_d1.acceleration_rad_s2 &&
                           d0.sin_angle == previous_d1.sin_angle &&
                           d0.cos_angle == previous_d1.cos_angle;
    const Eigen::Vector4d s0 =
        continued ? previous_end : scalars(stepping_detail::forcingScalars(ms, d0));
    const Eigen::Vector4d s1 = scalars(stepping_detail::forcingScalars(ms, d1));
    const Eigen::Vector4d rate = (s1 - s0) / drive.step_s;
    if (ringing_known) {  // across the boundary t_n: the particular solution's change
      const Eigen::Vector4d jump = (s0 - previous_end).cwiseAbs(), kink = (rate - previous_rate).cwiseAbs();
      for (int i = 0; i < interfaces; ++i)
        ringing[static_cast<std::size_t>(i)] += sums[static_cast<std::size_t>(i)].p.dot(jump) +
                                                sums[static_cast<std::size_t>(i)].pd.dot(kink);
    }
    bool exact = !ringing_known;
    const Eigen::Vector4d largest = s0.cwiseAbs().cwiseMax(s1.cwiseAbs());
    for (int i = 0; i < interfaces && !exact; ++i) {
      const Sums& su = sums[static_cast<std::size_t>(i)];
      const Eigen::VectorXd& c = evaluator.bound(i);
      const double screen = su.q.dot(largest) + su.qd.dot(rate.cwiseAbs()) +
                            ringing[static_cast<std::size_t>(i)] +
                            c.segment<kStressLoadCount>(k).dot(largest) + c[k + kStressLoadCount];
      exact = screen > peaks[static_cast<std::size_t>(i)].von_mises_pa;
    }
    if (exact) {
      refiner.prepare(eta.col(n), eta_dot.col(n), d0, d1, drive.step_s);
      for (int i = 0; i < interfaces; ++i) {
        ringing[static_cast<std::size_t>(i)] = refiner.ringingBound(i);
        refiner.refine(i, static_cast<double>(n), drive.step_s, peaks[static_cast<std::size_t>(i)]);
      }
      ringing_known = true;
    }
    previous_end = s1;
    previous_rate = rate;
    previous_d1 = d1;
    have_previous = true;
  }
}

std::vector<char> samplesNearBreakpoints(const SampledDrive& drive) {
  std::vector<char> marked(static_cast<std::size_t>(drive.steps + 1), 0);
  for (long n = 1; n < drive.steps; ++n) {
    const SampledDrive::Sample& s = drive.samples[static_cast<std::size_t>(n)];
    if (s.start_acceleration_rad_s2 != s.end_acceleration_rad_s2) marked[static_cast<std::size_t>(n)] = 1;
  }
  for (const SampledDrive::Split& split : drive.splits) {
    marked[static_cast<std::size_t>(split.step)] = 1;
    marked[static_cast<std::size_t>(split.step + 1)] = 1;
  }
  return marked;
}

Eigen::MatrixXd modalStressStates(const ModalModel& model, const ModalStressEvaluator& evaluator,
                                  const SampledDrive& drive, bool coriolis_coupling,
                                  Eigen::MatrixXd* eta, Eigen::MatrixXd* eta_dot) {
  const ModalStepping ms = prepareModalStepping(model, drive, coriolis_coupling);
  Eigen::MatrixXd states(evaluator.inputSize(), drive.steps + 1);
  const bool keep = eta != nullptr && eta_dot != nullptr;
  if (keep) {
    eta->resize(model.modeCount(), drive.steps + 1);
    eta_dot->resize(model.modeCount(), drive.steps + 1);
  }
  const ModalSampleObserver record = keep ? modalStressRecorder(evaluator, states, *eta, *eta_dot)
                                          : modalStressRecorder(evaluator, states);
  runModalStepping(model, ms, drive,
                   [&](long n, const Eigen::VectorXd& e, const Eigen::VectorXd& v,
                       const Eigen::VectorXd&) {
                     record(n, e, v, stepping_detail::forcingScalars(ms, drive.valueAt(n)));
                   });
  return states;
}

std::vector<ModalStressEvaluator::Peak> findStressPeaks(const ModalStressEvaluator& evaluator,
                                                        const Eigen::MatrixXd& states,
                                                        const std::vector<char>& no_polish,
                                                        const ModalModel& model,
                                                        const SampledDrive& drive,
                                                        const Eigen::MatrixXd& eta,
                                                        const Eigen::MatrixXd& eta_dot) {
  std::vector<ModalStressEvaluator::Peak> found;
  const Eigen::MatrixXd block_maxima = evaluator.blockMaxima(states);
  for (int i = 0; i < evaluator.interfaceCount(); ++i)
    found.push_back(evaluator.peak(i, states, no_polish, &block_maxima));
  if (eta.size() > 0 && stressPeaksNeedRefinement(evaluator, model, drive.step_s))
    refineStressPeaks(evaluator, model, drive, eta, eta_dot, found);
  return found;
}

fullorder::InterfaceStressResult modalInterfaceStresses(const ModalModel& model,
                                                        const fullorder::DriveLaw& drive,
                                                        const ModalDeploymentOptions& options) {
  const ModalStressEvaluator evaluator(model);
  const SampledDrive sampled = sampleDrive(drive, options);
  const std::vector<char> no_polish = samplesNearBreakpoints(sampled);
  const bool refine = stressPeaksNeedRefinement(evaluator, model, sampled.step_s);
  Eigen::MatrixXd eta, eta_dot;
  const Eigen::MatrixXd states =
      modalStressStates(model, evaluator, sampled, options.coriolis_coupling,
                        refine ? &eta : nullptr, refine ? &eta_dot : nullptr);
  const std::vector<ModalStressEvaluator::Peak> peaks =
      findStressPeaks(evaluator, states, no_polish, model, sampled, eta, eta_dot);
  const ModalStress& s = model.stress;
  fullorder::InterfaceStressResult r;
  const long samples = sampled.steps + 1;
  for (long n = 0; n < samples; ++n) r.time_s.push_back(static_cast<double>(n) * sampled.step_s);
  r.recovery_points = fullorder::ShellStressRecovery::gridPoints();
  const int per_point = fullorder::kShellSurfaces;
  for (int i = 0; i < evaluator.interfaceCount(); ++i) {
    fullorder::InterfaceStressHistory h;
    evaluator.largestHistory(i, states, h.max_von_mises_pa);
    r.history.push_back(std::move(h));

    const ModalStressEvaluator::Peak& pk = peaks[static_cast<std::size_t>(i)];
    fullorder::InterfaceStressPeak peak;
    peak.von_mises_pa = pk.von_mises_pa;
    peak.time_s = pk.sample * sampled.step_s;
    const int point = pk.station / per_point;
    const int per_element = static_cast<int>(r.recovery_points.size());
    peak.element = point / per_element;
    peak.point = point % per_element;
    peak.surface = pk.station % per_point;
    const Eigen::Index global = s.interface_offsets[i] + point;
    peak.axial_position_m = s.points(0, global);
    peak.angle_rad = s.points(1, global);
    evaluator.field(i, states.col(pk.nearest_sample), peak.field_von_mises_pa);
    r.peak.push_back(std::move(peak));

    std::vector<std::array<double, 2>> coords;
    for (Eigen::Index p = s.interface_offsets[i]; p < s.interface_offsets[i + 1]; ++p)
      coords.push_back({s.points(0, p), s.points(1, p)});
    r.point_coordinates.push_back(std::move(coords));
  }
  return r;
}

std::vector<double> modalStressPeaks(const ModalStressEvaluator& evaluator,
                                     const Eigen::MatrixXd& states,
                                     const std::vector<char>& no_polish,
                                     const ModalModel& model, const SampledDrive& drive,
                                     const Eigen::MatrixXd& eta, const Eigen::MatrixXd& eta_dot) {
  const std::vector<ModalStressEvaluator::Peak> found =
      findStressPeaks(evaluator, states, no_polish, model, drive, eta, eta_dot);
  std::vector<double> peaks;
  for (const ModalStressEvaluator::Peak& p : found) peaks.push_back(p.von_mises_pa);
  return peaks;
}

}  // namespace mastrom::rom
