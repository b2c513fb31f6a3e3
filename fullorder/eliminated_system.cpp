#include "fullorder/eliminated_system.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "common/error.hpp"
#include "fullorder/two_threads.hpp"

namespace mastrom::fullorder {
namespace {
using Triplet = Eigen::Triplet<double>;
}

EliminatedSystem::EliminatedSystem(MultibodySystem& full) : full_(full) {
  MASTROM_REQUIRE(full.isFinalized(), InputError, "eliminated system: finalize() the system first");
  const int n = full.dofCount(), m = full.constraintCount();
  const int first_node_dof = 12 * full.bodyCount();
  const Eigen::VectorXd q0 = full.referenceCoordinates();

  // Affine, time-independent rows: the Jacobian is the same at two unrelated states, and
  // Φ(q) − Φ_q q is the same constant b there too.
  Eigen::VectorXd q1 = q0;
  std::mt19937 gen(12345);
  std::uniform_real_distribution<double> ud(-0.1, 0.1);
  for (int i = 0; i < n; ++i) q1[i] += ud(gen);
  SparseMatrix g0, g1;
  Eigen::VectorXd phi0, phi1, phit;
  full.constraintJacobian(q0, 0.0, g0);
  full.constraintJacobian(q1, 0.0, g1);
  full.constraints(q0, 0.0, phi0);
  full.constraints(q1, 0.0, phi1);
  full.constraintTimeDerivative(q0, 0.0, phit);
  const SparseMatrix g0_rows = SparseMatrix(g0.transpose());  // column j = row j of Φ_q
  const SparseMatrix g1_rows = SparseMatrix(g1.transpose());
  const Eigen::VectorXd b0 = phi0 - g0 * q0, b1 = phi1 - g1 * q1;

  std::vector<char> is_slave(n, 0), is_master(n, 0), row_eliminated(m, 0);
  std::vector<std::vector<std::pair<int, double>>> slave_rows(n);  // slave → (master, coefficient)
  offset_ = Eigen::VectorXd::Zero(n);
  for (int r = 0; r < m; ++r) {
    if (phit[r] != 0.0) continue;
    const double scale = g0_rows.col(r).cwiseAbs().sum() + std::abs(b0[r]);
    if (scale == 0.0 || (g0_rows.col(r) - g1_rows.col(r)).norm() > 1e-13 * scale ||
        std::abs(b0[r] - b1[r]) > 1e-12 * scale)
      continue;
    // Choose the slave: a shell-node coordinate with a unit-size coefficient, not yet used.
    int slave = -1;
    double a_s = 0.0;
    bool masters_free = true;
    for (SparseMatrix::InnerIterator it(g0_rows, r); it; ++it) {
      const int j = static_cast<int>(it.row());
      if (it.value() == 0.0) continue;
      if (is_slave[j]) masters_free = false;
      if (slave < 0 && j >= first_node_dof && !is_master[j] && !is_slave[j] &&
          std::abs(std::abs(it.value()) - 1.0) < 1e-12) {
        slave = j;
        a_s = it.value();
      }
    }
    if (slave < 0) continue;
    // Every other coordinate of the row becomes a master; none may be a slave.
    for (SparseMatrix::InnerIterator it(g0_rows, r); it; ++it)
      if (static_cast<int>(it.row()) != slave && it.value() != 0.0 &&
          is_slave[static_cast<int>(it.row())])
        masters_free = false;
    if (!masters_free) continue;
    for (SparseMatrix::InnerIterator it(g0_rows, r); it; ++it) {
      const int j = static_cast<int>(it.row());
      if (j == slave || it.value() == 0.0) continue;
      is_master[j] = 1;
      slave_rows[slave].emplace_back(j, -it.value() / a_s);
    }
    offset_[slave] = -b0[r] / a_s;
    is_slave[slave] = 1;
    row_eliminated[r] = 1;
  }

  std::vector<int> reduced_index(n, -1);
  for (int j = 0; j < n; ++j)
    if (!is_slave[j]) {
      reduced_index[j] = static_cast<int>(kept_dofs_.size());
      kept_dofs_.push_back(j);
    }
  const int nr = static_cast<int>(kept_dofs_.size());
  std::vector<Triplet> t;
  for (int j = 0; j < n; ++j) {
    if (!is_slave[j]) {
      t.emplace_back(j, reduced_index[j], 1.0);
    } else {
      for (const auto& [master, coefficient] : slave_rows[j])
        t.emplace_back(j, reduced_index[master], coefficient);
    }
  }
  transformation_.resize(n, nr);
  transformation_.setFromTriplets(t.begin(), t.end());
  transformation_.makeCompressed();

  for (int r = 0; r < m; ++r)
    if (!row_eliminated[r]) kept_rows_.push_back(r);
  const int mr = static_cast<int>(kept_rows_.size());
  std::vector<Triplet> s;
  for (int i = 0; i < mr; ++i) s.emplace_back(i, kept_rows_[static_cast<std::size_t>(i)], 1.0);
  select_rows_.resize(mr, m);
  select_rows_.setFromTriplets(s.begin(), s.end());

  std::vector<Triplet> bt;
  for (int k = 0; k < transformation_.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(transformation_, k); it; ++it)
      bt.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
  for (int i = 0; i < mr; ++i) bt.emplace_back(n + kept_rows_[static_cast<std::size_t>(i)], nr + i, 1.0);
  block_map_.resize(n + m, nr + mr);
  block_map_.setFromTriplets(bt.begin(), bt.end());

  // G_r = S G T: pattern from the full pattern (unit values, no cancellation), then every product
  // term G(r, k)·T(k, j) of a kept row r as (position in G_r, position in G, T(k, j)).
  {
    SparseMatrix g_ones = g0;
    g_ones.coeffs().setOnes();
    SparseMatrix t_abs = transformation_;
    t_abs.coeffs() = t_abs.coeffs().cwiseAbs();
    g_reduced_pattern_ = SparseMatrix(select_rows_ * g_ones * t_abs);
    g_reduced_pattern_.makeCompressed();
    g_reduced_pattern_.coeffs().setZero();
    std::vector<int> kept_index(static_cast<std::size_t>(m), -1);
    for (int i = 0; i < mr; ++i)
      kept_index[static_cast<std::size_t>(kept_rows_[static_cast<std::size_t>(i)])] = i;
    const Eigen::SparseMatrix<double, Eigen::RowMajor> t_rows = transformation_;
    const int* g_inner = g0.innerIndexPtr();
    for (int k = 0; k < n; ++k) {
      for (int p = g0.outerIndexPtr()[k]; p < g0.outerIndexPtr()[k + 1]; ++p) {
        const int i = kept_index[static_cast<std::size_t>(g_inner[p])];
        if (i < 0) continue;
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(t_rows, k); it; ++it) {
          const int j = static_cast<int>(it.col());
          const int* inner = g_reduced_pattern_.innerIndexPtr();
          const int* begin = inner + g_reduced_pattern_.outerIndexPtr()[j];
          const int* end = inner + g_reduced_pattern_.outerIndexPtr()[j + 1];
          const int* pos = std::lower_bound(begin, end, i);
          MASTROM_ASSERT(pos != end && *pos == i);
          g_reduced_terms_.push_back({static_cast<int>(pos - inner), p, it.value()});
        }
      }
    }
  }

