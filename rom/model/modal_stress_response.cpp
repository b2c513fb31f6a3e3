// The stresses of a ROM deployment (modal_stress_response.hpp, docs/theory.md §6.5): the modal
// state x of every sample recorded while the modes step, the peaks found and refined from it, and
// the result assembled in the full order's form. The evaluator is in modal_stress_evaluator.cpp,
// the peak search in stress_peak_search.cpp, the refinement between samples in
// stress_peak_refinement.cpp.
#include "rom/model/modal_stress_response.hpp"

#include <algorithm>
#include <array>
#include <vector>

#include "fullorder/shell_stress.hpp"

namespace mastrom::rom {

ModalSampleObserver modalStressRecorder(const ModalStressEvaluator& evaluator,
                                        Eigen::MatrixXd& states) {
  return [&evaluator, &states](long n, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
                               const stepping_detail::ForcingScalars& f) {
    evaluator.input(eta, eta_dot, f, states.col(n));
  };
}

ModalSampleObserver modalStressRecorder(const ModalStressEvaluator& evaluator,
                                        Eigen::MatrixXd& states, Eigen::MatrixXd& eta,
                                        Eigen::MatrixXd& eta_dot) {
  return [&evaluator, &states, &eta, &eta_dot](long n, const Eigen::VectorXd& e,
                                               const Eigen::VectorXd& v,
                                               const stepping_detail::ForcingScalars& f) {
    evaluator.input(e, v, f, states.col(n));
    eta.col(n) = e;
    eta_dot.col(n) = v;
  };
}

Eigen::MatrixXd modalStressStates(const ModalModel& model, const ModalStressEvaluator& evaluator,
                                  const SampledDrive& drive, bool coriolis_coupling,
                                  Eigen::MatrixXd* eta, Eigen::MatrixXd* eta_dot) {
  const ModalStepping ms = prepareModalStepping(model, drive, coriolis_coupling);
  Eigen::MatrixXd states(evaluator.inputSize(), drive.steps + 1);
  const bool keep = eta != nullptr && eta_dot != nullptr;
  if (keep) {
    eta->resize(model.modeCount(), drive.steps + 1);
    eta_dot->resize(model.modeCount(), drive.steps + 1);
  }
  const ModalSampleObserver record = keep ? modalStressRecorder(evaluator, states, *eta, *eta_dot)
                                          : modalStressRecorder(evaluator, states);
  runModalStepping(
      model, ms, drive,
      [&](long n, const Eigen::VectorXd& e, const Eigen::VectorXd& v, const Eigen::VectorXd&) {
        record(n, e, v, stepping_detail::forcingScalars(ms, drive.valueAt(n)));
      });
  return states;
}

std::vector<ModalStressEvaluator::Peak> findStressPeaks(
    const ModalStressEvaluator& evaluator, const Eigen::MatrixXd& states,
    const std::vector<char>& no_polish, const ModalModel& model, const SampledDrive& drive,
    const Eigen::MatrixXd& eta, const Eigen::MatrixXd& eta_dot) {
  std::vector<ModalStressEvaluator::Peak> found;
  const Eigen::MatrixXd block_maxima = evaluator.blockMaxima(states);
  for (int i = 0; i < evaluator.interfaceCount(); ++i)
    found.push_back(evaluator.peak(i, states, no_polish, &block_maxima));
  if (eta.size() > 0 && stressPeaksNeedRefinement(evaluator, model, drive.step_s))
    refineStressPeaks(evaluator, model, drive, eta, eta_dot, found);
  return found;
}

fullorder::InterfaceStressResult modalInterfaceStresses(const ModalModel& model,
                                                        const fullorder::DriveLaw& drive,
                                                        const ModalDeploymentOptions& options,
                                                        bool history) {
  const ModalStressEvaluator evaluator(model);
  const SampledDrive sampled = sampleDrive(drive, options);
  const bool refine = stressPeaksNeedRefinement(evaluator, model, sampled.step_s);
  Eigen::MatrixXd eta, eta_dot;
  const Eigen::MatrixXd states =
      modalStressStates(model, evaluator, sampled, options.coriolis_coupling,
                        refine ? &eta : nullptr, refine ? &eta_dot : nullptr);
  return modalInterfaceStresses(model, evaluator, sampled, states, eta, eta_dot, history);
}

fullorder::InterfaceStressResult modalInterfaceStresses(
    const ModalModel& model, const ModalStressEvaluator& evaluator, const SampledDrive& sampled,
    const Eigen::MatrixXd& states, const Eigen::MatrixXd& eta, const Eigen::MatrixXd& eta_dot,
    bool history) {
  const std::vector<char> no_polish = samplesNearBreakpoints(sampled);
  const std::vector<ModalStressEvaluator::Peak> peaks =
      findStressPeaks(evaluator, states, no_polish, model, sampled, eta, eta_dot);
  std::vector<Eigen::VectorXd> peak_states;
  for (const ModalStressEvaluator::Peak& pk : peaks)
    peak_states.push_back(states.col(pk.nearest_sample));
  fullorder::InterfaceStressResult r =
      interfaceStressResult(model, evaluator, sampled, sampled.step_s, peaks, peak_states);
  if (history)
    for (int i = 0; i < evaluator.interfaceCount(); ++i)
      evaluator.largestHistory(i, states, r.history[static_cast<std::size_t>(i)].max_von_mises_pa);
  return r;
}

fullorder::InterfaceStressResult interfaceStressResult(
    const ModalModel& model, const ModalStressEvaluator& evaluator, const SampledDrive& sampled,
    double peak_step_s, const std::vector<ModalStressEvaluator::Peak>& peaks,
    const std::vector<Eigen::VectorXd>& peak_states) {
  fullorder::InterfaceStressResult r =
      interfaceStressPeaks(model, evaluator, peak_step_s, peaks, peak_states);
  setStressOutputInstants(sampled, r);
  return r;
}

void setStressOutputInstants(const SampledDrive& sampled, fullorder::InterfaceStressResult& r) {
  const long samples = sampled.steps + 1;
  r.time_s.clear();
  r.time_s.reserve(static_cast<std::size_t>(samples));
  for (long n = 0; n < samples; ++n) r.time_s.push_back(static_cast<double>(n) * sampled.step_s);
}

fullorder::InterfaceStressResult interfaceStressPeaks(
    const ModalModel& model, const ModalStressEvaluator& evaluator, double peak_step_s,
    const std::vector<ModalStressEvaluator::Peak>& peaks,
    const std::vector<Eigen::VectorXd>& peak_states) {
  const ModalStress& s = model.stress;
  fullorder::InterfaceStressResult r;
  r.recovery_points = fullorder::ShellStressRecovery::gridPoints();
  const int per_point = fullorder::kShellSurfaces;
  for (int i = 0; i < evaluator.interfaceCount(); ++i) {
    r.history.emplace_back();
    const ModalStressEvaluator::Peak& pk = peaks[static_cast<std::size_t>(i)];
    fullorder::InterfaceStressPeak peak;
    peak.von_mises_pa = pk.von_mises_pa;
    peak.time_s = pk.sample * peak_step_s;
    const int point = pk.station / per_point;
    const int per_element = static_cast<int>(r.recovery_points.size());
    peak.element = point / per_element;
    peak.point = point % per_element;
    peak.surface = pk.station % per_point;
    const Eigen::Index global = s.interface_offsets[i] + point;
    peak.axial_position_m = s.points(0, global);
    peak.angle_rad = s.points(1, global);
    evaluator.field(i, peak_states[static_cast<std::size_t>(i)], peak.field_von_mises_pa);
    r.peak.push_back(std::move(peak));

    std::vector<std::array<double, 2>> coords;
    for (Eigen::Index p = s.interface_offsets[i]; p < s.interface_offsets[i + 1]; ++p)
      coords.push_back({s.points(0, p), s.points(1, p)});
    r.point_coordinates.push_back(std::move(coords));
  }
  return r;
}

void streamModalStressHistories(const ModalModel& model, const ModalStressEvaluator& evaluator,
                                const SampledDrive& drive, bool coriolis_coupling,
                                const StressHistoryBlockSink& sink) {
  const ModalStepping ms = prepareModalStepping(model, drive, coriolis_coupling);
  constexpr long kColumns = 128;  // samples handed to the sink at a time
  const int interfaces = evaluator.interfaceCount();
  std::vector<ModalStressEvaluator::History> histories;
  for (int i = 0; i < interfaces; ++i) histories.emplace_back(evaluator, i);
  std::vector<std::vector<double>> values(static_cast<std::size_t>(interfaces));
  for (std::vector<double>& v : values) v.reserve(kColumns);
  Eigen::VectorXd x(evaluator.inputSize());
  long first = 0;
  const auto flush = [&] {
    sink(first, values);
    first += static_cast<long>(values[0].size());
    for (std::vector<double>& v : values) v.clear();
  };
  runModalStepping(
      model, ms, drive,
      [&](long n, const Eigen::VectorXd& e, const Eigen::VectorXd& v, const Eigen::VectorXd&) {
        evaluator.input(e, v, stepping_detail::forcingScalars(ms, drive.valueAt(n)), x);
        for (int i = 0; i < interfaces; ++i)
          values[static_cast<std::size_t>(i)].push_back(
              histories[static_cast<std::size_t>(i)].next(x));
        if (static_cast<long>(values[0].size()) == kColumns) flush();
      });
  if (interfaces > 0 && !values[0].empty()) flush();
}

void modalStressHistories(const ModalModel& model, const ModalStressEvaluator& evaluator,
                          const SampledDrive& drive, bool coriolis_coupling,
                          fullorder::InterfaceStressResult& result) {
  result.history.resize(static_cast<std::size_t>(evaluator.interfaceCount()));
  for (fullorder::InterfaceStressHistory& h : result.history)
    h.max_von_mises_pa.resize(static_cast<std::size_t>(drive.steps + 1));
  streamModalStressHistories(model, evaluator, drive, coriolis_coupling,
                             [&result](long first, const std::vector<std::vector<double>>& values) {
                               for (std::size_t i = 0; i < values.size(); ++i)
                                 std::copy(values[i].begin(), values[i].end(),
                                           result.history[i].max_von_mises_pa.begin() + first);
                             });
}

std::vector<double> modalStressPeaks(const ModalStressEvaluator& evaluator,
                                     const Eigen::MatrixXd& states,
                                     const std::vector<char>& no_polish, const ModalModel& model,
                                     const SampledDrive& drive, const Eigen::MatrixXd& eta,
                                     const Eigen::MatrixXd& eta_dot) {
  const std::vector<ModalStressEvaluator::Peak> found =
      findStressPeaks(evaluator, states, no_polish, model, drive, eta, eta_dot);
  std::vector<double> peaks;
  for (const ModalStressEvaluator::Peak& p : found) peaks.push_back(p.von_mises_pa);
  return peaks;
}

}  // namespace mastrom::rom
