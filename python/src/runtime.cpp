#include "python/src/runtime.hpp"

#include <memory>

#include "modes/slepc_session.hpp"

namespace py = pybind11;

namespace mastrom::python {

PythonPoller::PythonPoller(py::object callback, double interval_s)
    : callback_(std::move(callback)),
      interval_(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
          std::chrono::duration<double>(interval_s))),
      last_(std::chrono::steady_clock::now()) {}

void PythonPoller::rethrowIfAborted() {
  if (error_) {
    std::exception_ptr e = error_;
    error_ = nullptr;
    std::rethrow_exception(e);
  }
}

namespace {
std::mutex slepc_mutex;
std::unique_ptr<modes::SlepcSession> slepc_session;  // guarded by slepc_mutex
}  // namespace

std::unique_lock<std::mutex> lockEigenSolvers(bool initialize_slepc) {
  std::unique_lock<std::mutex> lock(slepc_mutex);
  if (initialize_slepc && !slepc_session) {
    slepc_session = std::make_unique<modes::SlepcSession>();
    // Finalise before the interpreter tears down; MPI cannot be initialised again afterwards,
    // which is why the session lives until exit rather than per call.
    py::gil_scoped_acquire gil;
    py::module_::import("atexit").attr("register")(py::cpp_function([] {
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> guard(slepc_mutex);
      slepc_session.reset();
    }));
  }
  return lock;
}

}  // namespace mastrom::python
