// PETSc/SLEPc wrapped once: the checked-call macro that turns a PETSc
// error code into a NumericalError carrying PETSc's own one-line message, RAII owners of PETSc
// objects, the Eigen → PETSc matrix conversion and the gather of a distributed vector. Together
// with the SLEPc backend this is the only place raw PETSc appears; code outside modes/ that just
// needs SLEPc running includes modes/slepc_session.hpp instead.
#pragma once

#include <petscmat.h>
#include <petscvec.h>
#include <slepceps.h>

#include <utility>

#include "modes/eigen_solver.hpp"
#include "modes/slepc_session.hpp"

namespace mastrom::modes::petsc {

/// Throws NumericalError("PETSc error <code> in <call> (<file>:<line>): <PETSc's message>") if code
/// ≠ 0.
void check(PetscErrorCode code, const char* call, const char* file, int line);

/// Scope in which PETSc errors are recorded for check() instead of printed (pushes the handler,
/// pops it on exit). SlepcSession installs one for the whole session; backends add their own so
/// that they stay quiet whoever initialised PETSc.
class QuietErrors {
public:
  QuietErrors();
  ~QuietErrors();
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;
};

/// Unique owner of a PETSc object handle (Mat, Vec, EPS, VecScatter, …); destroys it with Destroy.
/// Must not outlive PETSc itself (keep owners inside the scope of a SlepcSession).
template <typename Handle, PetscErrorCode (*Destroy)(Handle*)>
class Owner {
public:
  Owner() = default;
  explicit Owner(Handle handle) : handle_(handle) {}
  ~Owner() { reset(); }
  Owner(const Owner&) = delete;
  Owner& operator=(const Owner&) = delete;
  Owner(Owner&& other) noexcept : handle_(std::exchange(other.handle_, nullptr)) {}
  Owner& operator=(Owner&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, nullptr);
    }
    return *this;
  }

  Handle get() const { return handle_; }
  /// Address for a PETSc XxxCreate(…, &handle) call; releases what was held before.
  Handle* out() {
    reset();
    return &handle_;
  }
  void reset() {
    if (handle_ != nullptr) static_cast<void>(Destroy(&handle_));  // destructors cannot throw
    handle_ = nullptr;
  }

private:
  Handle handle_ = nullptr;
};

using MatOwner = Owner<Mat, MatDestroy>;
using VecOwner = Owner<Vec, VecDestroy>;
using EpsOwner = Owner<EPS, EPSDestroy>;
using ScatterOwner = Owner<VecScatter, VecScatterDestroy>;

/// Distributed AIJ matrix (MPIAIJ on several ranks, SeqAIJ on one) equal to `a`, with PETSc's
/// default row ownership (PetscSplitOwnership). Every rank passes the same full matrix and inserts
/// only the rows it owns; preallocation is exact, counted from the Eigen structure (explicitly
/// stored zeros are kept). Collective on comm.
MatOwner toPetscMatrix(const SparseMatrix& a, MPI_Comm comm);

/// Copies distributed vectors (all with the layout of the one given to the constructor) into a full
/// Eigen vector on every rank (VecScatterCreateToAll). Collective.
class AllGather {
public:
  explicit AllGather(Vec layout);
  Eigen::VectorXd operator()(Vec v);

private:
  ScatterOwner scatter_;
  VecOwner all_;
};

}  // namespace mastrom::modes::petsc

/// Checked PETSc/SLEPc call: MASTROM_PETSC_CALL(MatAssemblyBegin(a, MAT_FINAL_ASSEMBLY));
#define MASTROM_PETSC_CALL(...) \
  ::mastrom::modes::petsc::check((__VA_ARGS__), #__VA_ARGS__, __FILE__, __LINE__)
