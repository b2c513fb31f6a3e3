// Forces and energies of the multibody system: element forces in chunks over threads, summed in
// a fixed order (bit-identical for any thread count; docs/architecture.md), loads, constraint
// forces, and the energies of the energy balance (see multibody_system.hpp).
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

namespace mastrom::fullorder {

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

}  // namespace mastrom::fullorder
