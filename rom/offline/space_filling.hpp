// Space-filling point sets of a parameter box, in the box-normalised coordinates u ∈ [0, 1]^p of
// the radial-basis interpolation (rom/interpolation/rbf_weights.hpp: log coordinates on axes of
// positive values): the Halton sequence [Hal60] (radical inverses in the first p primes), which
// fills the box evenly for any prefix length, and the box's corners.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace mastrom::rom {

/// Point `index` (≥ 0) of the p-dimensional Halton sequence; index 0 is the origin.
Eigen::VectorXd haltonPoint(long index, int p);

/// The 2^p corners of the unit box (empty when p > 16).
std::vector<Eigen::VectorXd> unitBoxCorners(int p);

}  // namespace mastrom::rom
