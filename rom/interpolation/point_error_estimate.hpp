// The estimated error of a database's default method at one point, from its held-out probes
// (docs/theory.md §4.3): on a grid the cell-centre probes scaled by the node polynomials (4.13),
// rom/database/probe_point_estimate.hpp; on scattered samples (4.14) below.
//
// Scattered samples (rbf, rom/offline/scattered_probes.hpp). The native-space bound
// |f − s|(x) ≤ P(x) |f|_N [Wen05, §11.1] puts the geometry of the samples into the power function
// P and the function into one scale. Each probe j measures that scale where it is,
// ε_j = e_j / P(x_j); the typical value at x is P(x) times their geometric mean, the upper value
// P(x) times the largest:
//
//     e(x) ≈ P(x) · exp( mean_j log ε_j ),     e⁺(x) = P(x) · max_j ε_j.                  (4.14)
//
// e is centred (geometric mean of e ÷ error 0.91–1.02 at 40 random points of the five-parameter
// box, on two databases) but not pointwise honest: at fixed P the error there still varies by a
// factor e^0.83…0.88 ≈ 2.3–2.4 (one standard deviation of log(e/P)), so half the points lie within
// [½, 2] of it — the spread of the error field itself, which no combination of distant
// measurements removed. e⁺ was at or above the error at 80 of 80 points (geometric mean 4.2 ×)
// (benchmarks/README.md "Held-out probes of a scattered database"). With Young's modulus handled
// exactly both live in the sampled axes, at E₀.
#pragma once

#include <utility>
#include <vector>

#include "rom/database/rom_database.hpp"

namespace mastrom::rom {

/// (ω₁ relative error, NRMSE of the relative end angular acceleration) of the default method at
/// `point` (all of the database's axes): (4.13) on a grid, e of (4.14) on scattered samples; {−1, −1}
/// when the database carries no probes.
std::pair<double, double> pointErrorEstimate(const RomDatabase& db, const std::vector<double>& point);

/// e⁺ of (4.14) on scattered samples: the (ω₁, response NRMSE) upper values at `point`; on a grid the
/// estimate (4.13) itself (never below ½ of the error in the measured boxes); {−1, −1} without
/// probes.
std::pair<double, double> pointErrorUpperEstimate(const RomDatabase& db,
                                                  const std::vector<double>& point);

}  // namespace mastrom::rom
