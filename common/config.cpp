// Derived values of a Config: items with their overrides applied, angles in radians, the output
// interval, equality (the TOML reading, validation and writing are the config_*.cpp files).
#include "common/config.hpp"


#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <system_error>
#include <tuple>

#include "common/drive_table.hpp"
#include "common/error.hpp"
#include "common/text_parsing.hpp"

#include "common/config_detail.hpp"

namespace mastrom {
using namespace config_detail;

// -----------------------------------------------------------------------------------------------

std::array<double, 3> ModuleConfig::principalInertia() const {
  if (inertia_kg_m2) return *inertia_kg_m2;
  const double i = mass_kg * side_m * side_m / 6.0;  // uniform solid cube about its centroid
  return {i, i, i};
}

double DriveConfig::angleRad() const { return angle_deg * kPi / 180.0; }

ModuleConfig Config::moduleItem(int k) const {
  ModuleConfig m = module;
  const auto it = module_items.find(k);
  if (it == module_items.end()) return m;
  const ModuleItemConfig& o = it->second;
  if (o.side_m) m.side_m = *o.side_m;
  if (o.mass_kg) m.mass_kg = *o.mass_kg;
  if (o.inertia_kg_m2) m.inertia_kg_m2 = o.inertia_kg_m2;
  if (o.centroid_offset_m) m.centroid_offset_m = *o.centroid_offset_m;
  return m;
}

InterfaceConfig Config::interfaceItem(int k) const {
  InterfaceConfig f = interface;
  const auto it = interface_items.find(k);
  if (it == interface_items.end()) return f;
  const InterfaceItemConfig& o = it->second;
  if (o.length_m) f.length_m = *o.length_m;
  if (o.thickness_m) f.thickness_m = *o.thickness_m;
  if (o.radius_m) {
    f.radius_m = *o.radius_m;
    f.inner_diameter_m.reset();
  }
  if (o.inner_diameter_m) f.inner_diameter_m = o.inner_diameter_m;
  if (o.elements_axial) f.elements_axial = *o.elements_axial;
  if (o.elements_circumferential) f.elements_circumferential = *o.elements_circumferential;
  // docs/theory.md (1.1): R = (D_in + h)/2, with this item's D_in and h.
  if (f.inner_diameter_m) f.radius_m = 0.5 * (*f.inner_diameter_m + f.thickness_m);
  return f;
}
double ModesConfig::angleRad() const { return angle_deg * kPi / 180.0; }

double outputInterval(const Config& c) {
  return c.simulation.adaptive ? c.output.step_s.value_or(kFallbackOutputStepS)
                               : c.simulation.time_step_s * static_cast<double>(c.output.every);
}

bool operator==(const ModuleItemConfig& a, const ModuleItemConfig& b) {
  return std::tie(a.side_m, a.mass_kg, a.inertia_kg_m2, a.centroid_offset_m) ==
         std::tie(b.side_m, b.mass_kg, b.inertia_kg_m2, b.centroid_offset_m);
}

bool operator==(const InterfaceItemConfig& a, const InterfaceItemConfig& b) {
  const auto tie = [](const InterfaceItemConfig& f) {
    return std::tie(f.length_m, f.radius_m, f.thickness_m, f.inner_diameter_m, f.elements_axial,
                    f.elements_circumferential);
  };
  return tie(a) == tie(b);
}

bool operator==(const UncertainInput& a, const UncertainInput& b) {
  return std::tie(a.distribution, a.mean, a.std_dev, a.lower, a.upper) ==
         std::tie(b.distribution, b.mean, b.std_dev, b.lower, b.upper);
}

bool operator==(const Config& a, const Config& b) {
  const auto tie = [](const Config& c) {
    return std::tie(c.mast.modules, c.module.side_m, c.module.mass_kg, c.module.inertia_kg_m2,
                    c.module.centroid_offset_m, c.module_items, c.interface_items, c.drive.table,
                    c.drive.table_time_s, c.drive.table_angle_rad, c.interface.length_m,
                    c.interface.radius_m, c.interface.thickness_m, c.interface.inner_diameter_m,
                    c.interface.elements_axial, c.interface.elements_circumferential,
                    c.material.youngs_modulus_pa, c.material.poisson_ratio,
                    c.material.density_kg_m3, c.material.damping_s, c.material.yield_strength_pa,
                    c.drive.law, c.drive.angle_deg, c.drive.duration_s, c.drive.ramp_s,
                    c.simulation.end_time_s, c.simulation.time_step_s, c.simulation.adaptive,
                    c.simulation.tolerance, c.simulation.min_time_step_s,
                    c.simulation.max_time_step_s, c.simulation.rho_inf, c.simulation.gravity_m_s2,
                    c.simulation.accelerations, c.modes.count, c.modes.angle_deg, c.modes.backend,
                    c.output.file, c.output.every, c.output.step_s, c.uncertainty);
  };
  return tie(a) == tie(b);
}

}  // namespace mastrom
