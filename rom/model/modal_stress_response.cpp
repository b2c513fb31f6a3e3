// ROM interface stresses (see modal_stress_response.hpp).
#include "rom/model/modal_stress_response.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "common/error.hpp"
#include "fullorder/shell_stress.hpp"

namespace mastrom::rom {
namespace {

thread_local long t_peak_evaluations = 0;

/// Squared plane-stress von Mises of [a, b, c] (tensor shear c; fullorder/shell_stress.hpp).
inline double vonMises2(double a, double b, double c) { return a * a - a * b + b * b + 3.0 * c * c; }

/// The three ζ stations of a point from its rows [σ_m; σ_b] (modal_stress.hpp).
template <class Rows>
void stationsOf(const Rows& y, double vm2[fullorder::kShellSurfaces]) {
  vm2[0] = vonMises2(y[0] - y[3], y[1] - y[4], y[2] - y[5]);
  vm2[1] = vonMises2(y[0], y[1], y[2]);
  vm2[2] = vonMises2(y[0] + y[3], y[1] + y[4], y[2] + y[5]);
}

}  // namespace

ModalStressEvaluator::ModalStressEvaluator(const ModalModel& model) {
  const ModalStress& s = model.stress;
  MASTROM_REQUIRE(!s.empty(), InputError,
                  "rom stresses: the modal model carries no stress modes (a database built "
                  "without them, or an affine one: rebuild it with this mastrom)");
  s.validate(model.modeCount(), /*check_values=*/false);
  modes_ = model.modeCount();
  inputs_ = modes_ + kStressLoadCount + 1;
  damping_s_ = s.damping_s;
  for (int i = 0; i < s.interfaceCount(); ++i) {
    Interface itf;
    itf.points = s.interface_offsets[i + 1] - s.interface_offsets[i];
    const Eigen::Index first = kStressRowsPerPoint * s.interface_offsets[i];
    const Eigen::Index rows = kStressRowsPerPoint * itf.points;
    itf.rows.resize(rows, inputs_);
    itf.rows.leftCols(modes_) = s.modes.middleRows(first, rows);
    itf.rows.middleCols(modes_, kStressLoadCount) = s.loads.middleRows(first, rows);
    itf.rows.col(inputs_ - 1) = s.preload.segment(first, rows);
    // c_j: the largest von Mises of column j alone over the stations (the bound b of the header).
    itf.bound.resize(inputs_);
    for (int j = 0; j < inputs_; ++j) {
      double c2 = 0.0;
      for (int p = 0; p < itf.points; ++p) {
        double vm2[fullorder::kShellSurfaces];
        stationsOf(itf.rows.col(j).segment<kStressRowsPerPoint>(kStressRowsPerPoint * p), vm2);
        c2 = std::max({c2, vm2[0], vm2[1], vm2[2]});
      }
      itf.bound[j] = std::sqrt(c2);
    }
    interfaces_.push_back(std::move(itf));
  }
}

void ModalStressEvaluator::input(const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
                                 const stepping_detail::ForcingScalars& f,
                                 Eigen::Ref<Eigen::VectorXd> x) const {
  x.head(modes_) = eta + damping_s_ * eta_dot;
  x[modes_] = f.acc;
  x[modes_ + 1] = f.rate2;
  x[modes_ + 2] = f.gx;
  x[modes_ + 3] = f.gy;
  x[modes_ + 4] = 1.0;
}

double ModalStressEvaluator::largest(int i, const Eigen::Ref<const Eigen::VectorXd>& x,
                                     int* station) const {
  const Interface& itf = interfaces_[static_cast<std::size_t>(i)];
  thread_local Eigen::VectorXd y;
  y.noalias() = itf.rows * x;
  double best = -1.0;
  int where = 0;
  for (int p = 0; p < itf.points; ++p) {
    double vm2[fullorder::kShellSurfaces];
    stationsOf(y.segment<kStressRowsPerPoint>(kStressRowsPerPoint * p), vm2);
    for (int z = 0; z < fullorder::kShellSurfaces; ++z)
      if (vm2[z] > best) best = vm2[z], where = fullorder::kShellSurfaces * p + z;
  }
  if (station) *station = where;
  return std::sqrt(std::max(best, 0.0));
}

void ModalStressEvaluator::largestHistory(int i, const Eigen::MatrixXd& states,
                                          std::vector<double>& out) const {
  const Interface& itf = interfaces_[static_cast<std::size_t>(i)];
  const Eigen::Index samples = states.cols();
  out.resize(static_cast<std::size_t>(samples));
  constexpr Eigen::Index kBlock = 128;  // columns per product: Y stays in the L2 cache
  Eigen::MatrixXd y(itf.rows.rows(), kBlock);
  for (Eigen::Index first = 0; first < samples; first += kBlock) {
    const Eigen::Index count = std::min(kBlock, samples - first);
    y.leftCols(count).noalias() = itf.rows * states.middleCols(first, count);
    for (Eigen::Index c = 0; c < count; ++c) {
      double best = 0.0;
      for (int p = 0; p < itf.points; ++p) {
        double vm2[fullorder::kShellSurfaces];
        stationsOf(y.col(c).segment<kStressRowsPerPoint>(kStressRowsPerPoint * p), vm2);
        best = std::max({best, vm2[0], vm2[1], vm2[2]});
      }
      out[static_cast<std::size_t>(first + c)] = std::sqrt(best);
    }
  }
}

void ModalStressEvaluator::field(int i, const Eigen::Ref<const Eigen::VectorXd>& x,
                                 std::vector<double>& vm) const {
  const Interface& itf = interfaces_[static_cast<std::size_t>(i)];
  const Eigen::VectorXd y = itf.rows * x;
  vm.resize(static_cast<std::size_t>(fullorder::kShellSurfaces * itf.points));
  for (int p = 0; p < itf.points; ++p) {
    double vm2[fullorder::kShellSurfaces];
    stationsOf(y.segment<kStressRowsPerPoint>(kStressRowsPerPoint * p), vm2);
    for (int z = 0; z < fullorder::kShellSurfaces; ++z)
      vm[static_cast<std::size_t>(fullorder::kShellSurfaces * p + z)] = std::sqrt(vm2[z]);
  }
}

double ModalStressEvaluator::station(int i, int station,
                                     const Eigen::Ref<const Eigen::VectorXd>& x) const {
  const Interface& itf = interfaces_[static_cast<std::size_t>(i)];
  const int p = station / fullorder::kShellSurfaces, z = station % fullorder::kShellSurfaces;
  const Eigen::Matrix<double, kStressRowsPerPoint, 1> y =
      itf.rows.middleRows<kStressRowsPerPoint>(kStressRowsPerPoint * p) * x;
  double vm2[fullorder::kShellSurfaces];
  stationsOf(y, vm2);
  return std::sqrt(vm2[z]);
}

ModalStressEvaluator::Peak ModalStressEvaluator::peak(int i, const Eigen::MatrixXd& states,
                                                      const std::vector<char>& no_polish) const {
  const Interface& itf = interfaces_[static_cast<std::size_t>(i)];
  const long samples = static_cast<long>(states.cols());
  MASTROM_REQUIRE(states.rows() == inputs_ && samples >= 1, InputError, "rom stresses: ",
                  states.rows(), " × ", samples, " states for inputs of size ", inputs_);
  // Upper bounds, then best-first (header comment).
  Eigen::VectorXd bound(samples);
  for (long n = 0; n < samples; ++n) bound[n] = itf.bound.dot(states.col(n).cwiseAbs());
  long first = 0;
  bound.maxCoeff(&first);
  Peak out;
  long evaluations = 1;
  out.von_mises_pa = largest(i, states.col(first), &out.station);
  out.nearest_sample = first;
  std::vector<long> candidates;
  for (long n = 0; n < samples; ++n)
    if (n != first && bound[n] > out.von_mises_pa) candidates.push_back(n);
  std::sort(candidates.begin(), candidates.end(),
            [&bound](long a, long b) { return bound[a] > bound[b]; });
  for (const long n : candidates) {
    if (bound[n] <= out.von_mises_pa) break;
    int where = 0;
    const double v = largest(i, states.col(n), &where);
    ++evaluations;
    if (v > out.von_mises_pa) out.von_mises_pa = v, out.station = where, out.nearest_sample = n;
  }
  t_peak_evaluations = evaluations;

  // The parabola through the peak sample and its neighbours at the same station.
  const long n = out.nearest_sample;
  out.sample = static_cast<double>(n);
  const auto near_breakpoint = [&no_polish](long m) {
    return m >= 0 && static_cast<std::size_t>(m) < no_polish.size() && no_polish[static_cast<std::size_t>(m)];
  };
  if (n > 0 && n + 1 < samples && !near_breakpoint(n - 1) && !near_breakpoint(n) &&
      !near_breakpoint(n + 1)) {
    const double v0 = station(i, out.station, states.col(n));
    const double vm = station(i, out.station, states.col(n - 1));
    const double vp = station(i, out.station, states.col(n + 1));
    const double curvature = vp + vm - 2.0 * v0, slope = 0.5 * (vp - vm);
    if (curvature < 0.0) {
      const double x = -slope / curvature;
      if (std::abs(x) <= 1.0) {
        out.von_mises_pa = std::max(out.von_mises_pa, v0 - 0.5 * slope * slope / curvature);
        out.sample = static_cast<double>(n) + x;
      }
    }
  }
  return out;
}

long ModalStressEvaluator::lastPeakEvaluations() { return t_peak_evaluations; }

ModalSampleObserver modalStressRecorder(const ModalStressEvaluator& evaluator,
                                        Eigen::MatrixXd& states) {
  return [&evaluator, &states](long n, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
                               const stepping_detail::ForcingScalars& f) {
    evaluator.input(eta, eta_dot, f, states.col(n));
  };
}

std::vector<char> samplesNearBreakpoints(const SampledDrive& drive) {
  std::vector<char> marked(static_cast<std::size_t>(drive.steps + 1), 0);
  for (long n = 1; n < drive.steps; ++n) {
    const SampledDrive::Sample& s = drive.samples[static_cast<std::size_t>(n)];
    if (s.start_acceleration_rad_s2 != s.end_acceleration_rad_s2) marked[static_cast<std::size_t>(n)] = 1;
  }
  for (const SampledDrive::Split& split : drive.splits) {
    marked[static_cast<std::size_t>(split.step)] = 1;
    marked[static_cast<std::size_t>(split.step + 1)] = 1;
  }
  return marked;
}

Eigen::MatrixXd modalStressStates(const ModalModel& model, const ModalStressEvaluator& evaluator,
                                  const SampledDrive& drive, bool coriolis_coupling) {
  const ModalStepping ms = prepareModalStepping(model, drive, coriolis_coupling);
  Eigen::MatrixXd states(evaluator.inputSize(), drive.steps + 1);
  const ModalSampleObserver record = modalStressRecorder(evaluator, states);
  runModalStepping(model, ms, drive,
                   [&](long n, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
                       const Eigen::VectorXd&) {
                     record(n, eta, eta_dot, stepping_detail::forcingScalars(ms, drive.valueAt(n)));
                   });
  return states;
}

fullorder::InterfaceStressResult modalInterfaceStresses(const ModalModel& model,
                                                        const fullorder::DriveLaw& drive,
                                                        const ModalDeploymentOptions& options) {
  const ModalStressEvaluator evaluator(model);
  const SampledDrive sampled = sampleDrive(drive, options);
  const std::vector<char> no_polish = samplesNearBreakpoints(sampled);
  const Eigen::MatrixXd states =
      modalStressStates(model, evaluator, sampled, options.coriolis_coupling);
  const ModalStress& s = model.stress;
  fullorder::InterfaceStressResult r;
  const long samples = sampled.steps + 1;
  for (long n = 0; n < samples; ++n) r.time_s.push_back(static_cast<double>(n) * sampled.step_s);
  r.recovery_points = fullorder::ShellStressRecovery::gridPoints();
  const int per_point = fullorder::kShellSurfaces;
  for (int i = 0; i < evaluator.interfaceCount(); ++i) {
    fullorder::InterfaceStressHistory h;
    evaluator.largestHistory(i, states, h.max_von_mises_pa);
    r.history.push_back(std::move(h));

    const ModalStressEvaluator::Peak pk = evaluator.peak(i, states, no_polish);
    fullorder::InterfaceStressPeak peak;
    peak.von_mises_pa = pk.von_mises_pa;
    peak.time_s = pk.sample * sampled.step_s;
    const int point = pk.station / per_point;
    const int per_element = static_cast<int>(r.recovery_points.size());
    peak.element = point / per_element;
    peak.point = point % per_element;
    peak.surface = pk.station % per_point;
    const Eigen::Index global = s.interface_offsets[i] + point;
    peak.axial_position_m = s.points(0, global);
    peak.angle_rad = s.points(1, global);
    evaluator.field(i, states.col(pk.nearest_sample), peak.field_von_mises_pa);
    r.peak.push_back(std::move(peak));

    std::vector<std::array<double, 2>> coords;
    for (Eigen::Index p = s.interface_offsets[i]; p < s.interface_offsets[i + 1]; ++p)
      coords.push_back({s.points(0, p), s.points(1, p)});
    r.point_coordinates.push_back(std::move(coords));
  }
  return r;
}

std::vector<double> modalStressPeaks(const ModalStressEvaluator& evaluator,
                                     const Eigen::MatrixXd& states,
                                     const std::vector<char>& no_polish) {
  std::vector<double> peaks;
  for (int i = 0; i < evaluator.interfaceCount(); ++i)
    peaks.push_back(evaluator.peak(i, states, no_polish).von_mises_pa);
  return peaks;
}

}  // namespace mastrom::rom