  mass_ = SparseMatrix(transformation_.transpose() * full.massMatrix() * transformation_);
  mass_.makeCompressed();
  // Structural pattern of H_r from the full pattern with unit values (no cancellation).
  SparseMatrix ones = full.iterationMatrixPattern();
  ones.coeffs().setOnes();
  SparseMatrix bt_abs = block_map_;
  bt_abs.coeffs() = bt_abs.coeffs().cwiseAbs();
  h_reduced_pattern_ = SparseMatrix(bt_abs.transpose() * ones * bt_abs);
  h_reduced_pattern_.makeCompressed();
  h_reduced_pattern_.coeffs().setZero();

  inheritRotationSymmetry(reduced_index);
}

void EliminatedSystem::inheritRotationSymmetry(const std::vector<int>& reduced_index) {
  // H_r = Bᵀ H B inherits the symmetry when the map commutes with the turn, B P_r = P B: every
  // rotating triple is kept whole (three consecutive reduced unknowns) or eliminated whole, and the
  // slaves follow their masters component by component (T = T̄ ⊗ I₃, d = 0).
  const RotationSymmetry* full_symmetry = full_.rotationSymmetry();
  if (full_symmetry == nullptr || offset_.cwiseAbs().maxCoeff() != 0.0) return;
  const int n = full_.dofCount(), nr = dofCount(), mr = constraintCount();
  std::vector<int> reduced_unknown(static_cast<std::size_t>(n + full_.constraintCount()), -1);
  for (int j = 0; j < n; ++j) reduced_unknown[static_cast<std::size_t>(j)] = reduced_index[j];
  for (int i = 0; i < mr; ++i)
    reduced_unknown[static_cast<std::size_t>(n + kept_rows_[static_cast<std::size_t>(i)])] = nr + i;
  RotationSymmetry reduced;
  for (int start : full_symmetry->triple_starts) {
    const int* r = &reduced_unknown[static_cast<std::size_t>(start)];
    if (r[0] < 0 && r[1] < 0 && r[2] < 0) continue;  // eliminated whole
    if (r[0] < 0 || r[1] != r[0] + 1 || r[2] != r[0] + 2) return;
    reduced.triple_starts.push_back(r[0]);
  }
  // Check B P_r x = P B x on a generic x rather than trusting the pattern analysis alone.
  std::mt19937 gen(4321);
  std::uniform_real_distribution<double> ud(-1.0, 1.0);
  Eigen::VectorXd x(nr + mr);
  for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = ud(gen);
  const double angle = 0.7;
  Eigen::VectorXd bx = block_map_ * x;
  full_symmetry->rotate(angle, bx);
  reduced.rotate(angle, x);
  const Eigen::VectorXd bpx = block_map_ * x;
  if ((bpx - bx).cwiseAbs().maxCoeff() > 1e-12 * (1.0 + bx.cwiseAbs().maxCoeff())) return;
  rotation_symmetry_ = std::move(reduced);
}

