// Cubic default and held-out probes (see probe_estimate.hpp).
#include "rom/offline/probe_estimate.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "common/error.hpp"
#include "rom/interpolation/interpolator.hpp"
#include "rom/model/modal_stepping.hpp"
#include "rom/offline/leave_one_out.hpp"

namespace mastrom::rom {

bool cubicIsDefault(const BuildReport& report, const std::vector<ParameterAxis>& axes, bool affine) {
  const bool refined = std::any_of(axes.begin(), axes.end(),
                                   [](const ParameterAxis& a) { return a.values.size() >= 3; });
  return refined && !affine && report.min_coupled_mac >= kCubicTrackingMac;
}

bool cubicHasLeaveOneOut(const std::vector<ParameterAxis>& axes) {
  return std::all_of(axes.begin(), axes.end(),
                     [](const ParameterAxis& a) { return a.values.size() >= 5; });
}

std::vector<Probe> cellCentreProbes(const RomDatabase& db) {
  MASTROM_REQUIRE(db.isGrid(), InputError, "rom build: probes need a grid database");
  const std::size_t p = db.axes.size();
  std::vector<int> cells_per_axis(p);
  long cells = 1;
  for (std::size_t a = 0; a < p; ++a) {
    cells_per_axis[a] = std::max(1, static_cast<int>(db.axes[a].values.size()) - 1);
    cells *= cells_per_axis[a];
  }
  const long count = std::min<long>(cells, kMaxProbes);
  std::vector<Probe> probes;
  for (long j = 0; j < count; ++j) {
    // Evenly spread cell indices (all of them when count == cells), first axis fastest.
    long cell = count == cells ? j : (j * cells + cells / 2) / count;
    std::vector<int> lower(p);
    for (std::size_t a = 0; a < p; ++a) {
      lower[a] = static_cast<int>(cell % cells_per_axis[a]);
      cell /= cells_per_axis[a];
    }
    Probe probe;
    for (std::size_t a = 0; a < p; ++a) {
      const std::vector<double>& v = db.axes[a].values;
      if (v.size() < 2) {
        probe.parameters.push_back(v.front());
        continue;
      }
      const double lo = v[static_cast<std::size_t>(lower[a])];
      const double hi = v[static_cast<std::size_t>(lower[a]) + 1];
      // The middle in the interpolation coordinate: log x where the axis is positive (§4.4 (a)).
      const bool logarithmic = v.front() > 0 && v.back() > 0;
      probe.parameters.push_back(logarithmic ? std::sqrt(lo * hi) : 0.5 * (lo + hi));
    }
    // The 2^p corners (an axis of one value contributes its only node).
    for (int mask = 0; mask < (1 << p); ++mask) {
      std::vector<int> corner = lower;
      bool valid = true;
      for (std::size_t a = 0; a < p; ++a) {
        if ((mask >> a) & 1) {
          if (db.axes[a].values.size() < 2) valid = false;
          ++corner[a];
        }
      }
      if (valid) probe.corners.push_back(db.sampleIndex(corner));
    }
    probes.push_back(std::move(probe));
  }
  return probes;
}

LeaveOneOutResult probeErrors(const RomDatabase& db, InterpolationMethod method,
                              const std::vector<Probe>& probes,
                              const std::vector<ModalModel>& solved,
                              const fullorder::DriveLaw& drive, const ModalDeploymentOptions& deploy,
                              std::vector<ProbeError>& measured) {
  MASTROM_REQUIRE(probes.size() == solved.size() && !probes.empty(), InputError,
                  "rom build: ", solved.size(), " probe solutions for ", probes.size(), " probes");
  LeaveOneOutResult r;
  r.method = method;
  r.frequency_error.assign(db.samples.size(), -1.0);
  r.response_error.assign(db.samples.size(), -1.0);
  measured.clear();
  const std::unique_ptr<ModalInterpolator> interpolator = makeInterpolator(db, method);
  const SampledDrive sampled = sampleDrive(drive, deploy);
  for (std::size_t i = 0; i < probes.size(); ++i) {
    const ModalModel interpolated = interpolator->evaluate(probes[i].parameters);
    const double w = solved[i].omega_rad_s.minCoeff();
    const double f = std::abs(interpolated.omega_rad_s.minCoeff() - w) / w;
    const double e = responseNrmse(relativeAccelerationSeries(solved[i], sampled, deploy),
                                   relativeAccelerationSeries(interpolated, sampled, deploy));
    measured.push_back(ProbeError{probes[i].parameters, f, e});
    for (const int s : probes[i].corners) {
      const auto k = static_cast<std::size_t>(s);
      r.frequency_error[k] = std::max(r.frequency_error[k], f);
      r.response_error[k] = std::max(r.response_error[k], e);
    }
    r.max_frequency_error = std::max(r.max_frequency_error, f);
    r.max_response_error = std::max(r.max_response_error, e);
  }
  for (const double f : r.frequency_error) r.estimated += f >= 0 ? 1 : 0;
  r.frequency_estimate = r.max_frequency_error;
  r.response_estimate = r.max_response_error;
  return r;
}

}  // namespace mastrom::rom
