// The C++ side of the Python module's speed check (python/benchmarks/python_vs_cpp.py): one ROM
// deployment through the library call that `mastrom rom eval` and RomDatabase.evaluate both make
// (rom/studies/rom_evaluation.hpp), repeated, and the median wall time printed. The interpolator is made
// once, as the Python object keeps it.
//
//   bench_rom_evaluate DB.h5 REPEATS [--set key=value]…
//   → "median_s <seconds> min_s <seconds>"
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "rom/database/database_io.hpp"
#include "rom/studies/rom_evaluation.hpp"

int main(int argc, char** argv) {
  using namespace mastrom;
  if (argc < 3) {
    std::fprintf(stderr, "usage: bench_rom_evaluate DB.h5 REPEATS [--set key=value]...\n");
    return 2;
  }
  const rom::RomDatabase db = rom::readDatabase(argv[1]);
  const int repeats = std::max(1, std::atoi(argv[2]));
  std::vector<std::string> overrides;
  for (int i = 3; i + 1 < argc; i += 2) overrides.emplace_back(argv[i + 1]);
  const auto interpolator = rom::makeInterpolator(db, db.default_method);
  std::vector<double> times;
  double sink = 0.0;
  for (int r = 0; r < repeats; ++r) {
    const auto start = std::chrono::steady_clock::now();
    const rom::RomEvaluationInput input =
        rom::romEvaluationInput(db, overrides, rom::BoxPolicy::Refuse);
    const rom::RomEvaluation e = rom::evaluateRomDeployment(*interpolator, input);
    times.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    sink += e.metrics.peak_rel_end_angular_acceleration;  // keep the work observable
  }
  std::sort(times.begin(), times.end());
  std::printf("median_s %.9g min_s %.9g samples %d check %.6g\n", times[times.size() / 2],
              times.front(), repeats, sink / repeats);
  return 0;
}
