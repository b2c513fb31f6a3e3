#include "rom/offline/modulus_reduction.hpp"

#include <cmath>
#include <cstdio>

#include "common/error.hpp"
#include "common/option_names.hpp"
#include "rom/database/parameter_space.hpp"

namespace mastrom::rom {

namespace {

std::string gigapascals(double pa) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", pa * 1e-9);
  return text;
}

}  // namespace

ModulusReduction planModulusReduction(const Config& base, const std::vector<ParameterAxis>& axes) {
  ModulusReduction plan;
  int axis = -1, count = 0;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    if (axes[a].key != kYoungsModulusKey) continue;
    axis = static_cast<int>(a);
    ++count;
  }
  if (count != 1) return plan;  // none, or repeated: databaseBaseConfig refuses that
  const auto& g = base.simulation.gravity_m_s2;
  if (g[0] != 0.0 || g[1] != 0.0 || g[2] != 0.0) {
    plan.reason = std::string(kYoungsModulusKey) +
                  " is sampled: with gravity the preload's geometric stiffness and stress depend "
                  "on E, so the modes do not scale with it exactly";
    return plan;
  }
  if (axes.size() < 2) {
    plan.reason = std::string(kYoungsModulusKey) +
                  " is sampled: it is the only parameter (nothing else to sample)";
    return plan;
  }
  const std::vector<double>& v = axes[static_cast<std::size_t>(axis)].values;
  MASTROM_REQUIRE(v.size() >= 2 && v.front() > 0.0 && v.front() < v.back(), InputError,
                  optionName(Option::Param), " ", kYoungsModulusKey,
                  ": the box must be LO < HI with LO > 0");
  plan.axis = axis;
  plan.reference_pa = std::sqrt(v.front() * v.back());
  plan.reason = std::string(kYoungsModulusKey) +
                " is handled exactly, not sampled: without gravity E only scales the shells' "
                "stiffness and damping (K, C ∝ E; M, G, q̄ fixed), so the modes at any E are those "
                "at E0 = " + gigapascals(plan.reference_pa) + " GPa with ω and ζ × √(E/E0) and modal stresses × E/E0";
  return plan;
}

Config reducedBuildBase(const Config& base, const ModulusReduction& plan) {
  if (!plan.applies()) return base;
  return applyOverrides(base, {formatOverride(kYoungsModulusKey, plan.reference_pa)});
}

std::vector<ParameterAxis> reducedBuildAxes(const std::vector<ParameterAxis>& axes,
                                            const ModulusReduction& plan) {
  std::vector<ParameterAxis> out = axes;
  if (plan.applies()) out.erase(out.begin() + plan.axis);
  return out;
}

void restoreModulusAxis(RomDatabase& db, const Config& base, const ParameterAxis& e_axis,
                        const ModulusReduction& plan) {
  if (!plan.applies()) return;
  const Config stored = parseConfigText(db.base_config_toml, "database");
  db.base_config_toml = toToml(applyOverrides(
      stored, {formatOverride(kYoungsModulusKey, configValue(base, kYoungsModulusKey))}));
  db.axes.insert(db.axes.begin() + plan.axis,
                 ParameterAxis{e_axis.key, {e_axis.values.front(), e_axis.values.back()}});
  for (RomSample& s : db.samples)
    s.parameters.insert(s.parameters.begin() + plan.axis, plan.reference_pa);
  for (ProbeError& e : db.probes)  // measured at E₀, as the samples were solved
    e.parameters.insert(e.parameters.begin() + plan.axis, plan.reference_pa);
  db.exact_modulus = ExactModulus{plan.reference_pa};
}

}  // namespace mastrom::rom
