// Writes the seed of the ROM database fuzzer (fuzz_rom_database.cpp): a small valid database —
// 2 × 2 samples (interface.thickness × module.mass), 2 modes each, with scrambled mode tracking —
// from the synthetic bilinear fixture of the ROM tests (tests/rom/rom_fixtures.hpp). Generated at
// fuzzing time rather than committed: HDF5 puts several KB of metadata around every dataset.
//
//   make_seed_database <output.h5>
#include <cstdio>
#include <exception>

#include "rom/database/database_io.hpp"
#include "rom_fixtures.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_seed_database <output.h5>\n");
    return 2;
  }
  try {
    using namespace mastrom::rom;
    const RomDatabase db =
        testing::bilinearDatabase(testing::randomBilinearModel(2, 7), {1e-3, 2e-3}, {0.4, 0.6}, 11);
    writeDatabase(argv[1], db);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_seed_database: %s\n", e.what());
    return 1;
  }
  return 0;
}
