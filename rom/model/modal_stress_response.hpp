// The interface stresses of a ROM deployment (docs/theory.md §6.5): the mode-acceleration sum of
// rom/model/modal_stress.hpp evaluated on the modal state of every output sample — per interface
// the largest von Mises stress over its recovery points and ζ stations (the full order's
// definition, fullorder/interface_stress.hpp), its history, and its peak with where and when.
//
// Cost. An interface's stresses at one instant are one matrix–vector product (6P × (k + 5)) and the
// von Mises of every station. The history needs that at every sample; a peak alone does not: von
// Mises is a norm of the stress vector, so at any state x = [η + μη̇; f; 1]
//     max over stations ≤ b(x) = Σ_j c_j |x_j|,   c_j = the largest von Mises of column j alone,
// and the peak is found best-first — the samples in descending b, evaluated until b falls to the
// largest value found (exact: the same max as the history's, at a few evaluations per deployment).
// b itself costs (k + 5) multiply-adds per sample and interface, more than the stepping: it is
// computed only inside blocks of 64 samples whose own bound Σ_j c_j max_block |x_j| (one max per
// sample and input for all interfaces) exceeds the largest value found, best block first.
// Between samples. The largest sample is polished by the parabola through it and its two
// neighbours at the same station (the stress is smooth: displacement-like, C¹ across the jumps of
// θ̈ up to the static correction's step, so no polish next to a breakpoint); error ≤ 0.0234 (ωΔ)⁴
// of the amplitude of a mode of frequency ω, against (ωΔ)²/8 for the plain sample max.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <utility>
#include <vector>

#include "fullorder/drive_law.hpp"
#include "fullorder/interface_stress.hpp"
#include "rom/model/deployment_metrics.hpp"
#include "rom/model/modal_deployment.hpp"
#include "rom/model/modal_model.hpp"
#include "rom/model/modal_stepping.hpp"

namespace mastrom::rom {

class ModalStressEvaluator {
public:
  /// InputError when the model carries no stresses.
  explicit ModalStressEvaluator(const ModalModel& model);

  int interfaceCount() const { return static_cast<int>(interfaces_.size()); }
  /// Length of the state x: modes + load scalars + 1 (the preload's coefficient).
  int inputSize() const { return inputs_; }
  /// x = [η + μη̇; θ̈, θ̇², g_x, g_y; 1] at an instant with forcing scalars f.
  void input(const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
             const stepping_detail::ForcingScalars& f, Eigen::Ref<Eigen::VectorXd> x) const;

  /// The largest von Mises stress [Pa] of interface i at x, and where (station = point·3 + s,
  /// s = 0, 1, 2 for ζ = −h/2, 0, +h/2).
  double largest(int i, const Eigen::Ref<const Eigen::VectorXd>& x, int* station = nullptr) const;
  /// Points per cluster of largestAbove(): consecutive recovery points, i.e. neighbouring ones.
  static constexpr int kClusterPoints = 16;
  /// largest() where it can reach `floor`: the clusters of kClusterPoints points are visited in
  /// descending order of their bound Σ_j c_gj |x_j| (c_gj: column j's largest von Mises over the
  /// cluster), and within a cluster a point's stresses are computed only when its own bound
  /// Σ_j c_pj |x_j| (the same over its three stations) reaches the threshold, max(floor, largest
  /// value found so far): a bound below it cannot hold the largest value. The exact largest value
  /// when that is ≥ floor (bit for bit largest()'s, each row summed over j in order; of equal
  /// values the lowest station); otherwise some value < floor (−1 when no point was computed),
  /// station then unset.
  double largestAbove(int i, const Eigen::Ref<const Eigen::VectorXd>& x, double floor,
                      int* station = nullptr) const;
  /// largest() at every column of `states` (inputSize × samples), into `out`: a History fed with
  /// every column.
  void largestHistory(int i, const Eigen::MatrixXd& states, std::vector<double>& out) const;

