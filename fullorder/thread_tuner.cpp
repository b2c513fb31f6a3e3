#include "fullorder/thread_tuner.hpp"

#include <algorithm>

#include "common/error.hpp"

namespace mastrom::fullorder {

namespace {
/// The median of a few step times: one step that refactorised (≈ 50 ordinary steps of work) or
/// was interrupted must not decide.
double median(std::vector<double>& values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}
}  // namespace

ThreadTuner::ThreadTuner(int max_threads, ThreadTunerOptions options)
    : max_threads_(max_threads), options_(options) {
  MASTROM_REQUIRE(max_threads >= 1, InputError, "threads = ", max_threads, " must be >= 1");
  MASTROM_REQUIRE(options_.probe_steps >= 1 && options_.first_hold_steps >= 1 &&
                      options_.max_hold_steps >= options_.first_hold_steps &&
                      options_.margin >= 1.0,
                  InputError, "thread tuner: probe_steps, hold steps >= 1 and margin >= 1");
  hold_steps_ = options_.first_hold_steps;
  active_ = max_threads_ > 1 && options_.enabled;
  phase_ = active_ ? Phase::kProbeMany : Phase::kHold;
  left_ = active_ ? options_.probe_steps : 0;
}

void ThreadTuner::record(double wall_s) {
  if (!active_) return;
  if (mode_one_) ++single_thread_steps_;
  switch (phase_) {
    case Phase::kProbeMany:
      many_s_.push_back(wall_s);
      if (--left_ == 0) {
        phase_ = Phase::kProbeOne;
        mode_one_ = true;
        left_ = options_.probe_steps;
      }
      break;
    case Phase::kProbeOne:
      one_s_.push_back(wall_s);
      if (--left_ == 0) decide();
      break;
    case Phase::kHold:
      if (--left_ <= 0) {
        phase_ = Phase::kProbeMany;
        mode_one_ = false;
        left_ = options_.probe_steps;
      }
      break;
  }
}

void ThreadTuner::decide() {
  const bool one = median(one_s_) * options_.margin < median(many_s_);
  many_s_.clear();
  one_s_.clear();
  // The same verdict again: the machine's state holds, probe half as often (each probe spends
  // probe_steps in the slower mode).
  hold_steps_ = has_verdict_ && one == verdict_one_
                    ? std::min(2 * hold_steps_, options_.max_hold_steps)
                    : options_.first_hold_steps;
  verdict_one_ = one;
  has_verdict_ = true;
  mode_one_ = one;
  phase_ = Phase::kHold;
  left_ = hold_steps_;
}

}  // namespace mastrom::fullorder
