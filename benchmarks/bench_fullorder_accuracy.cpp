// Accuracy of the full order's adaptive steps against a step-converged fixed-step reference
// (docs/user_guide.md §7, benchmarks/README.md "Full-order accuracy"). Reads deployment files only;
// benchmarks/fullorder_accuracy.sh runs the simulations.
//
//   bench_fullorder_accuracy [--order P] --ref H.h5 --ref H2.h5 [--ref H4.h5 ...] RUN.h5 ...
//
// The --ref files are fixed-step runs of the same case (simulation.adaptive = false), each with
// half the step of the one before, all written on the same output instants (output.every scaled
// with the step). Printed:
//  * the reference ladder: for each halving, the change of the relative end angular acceleration
//    r (NRMSE, ‖r_h/2 − r_h‖₂ / ‖r_h/2‖₂) and of every peak metric; with three or more files the
//    observed order p = log2(change(h) / change(h/2));
//  * the reference used: the Richardson extrapolation of the two finest files with the order p
//    (--order, default 2, the scheme's order on smooth solutions),
//    r* = r_h/2 + (r_h/2 − r_h) / (2^p − 1) (the series sample by sample, the metrics as scalars),
//    and the remaining error of the finest file against it;
//  * for every RUN file (adaptive runs, on instants that are a subset of those of the second-finest
//    reference, where r* lives): the
//    NRMSE of r against r* on the run's instants, the relative error of each metric (the RMS of r*
//    taken on the run's instants, like the run's own), the ratio of
//    the file's own estimate (/metrics estimated_nrmse_rel_end_angular_acceleration, simulate
//    --estimate-error) to the measured NRMSE, and the wall time of the run (× simulated time).
//
// A fixed-step reference's peaks come from its samples, each refined by the parabola through the
// largest sample and its neighbours (so an output step of 20 µs under-reads a 1.7 kHz ringing by
// ~1e-5 instead of ~0.5 %, but over-reads the ~40 µs wide peak right after a ramp's end by ~0.2 %:
// check such peaks with references written every step); the runs' peaks are their own /metrics (the adaptive full order's
// continuous peaks). Where the fixed steps do not converge (Scheme 3 below 10 µs, see
// benchmarks/README.md), the --ref files may be adaptive runs at halving tolerances with
// --order 0.667 (the global error ∝ tol^(2/3)); their peaks are then their continuous ones.
// A plain program; no timing of its own.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "fullorder/deployment_result.hpp"
#include "fullorder/results_io.hpp"

namespace {

using namespace mastrom;
using fullorder::DeploymentFile;
using fullorder::DeploymentSeries;

/// The metrics compared, in print order.
struct Metrics {
  double peak_rel = 0, peak_abs = 0, residual = 0, rms = 0, force = 0, torque = 0;
  static constexpr int kCount = 6;
  double operator[](int i) const {
    const double v[kCount] = {peak_rel, peak_abs, residual, rms, force, torque};
    return v[i];
  }
  static const char* name(int i) {
    static const char* const n[kCount] = {"peak_rel", "peak_abs", "residual",
                                          "rms_rel", "force", "torque"};
    return n[i];
  }
};

/// max |x_i| over samples with t_i ≥ t_from, refined by the parabola through the largest sample
/// and its two neighbours (signed values; only when the vertex lies between the neighbours).
double refinedPeak(const std::vector<double>& t, const std::vector<double>& x, double t_from) {
  std::size_t k = t.size();
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= t_from && (k == t.size() || std::abs(x[i]) > std::abs(x[k]))) k = i;
  if (k == t.size()) return 0.0;
  double peak = std::abs(x[k]);
  if (k == 0 || k + 1 >= t.size() || t[k - 1] < t_from) return peak;
  const double h1 = t[k] - t[k - 1], h2 = t[k + 1] - t[k];
  if (std::abs(h1 - h2) > 1e-6 * h1) return peak;
  const double a = 0.5 * (x[k + 1] - 2.0 * x[k] + x[k - 1]);  // x(s) = x_k + b s + a s², s ∈ [-1, 1]
  const double b = 0.5 * (x[k + 1] - x[k - 1]);
  if (a == 0.0) return peak;
  const double s = -b / (2.0 * a);
  if (std::abs(s) > 1.0) return peak;
  return std::max(peak, std::abs(x[k] + b * s + a * s * s));
}

Metrics fileMetrics(const DeploymentFile& f);

