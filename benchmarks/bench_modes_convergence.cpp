// Mesh-refinement study of the shell element's modes against converged thin-shell references (the
// refined part of tests/modes/test_plate_cylinder.cpp, too slow for CI): the cantilever square
// plate (a = 0.1 m, h = 1 mm, aluminium, ν = 0.33) on n × n meshes and the clamped–free cylinder
// (R = 41 mm, h = 2 mm, L = 0.30 m) on N_axial × N_circ meshes. Prints, per mesh, every reference
// quantity with its relative error [%] and the wall time.
//
//   bench_modes_convergence [--max-plate N] [--max-cylinder-circ N] [PETSc options]
//
// A plain program (each row is one model solve). SLEPc backend, serial (MPI_COMM_SELF).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "tests/support/clamped_cylinder.hpp"
#include "modes/linearize.hpp"
#include "modes/modal_analysis.hpp"
#include "modes/slepc_session.hpp"

namespace {

using namespace mastrom;
constexpr double kPi = 3.14159265358979323846;

modes::ModalAnalysis solve(const fullorder::ClampedShell& shell, int count, double* seconds) {
  const auto start = std::chrono::steady_clock::now();
  const modes::Linearization lin =
      modes::linearize(shell.system, shell.system.referenceCoordinates());
  modes::ModalAnalysisOptions options;
  options.solver.backend = EigenBackendKind::Slepc;
  options.solver.count = count;
  options.solver.communicator = MPI_COMM_SELF;
  modes::ModalAnalysis a = modes::runModalAnalysis(shell.system, lin, options);
  *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return a;
}

/// Frequency of the ordinal-th cluster of modes labelled `family…` (NaN if absent).
double findCluster(const modes::ModalAnalysis& a, const std::string& family, int ordinal) {
  int seen = 0;
  double last = -1.0;
  for (int k = 0; k < a.eigen.converged; ++k) {
    if (a.labels[static_cast<std::size_t>(k)].rfind(family, 0) != 0) continue;
    const double f = a.eigen.frequencies_hz(k);
    if (last > 0.0 && std::abs(f - last) <= 1e-6 * f) continue;
    last = f;
    if (++seen == ordinal) return f;
  }
  return std::nan("");
}

}  // namespace

int main(int argc, char** argv) {
  const modes::SlepcSession session(&argc, &argv);
  int max_plate = 32, max_circ = 64;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--max-plate")) max_plate = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--max-cylinder-circ")) max_circ = std::atoi(argv[i + 1]);
  }

  // Plate: λ² = ω a² √(ρh/D).
  const double plate_ref[] = {3.4607, 8.3699, 21.108, 27.077, 30.589, 53.584};
  std::printf("# cantilever plate, lambda^2 (error %%)\n# %6s %7s", "mesh", "dofs");
  for (double r : plate_ref) std::printf(" %17.4f", r);
  std::printf(" %8s\n", "time_s");
  for (int n : {4, 8, 16, 24, 32}) {
    if (n > max_plate) break;
    fullorder::CantileverPlateParameters p;
    p.elements_x = p.elements_y = n;
    p.section.thickness_m = 0.001;
    p.section.poisson_ratio = 0.33;
    const fullorder::ClampedShell plate = fullorder::buildCantileverPlate(p);
    double seconds = 0.0;
    const modes::ModalAnalysis a = solve(plate, 6, &seconds);
    const double h = p.section.thickness_m, nu = p.section.poisson_ratio;
    const double d = p.section.youngs_modulus_pa * h * h * h / (12.0 * (1.0 - nu * nu));
    std::printf("  %3dx%-3d %7d", n, n, plate.system.dofCount());
    for (int k = 0; k < 6 && k < a.eigen.converged; ++k) {
      const double l2 = 2.0 * kPi * a.eigen.frequencies_hz(k) * p.length_m * p.length_m *
                        std::sqrt(p.section.density_kg_m3 * h / d);
      std::printf(" %8.4f (%+6.3f)", l2, 100.0 * (l2 / plate_ref[k] - 1.0));
    }
    std::printf(" %8.2f\n", seconds);
    std::fflush(stdout);
  }

  // Cylinder [Hz].
  struct Reference {
    const char* family;
    int ordinal;
    double hz;
  };
  const Reference cyl_ref[] = {{"bending", 1, 816.62},    {"shell n=2", 1, 845.33},
                               {"shell n=2", 2, 1773.51}, {"shell n=3", 1, 2243.53},
                               {"torsion", 1, 2602.21},   {"bending", 2, 3435.55},
                               {"axial", 1, 4243.52}};
  std::printf("\n# clamped-free cylinder, Hz (error %%)\n# %8s %7s", "mesh", "dofs");
  for (const Reference& r : cyl_ref) std::printf(" %18.2f", r.hz);
  std::printf(" %8s\n", "time_s");
  const std::vector<std::pair<int, int>> meshes{{4, 8},   {8, 16},  {12, 24},
                                                {16, 32}, {24, 48}, {32, 64}};
  for (const auto& mesh : meshes) {
    if (mesh.second > max_circ) break;
    fullorder::ClampedCylinderParameters p;
    p.elements_axial = mesh.first;
    p.elements_circumferential = mesh.second;
    const fullorder::ClampedShell cylinder = fullorder::buildClampedCylinder(p);
    double seconds = 0.0;
    const modes::ModalAnalysis a = solve(cylinder, 24, &seconds);
    std::printf("  %3dx%-4d %7d", mesh.first, mesh.second, cylinder.system.dofCount());
    for (const Reference& r : cyl_ref) {
      const double f = findCluster(a, r.family, r.ordinal);
      std::printf(" %9.2f (%+6.3f)", f, 100.0 * (f / r.hz - 1.0));
    }
    std::printf(" %8.2f\n", seconds);
    std::fflush(stdout);
  }
  return 0;
}
