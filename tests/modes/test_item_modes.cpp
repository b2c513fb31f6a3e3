// Modes of a mast whose modules differ (per-item configuration, docs/theory.md §1.4): module 1 is
// clamped by the locked joint, so a two-module mast's modes are those of module 2 on its
// interface alone — module 1's mass cannot enter them, module 2's must.
#include <gtest/gtest.h>

#include <cstdio>

#include "common/config.hpp"
#include "modes/mast_modes.hpp"

namespace mastrom::modes {
namespace {

Eigen::VectorXd lockedFrequencies(const std::vector<std::string>& overrides) {
  Config c;
  c.mast.modules = 2;
  c.interface.elements_axial = 1;
  c.interface.elements_circumferential = 6;
  c.modes.count = 6;
  c.modes.backend = EigenBackendKind::Dense;
  return solveMastModes(applyConfigOverrides(c, overrides)).data.frequency_hz;
}

TEST(ItemModes, TwoModuleMastDependsOnModule2Only) {
  const Eigen::VectorXd plain = lockedFrequencies({});
  const Eigen::VectorXd heavy_base = lockedFrequencies({"module.1.mass=5.0"});
  const Eigen::VectorXd heavy_tip = lockedFrequencies({"module.2.mass=1.0"});
  ASSERT_EQ(plain.size(), 6);
  const double change_base = ((heavy_base - plain).cwiseAbs().array() / plain.array()).maxCoeff();
  const double change_tip = ((heavy_tip - plain).cwiseAbs().array() / plain.array()).minCoeff();
  std::printf("[ measured ] relative frequency change: module 1 mass x10 %.1e, module 2 mass x2 "
              ">= %.2f\n", change_base, change_tip);
  EXPECT_LT(change_base, 1e-9);
  // Twice the tip mass (and its solid-cube inertia): every mode of module 2 on its shell drops,
  // towards 1/√2 for the modes the module's inertia dominates.
  EXPECT_GT(change_tip, 0.05);
}

}  // namespace
}  // namespace mastrom::modes