/// The peaks of a reference: its own continuous peaks when it has them (an adaptive run), else
/// the refined maxima of its samples.
Metrics referenceMetrics(const DeploymentFile& f) {
  if (f.metrics.peaks_resolved.rfind("continuous", 0) == 0) return fileMetrics(f);
  const DeploymentSeries& s = f.series;
  const std::vector<double>& t = s.time_s;
  std::vector<double> a_z(t.size()), force(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    a_z[i] = s.end_angular_acceleration_rad_s2[i].z();
    force[i] = s.joint_force_n[i].norm();
  }
  Metrics m;
  const double t0 = t.front();
  m.peak_rel = refinedPeak(t, s.end_relative_angular_acceleration_rad_s2, t0);
  m.peak_abs = refinedPeak(t, a_z, t0);
  m.residual = refinedPeak(t, s.end_relative_angular_acceleration_rad_s2, f.metrics.drive_end_time);
  m.rms = f.metrics.rms_rel_end_angular_acceleration;
  m.force = refinedPeak(t, force, t0);
  m.torque = refinedPeak(t, s.joint_torque_nm, t0);
  return m;
}

Metrics fileMetrics(const DeploymentFile& f) {
  Metrics m;
  m.peak_rel = f.metrics.peak_rel_end_angular_acceleration;
  m.peak_abs = f.metrics.peak_abs_end_angular_acceleration;
  m.residual = f.metrics.residual_rel_end_angular_acceleration;
  m.rms = f.metrics.rms_rel_end_angular_acceleration;
  m.force = f.metrics.peak_joint_force;
  m.torque = f.metrics.peak_drive_torque;
  return m;
}

/// Index in `ref_t` of every instant of `t` (within 1e-7 s); exits when one is missing.
std::vector<std::size_t> matchInstants(const std::vector<double>& t,
                                       const std::vector<double>& ref_t, const char* what) {
  std::vector<std::size_t> index;
  index.reserve(t.size());
  std::size_t j = 0;
  for (double ti : t) {
    while (j < ref_t.size() && ref_t[j] < ti - 1e-7) ++j;
    if (j == ref_t.size() || std::abs(ref_t[j] - ti) > 1e-7) {
      std::fprintf(stderr, "bench_fullorder_accuracy: %s: instant t = %.9g s is not in the "
                   "reference's output\n", what, ti);
      std::exit(2);
    }
    index.push_back(j);
  }
  return index;
}

/// ‖x − ref‖₂ / ‖ref‖₂ over the instants of x.
double nrmse(const std::vector<double>& x, const std::vector<double>& ref,
             const std::vector<std::size_t>& index) {
  double d2 = 0.0, r2 = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double d = x[i] - ref[index[i]];
    d2 += d * d;
    r2 += ref[index[i]] * ref[index[i]];
  }
  return r2 > 0.0 ? std::sqrt(d2 / r2) : 0.0;
}

