// The material law of the ANCF thin shell (docs/theory.md §2.2, §6; [LW24] eq. 31): plane-stress
// linear elasticity with Kelvin–Voigt damping (stress = D(ε + μ ε̇)), integrated through the
// thickness into membrane resultants σ and bending moments m, work-conjugate to the membrane strain
// E and the curvature change k (fullorder/shell_kinematics.hpp):
//   σ = c_m D (E + μ Ė),   m = c_b D (k + μ k̇),   c_m = E h,  c_b = E h³/12,
// where D is symmetric: w·dA·TᵀD̂T at a quadrature point (D̂ = planeStressUnitModulus, T the
// point's frame transform, w·dA its quadrature weight), or D̂ itself at a stress-recovery point.
//
// The element's forces, tangents and energy and the batched kernel's (all through
// fullorder/shell_point_force.hpp), the batch's section factors (shellSectionScales) and the stress
// recovery (fullorder/shell_stress.cpp) call it.
// A change of the law is an edit here: shellResultants, and shellResultantVariation and
// shellPointStrainEnergy beside it, which use that the law is linear and hyperelastic.
#pragma once

#include <Eigen/Core>

#include "common/cpu_features.hpp"

namespace mastrom::fullorder {

/// Material and section of one shell element. Units in the names: SI throughout.
struct ShellSection {
  double thickness_m = 0.002;
  double youngs_modulus_pa = 70e9;
  double poisson_ratio = 0.33;
  double density_kg_m3 = 2700.0;
  double damping_s = 0.0;  ///< Kelvin–Voigt strain-rate coefficient μ
};

/// Plane-stress matrix for unit Young's modulus ([LW24] eq. 31), Voigt [11, 22, 2·12]: σ = E·D̂·ε.
inline Eigen::Matrix3d planeStressUnitModulus(double nu) {
  Eigen::Matrix3d d;
  const double c = 1.0 / (1.0 - nu * nu);
  d << c, c * nu, 0.0, c * nu, c, 0.0, 0.0, 0.0, c * 0.5 * (1.0 - nu);
  return d;
}

/// The section's factors of the law: c_m = E h (membrane), c_b = E h³/12 (bending), μ.
struct ShellSectionScales {
  double membrane = 0.0;
  double bending = 0.0;
  double damping_s = 0.0;
};
inline ShellSectionScales shellSectionScales(const ShellSection& s) {
  const double h = s.thickness_m, young = s.youngs_modulus_pa;
  return {young * h, young * h * h * h / 12.0, s.damping_s};
}

/// Which part of the stress the resultants carry: the elastic D E, the Kelvin–Voigt D μĖ, or both.
enum class ShellStressPart { kElastic, kDamping, kBoth };

/// The law: out = [σ; m] from the strains [E; k] and their rates [Ė; k̇] (rates not read for
/// kElastic, strains not read for kDamping). d = D's upper triangle d00 d01 d02 d11 d12 d22.
/// Written on plain scalars so the batched kernel vectorises it across elements.
template <ShellStressPart kPart>
MASTROM_ALWAYS_INLINE void shellResultants(const double (&d)[6], const ShellSectionScales& c,
                                           const double (&strain)[6], const double (&rate)[6],
                                           double (&out)[6]) {
  double x[6];
  for (int i = 0; i < 6; ++i) {
    if constexpr (kPart == ShellStressPart::kElastic)
      x[i] = strain[i];
    else if constexpr (kPart == ShellStressPart::kDamping)
      x[i] = c.damping_s * rate[i];
    else
      x[i] = strain[i] + c.damping_s * rate[i];
  }
  out[0] = c.membrane * (d[0] * x[0] + d[1] * x[1] + d[2] * x[2]);
  out[1] = c.membrane * (d[1] * x[0] + d[3] * x[1] + d[4] * x[2]);
  out[2] = c.membrane * (d[2] * x[0] + d[4] * x[1] + d[5] * x[2]);
  out[3] = c.bending * (d[0] * x[3] + d[1] * x[4] + d[2] * x[5]);
  out[4] = c.bending * (d[1] * x[3] + d[3] * x[4] + d[4] * x[5]);
  out[5] = c.bending * (d[2] * x[3] + d[4] * x[4] + d[5] * x[5]);
}

/// The first variation of the resultants along a variation δ of [E; k] (kElastic) or of [Ė; k̇]
/// (kDamping): the material part of the tangents, ∂[σ; m]/∂e = (this) applied to the columns of
/// the strain-displacement matrix. The law is linear, so its variation is the law itself.
template <ShellStressPart kPart>
MASTROM_ALWAYS_INLINE void shellResultantVariation(const double (&d)[6],
                                                   const ShellSectionScales& c,
                                                   const double (&delta)[6], double (&out)[6]) {
  static_assert(kPart != ShellStressPart::kBoth, "a variation of the strains or of their rates");
  shellResultants<kPart>(d, c, delta, delta, out);
}

/// The point's share of the strain energy, ½ [E; k]·[σ; m] with the elastic resultants (D carries
/// the quadrature weight; the law is hyperelastic with this energy, docs/theory.md §2.2).
MASTROM_ALWAYS_INLINE double shellPointStrainEnergy(const double (&d)[6],
                                                      const ShellSectionScales& c,
                                                      const double (&strain)[6]) {
  double res[6];
  shellResultants<ShellStressPart::kElastic>(d, c, strain, strain, res);
  double u = 0.0;
  for (int i = 0; i < 6; ++i) u += strain[i] * res[i];
  return 0.5 * u;
}

}  // namespace mastrom::fullorder
