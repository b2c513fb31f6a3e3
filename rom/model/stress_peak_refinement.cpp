// Stress peaks between the samples of a coarse grid (modal_stress_response.hpp, docs/theory.md
// §6.5 "Between samples"): whether the samples' polish can be trusted, and the O(1) screening bound
// per step that picks the steps IntervalRefiner (stress_interval_refiner.hpp) re-steps exactly.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "common/error.hpp"
#include "rom/model/modal_stress_response.hpp"
#include "rom/model/parabola_polish.hpp"
#include "rom/model/stress_interval_refiner.hpp"

namespace mastrom::rom {
namespace {

thread_local StressRefinementStats t_refine_stats;

/// The largest value of interface i's stress at the peak's station over [n − 1, n + 1] (sample
/// units, n the peak's sample) by successive parabolic interpolation on exact values of the
/// continuous response: the parabola through the three best points bracketing the maximum, its
/// vertex evaluated exactly (one exact step from the sample before it), until the vertex moves
/// less than 1e-6 of a step (a few rounds: the iteration converges superlinearly on a smooth
/// maximum). Only for a peak the samples' polish accepted: the samples n − 1, n, n + 1 are then
/// away from splits and jumps of θ̈, so both steps are ordinary and the response is smooth there.
void polishedPeakExactly(stress_detail::IntervalRefiner& refiner, const SampledDrive& drive,
                         const ModalSampleStates& states, int k, int i,
                         ModalStressEvaluator::Peak& peak) {
  const long n = peak.nearest_sample;
  if (peak.sample == static_cast<double>(n) || n < 1 || n + 1 > drive.steps) return;
  const auto exact = [&](double t) {
    const long m = std::min(static_cast<long>(std::floor(t)), drive.steps - 1);
    const auto [eta, eta_dot] = states.at(m);
    refiner.prepare(Eigen::Map<const Eigen::VectorXd>(eta, k),
                    Eigen::Map<const Eigen::VectorXd>(eta_dot, k), drive.startOf(m),
                    drive.endAt(m + 1), drive.step_s);
    return refiner.valueAt(i, peak.station, t - static_cast<double>(m));
  };
  double a = static_cast<double>(n - 1), b = static_cast<double>(n), c = static_cast<double>(n + 1);
  double fa = exact(a), fb = exact(b), fc = exact(c);
  if (!(fb >= fa && fb >= fc)) {  // another station's peak: keep the sample's value
    peak.von_mises_pa = peak.sample_von_mises_pa;
    peak.sample = b;
    return;
  }
  constexpr int kMaxRounds = 8;
  for (int round = 0; round < kMaxRounds; ++round) {
    double value = 0.0, offset = 0.0;
    if (!parabolaMaximum(fa, fb, fc, b - a, c - b, value, offset)) break;
    const double t = b + offset;
    if (!(t > a && t < c) || std::abs(offset) < 1e-6) break;
    const double ft = exact(t);
    if (t > b) {
      if (ft >= fb) a = b, fa = fb, b = t, fb = ft;
      else c = t, fc = ft;
    } else {
      if (ft >= fb) c = b, fc = fb, b = t, fb = ft;
      else a = t, fa = ft;
    }
  }
  peak.von_mises_pa = std::max(fb, peak.sample_von_mises_pa);
  peak.sample = b;
}

}  // namespace

double ModalSampleStates::stepBound(int, long n, long* block_end) const {
  *block_end = n + 1;
  return std::numeric_limits<double>::infinity();
}

bool stressPeaksNeedRefinement(const ModalStressEvaluator& evaluator, const ModalModel& model,
                               double step_s) {
  // Each mode's share of the stress, c_k|Γ_k|/ω_k² (its static deflection per unit θ̈, also the
  // scale of its ringing after a jump of θ̈), weighted by the polish error e(ω_k Δ) of its peaks.
  const int k = model.modeCount();
  for (int i = 0; i < evaluator.interfaceCount(); ++i) {
    double largest = 0.0, error = 0.0;
    for (int j = 0; j < k; ++j) {
      const double w = model.omega_rad_s[j];
      if (!(w > 0.0)) continue;
      const double share =
          evaluator.bound(i)[j] * std::abs(model.rotation_participation[j]) / (w * w);
      const double x = w * step_s;
      largest = std::max(largest, share);
      error += share * polishError(x);
    }
    if (error > kStressPolishTolerance * largest) return true;
  }
  return false;
}

StressRefinementStats lastStressRefinementStats() { return t_refine_stats; }

void refineStressPeaks(const ModalStressEvaluator& evaluator, const ModalModel& model,
                       const SampledDrive& drive, const Eigen::MatrixXd& eta,
                       const Eigen::MatrixXd& eta_dot,
                       std::vector<ModalStressEvaluator::Peak>& peaks) {
  MASTROM_REQUIRE(eta.cols() == drive.steps + 1 && eta_dot.cols() == drive.steps + 1 &&
                      eta.rows() == model.modeCount() && eta_dot.rows() == model.modeCount(),
                  InputError, "rom stresses: refinement inputs do not match the deployment");
  refineStressPeaks(evaluator, model, drive, RecordedModalStates(eta, eta_dot), peaks);
}

void refineStressPeaks(const ModalStressEvaluator& evaluator, const ModalModel& model,
                       const SampledDrive& drive, const ModalSampleStates& states,
                       std::vector<ModalStressEvaluator::Peak>& peaks) {
  t_refine_stats = {};
  MASTROM_REQUIRE(static_cast<int>(peaks.size()) == evaluator.interfaceCount(), InputError,
                  "rom stresses: refinement inputs do not match the deployment");
  const ModalStepping ms = prepareModalStepping(model, drive, false);
  stress_detail::IntervalRefiner refiner(evaluator, model, ms, t_refine_stats);
  const int interfaces = evaluator.interfaceCount();
  const int k = model.modeCount();
  const auto mapped = [k](const double* v) { return Eigen::Map<const Eigen::VectorXd>(v, k); };

  // The samples' parabola can overshoot the continuous response where they are this coarse (its
  // error e(ωΔ), parabola_polish.hpp, has either sign), and the re-stepping below only ever raises
  // a peak. So each polished peak restarts from the continuous response's own maximum near its
  // sample (polishedPeakExactly): never above the true peak.
  for (int i = 0; i < interfaces; ++i)
    polishedPeakExactly(refiner, drive, states, k, i, peaks[static_cast<std::size_t>(i)]);

  // An O(1) screening bound per step and interface (most steps need no O(modes) prepare()): with
  // the load scalars s ∈ {θ̈, θ̇², g_x, g_y} and the modes' coefficients γ_sj (−Γ, −Γ_c, L_x, L_y),
  //   quasi-static part ≤ Σ_s max|s| Q_s + Σ_s |ṡ| Qd_s,
  //     Q_s = Σ_j c_j|γ_sj|/ω_j²,  Qd_s = Σ_j c_j|γ_sj|(2ζ_j/ω_j + μ)/ω_j²,
  //   ringing part R: exact after a prepare(), then raised at each step boundary by the change of
  //     the particular solution, ≤ Σ_s |Δs| P_s + Σ_s |Δṡ| Pd_s,
  //     P_s = Σ_j c_j(1 + μω_j)|γ_sj|/ω_j²,  Pd_s = Σ_j c_j(1 + μω_j)|γ_sj|(1 + 2ζ_j)/ω_j³
  // (the free amplitude never grows inside a step). Only a step whose screening bound exceeds a
  // peak is prepared exactly.
  struct Sums {
    Eigen::Vector4d q, qd, p, pd;
  };
  std::vector<Sums> sums(static_cast<std::size_t>(interfaces));
  const double mu = evaluator.damping();
  for (int i = 0; i < interfaces; ++i) {
    Sums& su = sums[static_cast<std::size_t>(i)];
    su.q.setZero();
    su.qd.setZero();
    su.p.setZero();
    su.pd.setZero();
    const Eigen::VectorXd& c = evaluator.bound(i);
    for (int j = 0; j < k; ++j) {
      const double w = std::max(model.omega_rad_s[j], 1e-300), z = model.damping_ratio[j];
      const double coef[4] = {std::abs(model.rotation_participation[j]),
                              std::abs(model.centrifugal_participation[j]),
                              std::abs(model.momentum_participation(0, j)),
                              std::abs(model.momentum_participation(1, j))};
      for (int q = 0; q < 4; ++q) {
        su.q[q] += c[j] * coef[q] / (w * w);
        su.qd[q] += c[j] * coef[q] * (2.0 * z / w + mu) / (w * w);
        su.p[q] += c[j] * (1.0 + mu * w) * coef[q] / (w * w);
        su.pd[q] += c[j] * (1.0 + mu * w) * coef[q] * (1.0 + 2.0 * z) / (w * w * w);
      }
    }
  }
  const auto scalars = [](const stepping_detail::ForcingScalars& f) {
    return Eigen::Vector4d(f.acc, f.rate2, f.gx, f.gy);
  };
  std::vector<double> ringing(static_cast<std::size_t>(interfaces), 0.0);
  bool ringing_known = false;                   // R valid at the start of step n
  Eigen::Vector4d previous_end, previous_rate;  // s at the end of step n − 1, and its ṡ
  DriveInstant previous_d1;                     // the drive there
  bool have_previous = false;
  bool previous_exact = false;  // the last whole step was prepared exactly
  Eigen::VectorXd e, v;
  std::size_t next_split = 0;
  long bounded_until = 0;  // the steps before it lie in blocks whose bound was checked
  for (long n = 0; n < drive.steps; ++n) {
    if (n >= bounded_until) {
      // A block whose stress bound no interface's peak is below cannot raise a peak (every value
      // the steps below could find is at most the bound): skipped whole, and the ringing bound,
      // carried from step to step, is re-derived exactly after it.
      bool can_raise = false;
      long end = drive.steps;
      for (int i = 0; i < interfaces; ++i) {
        long block_end = n + 1;
        const double bound = states.stepBound(i, n, &block_end);
        end = std::min(end, block_end);
        can_raise = can_raise || bound > peaks[static_cast<std::size_t>(i)].von_mises_pa;
      }
      bounded_until = end;
      if (!can_raise) {
        while (next_split < drive.splits.size() && drive.splits[next_split].step < end)
          ++next_split;
        ringing_known = false;
        have_previous = false;
        previous_exact = false;
        n = end - 1;
        continue;
      }
    }
    if (next_split < drive.splits.size() && drive.splits[next_split].step == n) {
      const auto [eta_n, eta_dot_n] = states.at(n);
      e = mapped(eta_n);
      v = mapped(eta_dot_n);
      double start = static_cast<double>(n);
      for (const SampledDrive::Piece& piece : drive.splits[next_split].pieces) {
        refiner.prepare(e, v, piece.start, piece.end, piece.duration_s);
        for (int i = 0; i < interfaces; ++i)
          refiner.refine(i, start, drive.step_s, peaks[static_cast<std::size_t>(i)]);
        refiner.end(e, v);
        start += piece.duration_s / drive.step_s;
      }
      ++next_split;
      ringing_known = false;  // re-derived exactly at the next step
      continue;
    }
    const DriveInstant d0 = drive.startOf(n), d1 = drive.endAt(n + 1);
    // The scalars are a function of the drive instant: where the drive is continuous at t_n, those
    // of the step's start are the previous step's end.
    const bool continued = have_previous && stress_detail::sameDriveInstant(d0, previous_d1);
    const Eigen::Vector4d s0 =
        continued ? previous_end : scalars(stepping_detail::forcingScalars(ms, d0));
    const Eigen::Vector4d s1 = scalars(stepping_detail::forcingScalars(ms, d1));
    // Loads held constant across the boundary and over the step (a cruise at constant θ̇ without
    // gravity, the hold after the drive): no jump, no kink, so every interface's screening bound
    // is the previous step's, which passed — the same decision without recomputing it.
    if (ringing_known && !previous_exact && continued && s1 == s0 && previous_rate.isZero()) {
      previous_d1 = d1;
      continue;
    }
    const Eigen::Vector4d rate = (s1 - s0) / drive.step_s;
    if (ringing_known) {  // across the boundary t_n: the particular solution's change
      const Eigen::Vector4d jump = (s0 - previous_end).cwiseAbs(),
                            kink = (rate - previous_rate).cwiseAbs();
      for (int i = 0; i < interfaces; ++i)
        ringing[static_cast<std::size_t>(i)] += sums[static_cast<std::size_t>(i)].p.dot(jump) +
                                                sums[static_cast<std::size_t>(i)].pd.dot(kink);
    }
    bool exact = !ringing_known;
    previous_exact = false;
    const Eigen::Vector4d largest = s0.cwiseAbs().cwiseMax(s1.cwiseAbs());
    for (int i = 0; i < interfaces && !exact; ++i) {
      const Sums& su = sums[static_cast<std::size_t>(i)];
      const Eigen::VectorXd& c = evaluator.bound(i);
      const double screen = su.q.dot(largest) + su.qd.dot(rate.cwiseAbs()) +
                            ringing[static_cast<std::size_t>(i)] +
                            c.segment<kStressLoadCount>(k).dot(largest) + c[k + kStressLoadCount];
      exact = screen > peaks[static_cast<std::size_t>(i)].von_mises_pa;
    }
    if (exact) {
      const auto [eta_n, eta_dot_n] = states.at(n);
      refiner.prepare(mapped(eta_n), mapped(eta_dot_n), d0, d1, drive.step_s);
      for (int i = 0; i < interfaces; ++i) {
        ringing[static_cast<std::size_t>(i)] = refiner.ringingBound(i);
        refiner.refine(i, static_cast<double>(n), drive.step_s, peaks[static_cast<std::size_t>(i)]);
      }
      ringing_known = true;
      previous_exact = true;
    }
    previous_end = s1;
    previous_rate = rate;
    previous_d1 = d1;
    have_previous = true;
  }
}

std::vector<Eigen::VectorXd> stressPeakStates(
    const ModalStressEvaluator& evaluator, const ModalModel& model, const SampledDrive& drive,
    const Eigen::MatrixXd& eta, const Eigen::MatrixXd& eta_dot,
    const std::vector<ModalStressEvaluator::Peak>& peaks) {
  MASTROM_REQUIRE(eta.cols() == drive.steps + 1 && eta_dot.cols() == drive.steps + 1 &&
                      eta.rows() == model.modeCount() && eta_dot.rows() == model.modeCount(),
                  InputError, "rom stresses: peak-state inputs do not match the deployment");
  return stressPeakStates(evaluator, model, drive, RecordedModalStates(eta, eta_dot), peaks);
}

std::vector<Eigen::VectorXd> stressPeakStates(
    const ModalStressEvaluator& evaluator, const ModalModel& model, const SampledDrive& drive,
    const ModalSampleStates& sample_states, const std::vector<ModalStressEvaluator::Peak>& peaks) {
  const int k = model.modeCount();
  const ModalStepping ms = prepareModalStepping(model, drive, false);
  StressRefinementStats unused;
  stress_detail::IntervalRefiner refiner(evaluator, model, ms, unused);
  std::vector<Eigen::VectorXd> states;
  for (const ModalStressEvaluator::Peak& pk : peaks) {
    Eigen::VectorXd x(evaluator.inputSize());
    const long m = std::clamp(static_cast<long>(std::floor(pk.sample)), 0L, drive.steps - 1);
    const auto [eta_m, eta_dot_m] = sample_states.at(m);
    const Eigen::Map<const Eigen::VectorXd> eta(eta_m, k), eta_dot(eta_dot_m, k);
    // Time into step m [s], then through the pieces of a split step to the one holding the peak.
    double into_s = std::clamp(pk.sample - static_cast<double>(m), 0.0, 1.0) * drive.step_s;
    const auto split = std::find_if(drive.splits.begin(), drive.splits.end(),
                                    [m](const SampledDrive::Split& s) { return s.step == m; });
    if (split == drive.splits.end()) {
      refiner.prepare(eta, eta_dot, drive.startOf(m), drive.endAt(m + 1), drive.step_s);
      refiner.stateAt(into_s / drive.step_s, x);
    } else {
      Eigen::VectorXd e = eta, v = eta_dot;
      for (std::size_t p = 0; p < split->pieces.size(); ++p) {
        const SampledDrive::Piece& piece = split->pieces[p];
        refiner.prepare(e, v, piece.start, piece.end, piece.duration_s);
        if (into_s <= piece.duration_s || p + 1 == split->pieces.size()) {
          refiner.stateAt(std::min(into_s / piece.duration_s, 1.0), x);
          break;
        }
        refiner.end(e, v);
        into_s -= piece.duration_s;
      }
    }
    states.push_back(std::move(x));
  }
  return states;
}

}  // namespace mastrom::rom