int EliminatedSystem::eliminatedCount() const {
  return static_cast<int>(transformation_.rows() - transformation_.cols());
}

Eigen::VectorXd EliminatedSystem::expandPositions(const Eigen::VectorXd& q_reduced) const {
  Eigen::VectorXd q = transformation_ * q_reduced;
  q += offset_;
  return q;
}

Eigen::VectorXd EliminatedSystem::expandRates(const Eigen::VectorXd& v_reduced) const {
  return transformation_ * v_reduced;
}

Eigen::VectorXd EliminatedSystem::restrict(const Eigen::VectorXd& full) const {
  Eigen::VectorXd r(static_cast<Eigen::Index>(kept_dofs_.size()));
  for (std::size_t j = 0; j < kept_dofs_.size(); ++j) r[static_cast<Eigen::Index>(j)] = full[kept_dofs_[j]];
  return r;
}

Eigen::VectorXd EliminatedSystem::expandMultipliers(const Eigen::VectorXd& lambda_reduced) const {
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(full_.constraintCount());
  for (std::size_t i = 0; i < kept_rows_.size(); ++i)
    lambda[kept_rows_[i]] = lambda_reduced[static_cast<Eigen::Index>(i)];
  return lambda;
}

namespace {
/// Bitwise equality (a cached expansion is reused only for exactly the same input).
bool sameBits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0;
}
}  // namespace

const Eigen::VectorXd& EliminatedSystem::fullPositions(Workspace& w, const Eigen::VectorXd& q) const {
  // Forces, Φ and Φ_q are asked for at the same iterate one after the other (three per Newton
  // iteration): expand it once.
  if (!sameBits(q, w.q_expanded_from)) {
    w.q_full.noalias() = transformation_ * q;
    w.q_full += offset_;
    w.q_expanded_from = q;
  }
  return w.q_full;
}

const Eigen::VectorXd& EliminatedSystem::fullRates(Workspace& w, const Eigen::VectorXd& v) const {
  if (!sameBits(v, w.v_expanded_from)) {
    w.v_full.noalias() = transformation_ * v;
    w.v_expanded_from = v;
  }
  return w.v_full;
}

void EliminatedSystem::selectKeptRows(const Workspace& w, Eigen::VectorXd& reduced) const {
  reduced.resize(static_cast<Eigen::Index>(kept_rows_.size()));
  for (std::size_t i = 0; i < kept_rows_.size(); ++i)
    reduced[static_cast<Eigen::Index>(i)] = w.phi_full[kept_rows_[i]];
}

void EliminatedSystem::forces(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot, double t,
                              Eigen::VectorXd& q_force) {
  // Into the work vectors: no allocation per Newton iteration.
  Workspace& w = work_[0];
  full_.forces(fullPositions(w, q), fullRates(w, qdot), t, w.f_full);
  q_force.noalias() = transformation_.transpose() * w.f_full;
}

void EliminatedSystem::constraints(const Eigen::VectorXd& q, double t, Eigen::VectorXd& phi) {
  Workspace& w = work_[0];
  full_.constraints(fullPositions(w, q), t, w.phi_full);
  selectKeptRows(w, phi);
}

void EliminatedSystem::constraintJacobian(const Eigen::VectorXd& q, double t, SparseMatrix& jac) {
  Workspace& w = work_[0];
  full_.constraintJacobian(fullPositions(w, q), t, w.g_full);
  reduceJacobian(w, jac);
}

