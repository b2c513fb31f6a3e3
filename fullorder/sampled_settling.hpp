// The part of the deployment metrics that follows r, the relative end angular acceleration, from
// sample to sample (DeploymentMetrics, docs/theory.md §1): the time-weighted RMS by the trapezoidal
// rule on r² and the settling time from the last sample outside the band. The full order's
// MetricsAccumulator and the ROM's metrics (rom/model/deployment_metrics.cpp) both reduce their
// samples with it, so the two definitions cannot drift apart.
#pragma once

#include <cstddef>

namespace mastrom::fullorder {

class SampledSettling {
public:
  /// band: the settling band b [rad/s²], finite and > 0 (the callers check it).
  explicit SampledSettling(double band_rad_s2) : band_(band_rad_s2) {}

  /// The next sample r [rad/s²] at t [s]; t must exceed the previous one (the callers check it).
  void add(double time_s, double relative_rad_s2);

  std::size_t count() const { return count_; }
  double firstTime() const { return first_t_; }
  double lastTime() const { return last_t_; }
  double lastValue() const { return last_r_; }

  /// ∫ r² dt over the samples by the trapezoidal rule [rad²/s³].
  double trapezoidalSquareIntegral() const { return square_integral_; }
  /// The RMS over the record for a given ∫ r² dt (the samples' own, or an exact one of the
  /// continuous response): |r| of a single sample, else sqrt(∫ r² dt / (t_last − t_first)).
  double rms(double square_integral) const;

  struct Settling {
    bool settled = false;
    double time_s = 0.0;
  };
  /// The settling verdict for a drive ending at t_d ≤ the last sample: settled at t_d when no
  /// sample left the band, not settled (time = the record's end) when the last sample is outside,
  /// else where r, linear between the last sample outside and the next, re-enters the band
  /// (never before t_d).
  Settling settling(double drive_end_time_s) const;

private:
  double band_;
  std::size_t count_ = 0;
  double first_t_ = 0.0, last_t_ = 0.0, last_r_ = 0.0;
  double square_integral_ = 0.0;
  // The last sample outside the band and the one after it.
  bool any_outside_ = false, have_after_ = false;
  double outside_t_ = 0.0, outside_r_ = 0.0, after_t_ = 0.0, after_r_ = 0.0;
};

}  // namespace mastrom::fullorder
