// Validation of a Config: ranges and cross-key relations (see config.hpp, validate()).
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

namespace {

// ---------------------------------------------------------------------------------------------
// Validation: ranges and cross-key relations.

[[noreturn]] void outOfRange(std::string_view key, const std::string& value,
                             const std::string& rule) {
  throw InputError(
      detail::concat(kPrefix, key, " = ", value, " is out of range: must satisfy ", rule));
}

void requireFinite(std::string_view key, double v) {
  if (!std::isfinite(v)) {
    throw InputError(
        detail::concat(kPrefix, key, " = ", formatDouble(v), " is not a finite number"));
  }
}

/// key = v must be finite and > 0.
void requirePositive(std::string_view key, std::string_view leaf, double v, std::string_view unit) {
  requireFinite(key, v);
  if (!(v > 0)) outOfRange(key, formatDouble(v), detail::concat(leaf, " > 0 (", unit, ")"));
}

void requireAtLeast(std::string_view key, std::string_view leaf, int v, int lo,
                    std::string_view why = "") {
  if (v < lo) outOfRange(key, std::to_string(v), detail::concat(leaf, " >= ", lo, why));
}

void requireVec3Finite(std::string_view key, const std::array<double, 3>& v,
                       std::string_view what) {
  for (const double x : v) {
    if (!std::isfinite(x)) {
      throw InputError(detail::concat(kPrefix, key, " = ", formatVec3(v),
                                      " is not a 3-vector of finite numbers: expected ", what));
    }
  }
}

/// The checks of one module; `at` is "module" for the defaults or "module.K" for item K.
void validateModule(const ModuleConfig& m, const std::string& at) {
  requirePositive(at + ".side", "side", m.side_m, "m");
  requirePositive(at + ".mass", "mass", m.mass_kg, "kg");
  requireVec3Finite(at + ".centroid_offset", m.centroid_offset_m,
                    "[x, y, z] in m, module frame, from the cube's centre");
  if (!m.inertia_kg_m2) return;
  const std::string inertia = at + ".inertia";
  const std::array<double, 3>& I = *m.inertia_kg_m2;
  requireVec3Finite(inertia, I, "[Ixx, Iyy, Izz] in kg m^2");
  static constexpr std::array<std::string_view, 3> kNames{"Ixx", "Iyy", "Izz"};
  const std::string rule =
      "0 < Ixx, Iyy, Izz and each <= the sum of the other two (principal moments of a rigid body)";
  for (int k = 0; k < 3; ++k) {
    if (!(I[k] > 0)) {
      outOfRange(inertia, formatVec3(I),
                 detail::concat(rule, "; ", kNames[k], " = ", formatDouble(I[k]), " <= 0"));
    }
  }
  for (int k = 0; k < 3; ++k) {
    const int a = (k + 1) % 3;
    const int b = (k + 2) % 3;
    if (I[k] > I[a] + I[b]) {
      outOfRange(inertia, formatVec3(I),
                 detail::concat(rule, "; ", kNames[k], " = ", formatDouble(I[k]), " > ", kNames[a],
                                " + ", kNames[b], " = ", formatDouble(I[a] + I[b])));
    }
  }
}

/// The checks of one interface; `at` is "interface" for the defaults or "interface.K".
void validateInterface(const InterfaceConfig& f, const std::string& at) {
  requirePositive(at + ".length", "length", f.length_m, "m");
  if (f.inner_diameter_m) {
    requirePositive(at + ".inner_diameter", "inner_diameter", *f.inner_diameter_m, "m");
  } else {
    requirePositive(at + ".radius", "radius", f.radius_m, "m");
  }
  requireFinite(at + ".thickness", f.thickness_m);
  if (!(f.thickness_m > 0 && f.thickness_m < f.radius_m)) {
    outOfRange(at + ".thickness", formatDouble(f.thickness_m),
               detail::concat("0 < thickness < radius (", formatDouble(f.radius_m), " m)"));
  }
  if (f.inner_diameter_m && f.radius_m != 0.5 * (*f.inner_diameter_m + f.thickness_m)) {
    throw InputError(detail::concat(
        kPrefix, at, ".radius = ", formatDouble(f.radius_m), " does not match ", at,
        ".inner_diameter = ", formatDouble(*f.inner_diameter_m),
        ": must satisfy radius = (inner_diameter + thickness)/2"));
  }
  requireAtLeast(at + ".elements_axial", "elements_axial", f.elements_axial, 1);
  requireAtLeast(at + ".elements_circumferential", "elements_circumferential",
                 f.elements_circumferential, 3, " (a periodic ring needs at least 3 elements)");
}

/// Item numbers K of `items` must lie in 1 … count; every item is checked resolved.
template <typename Items, typename Resolve, typename Check>
void validateItems(const Items& items, const char* section, int count, const char* count_rule,
                   Resolve resolve, Check check) {
  for (const auto& entry : items) {
    const int k = entry.first;
    const std::string at = detail::concat(section, ".", k);
    if (k < 1 || k > count) {
      throw InputError(detail::concat(kPrefix, "[", at, "] is out of range: item number ", k,
                                      " must satisfy 1 <= K <= ", count, " (", count_rule, ")"));
    }
    check(resolve(k), at);
  }
}

void validateMaterial(const MaterialConfig& m) {
  requirePositive("material.youngs_modulus", "youngs_modulus", m.youngs_modulus_pa, "Pa");
  requireFinite("material.poisson_ratio", m.poisson_ratio);
  if (!(m.poisson_ratio > -1.0 && m.poisson_ratio < 0.5)) {
    outOfRange("material.poisson_ratio", formatDouble(m.poisson_ratio),
               "-1 < poisson_ratio < 0.5 (isotropic, positive-definite elasticity)");
  }
  requirePositive("material.density", "density", m.density_kg_m3, "kg/m^3");
  requireFinite("material.damping", m.damping_s);
  if (!(m.damping_s >= 0)) {
    outOfRange("material.damping", formatDouble(m.damping_s), "damping >= 0 (s)");
  }
  if (m.yield_strength_pa) {
    requirePositive("material.yield_strength", "yield_strength", *m.yield_strength_pa, "Pa");
  }
}

void validateDrive(const DriveConfig& d) {
  requireFinite("drive.angle_deg", d.angle_deg);
  if (!(d.angle_deg > 0 && d.angle_deg <= 360)) {
    outOfRange("drive.angle_deg", formatDouble(d.angle_deg), "0 < angle_deg <= 360");
  }
  requirePositive("drive.duration", "duration", d.duration_s, "s");
  requireFinite("drive.ramp", d.ramp_s);
  // The ramp time only shapes the trapezoidal law; the other laws ignore it.
  if (d.law == DriveLawKind::Trapezoidal) {
    if (!(d.ramp_s > 0 && d.ramp_s <= 0.5 * d.duration_s)) {
      outOfRange("drive.ramp", formatDouble(d.ramp_s),
                 detail::concat("0 < ramp <= duration/2 (", formatDouble(0.5 * d.duration_s),
                                " s) for the trapezoidal law"));
    }
  } else if (!(d.ramp_s > 0)) {
    outOfRange("drive.ramp", formatDouble(d.ramp_s), "ramp > 0 (s)");
  }
  if (d.law == DriveLawKind::Table && !d.table_time_s.empty()) {
    validateDriveTable(DriveTable{d.table_time_s, d.table_angle_rad}, "drive.table = " + tomlString(d.table));
  }
}

void validateSimulation(const SimulationConfig& s) {
  requirePositive("simulation.end_time", "end_time", s.end_time_s, "s");
  requireFinite("simulation.time_step", s.time_step_s);
  if (!(s.time_step_s > 0 && s.time_step_s <= s.end_time_s)) {
    outOfRange("simulation.time_step", formatDouble(s.time_step_s),
               detail::concat("0 < time_step <= end_time (", formatDouble(s.end_time_s), " s)"));
  }
  requireFinite("simulation.tolerance", s.tolerance);
  if (!(s.tolerance > 0 && s.tolerance <= 0.1)) {
    outOfRange("simulation.tolerance", formatDouble(s.tolerance), "0 < tolerance <= 0.1");
  }
  requireFinite("simulation.min_time_step", s.min_time_step_s);
  requireFinite("simulation.max_time_step", s.max_time_step_s);
  // The first step is taken within these bounds (a time_step outside them is moved inside).
  if (!(s.min_time_step_s > 0 && s.min_time_step_s <= s.max_time_step_s)) {
    outOfRange("simulation.min_time_step", formatDouble(s.min_time_step_s),
               detail::concat("0 < min_time_step <= max_time_step (",
                              formatDouble(s.max_time_step_s), " s)"));
  }
  requireFinite("simulation.rho_inf", s.rho_inf);
  if (!(s.rho_inf >= 0 && s.rho_inf <= 1)) {
    outOfRange("simulation.rho_inf", formatDouble(s.rho_inf), "0 <= rho_inf <= 1");
  }
  requireVec3Finite("simulation.gravity", s.gravity_m_s2, "[gx, gy, gz] in m/s^2");
}

void validateModes(const ModesConfig& m) {
  requireAtLeast("modes.count", "count", m.count, 1);
  requireFinite("modes.angle_deg", m.angle_deg);
  if (!(m.angle_deg >= 0 && m.angle_deg <= 360)) {
    outOfRange("modes.angle_deg", formatDouble(m.angle_deg), "0 <= angle_deg <= 360");
  }
}

void validateOutput(const OutputConfig& o, const SimulationConfig& s) {
  if (o.file.empty()) outOfRange("output.file", tomlString(o.file), "a non-empty path");
  requireAtLeast("output.every", "every", o.every, 1);
  if (s.adaptive && o.every != 1) {
    outOfRange("output.every", std::to_string(o.every),
               "1 with adaptive steps (every n-th step is a fixed-step setting, "
               "simulation.adaptive = false); set output.step [s] instead");
  }
  if (!o.step_s) return;  // chosen from the response by the commands that write time series
  requireFinite("output.step", *o.step_s);
  if (!(*o.step_s > 0 && *o.step_s <= s.end_time_s)) {
    outOfRange(
        "output.step", formatDouble(*o.step_s),
        detail::concat("0 < step <= simulation.end_time (", formatDouble(s.end_time_s), " s)"));
  }
}

}  // namespace

void validate(const Config& c) {
  requireAtLeast("mast.modules", "modules", c.mast.modules, 2,
                 " (a mast has at least 2 modules and 1 interface)");
  validateModule(c.module, "module");
  validateInterface(c.interface, "interface");
  validateItems(
      c.module_items, "module", c.mast.modules, "mast.modules",
      [&c](int k) { return c.moduleItem(k); }, validateModule);
  validateItems(
      c.interface_items, "interface", c.mast.modules - 1, "mast.modules - 1: interface K joins "
      "module K to K + 1", [&c](int k) { return c.interfaceItem(k); }, validateInterface);
  validateMaterial(c.material);
  validateDrive(c.drive);
  validateSimulation(c.simulation);
  validateModes(c.modes);
  validateOutput(c.output, c.simulation);
  validateUncertainty(c.uncertainty);
}

}  // namespace mastrom
