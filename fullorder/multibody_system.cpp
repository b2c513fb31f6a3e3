// Assembly of the multibody system (see multibody_system.hpp; docs/theory.md §5).
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

/// Whether `h` already carries the pattern of `pattern` (same shape and structure).
bool hasPattern(const SparseMatrix& h, const SparseMatrix& pattern) {
  return h.rows() == pattern.rows() && h.cols() == pattern.cols() && h.isCompressed() &&
         h.nonZeros() == pattern.nonZeros() &&
         std::equal(h.outerIndexPtr(), h.outerIndexPtr() + h.cols() + 1, pattern.outerIndexPtr()) &&
         std::equal(h.innerIndexPtr(), h.innerIndexPtr() + h.nonZeros(), pattern.innerIndexPtr());
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
  const int n = dofCount();
  const int m = constraintCount();
  for (const auto& block : constraints_)
    for (int d : block->dofs())
      MASTROM_REQUIRE(d >= 0 && d < n, Error, "multibody system: constraint '", block->name(),
                      "' touches DOF ", d, " outside [0, ", n, ")");
  for (const auto& load : loads_)
    for (int d : load->dofs())
      MASTROM_REQUIRE(d >= 0 && d < n, Error, "multibody system: a load touches DOF ", d,
                      " outside [0, ", n, ")");

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
  std::vector<BoolMatrix> jac_struct, hess_struct;
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
  detectRotationSymmetry();
  finalized_ = true;
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

// ============================================================================ forces, energies

void MultibodySystem::forces(const ConstVec& q, const ConstVec& qdot, double t, Eigen::VectorXd& f,
                             double load_scale) const {
  requireFinalized("forces()");
  const int n = dofCount();
  MASTROM_ASSERT(q.size() == n && qdot.size() == n);
  f.resize(n);
  f = load_scale * gravity_force_;
  subtractElementForces(q.data(), qdot.data(), f.data());
  addLoadForces(load_scratch_, q, t, load_scale, f);
}

void MultibodySystem::forcesAndConstraints(const ConstVec& q, const ConstVec& qdot, double t,
                                           Eigen::VectorXd& f, Eigen::VectorXd& phi,
                                           SparseMatrix& g,
                                           const std::function<void()>* side_work) const {
  requireFinalized("forcesAndConstraints()");
  const int n = dofCount();
  MASTROM_ASSERT(q.size() == n && qdot.size() == n);
  // The caller's side work, then Φ and Φ_q (their own scratch), on one thread while the element
  // chunks run on the others; the forces are then summed exactly as forces() sums them.
  const std::function<void()> constraint_work = [&] {
    if (side_work != nullptr) (*side_work)();
    constraints(q, t, phi);
    constraintJacobian(q, t, g);
  };
  evaluateElementChunks(q.data(), qdot.data(), &constraint_work, side_work != nullptr);
  f.resize(n);
  f = gravity_force_;
  subtractChunkResults(chunk_lanes_.data(), f.data());
  addLoadForces(load_scratch_, q, t, 1.0, f);
}

void MultibodySystem::forcesAndConstraintsInSlot(int slot, const ConstVec& q, const ConstVec& qdot,
                                                 double t, Eigen::VectorXd& f,
                                                 Eigen::VectorXd& phi, SparseMatrix& g) const {
  requireFinalized("forcesAndConstraintsInSlot()");
  MASTROM_REQUIRE(slot == 0 || slot == 1, Error, "multibody system: scratch slot ", slot,
                  " is not 0 or 1");
  const int n = dofCount();
  MASTROM_ASSERT(q.size() == n && qdot.size() == n);
  // The second set is made on its first use, i.e. on the thread that uses it: its memory then
  // comes from that thread's allocator arena instead of lying between the first set's small
  // vectors, where a cache line could hold data of both threads.
  if (slot == 1 && spare_.blocks.size() != block_scratch_.size())
    spare_ = {chunk_lanes_, block_scratch_, load_scratch_};
  std::vector<double>& lanes = slot == 0 ? chunk_lanes_ : spare_.chunk_lanes;
  std::vector<BlockScratch>& blocks = slot == 0 ? block_scratch_ : spare_.blocks;
  std::vector<BlockScratch>& loads = slot == 0 ? load_scratch_ : spare_.loads;
  // The chunks one by one into their own buffers, then summed in chunk order: the sums of
  // forcesAndConstraints() in the same order, so the values are the same bit for bit.
  for (std::size_t c = 0; c < chunk_refs_.size(); ++c) {
    const ChunkRef& ref = chunk_refs_[c];
    force_batches_[static_cast<std::size_t>(ref.batch)].evaluateChunkForces(
        ref.chunk, q.data(), qdot.data(), lanes.data() + c * ShellForceBatch::kChunkValues);
  }
  constraintsWith(blocks, q, t, phi);
  constraintJacobianWith(blocks, q, t, g);
  f.resize(n);
  f = gravity_force_;
  subtractChunkResults(lanes.data(), f.data());
  addLoadForces(loads, q, t, 1.0, f);
}

void MultibodySystem::addLoadForces(std::vector<BlockScratch>& scratch, const ConstVec& q,
                                    double t, double load_scale, Eigen::VectorXd& f) const {
  for (size_t k = 0; k < loads_.size(); ++k) {
    const AppliedLoad& load = *loads_[k];
    BlockScratch& s = scratch[k];
    for (int i = 0; i < load.localDofCount(); ++i) s.q[i] = q[load.dofs()[static_cast<size_t>(i)]];
    load.force(s.q, t, s.out);
    for (int i = 0; i < load.localDofCount(); ++i)
      f[load.dofs()[static_cast<size_t>(i)]] += load_scale * s.out[i];
  }
}

void MultibodySystem::subtractElementForces(const double* q, const double* qdot, double* f) const {
  evaluateElementChunks(q, qdot, nullptr, false);
  subtractChunkResults(chunk_lanes_.data(), f);
}

void MultibodySystem::evaluateElementChunks(const double* q, const double* qdot,
                                            const std::function<void()>* side_work,
                                            bool heavy_side_work) const {
  // Elastic and Kelvin–Voigt forces of all elements, several elements per SIMD pass
  // (ShellForceBatch; equal to ShellElement::internalForce to round-off). Every chunk goes into
  // its own buffer — on up to threads_ threads — and subtractChunkResults() subtracts the buffers
  // in chunk order: the same sums in the same order for any thread count and any assignment of
  // chunks to threads, so results are bit-identical.
  const int chunks = static_cast<int>(chunk_refs_.size());
  double* lanes = chunk_lanes_.data();
  std::exception_ptr failure, side_failure;
  int failed_chunk = chunks;
  const auto run_chunk = [&](int c) {
    try {
      const ChunkRef& ref = chunk_refs_[static_cast<std::size_t>(c)];
      force_batches_[static_cast<std::size_t>(ref.batch)].evaluateChunkForces(
          ref.chunk, q, qdot, lanes + static_cast<std::size_t>(c) * ShellForceBatch::kChunkValues);
    } catch (...) {
#if MASTROM_HAVE_OPENMP
#pragma omp critical(mastrom_element_forces)
#endif
      if (c < failed_chunk) {  // report the first failing chunk, whatever the thread timing
        failed_chunk = c;
        failure = std::current_exception();
      }
    }
  };
  const auto run_side_work = [&] {
    try {
      (*side_work)();
    } catch (...) {
      side_failure = std::current_exception();
    }
  };
#if MASTROM_HAVE_OPENMP
  if (side_work != nullptr && threads_ > 1) {
    // The side work first on one thread, which then joins the others on the remaining chunks.
#pragma omp parallel num_threads(threads_)
    {
      // A fixed assignment (a chunk's reference data stays in one core's cache from call to
      // call): thread 0 runs the side work and one chunk less than an even share — none after
      // heavy side work (an index-1 recovery takes about as long as the other thread's chunks on
      // Scheme 3: 0.119 against 0.123 ms per step with one chunk) — the others split the rest.
      const int threads = omp_get_num_threads(), id = omp_get_thread_num();
      const int first_share =
          threads == 1 ? chunks : (heavy_side_work ? 0 : std::max(0, chunks / threads - 1));
      int begin = 0, end = 0;
      if (id == 0) {
        run_side_work();
        begin = chunks - first_share;
        end = chunks;
      } else {
        const int rest = chunks - first_share, others = threads - 1;
        begin = rest * (id - 1) / others;
        end = rest * id / others;
      }
      for (int c = begin; c < end; ++c) run_chunk(c);
    }
  } else {
    if (side_work != nullptr) run_side_work();
#pragma omp parallel for num_threads(threads_) schedule(static) if (threads_ > 1 && chunks > 1)
    for (int c = 0; c < chunks; ++c) run_chunk(c);
  }
#else
  if (side_work != nullptr) run_side_work();
  for (int c = 0; c < chunks; ++c) run_chunk(c);
#endif
  if (side_failure) std::rethrow_exception(side_failure);
  if (failure) std::rethrow_exception(failure);
}

void MultibodySystem::subtractChunkResults(const double* lanes, double* f) const {
  const int chunks = static_cast<int>(chunk_refs_.size());
  for (int c = 0; c < chunks; ++c) {
    const ChunkRef& ref = chunk_refs_[static_cast<std::size_t>(c)];
    force_batches_[static_cast<std::size_t>(ref.batch)].subtractChunkForces(
        ref.chunk, lanes + static_cast<std::size_t>(c) * ShellForceBatch::kChunkValues, f);
  }
}

void MultibodySystem::setThreadCount(int threads) {
  MASTROM_REQUIRE(threads >= 1, InputError, "threads = ", threads, " must be >= 1");
  threads_ = threads;  // built without OpenMP, the loop runs on the calling thread regardless
}

void MultibodySystem::addConstraintForces(const ConstVec& q, const ConstVec& lambda, double t,
                                          Eigen::VectorXd& f) const {
  requireFinalized("addConstraintForces()");
  MASTROM_ASSERT(f.size() == dofCount() && lambda.size() == constraintCount());
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const ConstraintBlock& block = *constraints_[k];
    BlockScratch& s = block_scratch_[k];
    gather(block, q, s.q);
    block.jacobian(s.q, t, s.jac);
    s.qdot.noalias() = s.jac.transpose() * lambda.segment(constraint_offset_[k], block.size());
    for (int i = 0; i < block.localDofCount(); ++i)
      f[block.dofs()[static_cast<size_t>(i)]] += s.qdot[i];
  }
}

