#include "fullorder/mast_config.hpp"
#include <algorithm>

namespace mastrom::fullorder {

DriveLawParameters driveFromConfig(const Config& config) {
  DriveLawParameters d;
  d.kind = config.drive.law;
  d.total_angle_rad = config.drive.angleRad();
  d.duration_s = config.drive.duration_s;
  d.ramp_s = config.drive.ramp_s;
  if (d.kind == DriveLawKind::Table) {
    d.table_time_s = config.drive.table_time_s;
    d.table_angle_rad = config.drive.table_angle_rad;
  }
  return d;
}

namespace {

Eigen::Vector3d vector3(const std::array<double, 3>& v) { return {v[0], v[1], v[2]}; }

ModuleProperties moduleProperties(const ModuleConfig& m) {
  ModuleProperties p;
  p.side_m = m.side_m;
  p.mass_kg = m.mass_kg;
  p.inertia_kg_m2 = vector3(m.principalInertia()).asDiagonal();
  p.centroid_offset_m = vector3(m.centroid_offset_m);
  return p;
}

InterfaceProperties interfaceProperties(const InterfaceConfig& f) {
  return {f.length_m, f.radius_m, f.thickness_m, f.elements_axial, f.elements_circumferential};
}

}  // namespace

MastParameters mastParametersFromConfig(const Config& config) {
  MastParameters p;
  p.modules = config.mast.modules;
  const ModuleProperties module = moduleProperties(config.module);
  p.module_side_m = module.side_m;
  p.module_mass_kg = module.mass_kg;
  p.module_inertia_kg_m2 = module.inertia_kg_m2;
  p.module_centroid_offset_m = module.centroid_offset_m;
  const InterfaceProperties iface = interfaceProperties(config.interface);
  p.interface_length_m = iface.length_m;
  p.interface_radius_m = iface.radius_m;
  p.interface_thickness_m = iface.thickness_m;
  p.elements_axial = iface.elements_axial;
  p.elements_circumferential = iface.elements_circumferential;
  // Items are numbered from 1 in the configuration, from 0 in the model.
  for (const auto& item : config.module_items)
    p.module_items[item.first - 1] = moduleProperties(config.moduleItem(item.first));
  for (const auto& item : config.interface_items)
    p.interface_items[item.first - 1] = interfaceProperties(config.interfaceItem(item.first));
  p.youngs_modulus_pa = config.material.youngs_modulus_pa;
  p.poisson_ratio = config.material.poisson_ratio;
  p.density_kg_m3 = config.material.density_kg_m3;
  p.damping_s = config.material.damping_s;
  p.gravity_m_s2 = vector3(config.simulation.gravity_m_s2);
  p.drive = driveFromConfig(config);
  return p;
}

GeneralizedAlphaOptions integratorFromConfig(const Config& config) {
  GeneralizedAlphaOptions o;
  o.time_step_s = config.simulation.time_step_s;
  o.rho_inf = config.simulation.rho_inf;
  o.recover_index1_accelerations =
      config.simulation.accelerations == AccelerationOutputKind::Index1;
  return o;
}

DeploymentOptions deploymentFromConfig(const Config& config) {
  const SimulationConfig& sim = config.simulation;
  DeploymentOptions o;
  o.integrator = integratorFromConfig(config);
  o.end_time_s = sim.end_time_s;
  o.output_every = config.output.every;
  o.adaptive = sim.adaptive;
  o.step_control.tolerance = sim.tolerance;
  o.step_control.initial_step_s =
      std::clamp(sim.time_step_s, sim.min_time_step_s, sim.max_time_step_s);
  o.step_control.min_step_s = sim.min_time_step_s;
  o.step_control.max_step_s = sim.max_time_step_s;
  o.output_step_s = outputInterval(config);
  // The error estimate differentiates the accelerations three times: the Newton iteration must
  // resolve them well below the tolerance (docs/theory.md §5.3: the momentum residual, relative
  // to the largest force — elastic forces ~10³ times the modules' inertial ones — becomes an
  // acceleration noise ~10³ times larger relative to the accelerations).
  if (o.adaptive) {
    o.integrator.force_tolerance = std::min(o.integrator.force_tolerance, 1e-4 * sim.tolerance);
  }
  return o;
}

}  // namespace mastrom::fullorder
