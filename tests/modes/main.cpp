// test_modes entry point: GoogleTest first (it removes its own flags from argv), then SLEPc once
// for the whole binary (each PETSc start-up costs ≈ 0.4 s), then the tests. Remaining
// arguments reach PETSc, e.g. `test_modes --gtest_filter=SlepcAgainstDense.* -eps_view`.
// Runs under `mpirun -n 2` as well (tests/cli/modes_mpi.cmake): SLEPc tests then share one
// distributed eigenproblem and every rank checks the gathered result.
#include <gtest/gtest.h>

#include "modes/slepc_session.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (GTEST_FLAG_GET(list_tests)) return RUN_ALL_TESTS();  // test discovery: no PETSc start-up
  const mastrom::modes::SlepcSession session(&argc, &argv);
  return RUN_ALL_TESTS();
}
