// Whether the next time steps run on all the threads the user allows or on one.
//
// A step of the full order joins its threads several times: the element forces of a Newton
// iterate, the pipelined pair of states, the recovery beside a solve — each a few tens of µs of
// work. On idle cores a second thread makes a step up to 1.7× faster. On cores other processes
// also want, a thread that waits for its partner is descheduled and woken a scheduler slice
// later, at every join: measured on Scheme 3 beside a two-job compile, a 0.5 s deployment took
// 25.8 s on two threads against 6.4 s on one. The numbers do not depend on the thread count (bit
// for bit: docs/architecture.md, "Invariants that bit-identity rests on"), so the choice is free
// to follow the machine: the tuner times a few steps both ways now and then and keeps the faster,
// re-checking less often while its verdict stays the same (a doubling back-off, as TCP's
// retransmission timer: load changes slowly against a step).
//
// The decision reads wall time, so which steps ran on one thread varies from run to run; the
// results do not.
#pragma once

#include <chrono>
#include <vector>

namespace mastrom::fullorder {

struct ThreadTunerOptions {
  bool enabled = true;          ///< false: always the user's thread count
  int probe_steps = 16;         ///< steps timed in each mode per probe (their medians compared)
  long first_hold_steps = 256;  ///< steps in the chosen mode after a probe that changed the verdict
  long max_hold_steps = 4096;   ///< the hold doubles up to this while the verdict stays
  /// The user's thread count is kept unless one thread is faster by more than this factor: an
  /// idle machine measured noisily keeps its threads.
  double margin = 1.05;
};

class ThreadTuner {
 public:
  /// max_threads: what the user allows (1, or options.enabled false: the tuner answers it always).
  explicit ThreadTuner(int max_threads, ThreadTunerOptions options = {});

  /// Threads for the next step.
  int threads() const { return mode_one_ ? 1 : max_threads_; }
  /// The step just run (on threads()) took wall_s seconds of wall time.
  void record(double wall_s);

  /// Steps run on one thread while more were allowed.
  long singleThreadSteps() const { return single_thread_steps_; }

 private:
  enum class Phase { kProbeMany, kProbeOne, kHold };
  void decide();

  int max_threads_;
  ThreadTunerOptions options_;
  bool active_ = false;
  Phase phase_;
  bool mode_one_ = false;
  bool verdict_one_ = false;
  bool has_verdict_ = false;
  long hold_steps_ = 0;
  long left_ = 0;
  long single_thread_steps_ = 0;
  std::vector<double> many_s_, one_s_;
};

/// Times one step for a ThreadTuner and hands the steps their thread count: construct before
/// the step (it sets the count through `apply`), destroy after.
template <class Apply>
class TunedStep {
 public:
  TunedStep(ThreadTuner& tuner, Apply apply)
      : tuner_(tuner), start_(std::chrono::steady_clock::now()) {
    apply(tuner.threads());
  }
  ~TunedStep() {
    tuner_.record(std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
  }
  TunedStep(const TunedStep&) = delete;
  TunedStep& operator=(const TunedStep&) = delete;

 private:
  ThreadTuner& tuner_;
  std::chrono::steady_clock::time_point start_;
};

/// Puts a system's thread count back when the tuned loop ends, normally or by an exception (the
/// model outlives the run).
template <class System>
class ThreadCountRestorer {
 public:
  explicit ThreadCountRestorer(System& system) : system_(system), threads_(system.threadCount()) {}
  ~ThreadCountRestorer() { system_.setThreadCount(threads_); }
  ThreadCountRestorer(const ThreadCountRestorer&) = delete;
  ThreadCountRestorer& operator=(const ThreadCountRestorer&) = delete;

 private:
  System& system_;
  int threads_;
};

}  // namespace mastrom::fullorder
