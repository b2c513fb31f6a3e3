// Two pieces of work at once, one on the calling thread and one on a second OpenMP thread — the
// building block of the pipelined time step (GeneralizedAlpha overlaps a Newton solve
// with the previous output's index-1 recovery, and evaluates the Newton iterate together with the
// next step's predictor, EliminatedSystem::evaluatePair).
//
// The second piece always runs on thread 1 of the OpenMP team, i.e. the same pool thread from call
// to call, so the data it works on stays in that core's cache. Without OpenMP, inside an active
// parallel region, or when `parallel` is false, both run on the calling thread, first then
// second. Both always run to completion; an exception of the first is rethrown, else one of the
// second.
#pragma once

#include <exception>

#if MASTROM_HAVE_OPENMP
#include <omp.h>
#endif

namespace mastrom::fullorder {

template <class First, class Second>
void runOnTwoThreads(First&& first, Second&& second, bool parallel) {
  std::exception_ptr failure[2];
  const auto guarded = [&failure](int k, auto& work) {
    try {
      work();
    } catch (...) {
      failure[k] = std::current_exception();
    }
  };
  bool done = false;
#if MASTROM_HAVE_OPENMP
  if (parallel && omp_get_level() == 0) {
#pragma omp parallel num_threads(2)
    {
      const int threads = omp_get_num_threads(), id = omp_get_thread_num();
      if (id == 0) {
        guarded(0, first);
        if (threads < 2) guarded(1, second);  // the runtime gave one thread only
      } else if (id == 1) {
        guarded(1, second);
      }
    }
    done = true;
  }
#else
  (void)parallel;
#endif
  if (!done) {
    guarded(0, first);
    guarded(1, second);
  }
  if (failure[0]) std::rethrow_exception(failure[0]);
  if (failure[1]) std::rethrow_exception(failure[1]);
}

}  // namespace mastrom::fullorder
