// ARPACK backend (docs/theory.md §3): implicitly restarted Lanczos in mode 3 (bmat "G", which
// "LM", shift-invert about σ) with the shifted saddle matrix factored once by Eigen's SparseLU
// (pivoting is needed: the (2,2) block is zero).
//
// The operator of the saddle pencil A = [K Gᵀ; G 0], B = [M 0; 0 0] is OP = (A − σB)⁻¹ B. Because B
// annihilates the multiplier block, OP x depends only on the displacement part u of x, and its
// displacement part is
//     S(σ) M u,   S(σ) = first block of (A − σB)⁻¹ restricted to [· ; 0] = Z (Zᵀ(K − σM)Z)⁻¹ Zᵀ
// (Z any basis of null(G)). So we run ARPACK on R^n with B = M and OP = S(σ) M: the same Krylov
// spaces as on the (n + m) pencil with the (never used) multiplier entries dropped. S(σ) is
// symmetric and maps into null(G), where M is positive definite, so OP is M-self-adjoint as dsaupd
// requires. M may still be singular on R^n; ARPACK's own remedy (the starting vector is forced into
// range(OP), ido = −1) keeps every Lanczos vector in null(G). On exit each Ritz vector is purified
// by one more application of OP (Ericsson & Ruhe 1980; Nour-Omid, Parlett, Ericsson & Jensen 1987),
// which removes any component outside range(OP) and gains one inverse-iteration step of accuracy;
// the common finish (eigen_solver.cpp) then M-normalises. ARPACK keeps state in Fortran SAVE
// variables: one solve at a time per process (not thread-safe).
#include <arpack/arpack.h>

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "modes/eigen_backends.hpp"

namespace mastrom::modes::detail {
namespace {

std::string dsaupdError(a_int info) {
  switch (info) {
    case -1:
      return "N must be positive";
    case -2:
      return "NEV must be positive";
    case -3:
      return "NCV must satisfy NEV < NCV ≤ N";
    case -4:
      return "the maximum number of iterations must be positive";
    case -5:
      return "WHICH is invalid";
    case -6:
      return "BMAT is invalid";
    case -7:
      return "the private work array WORKL is too short";
    case -8:
      return "error in the LAPACK tridiagonal eigenvalue computation";
    case -9:
      return "the starting vector is zero";
    case -10:
      return "IPARAM(7) (mode) is invalid";
    case -11:
      return "mode 1 is incompatible with BMAT = G";
    case -12:
      return "IPARAM(1) (shift strategy) is invalid";
    case -13:
      return "NEV and WHICH = BE are incompatible";
    case -9999:
      return "could not build a Lanczos factorisation (OP too small a range?)";
    default:
      return ::mastrom::detail::concat("ARPACK error ", info);
  }
}

std::string dseupdError(a_int info) {
  switch (info) {
    case -14:
      return "dsaupd did not find any eigenvalues to sufficient accuracy";
    case -17:
      return "dseupd got a different count of converged Ritz values than dsaupd";
    default:
      return dsaupdError(info);
  }
}

/// y = S(σ) r: the displacement block of (A − σB)⁻¹ [r; 0], one SparseLU factorisation for all
/// solves.
class ShiftInvert {
public:
  ShiftInvert(const ConstrainedEigenproblem& problem, double sigma)
      : n_(problem.dofs()), work_(problem.dofs() + problem.constraints()) {
    const SparseMatrix shifted = saddleMatrix(problem, sigma, constraintScale(problem, sigma));
    lu_.analyzePattern(shifted);
    lu_.factorize(shifted);
    if (lu_.info() != Eigen::Success) error_ = lu_.lastErrorMessage();
  }
  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }

  void apply(const double* rhs, double* out) {
    work_.head(n_) = Eigen::Map<const Eigen::VectorXd>(rhs, n_);
    work_.tail(work_.size() - n_).setZero();
    const Eigen::VectorXd solution = lu_.solve(work_);
    Eigen::Map<Eigen::VectorXd>(out, n_) = solution.head(n_);
  }

private:
  Eigen::Index n_;
  Eigen::VectorXd work_;
  Eigen::SparseLU<SparseMatrix> lu_;
  std::string error_;
};

}  // namespace

