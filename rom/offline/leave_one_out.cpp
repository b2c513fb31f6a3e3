// Leave-one-out estimate of a database's interpolation error (see leave_one_out.hpp).
#include "rom/offline/leave_one_out.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/model/modal_stepping.hpp"
#include "rom/model/output_resolution.hpp"

namespace mastrom::rom {

std::vector<double> relativeAccelerationSeries(const ModalModel& modal,
                                               const fullorder::DriveLaw& drive,
                                               const ModalDeploymentOptions& options) {
  return relativeAccelerationSeries(modal, sampleDrive(drive, options), options);
}

std::vector<int> modesInRelativeAcceleration(const ModalModel& modal, const SampledDrive& drive) {
  // Mode k's η̈ is driven by f_k = −θ̈Γ_k − θ̇²Γ_c,k + g_x L_x,k + g_y L_y,k (|g_x|, |g_y| ≤ 2|g|)
  // and, for a damped oscillator, is at most max(2, 1/(2ζ_k)) times its largest forcing (a step's
  // overshoot, or resonance); r sees it through ψ_z,k.
  const int k = modal.modeCount();
  Eigen::VectorXd bound(k);
  for (int i = 0; i < k; ++i) {
    const double forcing =
        modalForcingBound(modal, i, drive.max_abs_acceleration_rad_s2, drive.max_abs_rate_rad_s);
    const double zeta = modal.damping_ratio[i];
    const double gain = zeta > 0 ? std::max(2.0, 0.5 / zeta) : HUGE_VAL;
    bound[i] = std::abs(modal.end_rotation(2, i)) * forcing * gain;
  }
  const double largest = bound.maxCoeff();
  std::vector<int> kept;
  if (!std::isfinite(largest)) {  // an undamped mode (or bad data): no share to compare with
    for (int i = 0; i < k; ++i) kept.push_back(i);
    return kept;
  }
  for (int i = 0; i < k; ++i)
    if (!(bound[i] <= kUnobservedModeShare * largest)) kept.push_back(i);  // NaN and ∞ kept
  return kept;
}

std::vector<double> relativeAccelerationSeries(const ModalModel& modal, const SampledDrive& drive,
                                               const ModalDeploymentOptions& options) {
  // One model "together" steps only the modes r sees (modesInRelativeAcceleration).
  return std::move(relativeAccelerationSeriesTogether({&modal}, drive, options).front());
}

std::vector<double> relativeAccelerationSeriesOfAll(const ModalModel& modal,
                                                    const SampledDrive& drive,
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

namespace {

/// Models stepped together per pass (the state of 64 × ~6 modes stays in the L1 cache).
constexpr std::size_t kModelsPerPass = 64;

/// Steps models[j], j in `pass` (that share θ₀ and g), as one model of every mode r sees: the
/// per-mode fields side by side, the rigid data (which r does not read) of the first; calls
/// sample(n, j, r) at every output sample n.
template <typename Sample>
void stepPass(const std::vector<const ModalModel*>& models, const std::vector<std::size_t>& pass,
              const SampledDrive& drive, Sample& sample) {
  std::vector<ModalModel> parts;
  std::vector<Eigen::Index> begin{0};  // model pass[b] spans modes [begin[b], begin[b + 1])
  for (const std::size_t j : pass) {
    std::vector<int> kept = modesInRelativeAcceleration(*models[j], drive);
    if (kept.empty()) kept.push_back(0);  // r ≡ 0 within round-off: one mode keeps it honest
    parts.push_back(selectModes(*models[j], kept));
    begin.push_back(begin.back() + static_cast<Eigen::Index>(kept.size()));
  }
  const ModalModel all = concatenateModes(parts);
  const ModalStepping stepping = prepareModalStepping(all, drive, false);
  const Eigen::VectorXd psi_z = all.end_rotation.row(2).transpose();
  runModalStepping(all, stepping, drive,
                   [&](long n, const Eigen::VectorXd&, const Eigen::VectorXd&,
                       const Eigen::VectorXd& eta_ddot) {
                     for (std::size_t b = 0; b < pass.size(); ++b) {
                       const Eigen::Index size = begin[b + 1] - begin[b];
                       sample(n, pass[b],
                              psi_z.segment(begin[b], size).dot(eta_ddot.segment(begin[b], size)));
                     }
                   });
}

/// Calls sample(n, j, r) with r of models[j] at every output sample n, the models stepped
/// together (relativeAccelerationSeriesTogether) in passes of kModelsPerPass; one by one where
/// they cannot share a pass: with the Coriolis coupling (modes coupled: all of them stepped), or
/// when they differ in θ₀ or g (each its own pass).
template <typename Sample>
void stepTogether(const std::vector<const ModalModel*>& models, const SampledDrive& drive,
                  const ModalDeploymentOptions& options, Sample&& sample) {
  if (options.coriolis_coupling) {
    for (std::size_t j = 0; j < models.size(); ++j) {
      const std::vector<double> r = relativeAccelerationSeriesOfAll(*models[j], drive, options);
      for (std::size_t n = 0; n < r.size(); ++n) sample(static_cast<long>(n), j, r[n]);
    }
    return;
  }
  bool same_frame = true;
  for (const ModalModel* m : models)
    same_frame = same_frame && m->reference_angle_rad == models.front()->reference_angle_rad &&
                 m->gravity_m_s2 == models.front()->gravity_m_s2;
  const std::size_t per_pass = same_frame ? kModelsPerPass : 1;
  for (std::size_t first = 0; first < models.size(); first += per_pass) {
    std::vector<std::size_t> pass;
    for (std::size_t j = first; j < std::min(models.size(), first + per_pass); ++j)
      pass.push_back(j);
    stepPass(models, pass, drive, sample);
  }
}

}  // namespace

std::vector<std::vector<double>> relativeAccelerationSeriesTogether(
    const std::vector<const ModalModel*>& models, const SampledDrive& drive,
    const ModalDeploymentOptions& options) {
  std::vector<std::vector<double>> out(models.size());
  for (std::vector<double>& r : out) r.reserve(drive.samples.size());
  stepTogether(models, drive, options,
               [&out](long, std::size_t j, double r) { out[j].push_back(r); });
  return out;
}

std::vector<double> responseNrmseTogether(const std::vector<const ModalModel*>& models,
                                          const std::vector<const std::vector<double>*>& references,
                                          const SampledDrive& drive,
                                          const ModalDeploymentOptions& options) {
  MASTROM_REQUIRE(models.size() == references.size(), InputError, "rom build: ", models.size(),
                  " models for ", references.size(), " reference series");
  for (const std::vector<double>* ref : references)
    MASTROM_REQUIRE(ref->size() == drive.samples.size(), NumericalError,
                    "rom build: leave-one-out deployments of different lengths");
  std::vector<double> diff(models.size(), 0.0), norm(models.size(), 0.0);
  stepTogether(models, drive, options, [&](long n, std::size_t j, double r) {
    const double reference = (*references[j])[static_cast<std::size_t>(n)];
    diff[j] += (r - reference) * (r - reference);
    norm[j] += reference * reference;
  });
  std::vector<double> out(models.size());
  for (std::size_t j = 0; j < models.size(); ++j)
    out[j] = norm[j] > 0 ? std::sqrt(diff[j] / norm[j]) : 0.0;
  return out;
}

std::vector<double> responseNrmseAgainstCached(
    const std::vector<std::size_t>& index, const std::vector<ModalModel>& candidates,
    const std::function<const ModalModel&(std::size_t)>& own,
    std::vector<std::vector<double>>& exact, const SampledDrive& drive,
    const ModalDeploymentOptions& options) {
  MASTROM_REQUIRE(index.size() == candidates.size(), InputError, "rom build: ", index.size(),
                  " cached series for ", candidates.size(), " candidates");
  std::vector<const ModalModel*> missing;
  std::vector<std::size_t> missing_index;
  for (const std::size_t i : index)
    if (exact.at(i).empty() &&
        std::find(missing_index.begin(), missing_index.end(), i) == missing_index.end()) {
      missing.push_back(&own(i));
      missing_index.push_back(i);
    }
  std::vector<std::vector<double>> series =
      relativeAccelerationSeriesTogether(missing, drive, options);
  for (std::size_t j = 0; j < missing.size(); ++j) exact[missing_index[j]] = std::move(series[j]);
  std::vector<const ModalModel*> models;
  std::vector<const std::vector<double>*> references;
  for (std::size_t j = 0; j < index.size(); ++j) {
    models.push_back(&candidates[j]);
    references.push_back(&exact[index[j]]);
  }
  return responseNrmseTogether(models, references, drive, options);
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
