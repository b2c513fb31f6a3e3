// Newton with load stepping for static equilibrium (see static_solver.hpp).
#include "fullorder/static_solver.hpp"

#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>

#include "common/error.hpp"

namespace mastrom::fullorder {
namespace {

struct NewtonOutcome {
  bool converged = false;
  int iterations = 0;
  double force_residual = 0.0;
  double relative_force_residual = 0.0;
  double constraint_residual = 0.0;
  const char* reason = "";
};

class StaticNewton {
public:
  StaticNewton(const MultibodySystem& system, const StaticSolverOptions& options)
      : sys_(system), opt_(options), n_(system.dofCount()), m_(system.constraintCount()) {
    zero_velocity_ = Eigen::VectorXd::Zero(n_);
    h_ = system.iterationMatrixPattern();
    lu_.analyzePattern(h_);
    coeffs_.mass = 0.0;
    coeffs_.damping = 0.0;
    coeffs_.stiffness = 1.0;
    coeffs_.constraint_scale = 1.0;
  }

  /// σ = mean |diagonal| of the stiffness block at (q, λ), or the user's value.
  void chooseScale(const Eigen::VectorXd& q, const Eigen::VectorXd& lambda, double load) {
    if (opt_.constraint_scale > 0.0) {
      coeffs_.constraint_scale = opt_.constraint_scale;
      return;
    }
    sys_.assembleIterationMatrix(q, zero_velocity_, lambda, opt_.time_s, coeffs_, h_, load);
    double sum = 0.0;
    int count = 0;
    for (int i = 0; i < n_; ++i) {
      const double d = std::abs(h_.coeff(i, i));
      if (d > 0.0) {
        sum += d;
        ++count;
      }
    }
    coeffs_.constraint_scale = count > 0 ? sum / count : 1.0;
  }

  /// Newton at load factor `load` from (q, λ), updated in place.
  NewtonOutcome solve(double load, Eigen::VectorXd& q, Eigen::VectorXd& lambda) {
    NewtonOutcome out;
    const double sigma = coeffs_.constraint_scale;
    bool last_step_tiny = false;
    for (int it = 0;; ++it) {
      sys_.assembleForcesAndIterationMatrix(q, zero_velocity_, lambda, opt_.time_s, coeffs_, f_, h_,
                                            load);
      fc_.setZero(n_);
      sys_.addConstraintForces(q, lambda, opt_.time_s, fc_);
      residual_.resize(n_ + m_);
      residual_.head(n_) = fc_ - f_;
      sys_.constraints(q, opt_.time_s, phi_);
      residual_.tail(m_) = sigma * phi_;

      out.iterations = it;
      out.force_residual = residual_.head(n_).norm();
      out.constraint_residual = m_ > 0 ? phi_.cwiseAbs().maxCoeff() : 0.0;
      const double ref = std::max({f_.norm(), fc_.norm(), load * sys_.gravityForce().norm()});
      out.relative_force_residual = ref > 0.0 ? out.force_residual / ref : out.force_residual;
      if (!std::isfinite(out.force_residual) || !std::isfinite(out.constraint_residual)) {
        out.reason = "non-finite residual";
        return out;
      }
      const bool forces_ok = out.force_residual <= opt_.force_tolerance * ref || last_step_tiny;
      if (forces_ok && out.constraint_residual <= opt_.constraint_tolerance) {
        out.converged = true;
        return out;
      }
      if (it >= opt_.max_iterations) {
        out.reason = "iteration limit reached";
        return out;
      }
      lu_.factorize(h_);
      if (lu_.info() != Eigen::Success) {
        out.reason = "singular iteration matrix";
        return out;
      }
      step_ = lu_.solve(residual_);
      if (!step_.allFinite()) {
        out.reason = "non-finite Newton correction";
        return out;
      }
      q -= step_.head(n_);
      lambda -= sigma * step_.tail(m_);
      last_step_tiny =
          step_.head(n_).cwiseAbs().maxCoeff() <= 1e-13 * std::max(1.0, q.cwiseAbs().maxCoeff());
    }
  }

private:
  const MultibodySystem& sys_;
  const StaticSolverOptions& opt_;
  int n_, m_;
  IterationCoefficients coeffs_;
  Eigen::VectorXd zero_velocity_, f_, fc_, phi_, residual_, step_;
  SparseMatrix h_;
  Eigen::SparseLU<SparseMatrix, Eigen::COLAMDOrdering<int>> lu_;
};

}  // namespace

StaticResult solveStatic(const MultibodySystem& system, const Eigen::VectorXd& q_start,
                         const StaticSolverOptions& options) {
  return solveStatic(system, q_start, Eigen::VectorXd::Zero(system.constraintCount()), options);
}

StaticResult solveStatic(const MultibodySystem& system, const Eigen::VectorXd& q_start,
                         const Eigen::VectorXd& lambda_start, const StaticSolverOptions& options) {
  MASTROM_REQUIRE(system.isFinalized(), Error, "static solver: the system is not finalized");
  MASTROM_REQUIRE(q_start.size() == system.dofCount(), InputError, "static solver: q has size ",
                  q_start.size(), ", the system has ", system.dofCount(), " DOFs");
  MASTROM_REQUIRE(lambda_start.size() == system.constraintCount(), InputError,
                  "static solver: λ has size ", lambda_start.size(), ", the system has ",
                  system.constraintCount(), " constraints");
  MASTROM_REQUIRE(options.load_steps >= 1, InputError,
                  "static solver: load_steps = ", options.load_steps, " must be ≥ 1");
  MASTROM_REQUIRE(options.max_iterations >= 1, InputError,
                  "static solver: max_iterations = ", options.max_iterations, " must be ≥ 1");
  MASTROM_REQUIRE(options.min_load_increment > 0.0, InputError,
                  "static solver: min_load_increment = ", options.min_load_increment,
                  " must be > 0");

  StaticResult result;
  result.q = q_start;
  result.lambda = lambda_start;
  StaticNewton newton(system, options);
  newton.chooseScale(result.q, result.lambda, 1.0);

  double done = 0.0;
  double increment = 1.0 / options.load_steps;
  const double initial_increment = increment;
  Eigen::VectorXd q_trial, lambda_trial;
  while (true) {
    const double target = std::min(1.0, done + increment);
    q_trial = result.q;
    lambda_trial = result.lambda;
    const NewtonOutcome out = newton.solve(target, q_trial, lambda_trial);
    result.iterations += out.iterations;
    if (out.converged) {
      result.q = q_trial;
      result.lambda = lambda_trial;
      result.force_residual = out.force_residual;
      result.relative_force_residual = out.relative_force_residual;
      result.constraint_residual = out.constraint_residual;
      ++result.load_steps;
      done = target;
      if (done >= 1.0) return result;
      // Grow the increment again after easy steps (never beyond the initial one).
      if (out.iterations <= options.max_iterations / 4)
        increment = std::min(initial_increment, 1.5 * increment);
      continue;
    }
    ++result.rejected_steps;
    increment *= 0.5;
    MASTROM_REQUIRE(increment >= options.min_load_increment, NumericalError,
                    "static solver failed (", out.reason, ") at load factor ", target,
                    " (last converged ", done, ") after ", out.iterations,
                    " Newton iterations: force residual ", out.force_residual, " (relative ",
                    out.relative_force_residual, "), constraint residual ", out.constraint_residual,
                    "; load increment fell below ", options.min_load_increment);
  }
}

}  // namespace mastrom::fullorder
