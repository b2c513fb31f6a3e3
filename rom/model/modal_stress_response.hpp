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
// Between samples. The largest sample is polished by the parabola through it and its two
// neighbours at the same station (the stress is smooth: displacement-like, C¹ across the jumps of
// θ̈ up to the static correction's step, so no polish next to a breakpoint); error ≤ 0.0234 (ωΔ)⁴
// of the amplitude of a mode of frequency ω, against (ωΔ)²/8 for the plain sample max.
#pragma once

#include <vector>

#include <Eigen/Core>

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
  /// largest() at every column of `states` (inputSize × samples), into `out` — blocked products,
  /// several times faster than a loop of largest().
  void largestHistory(int i, const Eigen::MatrixXd& states, std::vector<double>& out) const;
  /// The von Mises stress of every station of interface i at x (point-major).
  void field(int i, const Eigen::Ref<const Eigen::VectorXd>& x, std::vector<double>& vm) const;
  /// The von Mises stress of one station.
  double station(int i, int station, const Eigen::Ref<const Eigen::VectorXd>& x) const;

  struct Peak {
    double von_mises_pa = 0.0;
    double sample = 0.0;  ///< the (fractional, after the polish) sample index of the peak
    long nearest_sample = 0;
    int station = 0;
  };
  /// The peak of interface i over the columns of `states` (inputSize × samples), found best-first
  /// (header comment) and polished between samples unless a breakpoint is near: no_polish[n] true
  /// for the samples where the drive's θ̈ jumps (may be empty).
  Peak peak(int i, const Eigen::MatrixXd& states, const std::vector<char>& no_polish) const;
  /// Exact evaluations spent by the last peak() on this thread (diagnostics for tests/benchmarks).
  static long lastPeakEvaluations();

private:
  struct Interface {
    Eigen::MatrixXd rows;   ///< [S | S_res | σ̄] of its points (6P × inputs)
    Eigen::VectorXd bound;  ///< c_j
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

/// The samples where the drive's θ̈ jumps (on the grid, or inside a split step): no polish there.
std::vector<char> samplesNearBreakpoints(const SampledDrive& drive);

/// The modal state x of every output sample of a ROM deployment (inputSize × (steps + 1)), stepped
/// as simulateModalDeployment steps it.
Eigen::MatrixXd modalStressStates(const ModalModel& model, const ModalStressEvaluator& evaluator,
                                  const SampledDrive& drive, bool coriolis_coupling);

/// The interface stresses of a ROM deployment in the full order's form: the largest von Mises per
/// interface at every output sample, the peak (polished) with where/when and the field at its
/// nearest sample, the points' unrolled coordinates. No edge resultants (the ROM does not recover
/// the bonded edges' reactions): those histories stay empty. InputError without stress data.
fullorder::InterfaceStressResult modalInterfaceStresses(const ModalModel& model,
                                                        const fullorder::DriveLaw& drive,
                                                        const ModalDeploymentOptions& options);

/// The peak von Mises stress [Pa] of each interface from recorded states (what a screen needs).
std::vector<double> modalStressPeaks(const ModalStressEvaluator& evaluator,
                                     const Eigen::MatrixXd& states,
                                     const std::vector<char>& no_polish);

}  // namespace mastrom::rom
