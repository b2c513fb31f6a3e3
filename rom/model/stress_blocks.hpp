// The stress peaks of a ROM deployment from the starts of its blocks (docs/theory.md §6.5, "Blocks
// instead of samples"). The peak search and the refinement between samples read the modal state of
// the samples that can hold a peak, a few blocks of a deployment; recording η, η̇ and the stress
// state x of every sample in the metrics' pass cost more than the search itself. So the pass keeps,
// per block of SampledDrive::kBlockSteps steps, only the state at its first sample and an upper
// bound of each interface's stress over the block, from the quiet blocks' bounds of the modal state
// (rom/model/quiet_blocks.hpp, docs/theory.md §4.2c) through (6.10):
//     max over the block and the stations of σ_vM ≤ Σ_k c_k (|η_k|max + μ|η̇_k|max)
//                                                  + c_θ̈ max|θ̈| + c_θ̇² max θ̇² + (c_gx + c_gy)
//                                                  max|g| + c_σ̄,
// and the search re-steps a block (runModalSteppingRange: the pass's own arithmetic, so the same
// states bit for bit) only when its bound reaches the largest value found so far — best block
// first, then its samples best-first as ModalStressEvaluator::peak does. Every sample whose stress
// reaches the final peak is evaluated, so the peak, its sample, station and polish are peak()'s on
// every sample's recorded state; the refinement between samples skips the blocks whose bound is
// below every interface's peak (no step in them can raise one: the same result). A block with a
// breakpoint, or a pass without quiet blocks, has no bound (+inf): it is always re-stepped.
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "rom/model/deployment_metrics.hpp"
#include "rom/model/modal_model.hpp"
#include "rom/model/modal_stepping.hpp"
#include "rom/model/modal_stress_response.hpp"

namespace mastrom::rom {

class StressBlockRecord final : public ModalSampleStates {
public:
  /// For a pass of modalDeploymentMetrics on `drive` with this Coriolis setting (borrowed: all
  /// must outlive the record).
  StressBlockRecord(const ModalStressEvaluator& evaluator, const ModalModel& model,
                    const SampledDrive& drive, bool coriolis_coupling);

  /// The observer that fills the record from the metrics' pass (modalDeploymentMetrics'
  /// block_observer; it borrows the record).
  ModalBlockObserver observer();
  /// The state at the first sample of `block` and the bounds of the modal state over it (null:
  /// none known).
  void add(long block, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
           const ModalStateBounds* bounds);

  long blockCount() const { return blocks_; }
  /// The upper bound of interface i's von Mises stress over block b [Pa] (+inf: none).
  double blockBound(int i, long b) const { return bound_(i, b); }
  /// Every interface's peak from the blocks (header), polished, then refined between the samples
  /// where the grid is coarse for the polish (stressPeaksNeedRefinement): what findStressPeaks
  /// gives from every sample's recorded state.
  std::vector<ModalStressEvaluator::Peak> peaks(const std::vector<char>& no_polish);
  /// The stress state x of sample n (re-stepping its block unless it is the one held).
  Eigen::VectorXd input(long n) const;
  /// Blocks re-stepped so far, and how many of them distinct (diagnostics for tests and
  /// benchmarks).
  long blocksReplayed() const { return replays_; }
  long distinctBlocksReplayed() const;

  std::pair<const double*, const double*> at(long n) const override;
  double stepBound(int i, long n, long* block_end) const override;

private:
  /// The states of one block's samples, first … last (the next block's first sample included).
  struct Replay {
    long block = -1, first = 0;
    Eigen::MatrixXd eta, eta_dot, x;
  };
  const Replay& replay(long block) const;
  long blockOf(long n) const { return std::min(n / SampledDrive::kBlockSteps, blocks_ - 1); }
  /// Every interface's largest sample (not yet polished).
  std::vector<ModalStressEvaluator::Peak> samplePeaks() const;

  const ModalStressEvaluator& ev_;
  const ModalModel& model_;
  const SampledDrive& drive_;
  ModalStepping ms_;
  long blocks_ = 0;
  Eigen::MatrixXd eta_, eta_dot_;  ///< modes × blocks: the state at each block's first sample
  Eigen::MatrixXd bound_;          ///< interfaces × blocks
  Eigen::VectorXd mode_weights_;   ///< scratch: |η|max + μ|η̇|max per mode
  static constexpr int kHeld = 4;
  mutable Replay held_[kHeld];  ///< the blocks re-stepped last (the polish and the refinement
                                ///< read neighbouring samples)
  mutable int next_slot_ = 0;
  mutable long replays_ = 0;
  mutable std::vector<char> replayed_;  ///< per block: re-stepped at least once
};

}  // namespace mastrom::rom
