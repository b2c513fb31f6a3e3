// The stress peaks of a ROM deployment found while its modes step, without the state of every
// sample (docs/theory.md §6.5). ModalStressEvaluator::peak searches the recorded states of all
// samples best-first; on the default output grid of an 8 s deployment (320 001 samples, 25 inputs)
// those are 64 MB written in the series' pass and read again, more than the series itself costs.
// The stream keeps one block of kBoundBlock states (and the samples either side of it), and when
// the block is complete runs peak()'s search on it: the block's bound Σ_j c_j max_block |x_j|
// against the largest value found so far (and a floor), then its samples in descending bound,
// each evaluated exactly where it can reach that value. Every sample whose stress is at least the
// final peak is evaluated, so the peak, its sample and station, and the parabola polish through
// its neighbours are those of peak() bit for bit (ties keep the earliest sample there too).
// The floor makes the early blocks cheap: a value the peak is known to reach (the samples of a
// coarser pass, less a margin) prunes every block that cannot reach it. A floor above the true
// peak is detected (no sample reached it), and the caller then needs the recorded search.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "rom/model/modal_stepping.hpp"
#include "rom/model/modal_stress_response.hpp"

namespace mastrom::rom {

/// The share a floor taken from a coarser grid's samples is lowered by: their states differ from
/// the output grid's at the same instants by the coarser first-order hold of the forcing, O(Δ²)
/// (a 2 ms grid's stress peaks are within 8e-5 of a 10 µs grid's on Scheme 3,
/// benchmarks/README.md), and a floor too high is only detected, at the price of a second pass.
inline constexpr double kStressFloorMargin = 0.02;

class StressPeakStream {
public:
  /// `floors`: one per interface, a value its peak reaches (≤ 0: none).
  StressPeakStream(const ModalStressEvaluator& evaluator, const SampledDrive& drive,
                   std::vector<double> floors);

  /// The state of sample n (called for n = 0, 1, … in order, as a ModalSampleObserver).
  void add(long n, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
           const stepping_detail::ForcingScalars& f);
  /// The observer that feeds this stream (it must outlive the deployment).
  ModalSampleObserver observer();

  /// After the last sample. True when every interface's peak reached its floor: then `peaks` are
  /// peak()'s on the states of every sample and `peak_states` the state at each peak's nearest
  /// sample. False otherwise (a floor above the peak: nothing is certain).
  bool finish(std::vector<ModalStressEvaluator::Peak>& peaks,
              std::vector<Eigen::VectorXd>& peak_states);

  /// Blocks whose samples were searched, over all interfaces (diagnostics).
  long blocksSearched() const { return blocks_searched_; }

private:
  static constexpr long kBlock = ModalStressEvaluator::kBoundBlock;
  struct Found {
    ModalStressEvaluator::Peak peak;
    Eigen::VectorXd before, at, after;  ///< x at the peak's sample and its neighbours
    bool has_before = false, has_after = false;
  };
  void searchBlock(bool has_next);

  const ModalStressEvaluator& evaluator_;
  std::vector<char> no_polish_;
  long samples_ = 0;
  std::vector<double> floors_;
  std::vector<Found> found_;
  /// Column 0: the sample before the block (when there is one); 1 … kBlock: the block from
  /// sample base_; kBlock + 1: the sample after it.
  Eigen::MatrixXd buffer_;
  long base_ = 0, filled_ = 0;  ///< first sample of the block, samples of it in the buffer
  long blocks_searched_ = 0;
  std::vector<std::pair<double, long>> candidates_;
};

}  // namespace mastrom::rom