double MultibodySystem::kineticEnergy(const ConstVec& qdot) const {
  requireFinalized("kineticEnergy()");
  return 0.5 * qdot.dot(mass_ * qdot);
}

double MultibodySystem::strainEnergy(const ConstVec& q) const {
  requireFinalized("strainEnergy()");
  double u = 0.0;
  Vec36 e;
  for (size_t k = 0; k < elements_.size(); ++k) {
    for (int i = 0; i < 36; ++i) e[i] = q[element_dofs_[k][static_cast<size_t>(i)]];
    u += elements_[k].strainEnergy(e);
  }
  return u;
}

double MultibodySystem::gravityPotential(const ConstVec& q) const {
  requireFinalized("gravityPotential()");
  return -gravity_force_.dot(q);
}

double MultibodySystem::dampingPower(const ConstVec& q, const ConstVec& qdot) const {
  requireFinalized("dampingPower()");
  double p = 0.0;
  Vec36 e, edot, fe;
  for (size_t k = 0; k < elements_.size(); ++k) {
    if (!element_damped_[k]) continue;
    for (int i = 0; i < 36; ++i) {
      e[i] = q[element_dofs_[k][static_cast<size_t>(i)]];
      edot[i] = qdot[element_dofs_[k][static_cast<size_t>(i)]];
    }
    elements_[k].dampingForce(e, edot, fe);
    p += edot.dot(fe);
  }
  return p;
}

