// CLI test helper: check a `mastrom modes` result and optionally compare it with another.
//
//   compare_modes A.h5 [B.h5 [relative_tolerance]]
//
// Checks A (and B): a readable modes file (modes/modes_file.hpp) with ascending frequencies and a
// well-formed A.xdmf whose every referenced dataset exists (tests/modes/xdmf_check.hpp). With B:
// the same number of modes and every frequency within the tolerance (default 1e-8) relative — the
// 1-rank versus 2-rank comparison of tests/cli/modes_cli.cmake. Prints one line per problem and
// exits 1 on any, 0 otherwise.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "modes/modes_file.hpp"
#include "modes/xdmf_writer.hpp"
#include "tests/modes/xdmf_check.hpp"

namespace {

int problems = 0;

void problem(const std::string& what) {
  std::printf("compare_modes: %s\n", what.c_str());
  ++problems;
}

mastrom::modes::ModesFile check(const std::string& path) {
  mastrom::modes::ModesFile file;
  try {
    file = mastrom::modes::readModesFile(path);
  } catch (const std::exception& e) {
    problem(e.what());
    return file;
  }
  const Eigen::VectorXd& f = file.modes.frequency_hz;
  if (f.size() == 0) problem(path + ": no modes");
  for (Eigen::Index k = 1; k < f.size(); ++k)
    if (f(k) < f(k - 1)) problem(path + ": /modes/frequency_hz not ascending");
  for (const std::string& p : mastrom::testing_xdmf::checkXdmf(mastrom::modes::xdmfPathFor(path)))
    problem(mastrom::modes::xdmfPathFor(path) + ": " + p);
  std::printf("compare_modes: %s: %d modes, first %.6f Hz, source %s\n", path.c_str(),
              static_cast<int>(f.size()), f.size() ? f(0) : 0.0, file.source.c_str());
  return file;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 4) {
    std::printf("usage: compare_modes A.h5 [B.h5 [relative_tolerance]]\n");
    return 2;
  }
  const mastrom::modes::ModesFile a = check(argv[1]);
  if (argc >= 3) {
    const mastrom::modes::ModesFile b = check(argv[2]);
    const double tolerance = argc == 4 ? std::atof(argv[3]) : 1e-8;
    const Eigen::VectorXd& fa = a.modes.frequency_hz;
    const Eigen::VectorXd& fb = b.modes.frequency_hz;
    if (fa.size() != fb.size()) {
      problem("different numbers of modes");
    } else {
      double worst = 0.0;
      for (Eigen::Index k = 0; k < fa.size(); ++k)
        worst = std::max(worst, std::abs(fb(k) - fa(k)) / std::abs(fa(k)));
      std::printf("compare_modes: max relative frequency difference %.2e (tolerance %.1e)\n", worst,
                  tolerance);
      if (!(worst <= tolerance)) problem("frequencies differ beyond the tolerance");
    }
  }
  std::printf("compare_modes: %d problem%s\n", problems, problems == 1 ? "" : "s");
  return problems == 0 ? 0 : 1;
}
