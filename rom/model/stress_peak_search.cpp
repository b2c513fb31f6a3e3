// The peak of a ROM stress history without the history (modal_stress_response.hpp, docs/theory.md
// §6.5): best-first over blocks of samples and then samples by the bound (6.10), an exact
// evaluation that computes only the clusters of points able to reach the peak, and the parabola
// polish of the largest sample away from the drive's breakpoints.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "common/error.hpp"
#include "rom/model/modal_stress_response.hpp"
#include "rom/model/parabola_polish.hpp"
#include "rom/model/stress_point_rows.hpp"
#include "rom/model/stress_stations.hpp"

namespace mastrom::rom {
namespace {

thread_local long t_peak_evaluations = 0;

}  // namespace

double ModalStressEvaluator::largestAbove(int i, const Eigen::Ref<const Eigen::VectorXd>& x,
                                          double floor, int* station) const {
  const Interface& itf = interfaces_[static_cast<std::size_t>(i)];
  const Eigen::Index all_rows = itf.rows.rows();
  const Eigen::Index clusters = itf.cluster_bound.rows();
  thread_local std::vector<double> abs_x, point_bounds;
  thread_local std::vector<std::pair<double, int>> order;
  abs_x.resize(static_cast<std::size_t>(inputs_));
  point_bounds.resize(static_cast<std::size_t>(kClusterPoints));
  for (int j = 0; j < inputs_; ++j) abs_x[static_cast<std::size_t>(j)] = std::abs(x[j]);
  // The clusters that can reach the floor, the highest bound first: the largest value is then
  // usually found in the first, and its value prunes the points of the others.
  order.clear();
  for (Eigen::Index g = 0; g < clusters; ++g) {
    double b = 0.0;
    for (int j = 0; j < inputs_; ++j)
      b += itf.cluster_bound(g, j) * abs_x[static_cast<std::size_t>(j)];
    if (b >= floor) order.emplace_back(b, static_cast<int>(g));
  }
  std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) {
    return a.first > b.first || (a.first == b.first && a.second < b.second);
  });
  double best = -1.0, threshold = floor;  // best: squared; threshold: max(floor, √best)
  int where = -1;
  for (const auto& [cluster_bound, g] : order) {
    if (cluster_bound < threshold) break;
    const int first_point = g * kClusterPoints;
    const int points = std::min(itf.points - first_point, kClusterPoints);
    // The points' own bounds, c_pj summed over j in one pass down the cluster's column slice.
    std::fill(point_bounds.begin(), point_bounds.begin() + points, 0.0);
    for (int j = 0; j < inputs_; ++j) {
      const double* column = itf.point_bound.data() + j * itf.points + first_point;
      const double v = abs_x[static_cast<std::size_t>(j)];
      for (int p = 0; p < points; ++p) point_bounds[static_cast<std::size_t>(p)] += column[p] * v;
    }
    for (int p = 0; p < points; ++p) {
      if (point_bounds[static_cast<std::size_t>(p)] < threshold) continue;
      // The point's six rows, each summed over j in order (the same arithmetic as any other
      // evaluation of the rows: largest(), field()).
      double y[kStressRowsPerPoint];
      stress_detail::pointRows(itf.rows.data() + kStressRowsPerPoint * (first_point + p), all_rows,
                               x.data(), inputs_, y);
      double vm2[fullorder::kShellSurfaces];
      stress_detail::stationsOf(y, vm2);
      for (int z = 0; z < fullorder::kShellSurfaces; ++z) {
        const int s = fullorder::kShellSurfaces * (first_point + p) + z;
        if (vm2[z] > best || (vm2[z] == best && s < where)) {
          best = vm2[z];
          where = s;
          threshold = std::max(floor, std::sqrt(best));
        }
      }
    }
  }
  if (where < 0) return -1.0;
  if (station) *station = where;
  return std::sqrt(std::max(best, 0.0));
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
  MASTROM_REQUIRE(states.rows() == inputs_ && samples >= 1, InputError,
                  "rom stresses: ", states.rows(), " × ", samples, " states for inputs of size ",
                  inputs_);
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
  out.sample_von_mises_pa = out.von_mises_pa;
  if (polishable(n, samples, no_polish))
    polish(i, states.col(n - 1), states.col(n), states.col(n + 1), out);
  return out;
}

bool ModalStressEvaluator::polishable(long n, long samples, const std::vector<char>& no_polish) {
  const auto near_breakpoint = [&no_polish](long m) {
    return m >= 0 && static_cast<std::size_t>(m) < no_polish.size() &&
           no_polish[static_cast<std::size_t>(m)];
  };
  return n > 0 && n + 1 < samples && !near_breakpoint(n - 1) && !near_breakpoint(n) &&
         !near_breakpoint(n + 1);
}

void ModalStressEvaluator::polish(int i, const Eigen::Ref<const Eigen::VectorXd>& before,
                                  const Eigen::Ref<const Eigen::VectorXd>& at,
                                  const Eigen::Ref<const Eigen::VectorXd>& after, Peak& out) const {
  double value = 0.0, offset = 0.0;
  if (parabolaMaximum(station(i, out.station, before), station(i, out.station, at),
                      station(i, out.station, after), value, offset)) {
    out.von_mises_pa = std::max(out.von_mises_pa, value);
    out.sample = static_cast<double>(out.nearest_sample) + offset;
  }
}

long ModalStressEvaluator::lastPeakEvaluations() { return t_peak_evaluations; }

std::vector<char> samplesNearBreakpoints(const SampledDrive& drive) {
  std::vector<char> marked(static_cast<std::size_t>(drive.steps + 1), 0);
  for (long n = 1; n < drive.steps; ++n) {
    const SampledDrive::Sample& s = drive.samples[static_cast<std::size_t>(n)];
    if (s.start_acceleration_rad_s2 != s.end_acceleration_rad_s2)
      marked[static_cast<std::size_t>(n)] = 1;
  }
  for (const SampledDrive::Split& split : drive.splits) {
    marked[static_cast<std::size_t>(split.step)] = 1;
    marked[static_cast<std::size_t>(split.step + 1)] = 1;
  }
  return marked;
}

}  // namespace mastrom::rom
