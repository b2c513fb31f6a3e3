// Rippa leave-one-out and power-function estimate of the rbf method (see rbf_leave_one_out.hpp).
#include "rom/offline/rbf_leave_one_out.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <optional>

#include "common/error.hpp"
#include "rom/interpolation/rbf_weights.hpp"
#include "rom/interpolation/tracked_interpolation.hpp"
#include "rom/model/modal_stepping.hpp"
#include "rom/offline/leave_one_out.hpp"
#include "rom/offline/space_filling.hpp"

namespace mastrom::rom {

std::vector<int> nearestSamples(const std::vector<Eigen::VectorXd>& coordinates,
                                const Eigen::VectorXd& u, int count) {
  std::vector<double> d(coordinates.size());
  for (std::size_t s = 0; s < coordinates.size(); ++s) d[s] = (coordinates[s] - u).squaredNorm();
  std::vector<int> order(coordinates.size());
  std::iota(order.begin(), order.end(), 0);
  const auto n = static_cast<std::ptrdiff_t>(std::min<std::size_t>(
      static_cast<std::size_t>(std::max(count, 1)), order.size()));
  std::partial_sort(order.begin(), order.begin() + n, order.end(),
                    [&d](int a, int b) { return d[a] < d[b] || (d[a] == d[b] && a < b); });
  order.resize(static_cast<std::size_t>(n));
  return order;
}

std::vector<std::vector<double>> estimateCandidates(const std::vector<ParameterAxis>& axes,
                                                    int count, long skip) {
  const int p = static_cast<int>(axes.size());
  std::vector<std::vector<double>> out;
  if (p <= 10)
    for (const Eigen::VectorXd& u : unitBoxCorners(p)) out.push_back(boxPoint(axes, u));
  for (long i = 0; i < count; ++i) out.push_back(boxPoint(axes, haltonPoint(skip + i, p)));
  return out;
}

Eigen::ArrayXd featureSpreadWeights(const std::vector<Eigen::VectorXd>& features) {
  Eigen::ArrayXd lo = features.front().array(), hi = lo;
  for (const Eigen::VectorXd& f : features) {
    lo = lo.min(f.array());
    hi = hi.max(f.array());
  }
  const Eigen::ArrayXd spread = hi - lo;
  return (spread > 0).select(spread.inverse(), 0.0);
}

LeftOutErrors radialBasisLeaveOneOut(const RomDatabase& db, const fullorder::DriveLaw& drive,
                                     const ModalDeploymentOptions& options,
                                     LeaveOneOutCache& cache, int first, int stride) {
  const std::unique_ptr<TrackedInterpolator> interpolator = TrackedInterpolator::radialBasis(db);
  const std::vector<Eigen::VectorXd>& features = interpolator->sampleFeatures();
  const auto n = static_cast<Eigen::Index>(features.size());
  Eigen::MatrixXd data(n, features.front().size());
  for (Eigen::Index s = 0; s < n; ++s) data.row(s) = features[static_cast<std::size_t>(s)];
  const Eigen::MatrixXd errors = interpolator->radialBasisWeights()->leaveOneOutErrors(data);
  const Eigen::ArrayXd weight = featureSpreadWeights(features);  // for the reuse test
  LeftOutErrors out;
  out.frequency.assign(static_cast<std::size_t>(n), -1.0);
  out.response.assign(static_cast<std::size_t>(n), -1.0);
  cache.exact.resize(static_cast<std::size_t>(n));
  cache.residual.resize(static_cast<std::size_t>(n));
  cache.response.resize(static_cast<std::size_t>(n), -1.0);
  cache.deployed = cache.reused = 0;
  // The samples to deploy, collected first and then deployed together (relativeAccelerationSeries
  // Together, responseNrmseTogether: the same values, a fraction of the time).
  std::vector<std::size_t> deploy;
  std::vector<ModalModel> left_outs;
  std::vector<Eigen::VectorXd> residuals;
  for (Eigen::Index s = first; s < n; s += stride) {
    const auto i = static_cast<std::size_t>(s);
    const ModalModel& own = db.samples[i].modal;
    const Eigen::VectorXd residual = errors.row(s).transpose();
    const ModalModel left_out = interpolator->modelFromFeatures(data.row(s).transpose() - residual);
    const double w = own.omega_rad_s.minCoeff();
    out.frequency[i] = w > 0 ? std::abs(left_out.omega_rad_s.minCoeff() - w) / w : 0.0;
    const Eigen::VectorXd& last = cache.residual[i];
    if (last.size() == residual.size()) {
      const double size_last = (last.array() * weight).matrix().norm();
      const double change = ((residual - last).array() * weight).matrix().norm();
      if (size_last > 0 && change <= kResidualReuseTolerance * size_last) {
        out.response[i] =
            cache.response[i] * (residual.array() * weight).matrix().norm() / size_last;
        ++cache.reused;
        continue;
      }
    }
    deploy.push_back(i);
    left_outs.push_back(left_out);
    residuals.push_back(residual);
  }
  if (deploy.empty()) return out;
  const std::vector<double> errors_now = responseNrmseAgainstCached(
      deploy, left_outs, [&db](std::size_t i) -> const ModalModel& { return db.samples[i].modal; },
      cache.exact, sampleDrive(drive, options), options);
  for (std::size_t j = 0; j < deploy.size(); ++j) {
    const std::size_t i = deploy[j];
    out.response[i] = errors_now[j];
    cache.residual[i] = std::move(residuals[j]);
    cache.response[i] = out.response[i];
    ++cache.deployed;
  }
  return out;
}

namespace {

std::vector<std::vector<double>> samplePoints(const RomDatabase& db) {
  std::vector<std::vector<double>> points;
  for (const RomSample& s : db.samples) points.push_back(s.parameters);
  return points;
}

}  // namespace

RadialBasisErrorEstimate::RadialBasisErrorEstimate(const RomDatabase& db, LeftOutErrors errors)
    : weights_(db.axes, samplePoints(db)), errors_(std::move(errors)), axes_(db.axes) {
  const std::size_t n = db.samples.size();
  MASTROM_REQUIRE(errors_.frequency.size() == n && errors_.response.size() == n, InputError,
                  "rom: leave-one-out errors of ", errors_.response.size(), " samples for ", n);
  for (std::size_t s = 0; s < n; ++s) {
    MASTROM_REQUIRE(errors_.response[s] >= 0 && errors_.frequency[s] >= 0, InputError,
                    "rom: sample ", s, " has no leave-one-out error");
    const double power = weights_.leaveOneOutPower(static_cast<int>(s));
    frequency_scale_.push_back(errors_.frequency[s] / power);
    response_scale_.push_back(errors_.response[s] / power);
    coordinates_.push_back(boxCoordinates(db.axes, db.samples[s].parameters));
  }
}

std::pair<double, double> RadialBasisErrorEstimate::at(const std::vector<double>& parameters) const {
  const PointEstimates e = atPoints({parameters});
  return {e.frequency(0), e.response(0)};
}

RadialBasisErrorEstimate::PointEstimates RadialBasisErrorEstimate::atPoints(
    const std::vector<std::vector<double>>& points) const {
  PointEstimates e;
  e.power = weights_.powerFunctions(points);
  const auto m = static_cast<Eigen::Index>(points.size());
  e.frequency_scale = Eigen::VectorXd::Zero(m);
  e.response_scale = Eigen::VectorXd::Zero(m);
  const int neighbours = static_cast<int>(axes_.size()) + 1;
  for (Eigen::Index j = 0; j < m; ++j) {
    const Eigen::VectorXd u = boxCoordinates(axes_, points[static_cast<std::size_t>(j)]);
    for (const int s : nearestSamples(coordinates_, u, neighbours)) {
      e.frequency_scale[j] = std::max(e.frequency_scale[j], frequency_scale_[static_cast<std::size_t>(s)]);
      e.response_scale[j] = std::max(e.response_scale[j], response_scale_[static_cast<std::size_t>(s)]);
    }
  }
  return e;
}

LeaveOneOutResult summariseRadialBasis(
    const RadialBasisErrorEstimate& estimate, const RomDatabase& db,
    const std::vector<std::vector<double>>& candidates,
    const RadialBasisErrorEstimate::PointEstimates& at_candidates) {
  LeaveOneOutResult r;
  r.method = InterpolationMethod::Rbf;
  const std::size_t n = db.samples.size();
  r.frequency_error.assign(n, -1.0);
  r.response_error.assign(n, -1.0);
  std::vector<Eigen::VectorXd> coordinates;
  for (const RomSample& s : db.samples) coordinates.push_back(boxCoordinates(db.axes, s.parameters));
  for (std::size_t c = 0; c < candidates.size(); ++c) {
    const auto j = static_cast<Eigen::Index>(c);
    const double f = at_candidates.frequency(j), e = at_candidates.response(j);
    const auto s = static_cast<std::size_t>(
        nearestSamples(coordinates, boxCoordinates(db.axes, candidates[c]), 1).front());
    r.frequency_error[s] = std::max(r.frequency_error[s], f);
    r.response_error[s] = std::max(r.response_error[s], e);
    r.frequency_estimate = std::max(r.frequency_estimate, f);
    r.response_estimate = std::max(r.response_estimate, e);
  }
  for (std::size_t s = 0; s < n; ++s) r.estimated += r.frequency_error[s] >= 0 ? 1 : 0;
  r.max_frequency_error = *std::max_element(estimate.frequencyErrors().begin(),
                                            estimate.frequencyErrors().end());
  r.max_response_error = *std::max_element(estimate.responseErrors().begin(),
                                           estimate.responseErrors().end());
  return r;
}

}  // namespace mastrom::rom
