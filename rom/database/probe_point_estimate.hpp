// The error of a grid database's cubic weights at any point, from the errors measured at its
// cells' centres (docs/theory.md §4.3, "Cubic by default"; the probes: rom/offline/probe_estimate.hpp).
//
// On each axis the cubic weights interpolate with a polynomial through the m = min(4, n) nodes of
// a local stencil, in s = log x on a positive axis (§4.4 (a′)); its error at s is, to leading order,
// f⁽ᵐ⁾ ω(s)/m! with the node polynomial ω(s) = Π_k (s − s_k). Within one cell the stencil and
// f⁽ᵐ⁾ are those of the cell's centre c, so the error along axis a at x is the centre's times
// |ω_a(x_a)| / |ω_a(c_a)|. The probe measures the centre's error with every axis contributing;
// the estimate at x scales it by the largest of the axes' ratios — the axis on which x is farthest
// from a node, whose term dominates near the centre and which keeps the estimate from vanishing
// when x approaches a node on one axis only:
//
//     e(x) ≈ ē(x) · max_a |ω_a(x_a)| / |ω_a(c_a)|.                                          (4.13)
//
// The centre's error ē(x) is interpolated multilinearly between the cells' probes (clamped at
// the outer centres) so that the estimate does not jump at a cell's face. Measured at 20 random
// points per box, interpolated ROM against the ROM of a direct modal solve (docs/theory.md §4.3):
// estimate ÷ error 0.82–2.07 on the main job's 3 × 3 box, never below ½ on three boxes.
#pragma once

#include <vector>

#include "rom/database/rom_database.hpp"

namespace mastrom::rom {

/// The estimated (ω₁ relative error, NRMSE of the relative end angular acceleration) of the
/// default method at `point` from (4.13); {−1, −1} when `db` carries no probes or is not a grid
/// (scattered samples: rom/interpolation/point_error_estimate.hpp). When the build
/// probed a subset of the cells (more than 64), ē is the probe nearest the point's cell
/// centre instead. A point outside the box is scaled as in its nearest cell.
std::pair<double, double> probePointEstimate(const RomDatabase& db, const std::vector<double>& point);

}  // namespace mastrom::rom
