#include "fullorder/mast_mass.hpp"

#include <cmath>

namespace mastrom::fullorder {

double shellMassKg(double radius_m, double thickness_m, double length_m, double density_kg_m3) {
  const double outer = radius_m + 0.5 * thickness_m, inner = radius_m - 0.5 * thickness_m;
  return density_kg_m3 * M_PI * (outer * outer - inner * inner) * length_m;
}

MastMass mastMass(const MastParameters& params) {
  MastMass m;
  for (int k = 0; k < params.modules; ++k) {
    m.module_kg.push_back(params.moduleAt(k).mass_kg);
    m.total_kg += m.module_kg.back();
  }
  for (int k = 0; k + 1 < params.modules; ++k) {
    const InterfaceProperties item = params.interfaceAt(k);
    m.interface_kg.push_back(
        shellMassKg(item.radius_m, item.thickness_m, item.length_m, params.density_kg_m3));
    m.total_kg += m.interface_kg.back();
  }
  return m;
}

}  // namespace mastrom::fullorder
