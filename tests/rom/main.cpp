// test_rom entry point: GoogleTest first, then SLEPc once for the whole binary (the ROM database
// build runs modal solves), then the tests. Test discovery (--gtest_list_tests) skips PETSc.
#include <gtest/gtest.h>

#include "modes/slepc_session.hpp"

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  if (::testing::GTEST_FLAG(list_tests)) return RUN_ALL_TESTS();
  const mastrom::modes::SlepcSession session(&argc, &argv);
  return RUN_ALL_TESTS();
}
