// Small constrained eigenproblems with known answers, shared by the modes tests.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "modes/eigen_solver.hpp"

namespace mastrom::modes::test_models {

/// Fixed–free chain: nodes 0 … N, node i (i ≥ 1) of mass m joined to node i−1 by a spring k. Node 0
/// carries no mass (M is only semidefinite) and is held by the constraint row x₀ = 0 of G (not by
/// deleting the DOF), so K is the singular free–free chain stiffness. Exact constrained
/// frequencies:
///     ω_j = 2 √(k/m) sin((2j − 1) π / (2 (2N + 1))),  j = 1 … N.
ConstrainedEigenproblem fixedFreeChain(int masses, double mass_kg, double stiffness_n_m);
/// ω_j [rad/s] of fixedFreeChain, j = 1 … count.
Eigen::VectorXd fixedFreeChainOmegas(int masses, double mass_kg, double stiffness_n_m, int count);

/// A 3-D lattice tower: `storeys` storeys of a square truss (side 1 m, storey height 0.8 m; square
/// edges, verticals, one diagonal per face and one horizontal diagonal per level as axial springs
/// EA/L e eᵀ), lumped node masses with a deterministic ±20 % spread plus consistent bar masses. The
/// constraints mix kinds: the four base nodes pinned (12 rows), a rigid link along the top square's
/// second diagonal, a tie u_x(a) = u_x(b) between two nodes, a slider (no motion of a mid-height
/// node along an inclined direction), and a multi-point constraint u_y(a) = ½(u_y(b) + u_y(c)). The
/// irregular masses split the symmetric bending pairs, so the lowest modes are simple.
ConstrainedEigenproblem latticeTower(int storeys);

}  // namespace mastrom::modes::test_models
