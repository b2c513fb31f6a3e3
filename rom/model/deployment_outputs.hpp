// The outputs the metrics of a ROM deployment need at one instant — |α_z|, the relative end
// angular acceleration r, the joint force ‖F‖ and the drive torque |τ| — from the modal state
// (η, η̇, η̈) and the drive there, by the formulas of the header comment of
// rom/model/deployment_metrics.hpp. The streaming metrics (deployment_metrics.cpp) evaluate them at
// every sample, the continuous peaks (peak_refinement.cpp) between samples. Not part of the
// library's interface.
#pragma once

#include <cmath>

#include <Eigen/Core>

#include "rom/model/modal_model.hpp"
#include "rom/model/modal_stepping.hpp"
#include "rom/model/output_contraction.hpp"

namespace mastrom::rom::metrics_detail {

/// The outputs the metrics need at one instant.
struct Outputs {
  double abs_acc = 0.0;  ///< |α_z|
  double rel_acc = 0.0;  ///< r, signed (the RMS and the settling need the sign)
  double force = 0.0;    ///< ‖F‖
  double torque = 0.0;   ///< |τ|
};

/// The output formulas (deployment_metrics.hpp), from (η, η̇, η̈) and the drive at one instant.
class OutputEvaluator {
public:
  OutputEvaluator(const ModalModel& m, const ModalStepping& ms)
      : m_(m), ms_(ms), w_(m), first_moment_ref_(m.total_mass_kg * m.centroid_m) {}

  /// c, s: cos and sin of θ − θ₀ (used with gravity only).
  Outputs at(const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
             const Eigen::VectorXd& eta_ddot, double th_d, double th_dd, double c, double s) const {
    // The contractions (output_contraction.hpp); only the x, y rows of Lη and Lη̇ enter (through
    // Z×, Z×(Z×) and the in-plane rotation of the gravity torque).
    Eigen::Matrix<double, OutputContraction::kRows, 1> y;
    w_.apply(eta.data(), eta_dot.data(), eta_ddot.data(), y.data());
    const Eigen::Vector4d y_eta = y.segment<4>(OutputContraction::kEta);
    const Eigen::Vector4d y_rate = y.segment<4>(OutputContraction::kRate);
    const Eigen::Matrix<double, 6, 1> y_acc = y.segment<6>(OutputContraction::kAcc);
    Outputs o;
    o.rel_acc = y_acc[0];
    o.abs_acc = std::abs(th_dd + y_acc[0]);
    // In-plane parts of m c̄ + Lη and of Lη̇ (their z components drop out,
    // deployment_metrics.hpp).
    const Eigen::Vector3d moment(first_moment_ref_.x() + y_eta[0], first_moment_ref_.y() + y_eta[1],
                                 0.0);
    const Eigen::Vector3d rate_moment(y_rate[0], y_rate[1], 0.0);
    const Eigen::Vector3d p_dot_rot = y_acc.segment<3>(1) + th_dd * crossZ(moment) -
                                      th_d * th_d * moment + 2.0 * th_d * crossZ(rate_moment);
    double tau_gravity = 0.0;
    if (ms_.gravity) {
      const Eigen::Vector3d& g = m_.gravity_m_s2;
      o.force = (rotateZ(c, s, p_dot_rot) - m_.total_mass_kg * g).norm();
      const Eigen::Vector3d moment_global = rotateZ(c, s, moment);
      tau_gravity = moment_global.x() * g.y() - moment_global.y() * g.x();
    } else {
      o.force = p_dot_rot.norm();  // a rotation keeps the length
    }
    o.torque = std::abs(th_dd * (m_.inertia_z_kg_m2 - 2.0 * y_eta[2]) - 2.0 * th_d * y_rate[2] +
                        y_acc[4] - tau_gravity);
    return o;
  }

private:
  const ModalModel& m_;
  const ModalStepping& ms_;
  OutputContraction w_;
  Eigen::Vector3d first_moment_ref_;
};

}  // namespace mastrom::rom::metrics_detail
