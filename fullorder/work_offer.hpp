// A PairRunner between two threads that are already running (docs/theory.md §5.6): one thread
// offers a piece of work while it does its own; the other, once done with its own task, serves —
// takes what is offered, runs it, and waits for the next offer — until the offering thread
// closes the offers. An offer nobody has taken when the offering thread is done with its own part
// is withdrawn and never runs, so neither thread waits for the other unless the work is under way.
//
// The speculative adaptive step uses it: the judging thread, once it has recovered, judged and
// recorded the step before, evaluates the next step's predicted state beside the last Newton
// evaluation of the speculative one (the pipelined evaluation of GeneralizedAlpha).
//
// Waiting is a bounded spin that yields the core between looks (std::this_thread::yield), so a
// serving thread costs little when another process needs the core; it lasts at most until the
// offering thread closes, i.e. one time step.
#pragma once

#include <atomic>
#include <exception>
#include <functional>
#include <thread>

#include "fullorder/dae_system.hpp"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace mastrom::fullorder {

class WorkOffer final : public PairRunner {
public:
  /// Ready for a new round (no offer, nobody serving).
  void open() {
    state_.store(kIdle, std::memory_order_relaxed);
    serving_.store(false, std::memory_order_relaxed);
  }

  bool secondThreadFree() const override { return serving_.load(std::memory_order_acquire); }

  /// The offering thread: `first` here, `second` offered meanwhile. An exception of `first` is
  /// rethrown after an offer under way has finished; `second` must not throw.
  bool run(const std::function<void()>& first, const std::function<void()>& second) override {
    work_ = &second;
    state_.store(kOffered, std::memory_order_release);
    std::exception_ptr failure;
    try {
      first();
    } catch (...) {
      failure = std::current_exception();
    }
    int expected = kOffered;
    bool ran = false;
    if (!state_.compare_exchange_strong(expected, kIdle, std::memory_order_acq_rel)) {
      waitFor(kDone);  // taken: it is running on the other thread
      state_.store(kIdle, std::memory_order_relaxed);
      ran = true;
    }
    if (failure) std::rethrow_exception(failure);
    return ran;
  }

  /// The serving thread, after its own task: run the offers until close().
  void serve() {
    serving_.store(true, std::memory_order_release);
    for (unsigned looks = 0;; ++looks) {
      int s = state_.load(std::memory_order_acquire);
      if (s == kClosed) break;
      if (s == kOffered && state_.compare_exchange_strong(s, kTaken, std::memory_order_acq_rel)) {
        (*work_)();
        state_.store(kDone, std::memory_order_release);
        looks = 0;
        continue;
      }
      pause(looks);
    }
    serving_.store(false, std::memory_order_relaxed);
  }

  /// The offering thread, with no offer outstanding: the serving thread stops serving.
  void close() { state_.store(kClosed, std::memory_order_release); }

private:
  enum : int { kIdle, kOffered, kTaken, kDone, kClosed };

  void waitFor(int wanted) const {
    for (unsigned looks = 0; state_.load(std::memory_order_acquire) != wanted; ++looks)
      pause(looks);
  }
  /// A few CPU pauses between the first looks, then the core is yielded between looks.
  static void pause(unsigned looks) {
    if (looks < 64) {
#if defined(__x86_64__) || defined(__i386__)
      _mm_pause();
#endif
    } else {
      std::this_thread::yield();
    }
  }

  std::atomic<int> state_{kIdle};
  std::atomic<bool> serving_{false};
  const std::function<void()>* work_ = nullptr;
};

}  // namespace mastrom::fullorder
