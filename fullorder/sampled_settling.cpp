#include "fullorder/sampled_settling.hpp"

#include <algorithm>
#include <cmath>

namespace mastrom::fullorder {

void SampledSettling::add(double t, double r) {
  if (count_ == 0) {
    first_t_ = t;
  } else {
    square_integral_ += 0.5 * (last_r_ * last_r_ + r * r) * (t - last_t_);
  }
  if (std::abs(r) > band_) {
    any_outside_ = true;
    have_after_ = false;
    outside_t_ = t;
    outside_r_ = r;
  } else if (any_outside_ && !have_after_) {
    have_after_ = true;
    after_t_ = t;
    after_r_ = r;
  }
  last_t_ = t;
  last_r_ = r;
  ++count_;
}

double SampledSettling::rms(double square_integral) const {
  return count_ == 1 ? std::abs(last_r_) : std::sqrt(square_integral / (last_t_ - first_t_));
}

SampledSettling::Settling SampledSettling::settling(double drive_end_s) const {
  if (!any_outside_) return {true, drive_end_s};
  if (!have_after_) return {false, last_t_};
  // Fraction of (t_out, t_after] at which r, linear between the two samples, returns to the band
  // edge on the side of r_out: |r_out| > b ≥ |r_after| puts it in (0, 1].
  const double side = outside_r_ > 0.0 ? 1.0 : -1.0;
  const double fraction = (std::abs(outside_r_) - band_) / (std::abs(outside_r_) - side * after_r_);
  return {true, std::max(drive_end_s, outside_t_ + fraction * (after_t_ - outside_t_))};
}

}  // namespace mastrom::fullorder
