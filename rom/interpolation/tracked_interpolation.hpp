// Interpolation method (a) of docs/theory.md §4.4: the modal quantities of the MAC-tracked,
// sign-aligned modes, interpolated multilinearly on the database's tensor grid.
//
// Every sample is turned once into one "feature" vector in reference-mode order: for reference mode
// j the sample's mode tracking[j], multiplied by tracking_sign[j] where the quantity is odd in the
// mode's sign (Γ, Γ_c, ψ, end translation, L; the Coriolis entry (i, j) by both signs; ω and ζ are
// even), followed by the rigid data (J, m, c̄, p̄, θ₀, g). A point of the box is then the weighted
// sum of the 2^p features of the grid cell around it, with the tensor-product hat weights
// w = Π_a ((1 − t_a) or t_a), t_a = log(x_a/v_i)/log(v_{i+1}/v_i) on an axis of positive values
// (t_a = (x_a − v_i)/(v_{i+1} − v_i) otherwise), and the frequencies enter as log ω: a power law
// ω ∝ p^a (E, h, R, ρ, module mass) is then interpolated exactly, as in method (b)
// (TrackedInterpolator's AxisWeighting::Linear keeps the plain multilinear form in p and ω)
// (rom/interpolation/spd_interpolation.hpp; linear ω and t had 1 % frequency errors at the cell midpoints of
// h ∈ [0.5, 2] mm in 5 points, i.e. phase drift of the response). At a grid node one weight is
// exactly 1 and the others exactly 0, so every sample is reproduced (up to the mode order and
// signs, and the round-off of exp(log ω)). Outside the box the boundary cell's weights extrapolate
// linearly (ω stays > 0, ζ is clipped at 0, J and m kept > 0).
//
// When θ₀ is a database parameter the 3-vectors (ψ, end translation, L, c̄, p̄) are rotated back to
// the stowed frame before interpolation and forward to the interpolated θ₀ after, so that the rigid
// rotation is not interpolated linearly.
//
// With degree 3 (method "cubic", docs/theory.md §4.4 (4.9)) the same features are combined with
// tensor-product local cubic Lagrange weights (lagrangeWeights: the 4 nodes around the cell on each
// axis, fewer when the axis has fewer) in the same coordinates (log x, log ω): third instead of
// second order in the grid spacing where the modal quantities are smooth; the weights can be
// negative, so it is for smooth data — where modes veer between samples the manifold method is the
// robust one.
//
// With radial-basis weights (method "rbf", docs/theory.md §4.4 (d), rom/interpolation/rbf_weights.hpp)
// the same features are combined with the cardinal weights of the polyharmonic spline r³ with a
// linear tail in the box-normalised (log) coordinates: samples anywhere in the box, a grid or a
// scattered design; power laws in the parameters are again reproduced exactly (log ω is linear
// in log p).
//
// The result lists the modes in ascending interpolated ω (all per-mode arrays permuted alike).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "rom/interpolation/interpolator.hpp"
#include "rom/database/rom_database.hpp"
#include "rom/interpolation/grid_weights.hpp"
#include "rom/interpolation/rbf_weights.hpp"

namespace mastrom::rom {

class TrackedInterpolator final : public ModalInterpolator {
public:
  /// Throws InputError when the database is inconsistent (grid size, mode counts, tracking, a
  /// frequency ≤ 0 with logarithmic weights). AxisWeighting::Linear is the plain multilinear
  /// interpolation of ω itself in t = (x − v_i)/(v_{i+1} − v_i). degree: 1 multilinear, ≥ 2 local
  /// Lagrange of that degree per axis.
  explicit TrackedInterpolator(const RomDatabase& db,
                               AxisWeighting weighting = AxisWeighting::Logarithmic,
                               int degree = 1);
  /// Method "rbf": radial-basis weights over the samples wherever they lie (grid or scattered).
  /// Throws InputError as the constructor, or when the samples do not determine the weights
  /// (RadialBasisWeights).
  /// tail_degree: of the polynomial tail (RadialBasisWeights).
  static std::unique_ptr<TrackedInterpolator> radialBasis(const RomDatabase& db,
                                                          int tail_degree = 1);

  ModalModel evaluate(const std::vector<double>& parameters) const override;
  ModalModel evaluateWithStresses(const std::vector<double>& parameters) const override;
  /// The stress rows of all points whose weights name the same samples (every point of the rbf
  /// method) in one pass over the samples' rows (rom/interpolation/weighted_sum_batch.hpp).
  std::vector<ModalModel> evaluateWithStressesAt(
      const std::vector<std::vector<double>>& points) const override;

  int modeCount() const { return modes_; }
  /// The feature vector of every sample (database order; see the header).
  const std::vector<Eigen::VectorXd>& sampleFeatures() const { return features_; }
  /// The modal model of a feature vector (a weighted sum of sampleFeatures), modes ascending.
  ModalModel modelFromFeatures(const Eigen::VectorXd& features) const;
  /// The interpolated feature vector at `parameters`: evaluate(p) = modelFromFeatures(featuresAt(p)).
  Eigen::VectorXd featuresAt(const std::vector<double>& parameters) const;
  /// The feature vector of a solved point tracked like the samples (its tracking set against
  /// the same reference), comparable with featuresAt: a held-out probe's own features.
  Eigen::VectorXd featuresOf(const RomSample& sample) const;
  /// The radial-basis weights (method "rbf" only; nullptr otherwise).
  const RadialBasisWeights* radialBasisWeights() const { return rbf_ ? &*rbf_ : nullptr; }

private:
  struct RadialBasisTag {};
  TrackedInterpolator(const RomDatabase& db, RadialBasisTag, int tail_degree);
  /// What every constructor does: features (and stresses) of the samples, checked.
  void addSamples(const RomDatabase& db);
  std::vector<GridWeight> weightsAt(const std::vector<double>& parameters) const;

  std::optional<RadialBasisWeights> rbf_;  ///< method "rbf": weights over scattered samples
  std::vector<ParameterAxis> axes_;
  int modes_ = 0;
  bool rotate_ = false;                    ///< θ₀ differs between samples
  bool logarithmic_ = true;                ///< log weights on positive axes and log ω
  int degree_ = 1;                         ///< 1: multilinear; else local Lagrange
  std::vector<Eigen::VectorXd> features_;  ///< one per sample, grid order
  /// Per sample, when the database carries stresses: [S of the tracked modes (signed) | S_res | σ̄]
  /// and the points; the interface offsets are common.
  std::vector<Eigen::MatrixXd> stress_features_;
  std::vector<Eigen::MatrixXd> stress_points_;
  std::vector<double> stress_damping_;
  Eigen::VectorXi stress_offsets_;

  ModalModel evaluateModel(const std::vector<double>& parameters, bool stresses) const;
  /// The stresses of models[b] (made from `features`[b]) with weights[b], for b in `batch`: all
  /// of them with the same samples in the same order.
  void addStresses(const std::vector<std::vector<GridWeight>>& weights,
                   const std::vector<Eigen::VectorXd>& features,
                   const std::vector<std::size_t>& batch, std::vector<ModalModel>& models) const;
};

}  // namespace mastrom::rom
