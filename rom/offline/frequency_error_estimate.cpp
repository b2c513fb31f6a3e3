// The per-frequency error estimate (see frequency_error_estimate.hpp, docs/theory.md (4.15)).
#include "rom/offline/frequency_error_estimate.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "rom/offline/rbf_leave_one_out.hpp"

namespace mastrom::rom {

FrequencyErrorEstimate::FrequencyErrorEstimate(const RomDatabase& db, int count)
    : count_(count), exact_axis_(db.exactModulusAxis()) {
  MASTROM_REQUIRE(count >= 1 && count <= db.modes_per_sample, InputError, "frequencies: ", count,
                  " asked for; the database holds ", db.modes_per_sample,
                  " modes per sample (allowed 1 … ", db.modes_per_sample, ")");
  const RomDatabase sampled = sampledDatabase(db);
  axes_ = sampled.axes;
  const int n = static_cast<int>(sampled.samples.size());
  const int p = static_cast<int>(axes_.size());
  if (n < radialBasisMinimumSamples(p)) {
    reason_ = detail::concat("the database has ", n, " samples; the estimate needs ",
                             radialBasisMinimumSamples(p), " for ", p, " parameters");
    return;
  }
  std::vector<std::vector<double>> points;
  Eigen::MatrixXd log_omega(n, count);
  for (int s = 0; s < n; ++s) {
    const RomSample& sample = sampled.samples[static_cast<std::size_t>(s)];
    points.push_back(sample.parameters);
    // The modal model's modes ascend (rom/model/modal_extraction.hpp); sorted again so that a
    // database of another writer cannot break the "k-th lowest" meaning.
    std::vector<double> omega(sample.modal.omega_rad_s.data(),
                              sample.modal.omega_rad_s.data() + sample.modal.modeCount());
    std::sort(omega.begin(), omega.end());
    for (int k = 0; k < count; ++k) log_omega(s, k) = std::log(omega[static_cast<std::size_t>(k)]);
  }
  try {
    weights_ = std::make_unique<RadialBasisWeights>(axes_, points);
  } catch (const InputError& e) {
    reason_ = e.what();
    return;
  }
  residuals_ = weights_->leaveOneOutErrors(log_omega).cwiseAbs();
  scales_.resize(n, count);
  for (int s = 0; s < n; ++s) {
    scales_.row(s) = residuals_.row(s) / weights_->leaveOneOutPower(s);
    coordinates_.push_back(boxCoordinates(axes_, points[static_cast<std::size_t>(s)]));
  }
}

std::vector<double> FrequencyErrorEstimate::at(const std::vector<double>& point) const {
  if (!available()) return std::vector<double>(static_cast<std::size_t>(count_), -1.0);
  std::vector<double> x = point;
  if (exact_axis_ >= 0) x.erase(x.begin() + exact_axis_);
  const double power = weights_->powerFunction(x);
  const std::vector<int> nearest =
      nearestSamples(coordinates_, boxCoordinates(axes_, x), static_cast<int>(axes_.size()) + 1);
  std::vector<double> out;
  for (int k = 0; k < count_; ++k) {
    double scale = 0.0;
    for (const int s : nearest) scale = std::max(scale, scales_(s, k));
    out.push_back(std::expm1(power * scale));
  }
  return out;
}

}  // namespace mastrom::rom
