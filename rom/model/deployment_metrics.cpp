// The metrics of a ROM deployment while stepping (see the header): the running reductions of
// computeMetrics' definitions over the output samples; the continuous peaks between samples are
// peak_refinement.cpp's, the output formulas deployment_outputs.hpp's.
#include "rom/model/deployment_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <memory>

#include "common/error.hpp"
#include "fullorder/sampled_settling.hpp"
#include "rom/model/deployment_outputs.hpp"
#include "rom/model/peak_refinement.hpp"
#include "rom/model/quiet_blocks.hpp"
#include "rom/model/settling_refinement.hpp"
#include "rom/model/square_integral.hpp"

namespace mastrom::rom {

using metrics_detail::OutputEvaluator;
using metrics_detail::Outputs;
using metrics_detail::PeakRefiner;
using metrics_detail::QuietBlockBound;
using metrics_detail::SettlingRefiner;


fullorder::DeploymentMetrics modalDeploymentMetrics(const ModalModel& m,
                                                    const fullorder::DriveLaw& drive,
                                                    const ModalDeploymentOptions& options,
                                                    double drive_end_time_s, double band,
                                                    PeakResolution peaks) {
  return modalDeploymentMetrics(m, sampleDrive(drive, options), options.coriolis_coupling,
                                drive_end_time_s, band, peaks);
}

fullorder::DeploymentMetrics modalDeploymentMetrics(const ModalModel& m, const SampledDrive& drive,
                                                    bool coriolis_coupling, double drive_end_time_s,
                                                    double band, PeakResolution peaks,
                                                    const ModalSampleObserver* observer,
                                                    const ModalBlockObserver* block_observer) {
  MASTROM_REQUIRE(std::isfinite(band) && band > 0.0, InputError, "settling band = ", band,
                  " rad/s^2; allowed: finite and > 0");
  MASTROM_REQUIRE(std::isfinite(drive_end_time_s), InputError,
                  "drive end time = ", drive_end_time_s, " s; allowed: finite");
  const ModalStepping ms = prepareModalStepping(m, drive, coriolis_coupling);
  const OutputEvaluator eval(m, ms);
  metrics_detail::threadPeakRefinementStats() = {};
  std::unique_ptr<PeakRefiner> refiner;
  std::unique_ptr<SettlingRefiner> settling;
  if (peaks == PeakResolution::Continuous) {
    refiner = std::make_unique<PeakRefiner>(m, ms, drive, eval, drive_end_time_s, band);
    settling = std::make_unique<SettlingRefiner>(m, ms, drive, drive_end_time_s, band);
  }
  // The RMS of the continuous response (exact ∫r², docs/theory.md §4.2a) where it applies; the
  // samples' trapezoidal rule with PeakResolution::Samples (computeMetrics' definition) or for an
  // undamped mode or the Coriolis coupling.
  std::unique_ptr<SquareIntegral> square;
  if (peaks == PeakResolution::Continuous && SquareIntegral::supported(m, ms))
    square = std::make_unique<SquareIntegral>(m, ms);
  // Quiet blocks (docs/theory.md §4.2c, quiet_blocks.hpp): where the exact RMS and the bounds of
  // the peaks apply, a block of steps whose output bounds stay below the running maxima is stepped
  // without evaluating its outputs (only r, for the settling time's samples).
  std::unique_ptr<QuietBlockBound> blocks;
  if (square && QuietBlockBound::supported(m, ms) && metrics_detail::quietBlocksEnabled())
    blocks = std::make_unique<QuietBlockBound>(m, ms, drive);
  if (blocks && block_observer) blocks->keepStateBounds();
  const Eigen::VectorXd psi_z = m.end_rotation.row(2).transpose();
  long evaluated_until = -1;  // samples n ≤ this, and steps n < this, are evaluated
  double square_integral = 0.0;
  stepping_detail::ForcingScalars last_end;  // of the last whole step, for the next one's start
  long last_whole = -2;
  fullorder::DeploymentMetrics out;
  out.drive_end_time = drive_end_time_s;
  out.settling_band = band;
  // The samples' RMS and settling bookkeeping: computeMetrics' definitions, the same code.
  fullorder::SampledSettling history(band);
  runModalStepping(
      m, ms, drive,
      [&](long n, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
          const Eigen::VectorXd& eta_ddot) {
        const double t = static_cast<double>(n) * drive.step_s;
        if (n % metrics_detail::kQuietBlockSteps != 0 || n >= drive.steps) {
          // not a block's first sample
        } else if (blocks) {
          const long last = std::min(n + metrics_detail::kQuietBlockSteps, drive.steps);
          metrics_detail::OutputBounds b;
          const PeakRefiner::RunningPeaks p = refiner->running(out);
          const double slack = refiner->relSlack();
          const bool bounded =
              blocks->bound(n / metrics_detail::kQuietBlockSteps, eta.data(), eta_dot.data(), b);
          const bool quiet = bounded && b.rel_acc <= p.rel_acc + slack &&
                             b.abs_acc <= p.abs_acc + slack && b.force <= p.force &&
                             b.torque <= p.torque &&
                             (static_cast<double>(last) * drive.step_s < drive_end_time_s ||
                              b.rel_acc <= p.residual + slack);
          if (quiet) {
            metrics_detail::threadPeakRefinementStats().quiet_steps += last - n;
          } else {
            evaluated_until = last;
          }
          if (block_observer) {
            const ModalStateBounds state = blocks->stateBounds();
            (*block_observer)(n / metrics_detail::kQuietBlockSteps, eta, eta_dot,
                              bounded ? &state : nullptr);
          }
        } else if (block_observer) {
          (*block_observer)(n / metrics_detail::kQuietBlockSteps, eta, eta_dot, nullptr);
        }
        if (blocks && n > evaluated_until) {  // a quiet sample: r for the settling time only
          if (square) {
            if (n == 0) square->start(eta, eta_dot);
            if (n == drive.steps) square_integral = square->finish(eta, eta_dot);
          }
          if (observer)
            (*observer)(n, eta, eta_dot, stepping_detail::forcingScalars(ms, drive.valueAt(n)));
          // The settling time depends on the samples from the last one before t_d on only (an
          // exit from the band earlier re-enters by t_d: t_s = t_d either way), and the
          // settling's refinement on the steps that end after t_d.
          if (history.count() > 0 && static_cast<double>(n + 1) * drive.step_s <= drive_end_time_s)
            return;
          const double r = psi_z.dot(eta_ddot);
          MASTROM_REQUIRE(std::isfinite(r), NumericalError,
                          "rom deployment metrics: non-finite output at t = ", t, " s");
          history.add(t, r);
          if (settling) settling->afterSample(n, r);
          return;
        }
        const SampledDrive::Sample& d = drive.samples[static_cast<std::size_t>(n)];
        double c = 1.0, s = 0.0;
        if (ms.gravity) ms.rotation(d.sin_angle, d.cos_angle, c, s);
        const Outputs o =
            eval.at(eta, eta_dot, eta_ddot, d.rate_rad_s, d.acceleration_rad_s2, c, s);
        const double r = o.rel_acc;
        MASTROM_REQUIRE(std::isfinite(r) && std::isfinite(o.force) && std::isfinite(o.torque),
                        NumericalError, "rom deployment metrics: non-finite output at t = ", t,
                        " s");
        out.peak_abs_end_angular_acceleration =
            std::max(out.peak_abs_end_angular_acceleration, o.abs_acc);
        out.peak_rel_end_angular_acceleration =
            std::max(out.peak_rel_end_angular_acceleration, std::abs(r));
        out.peak_joint_force = std::max(out.peak_joint_force, o.force);
        out.peak_drive_torque = std::max(out.peak_drive_torque, o.torque);
        if (t >= drive_end_time_s) {
          out.residual_rel_end_angular_acceleration =
              std::max(out.residual_rel_end_angular_acceleration, std::abs(r));
        }
        if (square) {
          if (n == 0) square->start(eta, eta_dot);
          if (n == drive.steps) square_integral = square->finish(eta, eta_dot);
        }
        history.add(t, r);
        if (refiner) refiner->afterSample(n, o, out);
        if (settling) settling->afterSample(n, r);
        if (observer)
          (*observer)(n, eta, eta_dot, stepping_detail::forcingScalars(ms, drive.valueAt(n)));
      },
      [&](long n, int piece, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
          const Eigen::ArrayXd& f_start, const Eigen::ArrayXd& f_end) {
        if (refiner && (!blocks || n < evaluated_until))
          refiner->beforeStep(n, piece, eta, eta_dot, f_start, f_end);
        if (settling && static_cast<double>(n + 1) * drive.step_s > drive_end_time_s)
          settling->beforeStep(n, piece, eta, eta_dot, f_start, f_end);
        if (square) {
          if (piece < 0) {
            // The end scalars of step n − 1 serve as the start of step n where the drive is
            // continuous at t_n (one forcing evaluation per step).
            const DriveInstant start = drive.startOf(n), left = drive.endAt(n);
            const bool continued = last_whole == n - 1 &&
                                   start.rate_rad_s == left.rate_rad_s &&
                                   start.acceleration_rad_s2 == left.acceleration_rad_s2;
            const stepping_detail::ForcingScalars s0 =
                continued ? last_end : stepping_detail::forcingScalars(ms, start);
            last_end = stepping_detail::forcingScalars(ms, drive.endAt(n + 1));
            last_whole = n;
            square->piece(drive.step_s, s0, last_end, eta, eta_dot);
          } else {
            const SampledDrive::Piece& p = drive.splitAt(n).pieces[static_cast<std::size_t>(piece)];
            square->piece(p.duration_s, stepping_detail::forcingScalars(ms, p.start),
                          stepping_detail::forcingScalars(ms, p.end), eta, eta_dot);
          }
        }
      });
  MASTROM_REQUIRE(history.lastTime() >= drive_end_time_s, InputError,
                  "the record ends at t = ", history.lastTime(), " s, before the drive ends at ",
                  drive_end_time_s,
                  " s: no residual vibration to measure (make simulation.end_time >= "
                  "drive.duration)");
  if (refiner) refiner->finish(out);
  // The exact ∫r² of the continuous response where it applies, ≥ 0 up to round-off.
  const double integral =
      square ? std::max(0.0, square_integral) : history.trapezoidalSquareIntegral();
  out.rms_rel_end_angular_acceleration = history.rms(integral);
  const fullorder::SampledSettling::Settling sampled = history.settling(drive_end_time_s);
  out.settled = sampled.settled;
  out.settling_time = sampled.time_s;
  if (settling) settling->finish(out);  // between the samples (settling_refinement.hpp)
  return out;
}

double peakRelativeEndAcceleration(const ModalModel& m, const fullorder::DriveLaw& drive,
                                   const ModalDeploymentOptions& options) {
  const SampledDrive sampled = sampleDrive(drive, options);
  const ModalStepping ms = prepareModalStepping(m, sampled, options.coriolis_coupling);
  const Eigen::VectorXd psi_z = m.end_rotation.row(2).transpose();
  double peak = 0.0;
  runModalStepping(
      m, ms, sampled,
      [&](long, const Eigen::VectorXd&, const Eigen::VectorXd&, const Eigen::VectorXd& eta_ddot) {
        peak = std::max(peak, std::abs(psi_z.dot(eta_ddot)));
      });
  return peak;
}

}  // namespace mastrom::rom
