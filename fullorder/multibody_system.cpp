// Building the multibody system: bodies, meshes, constraints and loads, then finalize() — force
// batches, reference state and mass matrix, the sparsity patterns of the iteration matrix and the
// Jacobian with their scatter maps, the rotation symmetry (see multibody_system.hpp). Forces and
// energies are in multibody_forces.cpp, constraints and the iteration matrix in
// multibody_assembly.cpp.
#include "fullorder/multibody_system.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <functional>
#include <utility>

#if MASTROM_HAVE_OPENMP
#include <omp.h>
#endif

#include "common/error.hpp"
#include "fullorder/block_rotation.hpp"
#include "fullorder/module_constraints.hpp"

namespace mastrom::fullorder {
namespace {

using Triplet = Eigen::Triplet<double>;

/// Position of entry (row, col) in the value array of a compressed CSC matrix (must exist).
int positionOf(const SparseMatrix& a, int row, int col) {
  const int* inner = a.innerIndexPtr();
  const int* begin = inner + a.outerIndexPtr()[col];
  const int* end = inner + a.outerIndexPtr()[col + 1];
  const int* it = std::lower_bound(begin, end, row);
  MASTROM_ASSERT(it != end && *it == row);
  return static_cast<int>(it - inner);
}

}  // namespace

// ============================================================================ building

void MultibodySystem::requireFinalized(const char* what) const {
  MASTROM_REQUIRE(finalized_, Error, "multibody system: ", what, " before finalize()");
}

int MultibodySystem::addRigidBody(const RigidModule& body, const Vec12& reference) {
  MASTROM_REQUIRE(!finalized_, Error, "multibody system: addRigidBody after finalize()");
  MASTROM_REQUIRE(node_reference_.empty(), Error,
                  "multibody system: every rigid body must be added before the first shell mesh");
  const int index = bodyCount();
  bodies_.push_back(body);
  body_reference_.push_back(reference);
  addConstraint(std::make_unique<ModuleConstraints>(body, bodyDofOffset(index)));
  return index;
}

int MultibodySystem::addShellMesh(const ShellMesh& mesh, const ShellSection& section,
                                  int gauss_order) {
  MASTROM_REQUIRE(!finalized_, Error, "multibody system: addShellMesh after finalize()");
  const int first = nodeCount();
  for (int k = 0; k < mesh.nodeCount(); ++k) {
    node_reference_.push_back(mesh.nodes[static_cast<size_t>(k)]);
    node_normal_.push_back(mesh.normals[static_cast<size_t>(k)]);
  }
  // Every element of a structured mesh has the same a × b parameter rectangle: one shape table.
  const auto table = makeShellShapeTable(mesh.side_a_m, mesh.side_b_m, gauss_order);
  for (int e = 0; e < mesh.elementCount(); ++e) {
    elements_.emplace_back(table, mesh.elementReference(e), section);
    element_damped_.push_back(section.damping_s > 0.0);
    std::array<int, 36> dofs{};
    for (int c = 0; c < 4; ++c) {
      // Node DOF offsets are final: no body can be added any more.
      const int node_offset = nodeDofOffset(first + mesh.elements[static_cast<size_t>(e)][c]);
      for (int k = 0; k < 9; ++k) dofs[static_cast<size_t>(9 * c + k)] = node_offset + k;
    }
    element_dofs_.push_back(dofs);
  }
  return first;
}

int MultibodySystem::addConstraint(std::unique_ptr<ConstraintBlock> block) {
  MASTROM_REQUIRE(!finalized_, Error, "multibody system: addConstraint after finalize()");
  MASTROM_REQUIRE(block != nullptr, Error, "multibody system: null constraint block");
  const int offset = n_constraints_;
  constraint_offset_.push_back(offset);
  n_constraints_ += block->size();
  constraints_.push_back(std::move(block));
  return offset;
}

void MultibodySystem::addLoad(std::unique_ptr<AppliedLoad> load) {
  MASTROM_REQUIRE(!finalized_, Error, "multibody system: addLoad after finalize()");
  MASTROM_REQUIRE(load != nullptr, Error, "multibody system: null load");
  loads_.push_back(std::move(load));
}

void MultibodySystem::setGravity(const Eigen::Vector3d& gravity_m_s2) {
  MASTROM_REQUIRE(gravity_m_s2.allFinite(), InputError,
                  "multibody system: gravity has a non-finite entry");
  gravity_ = gravity_m_s2;
  if (finalized_) gravity_force_ = mass_ * uniformField(gravity_);
}

void MultibodySystem::finalize() {
  MASTROM_REQUIRE(!finalized_, Error, "multibody system: finalize() called twice");
  checkDofRanges();
  buildForceBatches();
  assembleReferenceAndMass();
  std::vector<BoolMatrix> jac_struct, hess_struct;
  buildSparsityPatterns(jac_struct, hess_struct);
  buildScatterMaps(jac_struct, hess_struct);
  detectRotationSymmetry();
  finalized_ = true;
}

void MultibodySystem::checkDofRanges() const {
  const int n = dofCount();
  for (const auto& block : constraints_)
    for (int d : block->dofs())
      MASTROM_REQUIRE(d >= 0 && d < n, Error, "multibody system: constraint '", block->name(),
                      "' touches DOF ", d, " outside [0, ", n, ")");
  for (const auto& load : loads_)
    for (int d : load->dofs())
      MASTROM_REQUIRE(d >= 0 && d < n, Error, "multibody system: a load touches DOF ", d,
                      " outside [0, ", n, ")");
}

void MultibodySystem::buildForceBatches() {
  // Force batches: runs of consecutive elements that share a shape table (one per mesh).
  for (size_t first = 0; first < elements_.size();) {
    size_t last = first;
    while (last < elements_.size() &&
           elements_[last].shapeTable() == elements_[first].shapeTable())
      ++last;
    std::vector<const ShellElement*> members;
    std::vector<std::array<int, 36>> dofs;
    for (size_t k = first; k < last; ++k) {
      members.push_back(&elements_[k]);
      dofs.push_back(element_dofs_[k]);
    }
    force_batches_.emplace_back(members, dofs);
    first = last;
  }
  for (std::size_t b = 0; b < force_batches_.size(); ++b)
    for (int c = 0; c < force_batches_[b].chunkCount(); ++c)
      chunk_refs_.push_back({static_cast<int>(b), c});
  chunk_lanes_.assign(chunk_refs_.size() * ShellForceBatch::kChunkValues, 0.0);
}

void MultibodySystem::assembleReferenceAndMass() {
  const int n = dofCount();
  // Reference configuration.
  q_reference_.resize(n);
  for (int b = 0; b < bodyCount(); ++b)
    q_reference_.segment<12>(bodyDofOffset(b)) = body_reference_[static_cast<size_t>(b)];
  for (int k = 0; k < nodeCount(); ++k)
    q_reference_.segment<9>(nodeDofOffset(k)) = node_reference_[static_cast<size_t>(k)];

  // Mass matrix.
  {
    std::vector<Triplet> trip;
    for (int b = 0; b < bodyCount(); ++b) {
      const Mat12& mb = bodies_[static_cast<size_t>(b)].massMatrix();
      for (int j = 0; j < 12; ++j)
        for (int i = 0; i < 12; ++i)
          if (mb(i, j) != 0.0)
            trip.emplace_back(bodyDofOffset(b) + i, bodyDofOffset(b) + j, mb(i, j));
    }
    Mat36 me;
    for (int e = 0; e < elementCount(); ++e) {
      elements_[static_cast<size_t>(e)].mass(me);
      const auto& dofs = element_dofs_[static_cast<size_t>(e)];
      for (int j = 0; j < 36; ++j)
        for (int i = 0; i < 36; ++i)
          if (me(i, j) != 0.0)
            trip.emplace_back(dofs[static_cast<size_t>(i)], dofs[static_cast<size_t>(j)], me(i, j));
    }
    mass_.resize(n, n);
    mass_.setFromTriplets(trip.begin(), trip.end());
    mass_.makeCompressed();
  }
  gravity_force_ = mass_ * uniformField(gravity_);
  {
    const Eigen::VectorXd ux = uniformField(Eigen::Vector3d::UnitX());
    total_mass_ = ux.dot(mass_ * ux);
  }
}

void MultibodySystem::buildSparsityPatterns(std::vector<BoolMatrix>& jac_struct,
                                            std::vector<BoolMatrix>& hess_struct) {
  const int n = dofCount();
  const int m = constraintCount();
  // Pattern of H: body blocks, element blocks, constraint Jacobians (both sides) and Hessians, load
  // stiffnesses, and the whole diagonal.
  std::vector<Triplet> trip;
  for (int i = 0; i < n + m; ++i) trip.emplace_back(i, i, 0.0);
  for (int b = 0; b < bodyCount(); ++b)
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 12; ++i)
        trip.emplace_back(bodyDofOffset(b) + i, bodyDofOffset(b) + j, 0.0);
  for (const auto& dofs : element_dofs_)
    for (int j : dofs)
      for (int i : dofs) trip.emplace_back(i, j, 0.0);
  std::vector<Triplet> gtrip;
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const ConstraintBlock& block = *constraints_[k];
    jac_struct.push_back(block.jacobianStructure());
    hess_struct.push_back(block.hessianStructure());
    const auto& dofs = block.dofs();
    const BoolMatrix& js = jac_struct.back();
    const BoolMatrix& hs = hess_struct.back();
    MASTROM_REQUIRE(js.rows() == block.size() && js.cols() == block.localDofCount() &&
                        hs.rows() == block.localDofCount() && hs.cols() == block.localDofCount(),
                    Error, "multibody system: constraint '", block.name(),
                    "' has a bad structure size");
    for (int j = 0; j < block.localDofCount(); ++j) {
      for (int i = 0; i < block.size(); ++i) {
        if (!js(i, j)) continue;
        const int row = n + constraint_offset_[k] + i;
        trip.emplace_back(row, dofs[static_cast<size_t>(j)], 0.0);
        trip.emplace_back(dofs[static_cast<size_t>(j)], row, 0.0);
        gtrip.emplace_back(constraint_offset_[k] + i, dofs[static_cast<size_t>(j)], 0.0);
      }
      for (int i = 0; i < block.localDofCount(); ++i)
        if (hs(i, j))
          trip.emplace_back(dofs[static_cast<size_t>(i)], dofs[static_cast<size_t>(j)], 0.0);
    }
  }
  for (const auto& load : loads_) {
    if (!load->hasStiffness()) continue;
    for (int j : load->dofs())
      for (int i : load->dofs()) trip.emplace_back(i, j, 0.0);
  }
  h_pattern_.resize(n + m, n + m);
  h_pattern_.setFromTriplets(trip.begin(), trip.end());
  h_pattern_.makeCompressed();
  h_pattern_.coeffs().setZero();
  g_pattern_.resize(m, n);
  g_pattern_.setFromTriplets(gtrip.begin(), gtrip.end());
  g_pattern_.makeCompressed();
  g_pattern_.coeffs().setZero();
}

