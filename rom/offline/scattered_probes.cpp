// Held-out probes of a scattered database (see scattered_probes.hpp).
#include "rom/offline/scattered_probes.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "common/error.hpp"
#include "rom/interpolation/tracked_interpolation.hpp"
#include "rom/interpolation/rbf_weights.hpp"
#include "rom/model/modal_stepping.hpp"
#include "rom/offline/leave_one_out.hpp"
#include "rom/offline/probe_estimate.hpp"
#include "rom/offline/rbf_leave_one_out.hpp"
#include "rom/offline/space_filling.hpp"

namespace mastrom::rom {

int scatteredProbeCount(int p) {
  return std::clamp(kScatteredProbesPerParameter * (p + 1), 8, kMaxProbes);
}

std::vector<std::vector<double>> scatteredProbePoints(const std::vector<ParameterAxis>& axes,
                                                      int set) {
  MASTROM_REQUIRE(set >= 0, InputError, "rom build: probe set ", set, " (sets count from 0)");
  const int p = static_cast<int>(axes.size());
  const int count = scatteredProbeCount(p);
  // After the initial design (Halton 1 … 2p) and the candidates (the next
  // kCandidatesPerParameter · p points): distinct Halton indices are distinct points.
  const long first = 2L * p + 1 + static_cast<long>(kCandidatesPerParameter) * p +
                     static_cast<long>(set) * count;
  std::vector<std::vector<double>> points;
  for (int i = 0; i < count; ++i) points.push_back(boxPoint(axes, haltonPoint(first + i, p)));
  return points;
}

void measureProbeShare(const RomDatabase& db, const std::vector<std::vector<double>>& points,
                       const std::vector<RomSample>& solved, const fullorder::DriveLaw& drive,
                       const ModalDeploymentOptions& options, double carry_below,
                       ProbeResponseCache& cache, int first, int stride, std::vector<double>& out) {
  MASTROM_REQUIRE(points.size() == solved.size() && stride >= 1 && first >= 0, InputError,
                  "rom build: ", solved.size(), " probe solutions for ", points.size(), " probes");
  cache.deployed = cache.carried = 0;
  if (static_cast<std::size_t>(first) >= points.size()) return;
  const std::unique_ptr<TrackedInterpolator> interpolator = TrackedInterpolator::radialBasis(db);
  const Eigen::ArrayXd weight = featureSpreadWeights(interpolator->sampleFeatures());
  cache.exact.resize(points.size());
  cache.difference.resize(points.size());
  cache.response.resize(points.size(), -1.0);
  cache.reused.resize(points.size(), 0);
  // The probes to deploy, collected first and then deployed together (responseNrmseTogether:
  // the same values, a fraction of the time); their slots in `out` filled afterwards.
  std::vector<std::size_t> deploy, slot;
  std::vector<ModalModel> interpolated_models;
  for (std::size_t j = static_cast<std::size_t>(first); j < points.size();
       j += static_cast<std::size_t>(stride)) {
    const Eigen::VectorXd interpolated_features = interpolator->featuresAt(points[j]);
    const ModalModel interpolated = interpolator->modelFromFeatures(interpolated_features);
    const double w = solved[j].modal.omega_rad_s.minCoeff();
    out.push_back(static_cast<double>(j));
    out.push_back(std::abs(interpolated.omega_rad_s.minCoeff() - w) / w);
    const Eigen::VectorXd difference =
        ((interpolated_features - interpolator->featuresOf(solved[j])).array() * weight).matrix();
    const Eigen::VectorXd& last = cache.difference[j];
    if (last.size() == difference.size()) {
      const double size_last = last.norm();
      const double carried = cache.response[j] * difference.norm() / size_last;
      if (size_last > 0 && (difference - last).norm() <= kResidualReuseTolerance * size_last &&
          carried <= carry_below) {
        out.push_back(carried);
        cache.reused[j] = 1;
        ++cache.carried;
        continue;
      }
      if (carry_below <= 0 && !cache.reused[j]) {  // the final pass: measured already
        out.push_back(cache.response[j]);
        continue;
      }
    }
    deploy.push_back(j);
    slot.push_back(out.size());
    out.push_back(-1.0);  // filled below
    interpolated_models.push_back(interpolated);
    cache.difference[j] = difference;
  }
  if (deploy.empty()) return;
  const std::vector<double> errors = responseNrmseAgainstCached(
      deploy, interpolated_models,
      [&solved](std::size_t j) -> const ModalModel& { return solved[j].modal; }, cache.exact,
      sampleDrive(drive, options), options);
  for (std::size_t i = 0; i < deploy.size(); ++i) {
    const std::size_t j = deploy[i];
    cache.response[j] = errors[i];
    cache.reused[j] = 0;
    ++cache.deployed;
    out[slot[i]] = errors[i];
  }
}

LeaveOneOutResult summariseScatteredProbes(const RomDatabase& db,
                                           const std::vector<ProbeError>& measured) {
  MASTROM_REQUIRE(!measured.empty(), InputError, "rom build: no probe was measured");
  LeaveOneOutResult r;
  r.method = InterpolationMethod::Rbf;
  r.frequency_error.assign(db.samples.size(), -1.0);
  r.response_error.assign(db.samples.size(), -1.0);
  std::vector<std::vector<double>> points;
  for (const RomSample& s : db.samples) points.push_back(s.parameters);
  const RadialBasisWeights weights(db.axes, points);
  for (const ProbeError& e : measured) {
    const auto k = static_cast<std::size_t>(weights.nearestSample(e.parameters));
    r.frequency_error[k] = std::max(r.frequency_error[k], e.frequency_error);
    r.response_error[k] = std::max(r.response_error[k], e.response_error);
    r.max_frequency_error = std::max(r.max_frequency_error, e.frequency_error);
    r.max_response_error = std::max(r.max_response_error, e.response_error);
  }
  for (const double f : r.frequency_error) r.estimated += f >= 0 ? 1 : 0;
  r.frequency_estimate = r.max_frequency_error;
  r.response_estimate = r.max_response_error;
  return r;
}

}  // namespace mastrom::rom
