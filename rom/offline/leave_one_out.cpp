// Leave-one-out estimate of a database's interpolation error (see leave_one_out.hpp).
#include "rom/offline/leave_one_out.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/model/modal_stepping.hpp"

namespace mastrom::rom {

std::vector<double> relativeAccelerationSeries(const ModalModel& modal,
                                               const fullorder::DriveLaw& drive,
                                               const ModalDeploymentOptions& options) {
  return relativeAccelerationSeries(modal, sampleDrive(drive, options), options);
}

std::vector<double> relativeAccelerationSeries(const ModalModel& modal, const SampledDrive& drive,
                                               const ModalDeploymentOptions& options) {
  // (4.3): α_z − θ̈ = (ψη̈)_z — the rotation about Z and the term θ̇ Z × (Rψη̇) leave the
  // Z component alone — so the state contraction is one row, ψ_z.
  const ModalStepping stepping = prepareModalStepping(modal, drive, options.coriolis_coupling);
  const Eigen::VectorXd psi_z = modal.end_rotation.row(2).transpose();
  std::vector<double> series;
  series.reserve(drive.samples.size());
  runModalStepping(modal, stepping, drive,
                   [&](long, const Eigen::VectorXd&, const Eigen::VectorXd&,
                       const Eigen::VectorXd& eta_ddot) { series.push_back(psi_z.dot(eta_ddot)); });
  return series;
}

double responseNrmse(const std::vector<double>& reference, const std::vector<double>& candidate) {
  MASTROM_REQUIRE(reference.size() == candidate.size(), NumericalError,
                  "rom build: leave-one-out deployments of different lengths");
  double diff = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    diff += (candidate[i] - reference[i]) * (candidate[i] - reference[i]);
    norm += reference[i] * reference[i];
  }
  return norm > 0 ? std::sqrt(diff / norm) : 0.0;
}

LeaveOneOutResult leaveOneOutShare(const RomDatabase& db, InterpolationMethod method,
                                   const fullorder::DriveLaw& drive,
                                   const ModalDeploymentOptions& options, int first, int stride,
                                   std::vector<std::vector<double>>& exact) {
  MASTROM_REQUIRE(interpolationMethodAvailable(method), InputError, "rom: ", toString(method),
                  " interpolation is not available in this build");
  LeaveOneOutResult r;
  r.method = method;
  const std::size_t n = db.samples.size();
  r.frequency_error.assign(n, -1.0);
  r.response_error.assign(n, -1.0);
  exact.resize(n);
  for (std::size_t s = static_cast<std::size_t>(first); s < n;
       s += static_cast<std::size_t>(stride)) {
    const std::optional<RomDatabase> stencil =
        leaveOneOutStencil(db, static_cast<int>(s), method);
    if (!stencil) continue;
    const RomSample& sample = db.samples[s];
    const ModalModel interp = makeInterpolator(*stencil, method)->evaluate(sample.parameters);
    const double w_exact = sample.modal.omega_rad_s.minCoeff();
    const double w_interp = interp.omega_rad_s.minCoeff();
    r.frequency_error[s] = w_exact > 0 ? std::abs(w_interp - w_exact) / w_exact : 0.0;
    if (exact[s].empty()) exact[s] = relativeAccelerationSeries(sample.modal, drive, options);
    r.response_error[s] = responseNrmse(exact[s], relativeAccelerationSeries(interp, drive, options));
  }
  return r;
}

void summariseLeaveOneOut(LeaveOneOutResult& r, const std::vector<ParameterAxis>& axes) {
  r.estimated = 0;
  r.max_frequency_error = r.max_response_error = -1.0;
  r.frequency_estimate = r.response_estimate = -1.0;
  for (std::size_t s = 0; s < r.frequency_error.size(); ++s) {
    if (r.frequency_error[s] < 0) continue;
    ++r.estimated;
    const double scale = leaveOneOutScaleFor(axes, static_cast<int>(s), r.method);
    r.max_frequency_error = std::max(r.max_frequency_error, r.frequency_error[s]);
    r.max_response_error = std::max(r.max_response_error, r.response_error[s]);
    r.frequency_estimate = std::max(r.frequency_estimate, scale * r.frequency_error[s]);
    r.response_estimate = std::max(r.response_estimate, scale * r.response_error[s]);
  }
}

std::optional<RomDatabase> leaveOneOutStencil(const RomDatabase& db, int index,
                                              InterpolationMethod method) {
  const bool cubic = method == InterpolationMethod::Cubic;
  const std::vector<int> multi = gridIndex(db.axes, index);
  RomDatabase sub;
  sub.base_config_toml = db.base_config_toml;
  sub.modes_per_sample = db.modes_per_sample;
  sub.default_method = db.default_method;
  sub.mastrom_version = db.mastrom_version;
  bool interior_somewhere = false;
  // Per axis: the original node indices the stencil keeps.
  std::vector<std::vector<int>> keep(db.axes.size());
  for (std::size_t a = 0; a < db.axes.size(); ++a) {
    const int n = static_cast<int>(db.axes[a].values.size());
    const int i = multi[a];
    ParameterAxis axis;
    axis.key = db.axes[a].key;
    if (i > 0 && i < n - 1 && cubic && n >= 5) {
      interior_somewhere = true;
      for (int j = 0; j < n; ++j)
        if (j != i) keep[a].push_back(j);
    } else if (i > 0 && i < n - 1 && !cubic) {
      interior_somewhere = true;
      keep[a] = {i - 1, i + 1};
    } else {
      for (int j = 0; j < n; ++j) keep[a].push_back(j);
    }
    for (const int j : keep[a]) axis.values.push_back(db.axes[a].values[j]);
    sub.axes.push_back(std::move(axis));
  }
  if (!interior_somewhere) return std::nullopt;
  long count = 1;
  for (const ParameterAxis& a : sub.axes) count *= static_cast<long>(a.values.size());
  sub.samples.reserve(static_cast<std::size_t>(count));
  for (int s = 0; s < count; ++s) {
    const std::vector<int> sub_multi = gridIndex(sub.axes, s);
    std::vector<int> original(db.axes.size());
    for (std::size_t a = 0; a < db.axes.size(); ++a) original[a] = keep[a][sub_multi[a]];
    sub.samples.push_back(db.samples[db.sampleIndex(original)]);
  }
  // The tracking and alignment stay relative to the full database's reference; the stencil's own
  // reference is its sample nearest the centre.
  std::vector<int> centre(sub.axes.size());
  for (std::size_t a = 0; a < sub.axes.size(); ++a)
    centre[a] = static_cast<int>(sub.axes[a].values.size() - 1) / 2;
  sub.reference_sample = sub.sampleIndex(centre);
  return sub;
}

LeaveOneOutResult leaveOneOut(const RomDatabase& db, InterpolationMethod method,
                              const fullorder::DriveLaw& drive,
                              const ModalDeploymentOptions& options) {
  std::vector<std::vector<double>> exact_series;
  LeaveOneOutResult r = leaveOneOutShare(db, method, drive, options, 0, 1, exact_series);
  summariseLeaveOneOut(r, db.axes);
  return r;
}

}  // namespace mastrom::rom
