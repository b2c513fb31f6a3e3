// Radial-basis-function weights over samples anywhere in a database's box (docs/theory.md §4.4
// (d)): the polyharmonic spline φ(r) = r³ with a linear polynomial tail [Fas07, ch. 8 and 11;
// Wen05, ch. 8], in the box-normalised coordinates u_a = (log x_a − log lo_a)/(log hi_a − log lo_a)
// on an axis of positive values (the coordinates the grid weights are linear in), (x_a − lo_a)/
// (hi_a − lo_a) otherwise.
//
// r³ is conditionally positive definite of order 2, so with the tail p(u) = [1, uᵀ] the augmented
// system
//     M [c; d] = [f; 0],   M = [A P; Pᵀ 0],   A_ij = |u_i − u_j|³,   P_i = [1, u_iᵀ],        (4.10)
// is non-singular whenever the samples are distinct and not all on one hyperplane (unisolvent for
// linear polynomials), and the interpolant s(u) = Σ c_i |u − u_i|³ + d·p(u) reproduces every
// function linear in u exactly. Being linear in the data, it is a weighted sum of the samples with
// the cardinal weights w(u) = (M⁻¹ β(u))_{1..N}, β(u) = [|u − u_i|³; p(u)] — so the tracked
// features of every sample are combined exactly as the grid weights combine them.
//
// M⁻¹ is kept (N + p + 1 square, dense): it gives the weights (O(N²) per point), the power
// function P(u)² = −β(u)ᵀM⁻¹β(u) (the native-space error bound |f − s| ≤ P(u) |f|_N [Wen05,
// §11.1]; φ(0) = 0), and Rippa's leave-one-out residuals [Rip99]: the interpolant of all samples but
// k misses f_k by e_k = c_k / (M⁻¹)_kk, which holds for the augmented system as for A alone (it is
// the Schur-complement identity of a symmetric non-singular M; [Fas07, §17.1]). The same identity
// gives the power function of the samples without k at u_k: P₋ₖ(u_k)² = 1/(M⁻¹)_kk.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "rom/database/rom_database.hpp"
#include "rom/interpolation/grid_weights.hpp"

namespace mastrom::rom {

/// The box-normalised coordinates u of a point (see the header). `axes` give the box (front and
/// back of each axis' values). Throws InputError for a wrong count, a value that is not finite, or
/// not > 0 on a logarithmic axis.
Eigen::VectorXd boxCoordinates(const std::vector<ParameterAxis>& axes,
                               const std::vector<double>& parameters);

/// The parameters of box-normalised coordinates u (the inverse of boxCoordinates).
std::vector<double> boxPoint(const std::vector<ParameterAxis>& axes, const Eigen::VectorXd& u);

/// The fewest samples RadialBasisWeights accepts over `parameters` axes: one more than the
/// tail's terms (p + 2 for the linear tail).
int radialBasisMinimumSamples(int parameters, int tail_degree = 1);

class RadialBasisWeights {
public:
  /// The system (4.10) over `points` (one parameter vector each) in the box of `axes`. Throws
  /// InputError when there are fewer than p + 2 points (a leave-one-out must keep the linear tail
  /// determined), two points coincide, or the points are not unisolvent for linear polynomials.
  /// tail_degree 2: the quadratic tail [1, u, u_a u_b (a ≤ b)] instead of the linear one (r³ is
  /// conditionally positive definite of order 2, so any tail of degree ≥ 1 keeps M
  /// non-singular); quadratics in u are then reproduced too, and (p + 1)(p + 2)/2 + 1 samples are
  /// needed.
  RadialBasisWeights(const std::vector<ParameterAxis>& axes,
                     const std::vector<std::vector<double>>& points, int tail_degree = 1);

  int size() const { return static_cast<int>(points_.size()); }

  /// Cardinal weights at `parameters`: Σ_s w_s f_s interpolates any data f. At a sample (the same
  /// parameter values, bit for bit) exactly that sample with weight 1; elsewhere every sample, the
  /// weights summing to 1 to round-off. Outside the box the tail extrapolates linearly.
  std::vector<GridWeight> weights(const std::vector<double>& parameters) const;

  /// The power function P at `parameters` (0 at a sample): |f − s| ≤ P |f|_N.
  double powerFunction(const std::vector<double>& parameters) const;

  /// The same at many points at once (one matrix product instead of one per point).
  Eigen::VectorXd powerFunctions(const std::vector<std::vector<double>>& points) const;

  /// P₋ₖ(u_k) = 1/√(M⁻¹)_kk: the power function at sample k of the samples without it.
  double leaveOneOutPower(int k) const;

  /// Rippa's leave-one-out residuals of `data` (N × m, row s = sample s): row k = f_k minus the
  /// interpolant of the other samples at sample k, for every column at once (O(N² m)).
  Eigen::MatrixXd leaveOneOutErrors(const Eigen::MatrixXd& data) const;

  /// The sample nearest to `parameters` in box coordinates.
  int nearestSample(const std::vector<double>& parameters) const;

private:
  std::vector<ParameterAxis> axes_;
  std::vector<std::vector<double>> points_;
  Eigen::MatrixXd u_;        ///< p × N box coordinates of the samples
  Eigen::MatrixXd inverse_;  ///< M⁻¹, (N + p + 1) square

  int tail_degree_ = 1;

  Eigen::VectorXd tailOf(const Eigen::VectorXd& u) const;         ///< p(u)
  Eigen::VectorXd rightHandSide(const Eigen::VectorXd& u) const;  ///< β(u)
};

}  // namespace mastrom::rom
