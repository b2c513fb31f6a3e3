// Config → TOML text: every key with its value and unit, the items that differ (see config.hpp,
// toToml()).
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

std::string toToml(const Config& c) {
  std::ostringstream os;
  os << "[mast]\n"
     << "modules = " << c.mast.modules << "\n\n";

  os << "[module]\n"
     << "side = " << tomlFloat(c.module.side_m) << "  # m\n"
     << "mass = " << tomlFloat(c.module.mass_kg) << "  # kg\n";
  if (c.module.inertia_kg_m2) {
    os << "inertia = " << tomlVec3(*c.module.inertia_kg_m2)
       << "  # kg m^2, principal, about the centroid\n";
  } else {
    const std::array<double, 3> I = c.module.principalInertia();
    os << "# inertia = [" << formatShort(I[0]) << ", " << formatShort(I[1]) << ", "
       << formatShort(I[2]) << "]  # kg m^2: not given, solid cube m*side^2/6\n";
  }
  os << "centroid_offset = " << tomlVec3(c.module.centroid_offset_m)
     << "  # m, module frame, from the cube's centre\n\n";
  for (const auto& [k, m] : c.module_items) {
    os << "[module." << k << "]  # module " << k << (k == 1 ? " (driven)" : "")
       << ": these keys differ from [module]\n";
    if (m.side_m) os << "side = " << tomlFloat(*m.side_m) << "  # m\n";
    if (m.mass_kg) os << "mass = " << tomlFloat(*m.mass_kg) << "  # kg\n";
    if (m.inertia_kg_m2) os << "inertia = " << tomlVec3(*m.inertia_kg_m2) << "  # kg m^2\n";
    if (m.centroid_offset_m) {
      os << "centroid_offset = " << tomlVec3(*m.centroid_offset_m) << "  # m, module frame\n";
    }
    os << "\n";
  }

  const InterfaceConfig& f = c.interface;
  os << "[interface]\n"
     << "length = " << tomlFloat(f.length_m) << "  # m\n";
  if (f.inner_diameter_m) {
    os << "inner_diameter = " << tomlFloat(*f.inner_diameter_m)
       << "  # m; mid-surface radius = (inner_diameter + thickness)/2 = " << formatShort(f.radius_m)
       << " m\n";
  } else {
    os << "radius = " << tomlFloat(f.radius_m) << "  # m, mid-surface\n";
  }
  os << "thickness = " << tomlFloat(f.thickness_m) << "  # m\n"
     << "elements_axial = " << f.elements_axial << "\n"
     << "elements_circumferential = " << f.elements_circumferential << "\n\n";
  for (const auto& [k, item] : c.interface_items) {
    os << "[interface." << k << "]  # interface " << k << ": module " << k << " to " << k + 1
       << "; these keys differ from [interface]\n";
    if (item.length_m) os << "length = " << tomlFloat(*item.length_m) << "  # m\n";
    if (item.radius_m) os << "radius = " << tomlFloat(*item.radius_m) << "  # m, mid-surface\n";
    if (item.inner_diameter_m) {
      os << "inner_diameter = " << tomlFloat(*item.inner_diameter_m) << "  # m; mid-surface radius "
         << formatShort(c.interfaceItem(k).radius_m) << " m\n";
    }
    if (item.thickness_m) os << "thickness = " << tomlFloat(*item.thickness_m) << "  # m\n";
    if (item.elements_axial) os << "elements_axial = " << *item.elements_axial << "\n";
    if (item.elements_circumferential) {
      os << "elements_circumferential = " << *item.elements_circumferential << "\n";
    }
    os << "\n";
  }

  os << "[material]\n"
     << "youngs_modulus = " << tomlFloat(c.material.youngs_modulus_pa) << "  # Pa\n"
     << "poisson_ratio = " << tomlFloat(c.material.poisson_ratio) << "\n"
     << "density = " << tomlFloat(c.material.density_kg_m3) << "  # kg/m^3\n"
     << "damping = " << tomlFloat(c.material.damping_s)
     << "  # s, Kelvin-Voigt strain-rate coefficient\n";
  if (c.material.yield_strength_pa) {
    os << "yield_strength = " << tomlFloat(*c.material.yield_strength_pa)
       << "  # Pa; margin of safety = yield_strength / peak von Mises - 1\n\n";
  } else {
    os << "# yield_strength = (not given: no margin of safety)  # Pa\n\n";
  }

  os << "[drive]\n"
     << "law = " << tomlString(toString(c.drive.law)) << "  # " << allowedDriveLawNames() << "\n"
     << "angle_deg = " << tomlFloat(c.drive.angle_deg) << "  # degrees\n"
     << "duration = " << tomlFloat(c.drive.duration_s) << "  # s\n"
     << "ramp = " << tomlFloat(c.drive.ramp_s) << "  # s (trapezoidal law only)\n";
  if (!c.drive.table.empty()) {
    os << "table = " << tomlString(c.drive.table)
       << "  # CSV time [s], angle [deg] (table law: gives duration and angle_deg)\n";
  }
  os << "\n";

  const SimulationConfig& s = c.simulation;
  os << "[simulation]\n"
     << "end_time = " << tomlFloat(s.end_time_s) << "  # s\n"
     << "adaptive = " << (s.adaptive ? "true" : "false")
     << "  # error-controlled steps; false: fixed steps of time_step\n"
     << "tolerance = " << tomlFloat(s.tolerance) << "  # relative local error per step\n"
     << "time_step = " << tomlFloat(s.time_step_s)
     << "  # s: the first step (adaptive) or the step (fixed)\n"
     << "min_time_step = " << tomlFloat(s.min_time_step_s) << "  # s (adaptive)\n"
     << "max_time_step = " << tomlFloat(s.max_time_step_s) << "  # s (adaptive)\n"
     << "rho_inf = " << tomlFloat(s.rho_inf) << "\n"
     << "gravity = " << tomlVec3(s.gravity_m_s2) << "  # m/s^2, global frame\n"
     << "accelerations = " << tomlString(toString(s.accelerations)) << "  # "
     << allowedAccelerationOutputNames() << "\n\n";

  os << "[modes]\n"
     << "count = " << c.modes.count << "\n"
     << "angle_deg = " << tomlFloat(c.modes.angle_deg) << "  # degrees, locked joint angle\n"
     << "backend = " << tomlString(toString(c.modes.backend)) << "  # "
     << allowedEigenBackendNames() << "\n\n";

  os << "[output]\n"
     << "file = " << tomlString(c.output.file) << "\n"
     << "every = " << c.output.every << "  # fixed steps: write every n-th step\n";
  if (c.output.step_s)
    os << "step = " << tomlFloat(*c.output.step_s) << "  # s: output instants (adaptive steps)\n";
  else
    os << "# step: unset, chosen from the response (adaptive steps; docs/theory.md §5.4a)\n";
  os << uncertaintyToml(c.uncertainty);
  return os.str();
}

}  // namespace mastrom
