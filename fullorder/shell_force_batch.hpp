// Internal forces (elastic + Kelvin–Voigt) of all shell elements of a mesh at once — the hot path
// of full-order time stepping (profile: about half of every step; docs/theory.md §2.2 for the
// physics).
//
// One element's point algebra is short, dependent scalar work (cross products, a norm, a division),
// which keeps a SIMD unit mostly idle. Here the element's per-point algebra (shellPointForce,
// shell_point_force.hpp — the one ShellElement's forces and tangents call) runs for kLanes elements
// side by side: the fields of a point are arrays over the elements ("lanes"), and the loop over the
// lanes that calls shellPointForce is vectorised, so every operation is one vector instruction
// over the lanes. Elements in one batch share a shape table (congruent elements, the normal case:
// one table per mesh); their reference geometry, thickness, modulus and damping may differ per
// lane. The kernel is compiled for the baseline ISA and, where the CPU has them, AVX2 + FMA (chosen
// once at run time), so the binary stays portable. Results equal ShellElement::elasticForce +
// dampingForce to round-off (the fields are summed in another basis and order;
// tests/fullorder/test_shell_force_batch.cpp); a lane's result does not depend on its neighbours.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "fullorder/shell_element.hpp"

namespace mastrom::fullorder {

class ShellForceBatch {
public:
  static constexpr int kLanes = 8;

  /// @param elements  elements sharing one shape table (InputError otherwise); not retained
  /// @param dofs      per element, the global indices of its 36 coordinates
  ShellForceBatch(const std::vector<const ShellElement*>& elements,
                  const std::vector<std::array<int, 36>>& dofs);

  int elementCount() const { return element_count_; }

  /// f[dofs_k[i]] −= F_k[i] + F_d,k[i] for every element k: q and q̇ are the global coordinate and
  /// velocity vectors the dof lists index. Throws NumericalError on a degenerate surface
  /// (|g_x × g_y| = 0 or not finite) with the element's index.
  void subtractInternalForces(const double* q, const double* qdot, double* f) const;

  /// The same work split by chunk (kLanes elements), for callers that spread chunks over threads:
  /// evaluateChunkForces only reads the batch, so any chunks may run at once; subtracting them in
  /// chunk order afterwards gives exactly subtractInternalForces' sums.
  static constexpr int kChunkValues = 36 * kLanes;  ///< doubles of one chunk's result
  int chunkCount() const { return static_cast<int>(chunks_.size()); }
  void evaluateChunkForces(int chunk, const double* q, const double* qdot, double* lanes) const;
  void subtractChunkForces(int chunk, const double* lanes, double* f) const;

  /// The per-element results, row k = F_k + F_d,k (36 values; for tests and the element benchmark).
  void internalForces(const double* q, const double* qdot, std::vector<double>& out) const;

private:
  /// Reference data of one point for kLanes lanes, lane index fastest (see the .cpp for the order).
  static constexpr int kPointFields = 12;  // D (6, symmetric), metric0 (3), curv0 (3)
  struct Chunk {
    int lanes = 0;          ///< real elements in this chunk (≤ kLanes)
    int first_element = 0;  ///< index of lane 0 in the constructor's order
    bool damped = false;    ///< some lane has μ ≠ 0: rates are read and used
    std::array<std::array<int, kLanes>, 36> dofs{};        ///< padding lanes repeat lane 0
    std::array<std::array<double, kLanes>, 3> material{};  ///< cm = E h, cb = E h³/12, μ
    std::vector<double> reference;                         ///< points × kPointFields × kLanes
  };
  void evaluateChunk(const Chunk& chunk, const double* q, const double* qdot,
                     double* f_lanes) const;

  std::shared_ptr<const ShellShapeTable> table_;
  /// The shape in the monomial basis the kernel works in (shell_force_batch.cpp, docs/theory.md
  /// §2.2): the nonzeros of the nodal-to-monomial map C, and per point the monomial derivatives.
  std::vector<double> transform_;
  std::vector<double> field_terms_;
  int element_count_ = 0;
  std::vector<Chunk> chunks_;
  bool use_avx2_ = false;
};

}  // namespace mastrom::fullorder
