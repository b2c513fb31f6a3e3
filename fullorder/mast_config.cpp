#include "fullorder/mast_config.hpp"
#include <algorithm>

namespace mastrom::fullorder {

DriveLawParameters driveFromConfig(const Config& config) {
  DriveLawParameters d;
  d.kind = config.drive.law;
  d.total_angle_rad = config.drive.angleRad();
  d.duration_s = config.drive.duration_s;
  d.ramp_s = config.drive.ramp_s;
  return d;
}

MastParameters mastParametersFromConfig(const Config& config) {
  MastParameters p;
  p.modules = config.mast.modules;
  p.module_side_m = config.module.side_m;
  p.module_mass_kg = config.module.mass_kg;
  const std::array<double, 3> inertia = config.module.principalInertia();
  p.module_inertia_kg_m2 = Eigen::Vector3d(inertia[0], inertia[1], inertia[2]).asDiagonal();
  p.interface_length_m = config.interface.length_m;
  p.interface_radius_m = config.interface.radius_m;
  p.interface_thickness_m = config.interface.thickness_m;
  p.elements_axial = config.interface.elements_axial;
  p.elements_circumferential = config.interface.elements_circumferential;
  p.youngs_modulus_pa = config.material.youngs_modulus_pa;
  p.poisson_ratio = config.material.poisson_ratio;
  p.density_kg_m3 = config.material.density_kg_m3;
  p.damping_s = config.material.damping_s;
  p.gravity_m_s2 = Eigen::Vector3d(config.simulation.gravity_m_s2[0],
                                   config.simulation.gravity_m_s2[1],
                                   config.simulation.gravity_m_s2[2]);
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
  o.output_step_s = config.output.step_s;
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