void MultibodySystem::buildScatterMaps(const std::vector<BoolMatrix>& jac_struct,
                                       const std::vector<BoolMatrix>& hess_struct) {
  const int n = dofCount();
  // Scatter maps.
  mass_in_h_.clear();
  for (int j = 0; j < mass_.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(mass_, j); it; ++it)
      mass_in_h_.push_back(positionOf(h_pattern_, static_cast<int>(it.row()), j));
  element_in_h_.assign(element_dofs_.size(), std::vector<int>(36 * 36));
  for (size_t e = 0; e < element_dofs_.size(); ++e)
    for (int j = 0; j < 36; ++j)
      for (int i = 0; i < 36; ++i)
        element_in_h_[e][static_cast<size_t>(36 * j + i)] =
            positionOf(h_pattern_, element_dofs_[e][static_cast<size_t>(i)],
                       element_dofs_[e][static_cast<size_t>(j)]);
  const size_t nb = constraints_.size();
  jac_in_h_.assign(nb, {});
  jact_in_h_.assign(nb, {});
  hess_in_h_.assign(nb, {});
  jac_in_g_.assign(nb, {});
  block_scratch_.assign(nb, {});
  for (size_t k = 0; k < nb; ++k) {
    const ConstraintBlock& block = *constraints_[k];
    const auto& dofs = block.dofs();
    const int rows = block.size(), cols = block.localDofCount();
    for (int j = 0; j < cols; ++j) {
      for (int i = 0; i < rows; ++i) {
        if (!jac_struct[k](i, j)) continue;
        const int row = n + constraint_offset_[k] + i;
        const int local = rows * j + i;
        jac_in_h_[k].local.push_back(local);
        jac_in_h_[k].position.push_back(positionOf(h_pattern_, row, dofs[static_cast<size_t>(j)]));
        jact_in_h_[k].local.push_back(local);
        jact_in_h_[k].position.push_back(positionOf(h_pattern_, dofs[static_cast<size_t>(j)], row));
        jac_in_g_[k].local.push_back(local);
        jac_in_g_[k].position.push_back(
            positionOf(g_pattern_, constraint_offset_[k] + i, dofs[static_cast<size_t>(j)]));
      }
      for (int i = 0; i < cols; ++i) {
        if (!hess_struct[k](i, j)) continue;
        hess_in_h_[k].local.push_back(cols * j + i);
        hess_in_h_[k].position.push_back(
            positionOf(h_pattern_, dofs[static_cast<size_t>(i)], dofs[static_cast<size_t>(j)]));
      }
    }
    BlockScratch& s = block_scratch_[k];
    s.q.resize(cols);
    s.qdot.resize(cols);
    s.lambda.resize(rows);
    s.out.resize(rows);
    s.jac.setZero(rows, cols);  // blocks write only their structural entries (constraint.hpp)
    s.hess.resize(cols, cols);
  }
  load_in_h_.assign(loads_.size(), {});
  load_scratch_.assign(loads_.size(), {});
  for (size_t k = 0; k < loads_.size(); ++k) {
    const AppliedLoad& load = *loads_[k];
    const int cols = load.localDofCount();
    BlockScratch& s = load_scratch_[k];
    s.q.resize(cols);
    s.out.resize(cols);
    if (!load.hasStiffness()) continue;
    s.hess.resize(cols, cols);
    for (int j = 0; j < cols; ++j)
      for (int i = 0; i < cols; ++i) {
        load_in_h_[k].local.push_back(cols * j + i);
        load_in_h_[k].position.push_back(positionOf(h_pattern_, load.dofs()[static_cast<size_t>(i)],
                                                    load.dofs()[static_cast<size_t>(j)]));
      }
  }
}

