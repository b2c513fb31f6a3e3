// The scalar metrics of a deployment (fullorder/deployment_result.hpp DeploymentMetrics) gathered
// sample by sample, so that a run streaming its outputs to a file (fullorder/result_stream.hpp)
// needs no series in memory. computeMetrics() of a whole series is this accumulator fed with every
// sample: the two give the same numbers bit for bit (same operations in the same order).
#pragma once

#include <cstddef>

#include "fullorder/deployment_result.hpp"
#include "fullorder/sampled_settling.hpp"

namespace mastrom::fullorder {

class MetricsAccumulator {
public:
  /// InputError when the band is not finite and > 0 or the drive end time is not finite.
  MetricsAccumulator(double drive_end_time_s,
                     double settling_band_rad_s2 = kDefaultSettlingBandRadS2);

  /// The next output instant: time t [s], relative end angular acceleration r, the Z component of
  /// the end angular acceleration, the joint force's norm and the drive torque. NumericalError
  /// naming the value and the time when one is not finite; UsageError when t does not exceed the
  /// previous time.
  void add(double time_s, double relative_rad_s2, double absolute_z_rad_s2, double joint_force_n,
           double drive_torque_nm);
  void add(const DeploymentSample& sample);

  std::size_t count() const { return history_.count(); }
  /// The metrics of the samples so far (DeploymentMetrics says how each is defined); UsageError
  /// when there are none.
  DeploymentMetrics metrics() const;

private:
  double drive_end_s_, band_;
  double peak_abs_ = 0.0, peak_rel_ = 0.0, peak_force_ = 0.0, peak_torque_ = 0.0;
  double residual_ = 0.0;
  SampledSettling history_;  ///< RMS and settling (trapezoidal ∫r², the band's last exit)
};

}  // namespace mastrom::fullorder