// ============================================================================ constraints

void MultibodySystem::constraints(const ConstVec& q, double t, Eigen::VectorXd& phi) const {
  requireFinalized("constraints()");
  constraintsWith(block_scratch_, q, t, phi);
}

void MultibodySystem::constraintsWith(std::vector<BlockScratch>& scratch, const ConstVec& q,
                                      double t, Eigen::VectorXd& phi) const {
  phi.resize(constraintCount());
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const ConstraintBlock& block = *constraints_[k];
    BlockScratch& s = scratch[k];
    gather(block, q, s.q);
    block.evaluate(s.q, t, phi.segment(constraint_offset_[k], block.size()));
  }
}

void MultibodySystem::constraintJacobian(const ConstVec& q, double t, SparseMatrix& g) const {
  requireFinalized("constraintJacobian()");
  constraintJacobianWith(block_scratch_, q, t, g);
}

void MultibodySystem::constraintJacobianWith(std::vector<BlockScratch>& scratch, const ConstVec& q,
                                             double t, SparseMatrix& g) const {
  if (!hasPattern(g, g_pattern_)) g = g_pattern_;
  double* values = g.valuePtr();
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const ConstraintBlock& block = *constraints_[k];
    BlockScratch& s = scratch[k];
    gather(block, q, s.q);
    block.jacobian(s.q, t, s.jac);
    const Scatter& sc = jac_in_g_[k];
    for (size_t i = 0; i < sc.local.size(); ++i) values[sc.position[i]] = s.jac.data()[sc.local[i]];
  }
}

