// The database's estimate of the error of each of its lowest natural frequencies at any point
// (docs/theory.md §4.3, (4.15)): the scaled power function of (4.11) applied to every frequency
// on its own, with Rippa's leave-one-out at the samples [Rip99] — no deployment, no modal solve.
//
// Data: at every sample the K lowest frequencies in ascending order, as log ω (the coordinate the
// interpolators combine, in which a power law in the parameters is linear). The K-th lowest
// frequency is a continuous function of the parameters even where modes cross (it is then not
// smooth: the leave-one-out sees the kink as a larger error), so no tracking enters. Over the
// samples the radial-basis system (4.10) gives, for every frequency k at once, the left-out
// residuals e_sk = c_sk / (M⁻¹)_ss and the scales ε_sk = |e_sk| / P₋ₛ(x_s); at x
//
//     δ_k(x) = P(x) · max { ε_sk : s among the p + 1 samples nearest x },   err_k = e^{δ_k} − 1,
//
// the relative error of ω_k (and of f_k = ω_k/2π) — the upper of the two signs of a log error.
// The estimate is that of the rbf interpolant; the cubic weights of a grid are more accurate where
// the data are smooth (§4.4 (a′)), so there it reads high. With Young's modulus handled exactly
// the frequencies scale by √(E/E₀) exactly (4.12) and the relative error is that of the sampled
// axes, where the estimate is made.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "rom/database/rom_database.hpp"
#include "rom/interpolation/rbf_weights.hpp"

namespace mastrom::rom {

class FrequencyErrorEstimate {
public:
  /// The estimate of the `count` lowest frequencies over the samples of `db`. Unavailable (see
  /// available()) when the samples do not determine the radial-basis weights (fewer than p + 2,
  /// or all on one hyperplane). InputError when count is not in 1 … db.modes_per_sample.
  FrequencyErrorEstimate(const RomDatabase& db, int count);

  bool available() const { return weights_ != nullptr; }
  /// Why not, when not available.
  const std::string& unavailableReason() const { return reason_; }

  /// err_k of (4.15) at `point` (one value per database axis), k = 1 … count; −1 each when the
  /// estimate is not available.
  std::vector<double> at(const std::vector<double>& point) const;

  /// |e_sk| (log ω): the left-out residual of frequency k at sample s (rows: sampled database
  /// order).
  const Eigen::MatrixXd& leaveOneOutResiduals() const { return residuals_; }

private:
  int count_ = 0;
  int exact_axis_ = -1;  ///< the axis of an exactly handled E, dropped before the estimate
  std::vector<ParameterAxis> axes_;  ///< the sampled axes
  std::unique_ptr<RadialBasisWeights> weights_;
  std::vector<Eigen::VectorXd> coordinates_;  ///< the samples' box coordinates
  Eigen::MatrixXd residuals_;                 ///< N × count, |e_sk|
  Eigen::MatrixXd scales_;                    ///< N × count, ε_sk
  std::string reason_;
};

}  // namespace mastrom::rom