void EliminatedSystem::evaluate(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot, double t,
                                Eigen::VectorXd& q_force, Eigen::VectorXd& phi, SparseMatrix& jac,
                                const std::function<void()>* side_work) {
  Workspace& w = work_[0];
  full_.forcesAndConstraints(fullPositions(w, q), fullRates(w, qdot), t, w.f_full, w.phi_full,
                             w.g_full, side_work);
  q_force.noalias() = transformation_.transpose() * w.f_full;
  selectKeptRows(w, phi);
  reduceJacobian(w, jac);
}

bool EliminatedSystem::evaluatesPairs() const {
#if MASTROM_HAVE_OPENMP
  return full_.threadCount() > 1;
#else
  return false;
#endif
}

void EliminatedSystem::evaluateInSlot(int slot, const Evaluation& e) {
  Workspace& w = work_[slot];
  full_.forcesAndConstraintsInSlot(slot, fullPositions(w, *e.q), fullRates(w, *e.qdot), e.t,
                                   w.f_full, w.phi_full, w.g_full);
  e.q_force->noalias() = transformation_.transpose() * w.f_full;
  selectKeptRows(w, *e.phi);
  reduceJacobian(w, *e.jac);
  if (e.then != nullptr) (*e.then)();
}

namespace {
/// Both halves of a pair, at once on two threads where `parallel`, else one after the other.
class BothHalves final : public PairRunner {
public:
  explicit BothHalves(bool parallel) : parallel_(parallel) {}
  bool secondThreadFree() const override { return true; }
  bool run(const std::function<void()>& first, const std::function<void()>& second) override {
    runOnTwoThreads(first, second, parallel_);
    return true;
  }

private:
  bool parallel_;
};
}  // namespace

bool EliminatedSystem::evaluatePair(const Evaluation& first, const Evaluation& second) {
  BothHalves both(evaluatesPairs());
  return evaluatePairOn(both, first, second);
}

bool EliminatedSystem::evaluatePairOn(PairRunner& runner, const Evaluation& first,
                                      const Evaluation& second) {
  // Each state entirely on one thread with its own scratch (slot 0: the caller's; slot 1: the
  // other thread's), so the values are those of evaluate() bit for bit.
  std::exception_ptr failures[2];
  const auto run = [&](int slot) {
    try {
      evaluateInSlot(slot, slot == 0 ? first : second);
    } catch (...) {
      failures[slot] = std::current_exception();
    }
  };
  const bool ran = runner.run([&] { run(0); }, [&] { run(1); });
  if (failures[0]) std::rethrow_exception(failures[0]);
  return ran && !failures[1];
}

void EliminatedSystem::reduceJacobian(const Workspace& w, SparseMatrix& jac) const {
  if (jac.rows() != g_reduced_pattern_.rows() || jac.cols() != g_reduced_pattern_.cols() ||
      jac.nonZeros() != g_reduced_pattern_.nonZeros() || !jac.isCompressed())
    jac = g_reduced_pattern_;
  double* values = jac.valuePtr();
  std::fill(values, values + jac.nonZeros(), 0.0);
  const double* g = w.g_full.valuePtr();
  for (const ProductTerm& term : g_reduced_terms_)
    values[term.target] += term.coefficient * g[term.source];
}

void EliminatedSystem::velocityConstraintRhs(const Eigen::VectorXd& q, double t,
                                             Eigen::VectorXd& rhs) {
  Workspace& w = work_[0];
  full_.velocityConstraintRhs(fullPositions(w, q), t, w.phi_full);
  selectKeptRows(w, rhs);
}

void EliminatedSystem::accelerationConstraintRhs(const Eigen::VectorXd& q,
                                                 const Eigen::VectorXd& qdot, double t,
                                                 Eigen::VectorXd& rhs) {
  Workspace& w = work_[0];
  full_.accelerationConstraintRhs(fullPositions(w, q), fullRates(w, qdot), t, w.phi_full);
  selectKeptRows(w, rhs);
}

void EliminatedSystem::iterationMatrix(const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                                       const Eigen::VectorXd& lambda, double t,
                                       const IterationCoefficients& coeffs, SparseMatrix& h) {
  Workspace& w = work_[0];
  full_.iterationMatrix(fullPositions(w, q), fullRates(w, qdot), expandMultipliers(lambda), t,
                        coeffs, h_full_);
  // Union with the fixed structural pattern, so the reduced pattern never changes between calls.
  h = h_reduced_pattern_ + SparseMatrix(block_map_.transpose() * h_full_ * block_map_);
}

}  // namespace mastrom::fullorder
