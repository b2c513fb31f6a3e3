// The second-order correction of the constraints after each Newton update
// (GeneralizedAlphaOptions::correct_constraints, docs/theory.md §5.1): it must cut the iterations
// a short step spends on criterion (5.1), leave Φ as small as the criterion asks, and change the
// solution only within the Newton tolerance — far below the discretisation error.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>

#include "coarse_mast.hpp"
#include "fullorder/eliminated_system.hpp"
#include "fullorder/generalized_alpha.hpp"
#include "fullorder/mast_config.hpp"
#include "fullorder/mast_model.hpp"

namespace mastrom::fullorder {
namespace {

struct Trace {
  std::vector<DaeState> states;
  long iterations = 0;
  long long corrections = 0;
  double worst_phi_ratio = 0.0;  ///< largest β′‖Φ‖∞ / ‖q̈‖∞ of an accepted step
};

/// Fixed steps of 15.625 µs over the first 20 ms (the ramp and the start of the cruise), where the
/// constraint criterion (5.1) binds (β′ ≈ 1.5·10¹⁰ s⁻²).
constexpr int kSteps = 1280;
constexpr double kStep = 15.625e-6;  // s
Trace run(bool correct) {
  // The default Scheme 3 mast (2 × 8 rings) swung fast (10° in 40 ms, 10 ms ramps): a turning mast
  // ringing after a jump of θ̈, as the adaptive steps resolve it at ~16 µs.
  Config c;
  c.drive.angle_deg = 10.0;
  c.drive.duration_s = 0.04;
  c.drive.ramp_s = 0.01;
  MastModel model = buildMast(mastParametersFromConfig(c));
  EliminatedSystem reduced(model.system());
  Eigen::VectorXd q, v;
  model.initialState(q, v);
  GeneralizedAlphaOptions o = integratorFromConfig(c);
  o.time_step_s = kStep;
  o.correct_constraints = correct;
  GeneralizedAlpha integrator(reduced, o);
  integrator.initialize(reduced.restrict(q), reduced.restrict(v), 0.0);
  const double am = (2.0 * o.rho_inf - 1.0) / (o.rho_inf + 1.0), af = o.rho_inf / (o.rho_inf + 1.0);
  const double gamma = 0.5 + af - am, beta = 0.25 * (gamma + 0.5) * (gamma + 0.5);
  const double beta_prime = (1.0 - am) / (kStep * kStep * beta * (1.0 - af));
  Trace r;
  for (int k = 0; k < kSteps; ++k) {
    const StepReport report = integrator.step();
    r.iterations += report.iterations;
    const DaeState& s = integrator.state();
    const double roundoff =
        8.0 * std::numeric_limits<double>::epsilon() * (1.0 + s.q.cwiseAbs().maxCoeff());
    if (report.constraint_residual > roundoff)
      r.worst_phi_ratio = std::max(r.worst_phi_ratio, beta_prime * report.constraint_residual /
                                                          s.qddot.cwiseAbs().maxCoeff());
    r.states.push_back(integrator.state());
  }
  r.corrections = integrator.constraintCorrections();
  return r;
}

TEST(ConstraintCorrection, FewerIterationsTheSameSolution) {
  const Trace with = run(true), without = run(false);
  const double per_step_with = double(with.iterations) / kSteps,
               per_step_without = double(without.iterations) / kSteps;
  // The largest difference of the positions between the two runs, relative to the largest
  // displacement, and the same for the velocities.
  double dq = 0.0, u = 0.0, dv = 0.0, v = 0.0;
  for (std::size_t i = 0; i < with.states.size(); ++i) {
    dq = std::max(dq, (with.states[i].q - without.states[i].q).cwiseAbs().maxCoeff());
    u = std::max(u, (without.states[i].q - without.states.front().q).cwiseAbs().maxCoeff());
    dv = std::max(dv, (with.states[i].qdot - without.states[i].qdot).cwiseAbs().maxCoeff());
    v = std::max(v, without.states[i].qdot.cwiseAbs().maxCoeff());
  }
  std::printf(
      "[ measured ] Newton iterations per step %.2f with the correction, %.2f without; "
      "%lld corrections; largest difference of q %.1e of the displacement, of q' %.1e\n",
      per_step_with, per_step_without, with.corrections, dq / u, dv / v);
  EXPECT_GT(with.corrections, 0);
  EXPECT_EQ(without.corrections, 0);
  EXPECT_LT(per_step_with, per_step_without - 0.3);
  // Criterion (5.1) still holds at every accepted step (κ = 1e-6) with Φ above round-off.
  EXPECT_LE(with.worst_phi_ratio, 1e-6);
  // Both runs solve the same equations to the Newton tolerance: they differ by what that leaves
  // (force tolerance 1e-6, κ = 1e-6 of max|q̈|), not by anything the step's error would show.
  EXPECT_LT(dq / u, 1e-5);
  EXPECT_LT(dv / v, 1e-5);
}

}  // namespace
}  // namespace mastrom::fullorder