void MultibodySystem::constraintTimeDerivative(const ConstVec& q, double t,
                                               Eigen::VectorXd& phi_t) const {
  requireFinalized("constraintTimeDerivative()");
  phi_t.setZero(constraintCount());
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const ConstraintBlock& block = *constraints_[k];
    if (!block.isTimeDependent()) continue;
    BlockScratch& s = block_scratch_[k];
    gather(block, q, s.q);
    block.timeDerivative(s.q, t, phi_t.segment(constraint_offset_[k], block.size()));
  }
}

void MultibodySystem::constraintSecondTimeDerivative(const ConstVec& q, double t,
                                                     Eigen::VectorXd& phi_tt) const {
  requireFinalized("constraintSecondTimeDerivative()");
  phi_tt.setZero(constraintCount());
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const ConstraintBlock& block = *constraints_[k];
    if (!block.isTimeDependent()) continue;
    BlockScratch& s = block_scratch_[k];
    gather(block, q, s.q);
    block.secondTimeDerivative(s.q, t, phi_tt.segment(constraint_offset_[k], block.size()));
  }
}

void MultibodySystem::constraintVelocityTerm(const ConstVec& q, const ConstVec& qdot, double t,
                                             Eigen::VectorXd& gamma) const {
  requireFinalized("constraintVelocityTerm()");
  gamma.resize(constraintCount());
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const ConstraintBlock& block = *constraints_[k];
    BlockScratch& s = block_scratch_[k];
    gather(block, q, s.q);
    gather(block, qdot, s.qdot);
    block.velocityTerm(s.q, s.qdot, t, gamma.segment(constraint_offset_[k], block.size()));
  }
}

// ============================================================================ iteration matrix

void MultibodySystem::assembleIterationMatrix(const ConstVec& q, const ConstVec& qdot,
                                              const ConstVec& lambda, double t,
                                              const IterationCoefficients& coeffs, SparseMatrix& h,
                                              double load_scale) const {
  assemble(q, qdot, lambda, t, coeffs, load_scale, nullptr, h);
}

void MultibodySystem::assembleForcesAndIterationMatrix(const ConstVec& q, const ConstVec& qdot,
                                                       const ConstVec& lambda, double t,
                                                       const IterationCoefficients& coeffs,
                                                       Eigen::VectorXd& f, SparseMatrix& h,
                                                       double load_scale) const {
  assemble(q, qdot, lambda, t, coeffs, load_scale, &f, h);
}

