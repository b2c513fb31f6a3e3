// PETSc/SLEPc wrapper (modes/petsc_wrap.hpp) and SlepcSession (modes/slepc_session.hpp).
#include "modes/petsc_wrap.hpp"

#include <slepcsys.h>

#include <string>
#include <vector>

#include "common/error.hpp"

namespace mastrom::modes {
namespace petsc {
namespace {

/// The first ("initial") message of the error being propagated, recorded by the handler below and
/// consumed by check(). PETSc calls the handler again on every level of the call stack the error
/// passes through (PETSC_ERROR_REPEAT); only the first call carries the real message.
std::string& pendingMessage() {
  static std::string message;
  return message;
}

PetscErrorCode recordError(MPI_Comm /*comm*/, int line, const char* function, const char* file,
                           PetscErrorCode code, PetscErrorType type, const char* message,
                           void* /*ctx*/) {
  if (type == PETSC_ERROR_INITIAL) {
    std::string text = message != nullptr ? message : "";
    if (text.empty()) {
      const char* generic = nullptr;
      if (PetscErrorMessage(code, &generic, nullptr) == 0 && generic != nullptr) text = generic;
    }
    pendingMessage() =
        ::mastrom::detail::concat(text, " [", function != nullptr ? function : "?", "() at ",
                                  file != nullptr ? file : "?", ":", line, "]");
  }
  return code;
}

}  // namespace

void check(PetscErrorCode code, const char* call, const char* file, int line) {
  if (code == 0) return;
  std::string detail = std::move(pendingMessage());
  pendingMessage().clear();
  if (detail.empty()) {
    const char* generic = nullptr;
    if (PetscErrorMessage(code, &generic, nullptr) == 0 && generic != nullptr) detail = generic;
  }
  throw NumericalError(::mastrom::detail::concat("PETSc error ", code, " in ", call, " (", file,
                                                 ":", line, "): ", detail));
}

QuietErrors::QuietErrors() {
  pendingMessage()
      .clear();  // a message left by an error PETSc handled internally must not leak into ours
  MASTROM_PETSC_CALL(PetscPushErrorHandler(recordError, nullptr));
}
QuietErrors::~QuietErrors() { static_cast<void>(PetscPopErrorHandler()); }

MatOwner toPetscMatrix(const SparseMatrix& a, MPI_Comm comm) {
  PetscInt rows = static_cast<PetscInt>(a.rows());
  PetscInt cols = static_cast<PetscInt>(a.cols());
  PetscInt local_rows = PETSC_DECIDE;
  PetscInt local_cols = PETSC_DECIDE;
  MASTROM_PETSC_CALL(PetscSplitOwnership(comm, &local_rows, &rows));
  MASTROM_PETSC_CALL(PetscSplitOwnership(comm, &local_cols, &cols));
  // First owned row/column = exclusive prefix sum of the local sizes (PETSc's contiguous layout).
  PetscInt row_end = 0;
  PetscInt col_end = 0;
  MASTROM_PETSC_CALL(MPI_Scan(&local_rows, &row_end, 1, MPIU_INT, MPI_SUM, comm));
  MASTROM_PETSC_CALL(MPI_Scan(&local_cols, &col_end, 1, MPIU_INT, MPI_SUM, comm));
  const PetscInt row_begin = row_end - local_rows;
  const PetscInt col_begin = col_end - local_cols;

  // Row-major copy so that each owned row is one contiguous (columns, values) run.
  const Eigen::SparseMatrix<double, Eigen::RowMajor, PetscInt> by_rows(a);
  const PetscInt* outer = by_rows.outerIndexPtr();
  const PetscInt* inner = by_rows.innerIndexPtr();
  const double* values = by_rows.valuePtr();

  std::vector<PetscInt> diagonal_nnz(static_cast<std::size_t>(local_rows), 0);
  std::vector<PetscInt> off_diagonal_nnz(static_cast<std::size_t>(local_rows), 0);
  for (PetscInt i = 0; i < local_rows; ++i) {
    const PetscInt row = row_begin + i;
    for (PetscInt p = outer[row]; p < outer[row + 1]; ++p) {
      const bool in_diagonal_block = inner[p] >= col_begin && inner[p] < col_end;
      ++(in_diagonal_block ? diagonal_nnz : off_diagonal_nnz)[static_cast<std::size_t>(i)];
    }
  }

  MatOwner mat;
  MASTROM_PETSC_CALL(MatCreate(comm, mat.out()));
  MASTROM_PETSC_CALL(MatSetSizes(mat.get(), local_rows, local_cols, rows, cols));
  MASTROM_PETSC_CALL(MatSetType(mat.get(), MATAIJ));
  // Only the call matching the actual type (Seq on one rank, MPI above) takes effect.
  MASTROM_PETSC_CALL(MatSeqAIJSetPreallocation(mat.get(), 0, diagonal_nnz.data()));
  MASTROM_PETSC_CALL(
      MatMPIAIJSetPreallocation(mat.get(), 0, diagonal_nnz.data(), 0, off_diagonal_nnz.data()));
  MASTROM_PETSC_CALL(MatSetOption(mat.get(), MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  MASTROM_PETSC_CALL(MatSetOption(mat.get(), MAT_NO_OFF_PROC_ENTRIES, PETSC_TRUE));
  for (PetscInt row = row_begin; row < row_end; ++row) {
    const PetscInt count = outer[row + 1] - outer[row];
    if (count == 0) continue;
    MASTROM_PETSC_CALL(MatSetValues(mat.get(), 1, &row, count, inner + outer[row],
                                    values + outer[row], INSERT_VALUES));
  }
  MASTROM_PETSC_CALL(MatAssemblyBegin(mat.get(), MAT_FINAL_ASSEMBLY));
  MASTROM_PETSC_CALL(MatAssemblyEnd(mat.get(), MAT_FINAL_ASSEMBLY));
  return mat;
}

AllGather::AllGather(Vec layout) {
  MASTROM_PETSC_CALL(VecScatterCreateToAll(layout, scatter_.out(), all_.out()));
}

Eigen::VectorXd AllGather::operator()(Vec v) {
  MASTROM_PETSC_CALL(
      VecScatterBegin(scatter_.get(), v, all_.get(), INSERT_VALUES, SCATTER_FORWARD));
  MASTROM_PETSC_CALL(VecScatterEnd(scatter_.get(), v, all_.get(), INSERT_VALUES, SCATTER_FORWARD));
  PetscInt size = 0;
  MASTROM_PETSC_CALL(VecGetSize(all_.get(), &size));
  const PetscScalar* data = nullptr;
  MASTROM_PETSC_CALL(VecGetArrayRead(all_.get(), &data));
  Eigen::VectorXd out = Eigen::Map<const Eigen::VectorXd>(data, size);
  MASTROM_PETSC_CALL(VecRestoreArrayRead(all_.get(), &data));
  return out;
}

}  // namespace petsc

SlepcSession::SlepcSession(int* argc, char*** argv) {
  PetscBool initialized = PETSC_FALSE;
  MASTROM_PETSC_CALL(SlepcInitialized(&initialized));
  if (!initialized) {
    const PetscErrorCode code = SlepcInitialize(argc, argv, nullptr, nullptr);
    if (code != 0)
      throw NumericalError(::mastrom::detail::concat("SlepcInitialize failed with error ", code));
    owns_ = true;
  }
  MASTROM_PETSC_CALL(PetscPushErrorHandler(petsc::recordError, nullptr));
  pushed_handler_ = true;
}

SlepcSession::~SlepcSession() {
  if (pushed_handler_) static_cast<void>(PetscPopErrorHandler());
  if (owns_) static_cast<void>(SlepcFinalize());
}

bool SlepcSession::active() {
  PetscBool initialized = PETSC_FALSE;
  PetscBool finalized = PETSC_FALSE;
  if (SlepcInitialized(&initialized) != 0 || SlepcFinalized(&finalized) != 0) return false;
  return initialized && !finalized;
}

}  // namespace mastrom::modes
