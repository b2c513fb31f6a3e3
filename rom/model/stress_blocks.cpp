// The stress peaks from the starts of a deployment's blocks (stress_blocks.hpp; docs/theory.md
// §6.5, "Blocks instead of samples").
#include "rom/model/stress_blocks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/error.hpp"

namespace mastrom::rom {

StressBlockRecord::StressBlockRecord(const ModalStressEvaluator& evaluator, const ModalModel& model,
                                     const SampledDrive& drive, bool coriolis_coupling)
    : ev_(evaluator),
      model_(model),
      drive_(drive),
      ms_(prepareModalStepping(model, drive, coriolis_coupling)) {
  MASTROM_REQUIRE(drive.steps >= 1, InputError, "rom stresses: a deployment of ", drive.steps,
                  " steps");
  blocks_ = (drive.steps + SampledDrive::kBlockSteps - 1) / SampledDrive::kBlockSteps;
  eta_.resize(model.modeCount(), blocks_);
  eta_dot_.resize(model.modeCount(), blocks_);
  bound_ = Eigen::MatrixXd::Constant(evaluator.interfaceCount(), blocks_,
                                     std::numeric_limits<double>::infinity());
  mode_weights_.resize(model.modeCount());
  replayed_.assign(static_cast<std::size_t>(blocks_), 0);
}

long StressBlockRecord::distinctBlocksReplayed() const {
  return static_cast<long>(std::count(replayed_.begin(), replayed_.end(), 1));
}

ModalBlockObserver StressBlockRecord::observer() {
  return [this](long block, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
                const ModalStateBounds* bounds) { add(block, eta, eta_dot, bounds); };
}

void StressBlockRecord::add(long block, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
                            const ModalStateBounds* bounds) {
  eta_.col(block) = eta;
  eta_dot_.col(block) = eta_dot;
  if (!bounds) return;  // stays +inf
  // (6.10) over the block: |η_k + μη̇_k| ≤ |η_k|max + μ|η̇_k|max, and the load scalars' maxima.
  const int k = model_.modeCount();
  const double mu = ev_.damping();
  for (int j = 0; j < k; ++j) mode_weights_[j] = bounds->eta[j] + mu * bounds->rate[j];
  for (int i = 0; i < ev_.interfaceCount(); ++i) {
    const Eigen::VectorXd& c = ev_.bound(i);
    const double b = c.head(k).dot(mode_weights_) + c[k] * bounds->acc + c[k + 1] * bounds->rate2 +
                     (c[k + 2] + c[k + 3]) * bounds->gravity + c[k + kStressLoadCount];
    if (std::isfinite(b)) bound_(i, block) = b;
  }
}

const StressBlockRecord::Replay& StressBlockRecord::replay(long block) const {
  for (const Replay& r : held_)
    if (r.block == block) return r;
  Replay& r = held_[next_slot_];
  next_slot_ = (next_slot_ + 1) % kHeld;
  ++replays_;
  replayed_[static_cast<std::size_t>(block)] = 1;
  r.block = block;
  r.first = block * SampledDrive::kBlockSteps;
  const long last = std::min(r.first + SampledDrive::kBlockSteps, drive_.steps);
  const long count = last - r.first + 1;
  r.eta.resize(model_.modeCount(), count);
  r.eta_dot.resize(model_.modeCount(), count);
  r.x.resize(ev_.inputSize(), count);
  runModalSteppingRange(
      model_, ms_, drive_, r.first, last, eta_.col(block), eta_dot_.col(block),
      [&](long n, const Eigen::VectorXd& e, const Eigen::VectorXd& v, const Eigen::VectorXd&) {
        const long j = n - r.first;
        r.eta.col(j) = e;
        r.eta_dot.col(j) = v;
        // The recorder's state (modalStressRecorder): the same bits as a recorded pass.
        ev_.input(e, v, stepping_detail::forcingScalars(ms_, drive_.valueAt(n)), r.x.col(j));
      },
      [](long, int, const Eigen::VectorXd&, const Eigen::VectorXd&, const Eigen::ArrayXd&,
         const Eigen::ArrayXd&) {});
  return r;
}

std::pair<const double*, const double*> StressBlockRecord::at(long n) const {
  for (const Replay& r : held_)
    if (r.block >= 0 && n >= r.first && n - r.first < r.eta.cols())
      return {r.eta.col(n - r.first).data(), r.eta_dot.col(n - r.first).data()};
  const Replay& r = replay(blockOf(n));
  return {r.eta.col(n - r.first).data(), r.eta_dot.col(n - r.first).data()};
}

Eigen::VectorXd StressBlockRecord::input(long n) const {
  for (const Replay& r : held_)
    if (r.block >= 0 && n >= r.first && n - r.first < r.x.cols()) return r.x.col(n - r.first);
  const Replay& r = replay(blockOf(n));
  return r.x.col(n - r.first);
}

double StressBlockRecord::stepBound(int i, long n, long* block_end) const {
  const long b = blockOf(n);
  *block_end = b + 1 == blocks_ ? drive_.steps : (b + 1) * SampledDrive::kBlockSteps;
  return bound_(i, b);
}

std::vector<ModalStressEvaluator::Peak> StressBlockRecord::samplePeaks() const {
  const int interfaces = ev_.interfaceCount(), inputs = ev_.inputSize();
  // ModalStressEvaluator::peak's search with the blocks' bounds in place of its blocks of recorded
  // states, for all interfaces in one pass over the blocks (each re-stepped once): a block is
  // searched for the interfaces whose bound there reaches their largest value found, its samples
  // that can still hold more best first. Every sample whose stress reaches an interface's final
  // peak is evaluated whatever the order, so the result is peak()'s (ties: the earliest sample);
  // the order — the blocks by their largest bound relative to each interface's largest — only
  // makes the first values found high, so that the rest prune.
  Eigen::VectorXd scale(interfaces);
  for (int i = 0; i < interfaces; ++i) {
    double largest = 0.0;
    for (long b = 0; b < blocks_; ++b)
      if (std::isfinite(bound_(i, b))) largest = std::max(largest, bound_(i, b));
    scale[i] = largest > 0.0 ? largest : 1.0;
  }
  std::vector<std::pair<double, long>> order;
  for (long b = 0; b < blocks_; ++b)
    order.emplace_back((bound_.col(b).array() / scale.array()).maxCoeff(), b);
  std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) {
    return a.first > b.first || (a.first == b.first && a.second < b.second);
  });
  std::vector<ModalStressEvaluator::Peak> out(static_cast<std::size_t>(interfaces));
  for (ModalStressEvaluator::Peak& p : out) p.von_mises_pa = -1.0;
  std::vector<std::pair<double, long>> candidates;
  for (const auto& [key, b] : order) {
    bool needed = false;
    for (int i = 0; i < interfaces; ++i)
      needed = needed || bound_(i, b) >= out[static_cast<std::size_t>(i)].von_mises_pa;
    if (!needed) continue;
    const Replay& r = replay(b);
    // The block's samples; the next block's first sample belongs to that block, except after
    // the last block.
    const long end = b + 1 == blocks_ ? r.first + r.x.cols() : r.first + r.x.cols() - 1;
    for (int i = 0; i < interfaces; ++i) {
      ModalStressEvaluator::Peak& pk = out[static_cast<std::size_t>(i)];
      if (bound_(i, b) < pk.von_mises_pa) continue;
      const Eigen::VectorXd& c = ev_.bound(i);
      candidates.clear();
      for (long n = r.first; n < end; ++n) {
        const double* x = r.x.col(n - r.first).data();
        double bn = 0.0;
        for (int j = 0; j < inputs; ++j) bn += c[j] * std::abs(x[j]);
        if (bn >= pk.von_mises_pa) candidates.emplace_back(bn, n);
      }
      std::sort(candidates.begin(), candidates.end(), [](const auto& a, const auto& b) {
        return a.first > b.first || (a.first == b.first && a.second < b.second);
      });
      for (const auto& [bn, n] : candidates) {
        if (bn < pk.von_mises_pa) break;
        int where = 0;
        const double v = ev_.largestAbove(i, r.x.col(n - r.first), pk.von_mises_pa, &where);
        if (v > pk.von_mises_pa || (v == pk.von_mises_pa && n < pk.nearest_sample))
          pk.von_mises_pa = v, pk.station = where, pk.nearest_sample = n;
      }
    }
  }
  return out;
}

std::vector<ModalStressEvaluator::Peak> StressBlockRecord::peaks(
    const std::vector<char>& no_polish) {
  std::vector<ModalStressEvaluator::Peak> found = samplePeaks();
  for (int i = 0; i < ev_.interfaceCount(); ++i) {
    // peak()'s polish: the parabola through the peak sample and its neighbours.
    ModalStressEvaluator::Peak& out = found[static_cast<std::size_t>(i)];
    const long n = out.nearest_sample;
    out.sample = static_cast<double>(n);
    out.sample_von_mises_pa = out.von_mises_pa;
    if (ModalStressEvaluator::polishable(n, drive_.steps + 1, no_polish)) {
      const Eigen::VectorXd before = input(n - 1), at = input(n), after = input(n + 1);
      ev_.polish(i, before, at, after, out);
    }
  }
  if (stressPeaksNeedRefinement(ev_, model_, drive_.step_s))
    refineStressPeaks(ev_, model_, drive_, *this, found);
  return found;
}

}  // namespace mastrom::rom