void MultibodySystem::assemble(const ConstVec& q, const ConstVec& qdot, const ConstVec& lambda,
                               double t, const IterationCoefficients& coeffs, double load_scale,
                               Eigen::VectorXd* f, SparseMatrix& h) const {
  requireFinalized("iteration matrix assembly");
  const int n = dofCount();
  MASTROM_ASSERT(q.size() == n && qdot.size() == n && lambda.size() == constraintCount());
  if (!hasPattern(h, h_pattern_)) h = h_pattern_;
  double* values = h.valuePtr();
  std::fill(values, values + h.nonZeros(), 0.0);
  if (f != nullptr) {
    f->resize(n);
    *f = load_scale * gravity_force_;
  }
  const double cm = coeffs.mass, cd = coeffs.damping, ck = coeffs.stiffness;
  const double sigma = coeffs.constraint_scale;

  // c_m M
  if (cm != 0.0) {
    const double* mv = mass_.valuePtr();
    for (size_t i = 0; i < mass_in_h_.size(); ++i) values[mass_in_h_[i]] += cm * mv[i];
  }

  // Elements: c_k (K_t + K_d) + c_d C_t, and −F_elastic − F_damping.
  Vec36 e, edot, fe, fd;
  Mat36 ke, ce, kd;
  for (size_t k = 0; k < elements_.size(); ++k) {
    const auto& dofs = element_dofs_[k];
    for (int i = 0; i < 36; ++i) e[i] = q[dofs[static_cast<size_t>(i)]];
    const bool damped = element_damped_[k] && (f != nullptr || ck != 0.0 || cd != 0.0);
    const bool need_k = ck != 0.0;
    bool have_block = false;  // ke holds this element's contribution to H
    if (need_k) {
      elements_[k].elasticForceAndTangent(e, fe, ke);
      ke *= ck;
      have_block = true;
    } else if (f != nullptr) {
      elements_[k].elasticForce(e, fe);
    }
    if (damped) {
      for (int i = 0; i < 36; ++i) edot[i] = qdot[dofs[static_cast<size_t>(i)]];
      elements_[k].dampingForceAndTangents(e, edot, fd, ce, kd);
      if (need_k) ke.noalias() += ck * kd;
      if (cd != 0.0) {
        if (have_block) {
          ke.noalias() += cd * ce;
        } else {
          ke.noalias() = cd * ce;
          have_block = true;
        }
      }
    }
    if (have_block) {
      const std::vector<int>& pos = element_in_h_[k];
      const double* kv = ke.data();
      for (size_t i = 0; i < 36 * 36; ++i) values[pos[i]] += kv[i];
    }
    if (f != nullptr) {
      for (int i = 0; i < 36; ++i) (*f)[dofs[static_cast<size_t>(i)]] -= fe[i];
      if (damped)
        for (int i = 0; i < 36; ++i) (*f)[dofs[static_cast<size_t>(i)]] -= fd[i];
    }
  }

  // Constraints: σ Φ_q, σ Φ_qᵀ, c_k (Φ_qᵀλ)_q.
  for (size_t k = 0; k < constraints_.size(); ++k) {
    const ConstraintBlock& block = *constraints_[k];
    BlockScratch& s = block_scratch_[k];
    gather(block, q, s.q);
    block.jacobian(s.q, t, s.jac);
    const Scatter& sj = jac_in_h_[k];
    const Scatter& st = jact_in_h_[k];
    const double* jv = s.jac.data();
    for (size_t i = 0; i < sj.local.size(); ++i) {
      values[sj.position[i]] += sigma * jv[sj.local[i]];
      values[st.position[i]] += sigma * jv[st.local[i]];
    }
    if (ck != 0.0 && block.hasHessianTerm()) {
      s.lambda = lambda.segment(constraint_offset_[k], block.size());
      block.hessianTerm(s.q, s.lambda, t, s.hess);
      const Scatter& sh = hess_in_h_[k];
      const double* hv = s.hess.data();
      for (size_t i = 0; i < sh.local.size(); ++i) values[sh.position[i]] += ck * hv[sh.local[i]];
    }
  }

  // Applied loads: Q and −c_k s K_load.
  for (size_t k = 0; k < loads_.size(); ++k) {
    const AppliedLoad& load = *loads_[k];
    BlockScratch& s = load_scratch_[k];
    for (int i = 0; i < load.localDofCount(); ++i) s.q[i] = q[load.dofs()[static_cast<size_t>(i)]];
    if (f != nullptr) {
      load.force(s.q, t, s.out);
      for (int i = 0; i < load.localDofCount(); ++i)
        (*f)[load.dofs()[static_cast<size_t>(i)]] += load_scale * s.out[i];
    }
    if (ck != 0.0 && load.hasStiffness()) {
      load.stiffness(s.q, t, s.hess);
      const Scatter& sl = load_in_h_[k];
      const double* lv = s.hess.data();
      for (size_t i = 0; i < sl.local.size(); ++i)
        values[sl.position[i]] -= ck * load_scale * lv[sl.local[i]];
    }
  }
}

// ============================================================================ DaeSystem

void MultibodySystem::forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot, double t,
                             Eigen::VectorXd& q_force) {
  std::as_const(*this).forces(q, qdot, t, q_force, 1.0);
}

void MultibodySystem::constraints(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi) {
  std::as_const(*this).constraints(q, t, phi);
}

void MultibodySystem::evaluate(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot, double t,
                               Eigen::VectorXd& q_force, Eigen::VectorXd& phi, SparseMatrix& jac,
                               const std::function<void()>* side_work) {
  forcesAndConstraints(q, qdot, t, q_force, phi, jac, side_work);
}

void MultibodySystem::constraintJacobian(const Eigen::VectorXd& q, double t, SparseMatrix& jac) {
  std::as_const(*this).constraintJacobian(q, t, jac);
}

void MultibodySystem::velocityConstraintRhs(const Eigen::VectorXd& q, double t,
                                            Eigen::VectorXd& rhs) {
  constraintTimeDerivative(q, t, rhs);
  rhs = -rhs;
}

void MultibodySystem::accelerationConstraintRhs(const Eigen::VectorXd& q,
                                                const Eigen::VectorXd& qdot, double t,
                                                Eigen::VectorXd& rhs) {
  Eigen::VectorXd phi_tt;
  constraintVelocityTerm(q, qdot, t, rhs);
  constraintSecondTimeDerivative(q, t, phi_tt);
  rhs = -(rhs + phi_tt);
}

void MultibodySystem::iterationMatrix(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                                      const Eigen::VectorXd& lambda, double t,
                                      const IterationCoefficients& coeffs, SparseMatrix& h) {
  assembleIterationMatrix(q, qdot, lambda, t, coeffs, h, 1.0);
}

}  // namespace mastrom::fullorder