  /// The largest von Mises of interface i sample after sample (rom/model/stress_history.cpp,
  /// docs/theory.md §6.5 "Histories"): each value largest()'s bit for bit, computing only the
  /// points whose bound from their own last computed value, m_p + Σ_j c_pj |x_j − x_p,j|, can
  /// reach the largest value of the sample — the previous sample's largest point first.
  class History {
  public:
    History(const ModalStressEvaluator& evaluator, int interface_index);
    /// The largest von Mises [Pa] at state x (the samples in time order for the pruning to pay;
    /// any order gives the exact values).
    double next(const Eigen::Ref<const Eigen::VectorXd>& x);
    /// Points computed so far, and samples fed (diagnostics for tests and benchmarks).
    long pointsComputed() const { return computed_; }
    long samples() const { return samples_; }

  private:
    double computePoint(int p, const Eigen::Ref<const Eigen::VectorXd>& x);
    const ModalStressEvaluator& evaluator_;
    int interface_;
    Eigen::VectorXd point_value_;    ///< m_p: the point's largest value when last computed [Pa]
    Eigen::MatrixXd point_state_;    ///< x_p: the state it was computed at (points × inputs)
    Eigen::VectorXd cluster_value_;  ///< M_g: a bound of the cluster's points at x_g [Pa]
    Eigen::MatrixXd cluster_state_;  ///< x_g (clusters × inputs)
    Eigen::VectorXd cluster_drift_;  ///< Σ_j c_gj |x_j − x_g,j| of the current sample
    Eigen::MatrixXd point_rows_;     ///< a point's six rows, j-major (6·inputs × points)
    int largest_point_ = -1;         ///< the previous sample's largest point
    long computed_ = 0, samples_ = 0;
  };
  /// The von Mises stress of every station of interface i at x (point-major).
  void field(int i, const Eigen::Ref<const Eigen::VectorXd>& x, std::vector<double>& vm) const;
  /// The von Mises stress of one station.
  double station(int i, int station, const Eigen::Ref<const Eigen::VectorXd>& x) const;

