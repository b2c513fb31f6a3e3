// How much the mast bends under its drive, known before the first step: the scale of the vibration
// a drive excites, for the floors of the step control's scales (docs/theory.md §5.3a).
//
// A drive acceleration θ̈ loads the mast with the inertia of its rigid turn, −θ̈ M (Z × q) (every
// 3-block of the coordinates turns about Z, §2.4). With the joint held, the mast's elastic answer is
// the quasi-static deflection u θ̈,
//     [K  Gᵀ; G  0] [u; μ] = [−M (Z × q); 0],
// at the undeformed start state, and the Rayleigh quotient of u estimates the lowest frequency the
// drive excites, ω² = (uᵀ K u)/(uᵀ M u) = −(u · M (Z × q))/(uᵀ M u). A smooth drive whose θ̈ varies
// at the rate θ⃛ moves the mast's points at u θ⃛ relative to the rigid turn; a jump Δθ̈ rings
// the lowest mode with velocity amplitude ω u Δθ̈.
#pragma once

#include "fullorder/mast_model.hpp"

namespace mastrom::fullorder {

struct DriveCompliance {
  /// max over the modules' coordinates of |W u| [m per rad/s²]: points, and direction vectors
  /// times the module side (the weights of the step control, fullorder/step_control.hpp).
  double module_deflection_m_per_rad_s2 = 0.0;
  double rayleigh_frequency_rad_s = 0.0;  ///< ω of the header
};

/// The compliance of `model` at its start state (a driven mast: the driving constraint holds the
/// joint). Throws NumericalError when the held mast's stiffness cannot be factorised.
DriveCompliance driveCompliance(const MastModel& model);

}  // namespace mastrom::fullorder
