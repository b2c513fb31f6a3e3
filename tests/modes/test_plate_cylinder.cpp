// Convergence of the shell element's modes to independent thin-shell references (docs/theory.md
// §2.2 "tests must show … convergence of cantilever-plate and cylinder frequencies with mesh
// refinement"), on the clamped structures of tests/support/clamped_cylinder.hpp, solved by the SLEPc
// backend.
//
// References (converged Kirchhoff / thin-shell values):
//  * cantilever square plate a = 0.1 m, h = 1 mm, E = 70 GPa, ν = 0.33, ρ = 2700 kg/m³, clamped on
//    one edge: λ² = ω a² √(ρh/D) = 3.4607, 8.3699, 21.108, 27.077, 30.589, 53.584;
//  * clamped–free cylinder R = 41 mm, h = 2 mm, L = 0.30 m, same material [Hz]: 816.62 (bending
//    pair), 845.33 (n = 2 pair), 1773.51 (n = 2, 2nd axial order), 2243.53 (n = 3), 2602.21
//    (torsion), 3435.55 (2nd bending pair), 4243.52 (axial).
// CI runs a coarse and a medium mesh of each (≈ 1 s in all): every reference within 1 % on the
// medium mesh, and the error not growing from coarse to medium. The refined study (up to 32 × 32
// plates and 32 × 64 cylinders) is benchmarks/bench_modes_convergence.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "tests/support/clamped_cylinder.hpp"
#include "modes/linearize.hpp"
#include "modes/modal_analysis.hpp"

namespace mastrom::modes {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Converged references carry five significant digits: relative differences below this are not
// resolved by them.
constexpr double kReferenceDigits = 3e-5;

ModalAnalysis solveClamped(const fullorder::ClampedShell& shell, int count) {
  const Linearization lin = linearize(shell.system, shell.system.referenceCoordinates());
  ModalAnalysisOptions options;
  options.solver.backend = EigenBackendKind::Slepc;
  options.solver.count = count;
  options.solver.communicator = MPI_COMM_SELF;
  const ModalAnalysis a = runModalAnalysis(shell.system, lin, options);
  EXPECT_TRUE(a.eigen.ok()) << a.eigen.message;
  EXPECT_LE(a.residuals.maxCoeff(), 1e-8);
  return a;
}

/// λ² of the six lowest plate modes on an n × n mesh.
std::vector<double> plateParameters(int n) {
  fullorder::CantileverPlateParameters p;
  p.length_m = p.width_m = 0.1;
  p.elements_x = p.elements_y = n;
  p.section.thickness_m = 0.001;
  p.section.youngs_modulus_pa = 70e9;
  p.section.poisson_ratio = 0.33;
  p.section.density_kg_m3 = 2700.0;
  const fullorder::ClampedShell plate = fullorder::buildCantileverPlate(p);
  const ModalAnalysis a = solveClamped(plate, 6);
  const double h = p.section.thickness_m, nu = p.section.poisson_ratio;
  const double d = p.section.youngs_modulus_pa * h * h * h / (12.0 * (1.0 - nu * nu));
  std::vector<double> out;
  for (int k = 0; k < a.eigen.converged; ++k) {
    EXPECT_EQ(a.labels[static_cast<size_t>(k)], "bending");
    const double omega = 2.0 * kPi * a.eigen.frequencies_hz(k);
    out.push_back(omega * p.length_m * p.length_m * std::sqrt(p.section.density_kg_m3 * h / d));
  }
  return out;
}

TEST(CantileverPlate, FrequencyParametersConvergeToKirchhoffReference) {
  const std::vector<double> reference{3.4607, 8.3699, 21.108, 27.077, 30.589, 53.584};
  const std::vector<double> coarse = plateParameters(8), medium = plateParameters(16);
  ASSERT_EQ(coarse.size(), reference.size());
  ASSERT_EQ(medium.size(), reference.size());
  for (std::size_t k = 0; k < reference.size(); ++k) {
    const double e_coarse = coarse[k] / reference[k] - 1.0,
                 e_medium = medium[k] / reference[k] - 1.0;
    std::printf(
        "[ measured ] plate mode %zu: lambda^2 %.4f (8x8, %+.3f %%), %.4f (16x16, %+.3f %%), "
        "reference %.4f\n",
        k + 1, coarse[k], 100 * e_coarse, medium[k], 100 * e_medium, reference[k]);
    EXPECT_LT(std::abs(e_medium), 0.01) << "mode " << k + 1;
    EXPECT_LE(std::abs(e_medium), std::max(std::abs(e_coarse), kReferenceDigits))
        << "mode " << k + 1 << ": error grew with refinement";
  }
}

/// One reference of the cylinder: the `ordinal`-th (1-based) cluster of modes whose label starts
/// with `family`.
struct CylinderReference {
  const char* family;
  int ordinal;
  double frequency_hz;
};

/// Frequency of the ordinal-th cluster (modes within 1e-6 relative) of `family`; NaN if absent.
double findCluster(const ModalAnalysis& a, const std::string& family, int ordinal) {
  int seen = 0;
  double last = -1.0;
  for (int k = 0; k < a.eigen.converged; ++k) {
    if (a.labels[static_cast<size_t>(k)].rfind(family, 0) != 0) continue;
    const double f = a.eigen.frequencies_hz(k);
    if (last > 0.0 && std::abs(f - last) <= 1e-6 * f) continue;  // same cluster
    last = f;
    if (++seen == ordinal) return f;
  }
  return std::nan("");
}

TEST(ClampedCylinder, FrequenciesConvergeToThinShellReference) {
  const std::vector<CylinderReference> reference{
      {"bending", 1, 816.62},    {"shell n=2", 1, 845.33}, {"shell n=2", 2, 1773.51},
      {"shell n=3", 1, 2243.53}, {"torsion", 1, 2602.21},  {"bending", 2, 3435.55},
      {"axial", 1, 4243.52}};
  std::vector<ModalAnalysis> results;
  const std::vector<std::pair<int, int>> meshes{{8, 16}, {16, 32}};
  for (const auto& mesh : meshes) {
    fullorder::ClampedCylinderParameters p;
    p.radius_m = 0.041;
    p.length_m = 0.30;
    p.section.thickness_m = 0.002;
    p.elements_axial = mesh.first;
    p.elements_circumferential = mesh.second;
    results.push_back(solveClamped(fullorder::buildClampedCylinder(p), 24));
  }
  for (const CylinderReference& r : reference) {
    const double coarse = findCluster(results[0], r.family, r.ordinal);
    const double medium = findCluster(results[1], r.family, r.ordinal);
    const double e_coarse = coarse / r.frequency_hz - 1.0, e_medium = medium / r.frequency_hz - 1.0;
    std::printf(
        "[ measured ] cylinder %-9s #%d: %8.2f Hz (8x16, %+.3f %%), %8.2f Hz (16x32, "
        "%+.3f %%), reference %.2f\n",
        r.family, r.ordinal, coarse, 100 * e_coarse, medium, 100 * e_medium, r.frequency_hz);
    ASSERT_TRUE(std::isfinite(medium)) << r.family << " #" << r.ordinal << " not found";
    EXPECT_LT(std::abs(e_medium), 0.01) << r.family << " #" << r.ordinal;
    EXPECT_LE(std::abs(e_medium), std::max(std::abs(e_coarse), kReferenceDigits))
        << r.family << " #" << r.ordinal << ": error grew with refinement";
  }
}

}  // namespace
}  // namespace mastrom::modes
