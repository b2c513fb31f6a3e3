// Short human-readable labels for mode shapes (the `mastrom modes` table): "bending-y",
// "bending-z", "torsion", "axial", "breathing", "shell n=k" for cylindrical shells; "bending" /
// "in-plane" for flat ones. A heuristic for people, never used by computations.
//
// The heuristic (documented so a reader can predict it):
// 1. Mode shapes are first rotated back by −θ0 about Z, so that for the mast the stowed frame
//    applies: mast axis = X, "y" = the in-plane lateral direction (global Y at θ0 = 0), "z" = the
//    joint axis Z (out of the deployment plane).
// 2. Only the shell nodes' position displacements are used (the rigid modules move with the end
//    rings they are bonded to). Each node's displacement is split into axial (along its reference
//    r_x), radial (along its reference normal) and tangential (axis × normal) components.
// 3. Flat meshes (all reference normals parallel): "bending" when the normal component carries more
//    than half of Σ|u|², else "in-plane".
// 4. Cylindrical meshes: nodes are grouped into rings (same axis, same axial coordinate), and every
//    component is expanded in circumferential harmonics cos nφ, sin nφ per ring, φ measured from
//    the axis-perpendicular direction closest to global Y towards Z. The harmonic n with the
//    largest Σ amplitude² (all rings, all components; Parseval weights) decides:
//      n = 0: the largest of axial → "axial", tangential → "torsion", radial → "breathing";
//      n = 1: "bending-y" or "bending-z", whichever plane carries more of the n = 1 content
//             (radial cos, tangential sin and axial cos terms belong to y);
//      n ≥ 2: "shell n=<n>".
// 5. No shell nodes, or a zero shape: "rigid".
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "fullorder/multibody_system.hpp"

namespace mastrom::modes {

/// Label every column of `shapes` (n_dof × k, in the global frame of the linearisation at the
/// joint angle `frame_angle_rad`) for `system` (its reference = the stowed geometry).
std::vector<std::string> labelModes(const fullorder::MultibodySystem& system,
                                    const Eigen::Ref<const Eigen::MatrixXd>& shapes,
                                    double frame_angle_rad = 0.0);

}  // namespace mastrom::modes