  struct Peak {
    double von_mises_pa = 0.0;
    double sample = 0.0;  ///< the (fractional, after the polish) sample index of the peak
    long nearest_sample = 0;
    int station = 0;
    double sample_von_mises_pa = 0.0;  ///< the largest sample's value, before the polish
  };
  /// The largest |x_j| of every block of kBoundBlock consecutive columns of `states`
  /// (inputSize × blocks): what the block bounds of peak() are made of, one pass for all
  /// interfaces.
  static constexpr long kBoundBlock = 64;
  Eigen::MatrixXd blockMaxima(const Eigen::MatrixXd& states) const;
  /// The peak of interface i over the columns of `states` (inputSize × samples), found best-first
  /// (header comment) and polished between samples unless a breakpoint is near: no_polish[n] true
  /// for the samples where the drive's θ̈ jumps (may be empty).
  /// `block_maxima` (may be null): blockMaxima(states), computed once for all interfaces.
  Peak peak(int i, const Eigen::MatrixXd& states, const std::vector<char>& no_polish,
            const Eigen::MatrixXd* block_maxima = nullptr) const;
  /// Exact evaluations spent by the last peak() on this thread (diagnostics for tests/benchmarks).
  static long lastPeakEvaluations();
  /// Whether peak()'s parabola polish applies at sample n of `samples`: away from the ends and
  /// from the samples no_polish marks.
  static bool polishable(long n, long samples, const std::vector<char>& no_polish);
  /// peak()'s polish of `out` (at its nearest sample, polishable) from the states of that sample
  /// and its two neighbours: the parabola through them at the peak's station.
  void polish(int i, const Eigen::Ref<const Eigen::VectorXd>& before,
              const Eigen::Ref<const Eigen::VectorXd>& at,
              const Eigen::Ref<const Eigen::VectorXd>& after, Peak& out) const;
  /// c_j of interface i (the bound b of the header).
  const Eigen::VectorXd& bound(int i) const { return interfaces_[static_cast<std::size_t>(i)].bound; }
  int modeCount() const { return modes_; }
  double damping() const { return damping_s_; }

private:
  struct Interface {
    Eigen::MatrixXd rows;   ///< [S | S_res | σ̄] of its points (6P × inputs)
    Eigen::VectorXd bound;  ///< c_j
    Eigen::MatrixXd cluster_bound;  ///< c_gj (clusters × inputs)
    Eigen::MatrixXd point_bound;    ///< c_pj (points × inputs)
    int points = 0;
  };
  std::vector<Interface> interfaces_;
  int modes_ = 0, inputs_ = 0;
  double damping_s_ = 0.0;
};

/// The observer that records the modal state x of every output sample into `states`
/// (inputSize × (steps + 1), sized by the caller) — in the metrics pass of a screen
/// (modalDeploymentMetrics) or a pass of its own (modalStressStates).
ModalSampleObserver modalStressRecorder(const ModalStressEvaluator& evaluator,
                                        Eigen::MatrixXd& states);
/// The same, also keeping η and η̇ of every sample (modes × samples each, sized by the caller):
/// what refineStressPeaks re-steps from.
ModalSampleObserver modalStressRecorder(const ModalStressEvaluator& evaluator,
                                        Eigen::MatrixXd& states, Eigen::MatrixXd& eta,
                                        Eigen::MatrixXd& eta_dot);

/// η and η̇ at the samples of a deployment, what the refinement between samples re-steps from:
/// recorded at every sample (RecordedModalStates) or re-stepped from the start of their block on
/// demand (StressBlockRecord, rom/model/stress_blocks.hpp).
class ModalSampleStates {
public:
  virtual ~ModalSampleStates() = default;
  /// η (first) and η̇ (second) at sample n, the model's mode count each; valid until the next call.
  virtual std::pair<const double*, const double*> at(long n) const = 0;
  /// An upper bound of interface i's von Mises stress over a block of steps holding step n, and
  /// that block's end (the first step after it) into *block_end; +inf and n + 1 when none is known.
  virtual double stepBound(int i, long n, long* block_end) const;
};

/// Every sample's η and η̇ recorded (modes × samples each; borrowed).
class RecordedModalStates final : public ModalSampleStates {
public:
  RecordedModalStates(const Eigen::MatrixXd& eta, const Eigen::MatrixXd& eta_dot)
      : eta_(eta), eta_dot_(eta_dot) {}
  std::pair<const double*, const double*> at(long n) const override {
    return {eta_.col(n).data(), eta_dot_.col(n).data()};
  }
  long samples() const { return eta_.cols(); }

private:
  const Eigen::MatrixXd& eta_;
  const Eigen::MatrixXd& eta_dot_;
};

/// Between samples on a coarse grid. The parabola polish (header) needs ωΔ well below 1 for the
/// modes that carry the stress; at a 1 ms screen step the first bending mode of Scheme 3 (316 Hz)
/// has ωΔ ≈ 2 and the sampled peak after a jump of θ̈ reads 23 % low. Then every step whose bound
/// can exceed the peak is re-stepped exactly with the maps of h = Δ/m: over a step, each mode is
/// the particular solution η_p of its linear forcing plus a free oscillation whose amplitude
/// a = (y² + ẏ²/ω²)^½ cannot grow (the energy argument of rom/model/deployment_metrics.hpp), so
///     |η + μη̇| ≤ max(|η_p(t_n)|, |η_p(t_n+1)|) + μ|η̇_p| + a(1 + μω),
/// the load scalars are linear between the step's one-sided limits, and b of those maxima bounds
/// the stress over the step. m is the coarsest power of two whose estimated polish error
/// Σ_j c_j a_j e(ω_j h), e(x) = min(2, 0.0234 x⁴), is ≤ 1e-4 of the peak; the sub-samples whose b
/// exceeds the peak are evaluated and the largest polished.
/// The samples' polish is trusted when its estimated error Σ_k s_k e(ω_k Δ), s_k = c_k|Γ_k|/ω_k²
/// (a mode's static deflection per unit θ̈, also the scale of its ringing after a jump of θ̈),
/// e(x) = min(2, 0.0234 x⁴), is at most this share of max_k s_k; otherwise the grid is coarse and
/// the peaks are refined.
inline constexpr double kStressPolishTolerance = 1e-3;
bool stressPeaksNeedRefinement(const ModalStressEvaluator& evaluator, const ModalModel& model,
                               double step_s);
/// What the last refineStressPeaks did on this thread (tests, benchmarks): intervals bounded,
/// intervals re-stepped, sub-steps taken.
struct StressRefinementStats {
  long intervals = 0, refined = 0, sub_steps = 0;
  /// Sub-samples whose bound exceeded the peak, exact evaluations made (best-first: fewer), and
  /// those that raised the peak.
  long candidates = 0, evaluations = 0, raised = 0;
};
StressRefinementStats lastStressRefinementStats();
/// Refine `peaks` (one per interface, from peak()) between the samples of `drive` (header above).
/// The Coriolis coupling is not re-stepped (its O(θ̇/ω) share is below the tolerance).
void refineStressPeaks(const ModalStressEvaluator& evaluator, const ModalModel& model,
                       const SampledDrive& drive, const Eigen::MatrixXd& eta,
                       const Eigen::MatrixXd& eta_dot,
                       std::vector<ModalStressEvaluator::Peak>& peaks);
/// The same from η, η̇ of any source; the blocks of steps whose bound (stepBound) no interface's
/// peak is below are not looked at (no step in them can raise a peak: the same result).
void refineStressPeaks(const ModalStressEvaluator& evaluator, const ModalModel& model,
                       const SampledDrive& drive, const ModalSampleStates& states,
                       std::vector<ModalStressEvaluator::Peak>& peaks);

/// The state x at each peak's own instant (its fractional sample, after the refinement), by one
/// exact step from the sample before it (through the pieces of a split step): the field at the
/// continuous peak, not at a sample of a coarse grid. η and η̇ of every sample of `drive`.
std::vector<Eigen::VectorXd> stressPeakStates(const ModalStressEvaluator& evaluator,
                                              const ModalModel& model, const SampledDrive& drive,
                                              const Eigen::MatrixXd& eta,
                                              const Eigen::MatrixXd& eta_dot,
                                              const std::vector<ModalStressEvaluator::Peak>& peaks);
/// The same from η, η̇ of any source.
std::vector<Eigen::VectorXd> stressPeakStates(const ModalStressEvaluator& evaluator,
                                              const ModalModel& model, const SampledDrive& drive,
                                              const ModalSampleStates& states,
                                              const std::vector<ModalStressEvaluator::Peak>& peaks);

/// The samples where the drive's θ̈ jumps (on the grid, or inside a split step): no polish there.
std::vector<char> samplesNearBreakpoints(const SampledDrive& drive);

/// The modal state x of every output sample of a ROM deployment (inputSize × (steps + 1)), stepped
/// as simulateModalDeployment steps it; η and η̇ of every sample too when given.
Eigen::MatrixXd modalStressStates(const ModalModel& model, const ModalStressEvaluator& evaluator,
                                  const SampledDrive& drive, bool coriolis_coupling,
                                  Eigen::MatrixXd* eta = nullptr,
                                  Eigen::MatrixXd* eta_dot = nullptr);

/// The interface stresses of a ROM deployment in the full order's form: the peak (polished, and
/// refined between samples on a coarse grid) with where/when and the field at its nearest sample,
/// the points' unrolled coordinates, and with `history` the largest von Mises per interface at
/// every output sample (one product of the interface's rows with every sample's state: most of
/// the cost, so only on request; without it the histories are empty and time_s still lists the
/// output instants). No edge resultants (the ROM does not recover the bonded edges' reactions):
/// those histories stay empty. InputError without stress data.
fullorder::InterfaceStressResult modalInterfaceStresses(const ModalModel& model,
                                                        const fullorder::DriveLaw& drive,
                                                        const ModalDeploymentOptions& options,
                                                        bool history = true);

/// The same from the states recorded in a pass of the caller's (modalStressRecorder, e.g. in the
/// metrics' own pass of rom eval): `states` of every sample of `drive`, and η, η̇ of every sample
/// when stressPeaksNeedRefinement (else empty).
fullorder::InterfaceStressResult modalInterfaceStresses(
    const ModalModel& model, const ModalStressEvaluator& evaluator, const SampledDrive& drive,
    const Eigen::MatrixXd& states, const Eigen::MatrixXd& eta, const Eigen::MatrixXd& eta_dot,
    bool history);

/// The result of modalInterfaceStresses from peaks found elsewhere (e.g. StressPeakStream,
/// rom/model/stress_peak_stream.hpp, or the metrics' coarser pass): `drive` the output grid (its
/// instants are the histories'), `peak_step_s` the step of the grid the peaks' (fractional) samples
/// count, `peak_states` the state x whose field each peak reports. The histories are empty
/// (modalStressHistories fills them).
fullorder::InterfaceStressResult interfaceStressResult(
    const ModalModel& model, const ModalStressEvaluator& evaluator, const SampledDrive& drive,
    double peak_step_s, const std::vector<ModalStressEvaluator::Peak>& peaks,
    const std::vector<Eigen::VectorXd>& peak_states);
/// interfaceStressResult in two parts: the peaks with their fields and the points' coordinates
/// (time_s empty) …
fullorder::InterfaceStressResult interfaceStressPeaks(
    const ModalModel& model, const ModalStressEvaluator& evaluator, double peak_step_s,
    const std::vector<ModalStressEvaluator::Peak>& peaks,
    const std::vector<Eigen::VectorXd>& peak_states);
/// … and the output instants of `sampled` into r.time_s (an output's list, as long as the series).
void setStressOutputInstants(const SampledDrive& sampled, fullorder::InterfaceStressResult& r);

/// The largest von Mises of every interface at every sample of `drive` into result.history, in a
/// stepping pass of its own that keeps the states of one block of samples at a time (not those of
/// every sample): what `rom eval --stress-history` asks for.
void modalStressHistories(const ModalModel& model, const ModalStressEvaluator& evaluator,
                          const SampledDrive& drive, bool coriolis_coupling,
                          fullorder::InterfaceStressResult& result);
/// Receives the histories a block of samples at a time: values[i][j] is the largest von Mises of
/// interface i at sample first + j [Pa].
using StressHistoryBlockSink =
    std::function<void(long first, const std::vector<std::vector<double>>& values)>;
/// modalStressHistories handed to `sink` block by block (at most 128 samples), not held: the
/// streamed `rom eval -o --stress-history`. The same values bit for bit. An exception the sink
/// throws ends the stepping.
void streamModalStressHistories(const ModalModel& model, const ModalStressEvaluator& evaluator,
                                const SampledDrive& drive, bool coriolis_coupling,
                                const StressHistoryBlockSink& sink);

/// Every interface's peak from recorded states: best-first over the samples (one pass of block
/// maxima for all interfaces), then, with η and η̇ given (non-empty) on a coarse grid, refined
/// between samples. What rom eval and a screen both run.
std::vector<ModalStressEvaluator::Peak> findStressPeaks(const ModalStressEvaluator& evaluator,
                                                        const Eigen::MatrixXd& states,
                                                        const std::vector<char>& no_polish,
                                                        const ModalModel& model,
                                                        const SampledDrive& drive,
                                                        const Eigen::MatrixXd& eta,
                                                        const Eigen::MatrixXd& eta_dot);
/// The peak von Mises stress [Pa] of each interface from recorded states (what a screen needs);
/// with η and η̇ given (non-empty) and a coarse grid, refined between samples.
std::vector<double> modalStressPeaks(const ModalStressEvaluator& evaluator,
                                     const Eigen::MatrixXd& states,
                                     const std::vector<char>& no_polish,
                                     const ModalModel& model, const SampledDrive& drive,
                                     const Eigen::MatrixXd& eta, const Eigen::MatrixXd& eta_dot);

}  // namespace mastrom::rom
