// The exact time integral of r² over the continuous ROM response, for the RMS metric of (1.6)
// (docs/theory.md §4.2a): r = ψ_zᵀη̈ between the output samples is a sum of damped sinusoids, so
// the trapezoidal rule on the samples aliases the ringing once the output step is not small
// against the highest periods (39 % off at 1 ms on a five-parameter screen). The integral is
// computed in O(modes) per step from the observability Gramian W of the free vibration
// (AᵀW + WA = −CᵀC, per pair of modes a 4 × 4 Sylvester solve done once per model):
//   over a step of length h with forcing f linear in time, η = p + y with the particular solution
//   p = f/ω² − 2ζω ḟ/ω⁴ (p̈ = 0), so r = Cy with y free, and ∫₀^h r² = Y(y(0)) − Y(y(h)),
//   Y(y) = yᵀWy. Summed over the steps, the free parts telescope except where the particular
//   part changes between steps — a jump of a forcing scalar (θ̈, θ̇², g_x, g_y) or of its slope —,
//   and there the correction is a few dot products with fixed vectors (none in the cruise or
//   after the drive, one per step in a ramp).
// It needs every mode damped (2ζω > 0, ω > 0: W exists) and no Coriolis coupling (whose forcing is
// not a combination of fixed vectors); supported() says when, and the caller keeps the samples'
// trapezoidal rule otherwise.
#pragma once

#include <Eigen/Core>

#include "rom/model/modal_model.hpp"
#include "rom/model/modal_stepping.hpp"

namespace mastrom::rom {

class SquareIntegral {
 public:
  /// Whether the exact integral applies: no Coriolis coupling, every mode with ω > 0 and ζ > 0.
  static bool supported(const ModalModel& m, const ModalStepping& ms);

  /// Per-model constants (the Gramian and its products); requires supported(m, ms).
  SquareIntegral(const ModalModel& m, const ModalStepping& ms);

  /// The state at t = 0, before the first step (kept until the first piece gives its forcing).
  void start(const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot);
  /// A step or piece of length h_s begins in state (η, η̇) with the forcing scalars s0 at its
  /// start and s1 at its end (linear in between, as the stepping holds them).
  void piece(double h_s, const stepping_detail::ForcingScalars& s0,
             const stepping_detail::ForcingScalars& s1, const Eigen::VectorXd& eta,
             const Eigen::VectorXd& eta_dot);
  /// The state after the last step: returns ∫ r² dt over the whole record [(rad/s²)²·s].
  double finish(const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot);

  /// Y(x) = xᵀWx for x = [η; η̇] (exposed for the tests: ∫₀^∞ r² of the free vibration from x).
  double freeEnergy(const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot) const;

 private:
  static constexpr int kScalars = 4;  // θ̈, θ̇², g_x, g_y
  using Vector8 = Eigen::Matrix<double, 2 * kScalars, 1>;
  /// Σ_r weight_r (W[a b])_r · x over the rows r with weight_r ≠ 0 (rows 0–3 the a's, 4–7 the
  /// b's): most coefficients vanish (after the drive all; in the cruise all but θ̇²'s; without
  /// gravity g_x, g_y's), so only their rows are dotted.
  double weightedProducts(const Vector8& weight, const Eigen::VectorXd& eta,
                          const Eigen::VectorXd& eta_dot) const;
  /// cᵀ [a b]ᵀW[a b] c over the non-zero entries of c.
  double quadratic(const Vector8& c) const;
  /// Y(x − [a b] c): the free part's Y at state x = [η; η̇] with particular coefficients c.
  double freeEnergyAfter(const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
                         const Vector8& c) const;
  /// The particular part's coefficients [s; ṡ] of one piece end.
  static Vector8 coefficients(const stepping_detail::ForcingScalars& s,
                           const stepping_detail::ForcingScalars& slope);

  int modes_ = 0;
  Eigen::MatrixXd w_;                                         // W, 2k × 2k, layout [η; η̇]
  // Rows of (W[a b])ᵀ = [a b]ᵀW, each contiguous: the η part and the η̇ part.
  Eigen::Matrix<double, 2 * kScalars, Eigen::Dynamic, Eigen::RowMajor> h_eta_, h_rate_;
  Eigen::Matrix<double, 2 * kScalars, 2 * kScalars> gram_;   // [a b]ᵀ W [a b]
  Eigen::Matrix<double, Eigen::Dynamic, 2 * kScalars> basis_;  // [a b], 2k × 8
  Eigen::VectorXd eta_start_, rate_start_;                     // the state at t = 0
  double integral_ = 0.0;
  double last_h_ = 0.0, inv_h_ = 0.0;  // 1/h of the last piece length
  bool pending_ = false;  // a piece's end term waits for its end state
  Vector8 pending_end_ = Vector8::Zero();
};

}  // namespace mastrom::rom
