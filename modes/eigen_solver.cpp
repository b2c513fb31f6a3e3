// Validation, dispatch and the common finishing step of every backend (modes/eigen_solver.hpp).
#include "modes/eigen_solver.hpp"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "common/error.hpp"
#include "modes/eigen_backends.hpp"
#include "modes/mode_basis.hpp"

namespace mastrom::modes {
namespace {

constexpr double kTwoPi = 6.283185307179586;

bool allFinite(const SparseMatrix& a) {
  for (Eigen::Index k = 0; k < a.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(a, k); it; ++it)
      if (!std::isfinite(it.value())) return false;
  return true;
}

double maxAbs(const SparseMatrix& a) {
  double m = 0.0;
  for (Eigen::Index k = 0; k < a.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(a, k); it; ++it) m = std::max(m, std::abs(it.value()));
  return m;
}

/// Symmetric to round-off: max |a − aᵀ| ≤ 1e-8 · max |a|.
bool isSymmetric(const SparseMatrix& a) {
  const SparseMatrix diff = SparseMatrix(a.transpose()) - a;
  return maxAbs(diff) <= 1e-8 * maxAbs(a);
}

/// M-normalise each column: φ ← φ / √(φᵀMφ). Returns false if some φᵀMφ is not positive.
bool massNormalise(const SparseMatrix& mass, Eigen::MatrixXd& phi) {
  for (Eigen::Index j = 0; j < phi.cols(); ++j) {
    const Eigen::VectorXd m_phi = mass * phi.col(j);
    const double norm2 = phi.col(j).dot(m_phi);
    if (!(norm2 > 0.0) || !std::isfinite(norm2)) return false;
    phi.col(j) /= std::sqrt(norm2);
  }
  return true;
}

/// The common finish: Rayleigh–Ritz on the span of the backend's vectors. For accurate eigenvectors
/// it changes nothing but round-off, and it makes every backend's output M-orthonormal to machine
/// precision (purified Krylov vectors of a cluster are only orthogonal to the solver tolerance)
/// with Ritz values sorted ascending. Returns a message on failure, empty on success.
std::string finish(const ConstrainedEigenproblem& problem, detail::RawEigenpairs& raw,
                   EigenResult& out) {
  Eigen::MatrixXd phi = std::move(raw.vectors);
  const Eigen::Index k = phi.cols();
  if (k == 0) {
    out.eigenvalues_rad2_s2.resize(0);
    out.frequencies_hz.resize(0);
    out.modes.resize(problem.dofs(), 0);
    return {};
  }
  if (!massNormalise(problem.mass, phi))
    return "a returned vector has φᵀMφ ≤ 0 (M not positive on null(G)?)";

  Eigen::MatrixXd k_phi(phi.rows(), k), m_phi(phi.rows(), k);
  k_phi.noalias() = problem.stiffness * phi;
  m_phi.noalias() = problem.mass * phi;
  Eigen::MatrixXd k_r(k, k), m_r(k, k);
  k_r.noalias() = phi.transpose() * k_phi;
  m_r.noalias() = phi.transpose() * m_phi;
  Eigen::VectorXd ritz_values;
  Eigen::MatrixXd ritz_vectors;
  if (!detail::symmetricDefiniteEigen(k_r, m_r, ritz_values, ritz_vectors))
    return "Rayleigh–Ritz on the returned vectors failed (linearly dependent eigenvectors?)";

  out.modes.resize(phi.rows(), k);
  out.modes.noalias() = phi * ritz_vectors;
  if (!massNormalise(problem.mass, out.modes))
    return "Rayleigh–Ritz produced a vector with φᵀMφ ≤ 0";
  normaliseColumnSigns(out.modes);
  out.eigenvalues_rad2_s2 = ritz_values;
  out.frequencies_hz.resize(k);
  for (Eigen::Index j = 0; j < k; ++j) {
    const double lambda = out.eigenvalues_rad2_s2(j);
    out.frequencies_hz(j) = std::copysign(std::sqrt(std::abs(lambda)), lambda) / kTwoPi;
  }
  return {};
}

}  // namespace

void ConstrainedEigenproblem::validate() const {
  const Eigen::Index n = stiffness.rows();
  MASTROM_REQUIRE(n >= 1 && stiffness.cols() == n, InputError,
                  "eigenproblem: stiffness K must be square and non-empty, got ", stiffness.rows(),
                  "×", stiffness.cols());
  MASTROM_REQUIRE(mass.rows() == n && mass.cols() == n, InputError, "eigenproblem: mass M is ",
                  mass.rows(), "×", mass.cols(), " but K is ", n, "×", n);
  MASTROM_REQUIRE(constraint_jacobian.cols() == n, InputError,
                  "eigenproblem: constraint Jacobian G has ", constraint_jacobian.cols(),
                  " columns but K is ", n, "×", n);
  MASTROM_REQUIRE(constraint_jacobian.rows() < n, InputError, "eigenproblem: G has ",
                  constraint_jacobian.rows(), " rows for ", n,
                  " DOFs; need fewer constraints than DOFs");
  MASTROM_REQUIRE(allFinite(stiffness), InputError, "eigenproblem: K has a non-finite entry");
  MASTROM_REQUIRE(allFinite(mass), InputError, "eigenproblem: M has a non-finite entry");
  MASTROM_REQUIRE(allFinite(constraint_jacobian), InputError,
                  "eigenproblem: G has a non-finite entry");
  MASTROM_REQUIRE(isSymmetric(stiffness), InputError,
                  "eigenproblem: K is not symmetric (store both triangles)");
  MASTROM_REQUIRE(isSymmetric(mass), InputError,
                  "eigenproblem: M is not symmetric (store both triangles)");
}

void EigenSolverOptions::validate() const {
  MASTROM_REQUIRE(count >= 1, InputError, "eigen-solver option count = ", count, " must be ≥ 1");
  MASTROM_REQUIRE(std::isfinite(target_rad2_s2), InputError,
                  "eigen-solver option target = ", target_rad2_s2, " must be finite");
  MASTROM_REQUIRE(std::isfinite(tolerance) && tolerance > 0.0 && tolerance < 1.0, InputError,
                  "eigen-solver option tolerance = ", tolerance, " must be in (0, 1)");
  MASTROM_REQUIRE(max_iterations >= 1, InputError,
                  "eigen-solver option max_iterations = ", max_iterations, " must be ≥ 1");
  MASTROM_REQUIRE(subspace_dimension == 0 || subspace_dimension > count, InputError,
                  "eigen-solver option subspace_dimension = ", subspace_dimension,
                  " must be 0 (automatic) or > count = ", count);
}

std::string toString(EigenStatus status) {
  switch (status) {
    case EigenStatus::Converged:
      return "converged";
    case EigenStatus::NotConverged:
      return "not converged";
    case EigenStatus::Failed:
      return "failed";
  }
  return "?";
}

EigenResult solveConstrainedEigenproblem(const ConstrainedEigenproblem& problem,
                                         const EigenSolverOptions& options) {
  problem.validate();
  options.validate();
  const Eigen::Index free_dofs = problem.dofs() - problem.constraints();
  MASTROM_REQUIRE(options.count <= free_dofs, InputError,
                  "eigen-solver option count = ", options.count, " exceeds the ", free_dofs,
                  " unconstrained DOFs (n = ", problem.dofs(), ", m = ", problem.constraints(),
                  ")");

  EigenResult out;
  out.backend = options.backend;
  out.requested = options.count;
  const auto start = std::chrono::steady_clock::now();
  detail::RawEigenpairs raw;
  try {
    switch (options.backend) {
      case EigenBackendKind::Dense:
        raw = detail::solveDense(problem, options);
        break;
      case EigenBackendKind::Arpack:
        raw = detail::solveArpack(problem, options);
        break;
      case EigenBackendKind::Slepc:
        raw = detail::solveSlepc(problem, options);
        break;
    }
  } catch (const NumericalError& e) {
    raw = detail::RawEigenpairs{};
    raw.status = EigenStatus::Failed;
    raw.message = e.what();
  }
  out.status = raw.status;
  out.message = raw.message;
  out.iterations = raw.iterations;
  if (raw.status == EigenStatus::Failed) raw.vectors.resize(problem.dofs(), 0);
  const std::string finish_error = finish(problem, raw, out);
  if (!finish_error.empty()) {
    out.status = EigenStatus::Failed;
    out.message = finish_error;
    out.eigenvalues_rad2_s2.resize(0);
    out.frequencies_hz.resize(0);
    out.modes.resize(problem.dofs(), 0);
  }
  out.converged = static_cast<int>(out.eigenvalues_rad2_s2.size());
  out.solve_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

Eigen::VectorXd projectedResiduals(const ConstrainedEigenproblem& problem,
                                   const EigenResult& result) {
  const Eigen::Index k = result.modes.cols();
  MASTROM_REQUIRE(result.modes.rows() == problem.dofs() && result.eigenvalues_rad2_s2.size() == k,
                  InputError, "projectedResiduals: result does not match the problem size");
  const SparseMatrix& g = problem.constraint_jacobian;
  Eigen::SimplicialLDLT<SparseMatrix> ggt;
  if (g.rows() > 0) {
    const SparseMatrix gg = g * SparseMatrix(g.transpose());
    ggt.compute(gg);
    if (ggt.info() != Eigen::Success)
      throw NumericalError("projectedResiduals: G Gᵀ is singular (G rank-deficient)");
  }
  Eigen::VectorXd out(k);
  for (Eigen::Index j = 0; j < k; ++j) {
    const Eigen::VectorXd k_phi = problem.stiffness * result.modes.col(j);
    const Eigen::VectorXd m_phi = problem.mass * result.modes.col(j);
    const double lambda = result.eigenvalues_rad2_s2(j);
    Eigen::VectorXd r = k_phi - lambda * m_phi;
    if (g.rows() > 0) {
      const Eigen::VectorXd g_r = g * r;
      const Eigen::VectorXd y = ggt.solve(g_r);
      r.noalias() -= g.transpose() * y;
    }
    const double scale = std::max(k_phi.norm(), std::abs(lambda) * m_phi.norm());
    out(j) = scale > 0.0 ? r.norm() / scale : r.norm();
  }
  return out;
}

}  // namespace mastrom::modes
