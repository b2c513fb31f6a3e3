// Linearisation about a static equilibrium (see linearize.hpp).
#include "modes/linearize.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "common/error.hpp"
#include "modes/mode_labels.hpp"

namespace mastrom::modes {
namespace {

using fullorder::IterationCoefficients;
using fullorder::MultibodySystem;

/// The n × n top-left block of an iteration matrix, without its structural zeros.
SparseMatrix topLeftBlock(const SparseMatrix& h, Eigen::Index n) {
  SparseMatrix block = h.topLeftCorner(n, n);
  block.prune([](Eigen::Index, Eigen::Index, double v) { return v != 0.0; });
  block.makeCompressed();
  return block;
}

double maxAbs(const SparseMatrix& a) {
  double m = 0.0;
  for (Eigen::Index k = 0; k < a.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(a, k); it; ++it) m = std::max(m, std::abs(it.value()));
  return m;
}

/// ½(A + Aᵀ); returns max|A − Aᵀ| / max|A| through `asymmetry`.
SparseMatrix symmetrised(const SparseMatrix& a, double& asymmetry) {
  const SparseMatrix at = a.transpose();
  const double scale = maxAbs(a);
  asymmetry = scale > 0.0 ? maxAbs(SparseMatrix(a - at)) / scale : 0.0;
  SparseMatrix s = 0.5 * (a + at);
  s.prune([](Eigen::Index, Eigen::Index, double v) { return v != 0.0; });
  s.makeCompressed();
  return s;
}

/// Block (c_m, c_d, c_k) of the iteration matrix at (q, q̇ = 0, λ).
SparseMatrix assembleBlock(const MultibodySystem& system, const Eigen::VectorXd& q,
                           const Eigen::VectorXd& lambda, double t, double c_m, double c_d,
                           double c_k) {
  IterationCoefficients coeffs;
  coeffs.mass = c_m;
  coeffs.damping = c_d;
  coeffs.stiffness = c_k;
  coeffs.constraint_scale = 1.0;
  SparseMatrix h;
  const Eigen::VectorXd zero_velocity = Eigen::VectorXd::Zero(system.dofCount());
  system.assembleIterationMatrix(q, zero_velocity, lambda, t, coeffs, h);
  return topLeftBlock(h, system.dofCount());
}

/// True when the start state is already the equilibrium with λ = 0: no gravity, and the
/// generalized forces vanish to round-off against the stiffness scale (a stress-free state).
/// `stiffness` is the stiffness block at the start state.
bool isForceFreeStart(const MultibodySystem& system, const Eigen::VectorXd& q, double t,
                      const SparseMatrix& stiffness) {
  if (system.gravity().squaredNorm() > 0.0) return false;
  Eigen::VectorXd f;
  const Eigen::VectorXd zero_velocity = Eigen::VectorXd::Zero(system.dofCount());
  system.forces(q, zero_velocity, t, f);
  const double stiffness_scale = stiffness.diagonal().cwiseAbs().maxCoeff();
  const double length_scale = std::max(q.cwiseAbs().maxCoeff(), 1e-3);
  // Round-off forces of a stress-free state are ~1e-16 K ℓ; any physical load is far above 1e-10.
  return f.cwiseAbs().maxCoeff() <= 1e-10 * stiffness_scale * length_scale;
}

}  // namespace

Linearization linearize(const MultibodySystem& system, const Eigen::VectorXd& q_start,
                        const LinearizationOptions& options) {
  MASTROM_REQUIRE(system.isFinalized(), InputError, "linearize: the system is not finalized");
  const int n = system.dofCount();
  const int m = system.constraintCount();
  MASTROM_REQUIRE(q_start.size() == n, InputError, "linearize: q has size ", q_start.size(),
                  ", the system has ", n, " DOFs");
  const auto start = std::chrono::steady_clock::now();
  const double t = options.static_solver.time_s;

  Linearization out;
  // The stiffness at the start state with λ = 0: the answer itself when the start is the
  // equilibrium (no gravity, stress-free), and the scale of the force-free test otherwise.
  const Eigen::VectorXd no_lambda = Eigen::VectorXd::Zero(m);
  SparseMatrix stiffness = assembleBlock(system, q_start, no_lambda, t, 0, 0, 1);
  const bool solve = options.equilibrium == EquilibriumSolve::Always ||
                     (options.equilibrium == EquilibriumSolve::Auto &&
                      !isForceFreeStart(system, q_start, t, stiffness));
  if (solve) {
    out.statics = fullorder::solveStatic(system, q_start, options.static_solver);
    out.q = out.statics.q;
    out.lambda = out.statics.lambda;
    out.equilibrium_solved = true;
    const Eigen::VectorXd& lambda_in_k =
        options.multiplier_term == MultiplierTerm::Include ? out.lambda : no_lambda;
    stiffness = assembleBlock(system, out.q, lambda_in_k, t, 0, 0, 1);
  } else {
    out.q = q_start;
    out.lambda = no_lambda;
  }

  out.problem.stiffness = symmetrised(stiffness, out.stiffness_asymmetry);
  MASTROM_REQUIRE(out.stiffness_asymmetry <= 1e-6, NumericalError,
                  "linearize: the tangent stiffness is not symmetric (max|K − Kᵀ|/max|K| = ",
                  out.stiffness_asymmetry,
                  "): a non-conservative load? The modal analysis needs a symmetric K");
  double damping_asymmetry = 0.0;
  out.damping = symmetrised(assembleBlock(system, out.q, no_lambda, t, 0, 1, 0), damping_asymmetry);
  out.problem.mass = system.massMatrix();
  out.problem.mass.prune([](Eigen::Index, Eigen::Index, double v) { return v != 0.0; });
  out.problem.mass.makeCompressed();
  system.constraintJacobian(out.q, t, out.problem.constraint_jacobian);
  out.problem.constraint_jacobian.prune(
      [](Eigen::Index, Eigen::Index, double v) { return v != 0.0; });
  out.problem.constraint_jacobian.makeCompressed();
  out.linearize_time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

Linearization linearizeMast(const fullorder::MastModel& model,
                            const LinearizationOptions& options) {
  const auto& lock = model.parameters().lock_angle_rad;
  MASTROM_REQUIRE(lock.has_value(), InputError,
                  "linearizeMast: the mast's joint is driven, not locked (set lock_angle_rad; the "
                  "modes are those of the mast locked at θ0)");
  const Eigen::VectorXd start = model.rotatedReference(*lock);
  Linearization lin = linearize(model.system(), start, options);
  if (options.stability == StabilityPolicy::Skip) return lin;
  lin.stability = checkStability(lin.problem);
  if (!lin.stability.stable()) {
    lin.stability.lowest_label = labelModes(model.system(), lin.stability.lowest_shape, *lock)[0];
    if (options.continue_load && lin.equilibrium_solved &&
        options.static_solver.load_steps < kContinuationSteps) {
      // Continue the load (see the header): the stable branch a gradual loading follows.
      LinearizationOptions continued = options;
      continued.equilibrium = EquilibriumSolve::Always;
      continued.static_solver.load_steps = kContinuationSteps;
      try {
        Linearization other = linearize(model.system(), start, continued);
        other.stability = checkStability(other.problem);
        if (other.stability.stable()) {
          other.stability.branch = ::mastrom::detail::concat(
              "reached by applying gravity in ", kContinuationSteps,
              " increments; applied at once it gave an unstable equilibrium (",
              lin.stability.describe(), ")");
          return other;
        }
      } catch (const NumericalError&) {
        // The continuation did not converge: the first equilibrium is reported below.
      }
    }
    MASTROM_REQUIRE(options.stability != StabilityPolicy::Refuse, NumericalError,
                    "the static equilibrium at the locked angle ", *lock * 180.0 / M_PI,
                    " deg is unstable (", lin.stability.describe(),
                    "): its modes would not describe vibrations about it; refused (mastrom "
                    "modes --allow-unstable writes them, flagged)");
  }
  return lin;
}

fullorder::MastModel buildLockedMast(fullorder::MastParameters params, double angle_rad) {
  params.lock_angle_rad = angle_rad;
  return fullorder::buildMast(params);
}

}  // namespace mastrom::modes
