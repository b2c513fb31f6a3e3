// StressPeakStream (stress_peak_stream.hpp): ModalStressEvaluator::peak's best-first search run one
// block of samples at a time while the modes step (docs/theory.md §6.5).
#include "rom/model/stress_peak_stream.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "rom/model/parabola_polish.hpp"

namespace mastrom::rom {

StressPeakStream::StressPeakStream(const ModalStressEvaluator& evaluator, const SampledDrive& drive,
                                   std::vector<double> floors)
    : evaluator_(evaluator),
      no_polish_(samplesNearBreakpoints(drive)),
      samples_(drive.steps + 1),
      floors_(std::move(floors)),
      found_(static_cast<std::size_t>(evaluator.interfaceCount())),
      buffer_(evaluator.inputSize(), kBlock + 2) {
  floors_.resize(found_.size(), -1.0);
  // No floor is peak()'s start: every value (≥ 0) beats −1.
  for (double& f : floors_)
    if (!(f > 0.0)) f = -1.0;
  for (Found& f : found_) f.peak.von_mises_pa = -1.0;
}

void StressPeakStream::add(long n, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
                           const stepping_detail::ForcingScalars& f) {
  if (filled_ == kBlock) {  // n opens the next block: the current one is complete
    evaluator_.input(eta, eta_dot, f, buffer_.col(kBlock + 1));
    searchBlock(/*has_next=*/true);
    buffer_.col(0) = buffer_.col(kBlock);
    buffer_.col(1) = buffer_.col(kBlock + 1);
    base_ += kBlock;
    filled_ = 1;
    return;
  }
  evaluator_.input(eta, eta_dot, f, buffer_.col(1 + filled_));
  ++filled_;
  (void)n;  // the samples come in order: n = base_ + filled_ − 1
}

ModalSampleObserver StressPeakStream::observer() {
  return [this](long n, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
                const stepping_detail::ForcingScalars& f) { add(n, eta, eta_dot, f); };
}

void StressPeakStream::searchBlock(bool has_next) {
  const int inputs = evaluator_.inputSize();
  const long count = filled_;
  const Eigen::VectorXd block_max = buffer_.middleCols(1, count).cwiseAbs().rowwise().maxCoeff();
  for (int i = 0; i < evaluator_.interfaceCount(); ++i) {
    Found& found = found_[static_cast<std::size_t>(i)];
    ModalStressEvaluator::Peak& out = found.peak;
    const double floor = floors_[static_cast<std::size_t>(i)];
    const Eigen::VectorXd& c = evaluator_.bound(i);
    if (block_max.dot(c) < std::max(floor, out.von_mises_pa)) continue;
    ++blocks_searched_;
    // As peak(): the samples that can still reach the largest value, in descending bound (ties:
    // earliest first), each evaluated where it can reach it.
    candidates_.clear();
    for (long col = 1; col <= count; ++col) {
      const double* x = buffer_.col(col).data();
      double b = 0.0;
      for (int j = 0; j < inputs; ++j) b += c[j] * std::abs(x[j]);
      if (b >= std::max(floor, out.von_mises_pa)) candidates_.emplace_back(b, base_ + col - 1);
    }
    std::sort(candidates_.begin(), candidates_.end(),
              [](const std::pair<double, long>& a, const std::pair<double, long>& b) {
                return a.first > b.first || (a.first == b.first && a.second < b.second);
              });
    for (const auto& [b, n] : candidates_) {
      const double threshold = std::max(floor, out.von_mises_pa);
      if (b < threshold) break;
      const long col = n - base_ + 1;
      int where = 0;
      // Exact when it reaches the threshold (largestAbove); below it, not a value to keep.
      const double v = evaluator_.largestAbove(i, buffer_.col(col), threshold, &where);
      if (v < threshold) continue;
      if (v > out.von_mises_pa || (v == out.von_mises_pa && n < out.nearest_sample)) {
        out.von_mises_pa = v, out.station = where, out.nearest_sample = n;
        found.at = buffer_.col(col);
        found.has_before = n > 0;
        if (found.has_before) found.before = buffer_.col(col - 1);
        found.has_after = col < count || has_next;
        if (found.has_after) found.after = buffer_.col(col + 1);
      }
    }
  }
}

bool StressPeakStream::finish(std::vector<ModalStressEvaluator::Peak>& peaks,
                              std::vector<Eigen::VectorXd>& peak_states) {
  if (filled_ > 0) searchBlock(/*has_next=*/false);
  filled_ = 0;
  peaks.clear();
  peak_states.clear();
  bool certain = true;
  const auto near_breakpoint = [this](long m) {
    return m >= 0 && static_cast<std::size_t>(m) < no_polish_.size() &&
           no_polish_[static_cast<std::size_t>(m)];
  };
  for (int i = 0; i < evaluator_.interfaceCount(); ++i) {
    Found& found = found_[static_cast<std::size_t>(i)];
    ModalStressEvaluator::Peak out = found.peak;
    if (out.von_mises_pa < floors_[static_cast<std::size_t>(i)] || out.von_mises_pa < 0.0) {
      certain = false;
      continue;
    }
    // peak()'s polish: the parabola through the peak sample and its neighbours, same station.
    const long n = out.nearest_sample;
    out.sample = static_cast<double>(n);
    out.sample_von_mises_pa = out.von_mises_pa;
    if (n > 0 && n + 1 < samples_ && found.has_before && found.has_after &&
        !near_breakpoint(n - 1) && !near_breakpoint(n) && !near_breakpoint(n + 1)) {
      double value = 0.0, offset = 0.0;
      if (parabolaMaximum(evaluator_.station(i, out.station, found.before),
                          evaluator_.station(i, out.station, found.at),
                          evaluator_.station(i, out.station, found.after), value, offset)) {
        out.von_mises_pa = std::max(out.von_mises_pa, value);
        out.sample = static_cast<double>(n) + offset;
      }
    }
    peaks.push_back(out);
    peak_states.push_back(found.at);
  }
  return certain;
}

}  // namespace mastrom::rom
