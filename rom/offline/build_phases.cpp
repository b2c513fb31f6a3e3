// The per-rank phases of a database build (see build_phases.hpp).
#include "rom/offline/build_phases.hpp"

#include "rom/offline/mode_tracking.hpp"

namespace mastrom::rom {
namespace {

/// The sample as tracked against the reference (the reference itself: the identity).
ExchangedSample trackedSample(const SampleSolution& sol, const SampleSolution& ref, int modes,
                              int index) {
  ExchangedSample x;
  x.index = index;
  RomSample& sample = x.sample;
  sample.modal = sol.modal;
  x.times[0] = sol.assembly_s;
  x.times[1] = sol.eigensolve_s;
  x.times[2] = sol.extraction_s;
  if (&sol == &ref) {
    sample.alignment = Eigen::MatrixXd::Identity(modes, modes);
    for (int j = 0; j < modes; ++j) {
      sample.tracking.push_back(j);
      sample.tracking_sign.push_back(1);
    }
    return x;
  }
  const auto start = BuildClock::now();
  const ModeTracking t =
      trackModes(rotateModes(sol.modes.leftCols(modes),
                             ref.modal.reference_angle_rad - sol.modal.reference_angle_rad),
                 ref.modes.leftCols(modes), ref.mass);
  sample.alignment = t.alignment;
  sample.tracking = t.tracking;
  sample.tracking_sign = t.sign;
  // The modes the drive excites: effective-mass fraction Γ_j²/J of the reference ≥
  // kExcitedMassFraction. (A relative |Γ| of 1e-3 counted modes carrying 1e-6 of the rotary
  // inertia, whose leaving the window says nothing about the response.)
  const Eigen::VectorXd& g = ref.modal.rotation_participation;
  const double j_total = ref.modal.inertia_z_kg_m2;
  for (int j = 0; j < modes; ++j) {
    if (t.mac[j] < x.mac_min[0]) {
      x.mac_min[0] = t.mac[j];
      x.mac_min_mode[0] = j;
    }
    if (g[j] * g[j] >= kExcitedMassFraction * j_total && t.mac[j] < x.mac_min[1]) {
      x.mac_min[1] = t.mac[j];
      x.mac_min_mode[1] = j;
    }
  }
  x.times[2] += secondsSince(start);
  return x;
}

}  // namespace

void SolveTimes::add(const SampleSolution& s) {
  assembly_s += s.assembly_s;
  eigensolve_s += s.eigensolve_s;
  extraction_s += s.extraction_s;
  ++solves;
}

SampleSolution solveReference(const SampleSettings& settings, const std::vector<double>& point,
                              int index, SolveTimes& times) {
  SampleSolution ref = solveSample(settings.base, settings.axes, point, settings.modes,
                                   settings.backend, index, nullptr, settings.stresses);
  times.add(ref);
  return ref;
}

void solveShare(const SampleSettings& settings, const std::vector<std::vector<double>>& points,
                int first, const SampleSolution& reference, int reference_index, int rank, int size,
                SolveTimes& times, RankOutcome& out,
                const std::function<void(int, int)>& progress) {
  runCatching(out, "rom build: ", [&] {
    const int count = static_cast<int>(points.size());
    // The indices s ≡ rank (mod size) in [first, first + count).
    const int start = first + ((rank - first) % size + size) % size;
    const int share = start < first + count ? (first + count - start + size - 1) / size : 0;
    int done = 0;
    for (int s = start; s < first + count; s += size) {
      if (s == reference_index) {
        packSample(out.values, trackedSample(reference, reference, settings.modes, s));
      } else {
        const SampleSolution sol =
            solveSample(settings.base, settings.axes, points[static_cast<std::size_t>(s - first)],
                        settings.modes, settings.backend, s, &reference, settings.stresses);
        const ExchangedSample x = trackedSample(sol, reference, settings.modes, s);
        times.add(sol);
        times.extraction_s += x.times[2] - sol.extraction_s;  // the tracking
        packSample(out.values, x);
      }
      ++done;
      if (progress) progress(done, share);
    }
  });
}

void collectSamples(const std::vector<double>& all, const std::vector<std::vector<double>>& points,
                    int first, RomDatabase& db, BuildReport& rep) {
  const int count = static_cast<int>(points.size());
  std::vector<char> filled(static_cast<std::size_t>(count), 0);
  for (ExchangedSample& x : unpackSamples(all)) {
    const int i = x.index - first;
    MASTROM_REQUIRE(i >= 0 && i < count && !filled[static_cast<std::size_t>(i)] &&
                        x.index < static_cast<int>(db.samples.size()),
                    NumericalError, "rom build: gathered sample ", x.index,
                    " is invalid or duplicated");
    x.sample.parameters = points[static_cast<std::size_t>(i)];
    if (x.mac_min[0] < rep.min_mac) {
      rep.min_mac = x.mac_min[0];
      rep.min_mac_sample = x.index;
      rep.min_mac_mode = x.mac_min_mode[0];
    }
    if (x.mac_min[1] < rep.min_coupled_mac) {
      rep.min_coupled_mac = x.mac_min[1];
      rep.min_coupled_mac_sample = x.index;
      rep.min_coupled_mac_mode = x.mac_min_mode[1];
    }
    db.samples[static_cast<std::size_t>(x.index)] = std::move(x.sample);
    filled[static_cast<std::size_t>(i)] = 1;
  }
  for (int i = 0; i < count; ++i)
    MASTROM_REQUIRE(filled[static_cast<std::size_t>(i)], NumericalError, "rom build: sample ",
                    first + i, " was not computed");
}

}  // namespace mastrom::rom