RawEigenpairs solveArpack(const ConstrainedEigenproblem& problem,
                          const EigenSolverOptions& options) {
  const Eigen::Index n = problem.dofs();
  const double sigma = options.target_rad2_s2;
  const SparseMatrix& mass = problem.mass;
  RawEigenpairs raw;

  const auto nn = static_cast<a_int>(n);
  const auto nev = static_cast<a_int>(options.count);
  const auto ncv = static_cast<a_int>(subspaceDimension(options, n - problem.constraints()));
  if (nev >= ncv) {  // dsaupd needs NEV < NCV, and NCV ≤ n − m (the dimension of null(G))
    raw.message = ::mastrom::detail::concat("arpack: needs count < n − m, got count = ", nev,
                                            ", n − m = ", n - problem.constraints(),
                                            "; use the dense backend for such small models");
    return raw;
  }

  ShiftInvert op(problem, sigma);
  if (!op.ok()) {
    raw.message = ::mastrom::detail::concat(
        "arpack: SparseLU of the shifted saddle matrix [K − σM, Gᵀ; G, 0] failed (σ = ", sigma,
        " an eigenvalue, or G rank-deficient?): ", op.error());
    return raw;
  }

  // Deterministic starting vector (ARPACK's own random start advances a hidden seed between calls,
  // which would make repeated solves differ in the last digits).
  std::vector<double> resid(static_cast<std::size_t>(n));
  std::mt19937 generator(20240117u);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (double& r : resid) r = uniform(generator);

  std::vector<double> v(static_cast<std::size_t>(n) * static_cast<std::size_t>(ncv));
  std::vector<double> workd(3 * static_cast<std::size_t>(n));
  const a_int lworkl = ncv * (ncv + 8);
  std::vector<double> workl(static_cast<std::size_t>(lworkl));
  a_int iparam[11] = {};
  iparam[0] = 1;                       // exact shifts
  iparam[2] = options.max_iterations;  // maximum Arnoldi update iterations
  iparam[6] = 3;                       // mode 3: shift-invert
  a_int ipntr[11] = {};
  a_int ido = 0;
  a_int info = 1;  // use resid as the starting vector
  Eigen::VectorXd scratch(n);

  for (;;) {
    dsaupd_c(&ido, "G", nn, "LM", nev, options.tolerance, resid.data(), ncv, v.data(), nn, iparam,
             ipntr, workd.data(), workl.data(), lworkl, &info);
    if (ido != -1 && ido != 1 && ido != 2) break;  // 99: done (or an error in info)
    // ipntr holds Fortran (1-based) offsets into workd: x = operand, y = result, bx = B x.
    const double* x = workd.data() + (ipntr[0] - 1);
    double* y = workd.data() + (ipntr[1] - 1);
    if (ido == -1) {  // y = OP x, from scratch
      scratch.noalias() = mass * Eigen::Map<const Eigen::VectorXd>(x, n);
      op.apply(scratch.data(), y);
    } else if (ido == 1) {  // y = OP x with B x already computed
      op.apply(workd.data() + (ipntr[2] - 1), y);
    } else {  // y = B x
      Eigen::Map<Eigen::VectorXd>(y, n).noalias() = mass * Eigen::Map<const Eigen::VectorXd>(x, n);
    }
  }
  // iparam(3) is the update-iteration counter, which dsaup2 increments once past the limit before
  // stopping: report at most the limit.
  raw.iterations = std::min(static_cast<int>(iparam[2]), options.max_iterations);
  if (info < 0) {
    raw.message = "arpack: dsaupd failed: " + dsaupdError(info);
    return raw;
  }
  const bool all_converged = info == 0;
  const std::string stop_reason = info == 0 ? "converged"
                                  : info == 1
                                      ? "maximum iterations reached"
                                      : "no shifts could be applied (increase subspace_dimension)";
  a_int nconv = iparam[4];
  if (nconv == 0) {
    raw.status = EigenStatus::NotConverged;
    raw.message = ::mastrom::detail::concat("arpack: 0 of ", nev, " eigenpairs converged in ",
                                            raw.iterations, " iterations (", stop_reason, ")");
    return raw;
  }

  std::vector<a_int> select(static_cast<std::size_t>(ncv));
  std::vector<double> d(static_cast<std::size_t>(ncv));
  std::vector<double> z(static_cast<std::size_t>(n) * static_cast<std::size_t>(ncv));
  a_int info_eupd = 0;
  dseupd_c(1, "A", select.data(), d.data(), z.data(), nn, sigma, "G", nn, "LM", nev,
           options.tolerance, resid.data(), ncv, v.data(), nn, iparam, ipntr, workd.data(),
           workl.data(), lworkl, &info_eupd);
  if (info_eupd != 0) {
    raw.status = all_converged ? EigenStatus::Failed : EigenStatus::NotConverged;
    raw.message =
        "arpack: dseupd failed: " + dseupdError(info_eupd) + " (dsaupd: " + stop_reason + ")";
    return raw;
  }
  nconv = iparam[4];

  // The `count` values nearest σ, each vector purified by one application of OP.
  std::vector<a_int> order(static_cast<std::size_t>(nconv));
  std::iota(order.begin(), order.end(), a_int{0});
  std::stable_sort(order.begin(), order.end(), [&](a_int p, a_int q) {
    return std::abs(d[static_cast<std::size_t>(p)] - sigma) <
           std::abs(d[static_cast<std::size_t>(q)] - sigma);
  });
  const a_int k = std::min(nconv, nev);
  raw.values.resize(k);
  raw.vectors.resize(n, k);
  for (a_int j = 0; j < k; ++j) {
    const auto src = static_cast<std::size_t>(order[static_cast<std::size_t>(j)]);
    raw.values(j) = d[src];
    scratch.noalias() =
        mass * Eigen::Map<const Eigen::VectorXd>(z.data() + src * static_cast<std::size_t>(n), n);
    op.apply(scratch.data(), raw.vectors.col(j).data());
  }
  raw.status = all_converged && k == nev ? EigenStatus::Converged : EigenStatus::NotConverged;
  raw.message = ::mastrom::detail::concat("arpack: ", k, " of ", nev, " eigenpairs converged in ",
                                          raw.iterations, " iterations (", stop_reason, ")");
  return raw;
}

}  // namespace mastrom::modes::detail