void MultibodySystem::detectRotationSymmetry() {
  rotation_symmetry_.triple_starts.clear();
  frame_block_ = -1;
  for (const auto& load : loads_)
    if (load->hasStiffness()) return;  // a load tangent need not turn with the system
  std::vector<int> starts;
  const int n = dofCount();
  for (int i = 0; i < n; i += 3) starts.push_back(i);  // every coordinate block is a 3-vector
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const ConstraintBlock& block = *constraints_[k];
    const std::optional<std::vector<int>> rows = block.rotatingRowTriples();
    if (!rows) return;
    if (block.isTimeDependent()) {
      if (frame_block_ >= 0) return;  // two drives could turn their frames differently
      frame_block_ = static_cast<int>(k);
    }
    for (int r : *rows) {
      MASTROM_REQUIRE(r >= 0 && r + 3 <= block.size(), Error, "multibody system: constraint '",
                      block.name(), "' declares a rotating row triple at ", r, " of ",
                      block.size(), " rows");
      starts.push_back(n + constraint_offset_[k] + r);
    }
  }
  rotation_symmetry_.triple_starts = std::move(starts);
}

double MultibodySystem::rotationAngle(double t) const {
  return frame_block_ >= 0 ? constraints_[static_cast<size_t>(frame_block_)]->frameAngle(t) : 0.0;
}

// ============================================================================ helpers

void MultibodySystem::gather(const ConstraintBlock& block, const ConstVec& q,
                             Eigen::VectorXd& out) const {
  const auto& dofs = block.dofs();
  for (size_t i = 0; i < dofs.size(); ++i) out[static_cast<Eigen::Index>(i)] = q[dofs[i]];
}

Eigen::VectorXd MultibodySystem::rotated(const ConstVec& q, const Eigen::Matrix3d& rotation) const {
  MASTROM_ASSERT(q.size() == dofCount());
  return rotateEveryBlock(q, rotation);
}

Eigen::VectorXd MultibodySystem::uniformField(const Eigen::Vector3d& v) const {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(dofCount());
  for (int b = 0; b < bodyCount(); ++b) {
    out.segment<3>(bodyDofOffset(b)) = v;      // r_i
    out.segment<3>(bodyDofOffset(b) + 3) = v;  // r_j
  }
  for (int k = 0; k < nodeCount(); ++k) out.segment<3>(nodeDofOffset(k)) = v;
  return out;
}

}  // namespace mastrom::fullorder
