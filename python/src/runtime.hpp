// What the long calls of the module share: releasing the GIL while C++ works, a periodic return to
// Python while it does (so Ctrl-C and a progress callback work), and SLEPc, which a process
// initialises once and which is not thread-safe.
#pragma once

#include <pybind11/pybind11.h>

#include <chrono>
#include <exception>
#include <mutex>

namespace mastrom::python {

/// Held while the GIL is released: takes the GIL back at most every `interval_s` of wall time to
/// check for signals (KeyboardInterrupt) and to call the user's progress callback. A Python
/// exception raised there stops the C++ work (poll() throws Aborted) and is re-raised by
/// rethrowIfAborted() once the GIL is held again.
class PythonPoller {
public:
  /// An exception type of our own, so that the library's handlers never mistake it for theirs.
  struct Aborted {};

  explicit PythonPoller(pybind11::object callback = pybind11::none(), double interval_s = 0.2);

  /// Call from the C++ side without the GIL. `args` are passed to the callback.
  template <typename... Args>
  void poll(bool final, Args... args) {
    const auto now = std::chrono::steady_clock::now();
    if (!final && now - last_ < interval_) return;
    last_ = now;
    pybind11::gil_scoped_acquire gil;
    try {
      if (PyErr_CheckSignals() != 0) throw pybind11::error_already_set();
      if (!callback_.is_none()) callback_(args...);
    } catch (pybind11::error_already_set&) {
      error_ = std::current_exception();
      throw Aborted{};
    }
  }

  /// With the GIL held: raise the Python exception that aborted the work, if any.
  void rethrowIfAborted();

private:
  pybind11::object callback_;
  std::chrono::steady_clock::duration interval_;
  std::chrono::steady_clock::time_point last_;
  std::exception_ptr error_;
};

/// The lock that serialises the eigen-solvers in this process (PETSc and ARPACK keep global state
/// and are not thread-safe); hold it for the whole call, after releasing the GIL. With
/// `initialize_slepc`, SLEPc (hence PETSc and MPI) is initialised on first use, once per process,
/// and finalised at interpreter exit.
std::unique_lock<std::mutex> lockEigenSolvers(bool initialize_slepc);

}  // namespace mastrom::python
