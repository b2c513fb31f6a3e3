// Scoped SLEPc (and PETSc, and MPI) initialisation, shareable by the CLI, the tests and library
// code without exposing PETSc headers. Create one SlepcSession near the top of main() and keep it
// for the life of the process: MPI cannot be initialised again once finalised.
#pragma once

namespace mastrom::modes {

class SlepcSession {
public:
  /// Initialises SLEPc (hence PETSc, hence MPI) unless already initialised; argc/argv, if given,
  /// are scanned for PETSc/SLEPc options (-eps_view, -st_pc_factor_mat_solver_type …). Also
  /// installs an error handler that records PETSc's message instead of printing its multi-kilobyte
  /// banner (the checked calls of modes/petsc_wrap.hpp put that message into the exception). Throws
  /// NumericalError if initialisation fails.
  explicit SlepcSession(int* argc = nullptr, char*** argv = nullptr);
  /// Removes the error handler; finalises SLEPc only if this object initialised it.
  ~SlepcSession();
  SlepcSession(const SlepcSession&) = delete;
  SlepcSession& operator=(const SlepcSession&) = delete;

  /// True if SLEPc is initialised and not yet finalised in this process.
  static bool active();

private:
  bool owns_ = false;
  bool pushed_handler_ = false;
};

}  // namespace mastrom::modes