double relative(double value, double ref) {
  return ref != 0.0 ? std::abs(value - ref) / std::abs(ref) : 0.0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> ref_paths, run_paths;
  double order = 2.0;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--ref") && i + 1 < argc) {
      ref_paths.push_back(argv[++i]);
    } else if (!std::strcmp(argv[i], "--order") && i + 1 < argc) {
      order = std::atof(argv[++i]);
    } else if (argv[i][0] == '-') {
      std::fprintf(stderr, "usage: %s [--order P] --ref H.h5 --ref H2.h5 [--ref ...] RUN.h5 ...\n",
                   argv[0]);
      return 2;
    } else {
      run_paths.push_back(argv[i]);
    }
  }
  if (ref_paths.empty()) {
    std::fprintf(stderr, "bench_fullorder_accuracy: at least one --ref file is needed\n");
    return 2;
  }
  std::vector<DeploymentFile> refs;
  std::vector<Metrics> ref_metrics;
  for (const std::string& p : ref_paths) {
    refs.push_back(fullorder::readDeploymentFile(p));
    ref_metrics.push_back(referenceMetrics(refs.back()));
  }

  // The ladder of fixed steps: what each halving changes.
  std::printf("# reference ladder (each file against the next, half-step one)\n");
  std::printf("# %-40s %9s %9s", "file", "wall_s", "NRMSE%");
  for (int k = 0; k < Metrics::kCount; ++k) std::printf(" %9s%%", Metrics::name(k));
  std::printf("\n");
  std::vector<double> changes;
  for (std::size_t i = 0; i < refs.size(); ++i) {
    std::printf("  %-40s %9.1f", ref_paths[i].c_str(), refs[i].wall_time_s);
    if (i + 1 < refs.size()) {
      const DeploymentSeries& fine = refs[i + 1].series;
      const std::vector<std::size_t> index =
          matchInstants(refs[i].series.time_s, fine.time_s, ref_paths[i].c_str());
      const double change = nrmse(refs[i].series.end_relative_angular_acceleration_rad_s2,
                                  fine.end_relative_angular_acceleration_rad_s2, index);
      changes.push_back(change);
      std::printf(" %9.4f", 100.0 * change);
      for (int k = 0; k < Metrics::kCount; ++k)
        std::printf(" %10.4f", 100.0 * relative(ref_metrics[i][k], ref_metrics[i + 1][k]));
    }
    std::printf("\n");
  }
  for (std::size_t i = 0; i + 1 < changes.size(); ++i)
    std::printf("  observed order of the NRMSE change, halving %zu -> %zu: p = %.2f\n", i + 1,
                i + 2, std::log2(changes[i] / changes[i + 1]));

  // The reference: Richardson from the two finest files (order p), or the finest alone.
  const double divisor = std::pow(2.0, order) - 1.0;
  // On the instants of the second-finest file (the finest may write more often).
  const DeploymentFile& finest = refs.back();
  const DeploymentFile& base = refs.size() >= 2 ? refs[refs.size() - 2] : finest;
  const std::vector<std::size_t> in_finest =
      matchInstants(base.series.time_s, finest.series.time_s, "reference");
  std::vector<double> ref_r(base.series.size()), finest_r(base.series.size());
  for (std::size_t i = 0; i < ref_r.size(); ++i)
    ref_r[i] = finest_r[i] = finest.series.end_relative_angular_acceleration_rad_s2[in_finest[i]];
  const std::vector<double>& ref_t = base.series.time_s;
  Metrics ref_m = ref_metrics.back();
  if (refs.size() >= 2) {
    const std::vector<double>& rc = base.series.end_relative_angular_acceleration_rad_s2;
    for (std::size_t i = 0; i < ref_r.size(); ++i) ref_r[i] += (ref_r[i] - rc[i]) / divisor;
    const Metrics& mc = ref_metrics[refs.size() - 2];
    double* fields[Metrics::kCount] = {&ref_m.peak_rel, &ref_m.peak_abs, &ref_m.residual,
                                       &ref_m.rms,      &ref_m.force,    &ref_m.torque};
    for (int k = 0; k < Metrics::kCount; ++k) *fields[k] += (*fields[k] - mc[k]) / divisor;
    std::vector<std::size_t> identity(ref_r.size());
    for (std::size_t i = 0; i < identity.size(); ++i) identity[i] = i;
    std::printf("# reference: Richardson (order %g) of the two finest files; the finest file's "
                "own error against it: NRMSE %.4f %%\n",
                order, 100.0 * nrmse(finest_r, ref_r, identity));
  } else {
    std::printf("# reference: the finest file as it is\n");
  }
  std::printf("# reference metrics:");
  for (int k = 0; k < Metrics::kCount; ++k) std::printf(" %s %.6g", Metrics::name(k), ref_m[k]);
  std::printf("\n");

  if (run_paths.empty()) return 0;
  std::printf("# runs against the reference (errors in %%; est/meas = estimated / measured "
              "NRMSE; xreal = wall / simulated time)\n");
  std::printf("# %-40s %9s", "file", "NRMSE%");
  for (int k = 0; k < Metrics::kCount; ++k) std::printf(" %10s", Metrics::name(k));
  std::printf(" %9s %9s %8s %7s\n", "est%", "est/meas", "wall_s", "xreal");
  for (const std::string& p : run_paths) {
    const DeploymentFile run = fullorder::readDeploymentFile(p);
    const std::vector<std::size_t> index =
        matchInstants(run.series.time_s, ref_t, p.c_str());
    const double e = nrmse(run.series.end_relative_angular_acceleration_rad_s2, ref_r, index);
    const Metrics m = fileMetrics(run);
    // RMS like with like: the reference's on the run's instants (the trapezoidal rule of the file's
    // metric depends on the sampling).
    Metrics ref_here = ref_m;
    {
      const std::vector<double>& t = run.series.time_s;
      double integral = 0.0;
      for (std::size_t i = 0; i + 1 < t.size(); ++i) {
        const double a = ref_r[index[i]], b = ref_r[index[i + 1]];
        integral += 0.5 * (a * a + b * b) * (t[i + 1] - t[i]);
      }
      if (t.size() > 1) ref_here.rms = std::sqrt(integral / (t.back() - t.front()));
    }
    std::printf("  %-40s %9.4f", p.c_str(), 100.0 * e);
    for (int k = 0; k < Metrics::kCount; ++k)
      std::printf(" %10.4f", 100.0 * relative(m[k], ref_here[k]));
    const double est = run.metrics.estimated_nrmse_rel_end_angular_acceleration;
    const double span = run.series.time_s.back() - run.series.time_s.front();
    std::printf(" %9.4f %9.2f %8.1f %7.2f\n", 100.0 * est, est / e, run.wall_time_s,
                run.wall_time_s / span);
  }
  return 0;
}
