#include "rom/model/modal_deployment.hpp"

#include <cstring>

#include "common/cpu_features.hpp"
#include "rom/model/modal_stepping.hpp"
#include "rom/model/state_contraction.hpp"

// The output contraction (24 rows × K modes per sample) is bound by floating-point throughput: the
// baseline x86-64 build (SSE2, two doubles per operation) already runs it at the machine's
// multiply/add rate, and a blocked matrix product (the states of 64 samples buffered, one Eigen
// product per block) measured slower, 1.55 vs 1.14 ms for 20 modes. Four doubles per
// operation halve it: on x86-64 a second copy of the kernel is compiled for AVX2 + FMA and chosen
// at run time where the CPU has them (common/cpu_features.hpp).

namespace mastrom::rom {
namespace {

/// Rows of the stacked contraction matrix [W_η; W_η̇; W_η̈].
constexpr int kEtaRows = 6, kRateRows = 8, kAccRows = 10;
constexpr int kRows = kEtaRows + kRateRows + kAccRows;

// Both variants compute y = [W_η; W_η̇; W_η̈] (η; η̇; η̈) (24 values) with `rows` the column-major
// 24 × K matrix, one independent accumulator per pack of rows, the states broadcast in registers
// (rom/model/state_contraction.hpp).

/// SSE2: twelve packs of two rows; rows 0–5 take η, 6–13 η̇, 14–23 η̈.
void contractStatesBaseline(long modes, const double* __restrict rows, const double* __restrict eta,
                            const double* __restrict eta_dot, const double* __restrict eta_ddot,
                            double* __restrict y) {
  static_assert(kEtaRows % 2 == 0 && kRateRows % 2 == 0 && kAccRows % 2 == 0, "pairs of rows");
  contraction_detail::contractInOrder<kRows / 2, kEtaRows / 2, kRateRows / 2>(
      modes, kRows, rows, eta, eta_dot, eta_ddot, y);
}

#if MASTROM_HAVE_AVX2_KERNELS
/// AVX2 + FMA: six packs of four rows; packs 1 (rows 4–7) and 3 (rows 12–15) straddle two state
/// kinds and multiply by (η, η, η̇, η̇) and (η̇, η̇, η̈, η̈).
__attribute__((target("avx2,fma"))) void contractStatesAvx2(
    long modes, const double* __restrict rows, const double* __restrict eta,
    const double* __restrict eta_dot, const double* __restrict eta_ddot, double* __restrict y) {
  static_assert(kEtaRows == 6 && kRateRows == 8 && kAccRows == 10, "packs laid out for 6, 8, 10");
  Pack4 y0 = {0.0, 0.0, 0.0, 0.0}, y1 = y0, y2 = y0, y3 = y0, y4 = y0, y5 = y0;
  for (long i = 0; i < modes; ++i) {
    const double e = eta[i], v = eta_dot[i], a = eta_ddot[i];
    const Pack4 m_e = {e, e, e, e}, m_ev = {e, e, v, v}, m_v = {v, v, v, v}, m_va = {v, v, a, a},
                m_a = {a, a, a, a};
    const double* col = rows + kRows * i;
    Pack4 c0, c1, c2, c3, c4, c5;
    std::memcpy(&c0, col, sizeof(Pack4));
    std::memcpy(&c1, col + 4, sizeof(Pack4));
    std::memcpy(&c2, col + 8, sizeof(Pack4));
    std::memcpy(&c3, col + 12, sizeof(Pack4));
    std::memcpy(&c4, col + 16, sizeof(Pack4));
    std::memcpy(&c5, col + 20, sizeof(Pack4));
    y0 += c0 * m_e;
    y1 += c1 * m_ev;
    y2 += c2 * m_v;
    y3 += c3 * m_va;
    y4 += c4 * m_a;
    y5 += c5 * m_a;
  }
  std::memcpy(y, &y0, sizeof(Pack4));
  std::memcpy(y + 4, &y1, sizeof(Pack4));
  std::memcpy(y + 8, &y2, sizeof(Pack4));
  std::memcpy(y + 12, &y3, sizeof(Pack4));
  std::memcpy(y + 16, &y4, sizeof(Pack4));
  std::memcpy(y + 20, &y5, sizeof(Pack4));
}
#endif

/// The variant for this CPU.
void contractStates(long modes, const double* rows, const double* eta, const double* eta_dot,
                    const double* eta_ddot, double* y) {
#if MASTROM_HAVE_AVX2_KERNELS
  if (cpuHasAvx2Fma()) return contractStatesAvx2(modes, rows, eta, eta_dot, eta_ddot, y);
#endif
  contractStatesBaseline(modes, rows, eta, eta_dot, eta_ddot, y);
}

}  // namespace

fullorder::DeploymentSeries simulateModalDeployment(const ModalModel& m,
                                                    const fullorder::DriveLaw& drive,
                                                    const ModalDeploymentOptions& options) {
  return simulateModalDeployment(m, sampleDrive(drive, options), options.coriolis_coupling);
}

fullorder::DeploymentSeries simulateModalDeployment(const ModalModel& m,
                                                    const SampledDrive& sampled,
                                                    bool coriolis_coupling,
                                                    const ModalSampleObserver* observer) {
  const ModalStepping ms = prepareModalStepping(m, sampled, coriolis_coupling);
  const int k = m.modeCount();

  // The modal contractions every output needs, stacked so one pass over the modes per state
  // vector gives them all (derivations in rom/model/modal_model.hpp):
  //   η:  Tη (0–2), (Lη)_x,y (3–4), Γ_cᵀη (5)
  //   η̇:  (ψη̇)_x,y (0–1), (Tη̇)_x,y (2–3), (Lη̇)_x,y (4–5), Γ_cᵀη̇ (6), padding (7)
  //   η̈:  ψη̈ (0–2), Tη̈ (3–5), Lη̈ (6–8), Γᵀη̈ (9)
  // η̇ enters only through Z× and Lη only through Z×, Z×(Z×) and the in-plane gravity torque, so
  // their z rows are not needed.
  // Stacked as [W_η; W_η̇; W_η̈] for contractStates.
  Eigen::Matrix<double, kRows, Eigen::Dynamic> w =
      Eigen::Matrix<double, kRows, Eigen::Dynamic>::Zero(kRows, k);
  auto w_eta = w.middleRows<kEtaRows>(0);
  auto w_rate = w.middleRows<kRateRows>(kEtaRows);
  auto w_acc = w.middleRows<kAccRows>(kEtaRows + kRateRows);
  w_eta.middleRows<3>(0) = m.end_translation;
  w_eta.middleRows<2>(3) = m.momentum_participation.topRows<2>();
  w_eta.row(5) = m.centrifugal_participation.transpose();
  w_rate.middleRows<2>(0) = m.end_rotation.topRows<2>();
  w_rate.middleRows<2>(2) = m.end_translation.topRows<2>();
  w_rate.middleRows<2>(4) = m.momentum_participation.topRows<2>();
  w_rate.row(6) = m.centrifugal_participation.transpose();
  w_acc.middleRows<3>(0) = m.end_rotation;
  w_acc.middleRows<3>(3) = m.end_translation;
  w_acc.middleRows<3>(6) = m.momentum_participation;
  w_acc.row(9) = m.rotation_participation.transpose();
  // In-plane part (x, y, 0) of rows r, r+1 of a contraction: all that Z× and Z×(Z×) need.
  const auto planar = [](const auto& y, int r) { return Eigen::Vector3d(y[r], y[r + 1], 0.0); };

  const std::size_t samples = sampled.samples.size();
  fullorder::DeploymentSeries series;
  series.time_s.resize(samples);
  series.drive_angle_rad.resize(samples);
  series.drive_rate_rad_s.resize(samples);
  series.drive_acceleration_rad_s2.resize(samples);
  series.end_angular_acceleration_rad_s2.resize(samples);
  series.end_relative_angular_acceleration_rad_s2.resize(samples);
  series.end_position_m.resize(samples);
  series.end_acceleration_m_s2.resize(samples);
  series.joint_force_n.resize(samples);
  series.joint_torque_nm.resize(samples);
  series.newton_iterations.assign(samples, 0);
  series.constraint_residual.assign(samples, 0.0);

  const double m_tot = m.total_mass_kg;
  const Eigen::Vector3d first_moment_ref = m_tot * m.centroid_m;
  const Eigen::Vector3d& g = m.gravity_m_s2;
  runModalStepping(
      m, ms, sampled,
      [&](long n, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
          const Eigen::VectorXd& eta_ddot) {
        const auto i = static_cast<std::size_t>(n);
        const SampledDrive::Sample& d = sampled.samples[i];
        Eigen::Matrix<double, kRows, 1> y;
        contractStates(k, w.data(), eta.data(), eta_dot.data(), eta_ddot.data(), y.data());
        const auto y_eta = y.segment<kEtaRows>(0);
        const auto y_rate = y.segment<kRateRows>(kEtaRows);
        const auto y_acc = y.segment<kAccRows>(kEtaRows + kRateRows);
        double c = 1.0, s = 0.0;
        ms.rotation(d.sin_angle, d.cos_angle, c, s);
        const double th_d = d.rate_rad_s, th_dd = d.acceleration_rad_s2, th_d2 = th_d * th_d;
        series.time_s[i] = static_cast<double>(n) * sampled.step_s;
        series.drive_angle_rad[i] = d.angle_rad;
        series.drive_rate_rad_s[i] = th_d;
        series.drive_acceleration_rad_s2[i] = th_dd;
        // α = θ̈ Z + R ψ η̈ + θ̇ Z × (R ψ η̇) = θ̈ Z + R (ψη̈ + θ̇ Z × ψη̇)  (R commutes with Z×).
        Eigen::Vector3d alpha = rotateZ(c, s, y_acc.head<3>() + th_d * crossZ(planar(y_rate, 0)));
        alpha.z() += th_dd;
        series.end_angular_acceleration_rad_s2[i] = alpha;
        series.end_relative_angular_acceleration_rad_s2[i] = y_acc[2];  // (ψη̈)_z, R keeps z
        // End centroid: p = R(p̄ + Tη); a = R[Tη̈ + θ̈ Z×p' + θ̇² Z×(Z×p') + 2θ̇ Z×Tη̇],
        // Z×(Z×v) = −(v_x, v_y, 0).
        const Eigen::Vector3d p_rot = m.end_position_m + y_eta.segment<3>(0);
        series.end_position_m[i] = rotateZ(c, s, p_rot);
        series.end_acceleration_m_s2[i] =
            rotateZ(c, s,
                    y_acc.segment<3>(3) + th_dd * crossZ(p_rot) -
                        th_d2 * Eigen::Vector3d(p_rot.x(), p_rot.y(), 0.0) +
                        2.0 * th_d * crossZ(planar(y_rate, 2)));
        // Joint force = Ṗ − m g with P = R[θ̇ Z × (m c̄ + Lη) + Lη̇].
        // (m c̄ + Lη)_z enters no output (Z× and the in-plane gravity torque drop it).
        const Eigen::Vector3d moment = planar(first_moment_ref, 0) + planar(y_eta, 3);
        const Eigen::Vector3d p_dot =
            rotateZ(c, s,
                    y_acc.segment<3>(6) + th_dd * crossZ(moment) -
                        th_d2 * Eigen::Vector3d(moment.x(), moment.y(), 0.0) +
                        2.0 * th_d * crossZ(planar(y_rate, 4)));
        series.joint_force_n[i] = p_dot - m_tot * g;
        // Drive torque = Ḣ − τ_g, H = θ̇ (J − 2Γ_cᵀη) + Γᵀη̇, τ_g = ((R s) × g)_z.
        const double h_dot =
            th_dd * (m.inertia_z_kg_m2 - 2.0 * y_eta[5]) - 2.0 * th_d * y_rate[6] + y_acc[9];
        const Eigen::Vector3d moment_global = rotateZ(c, s, moment);
        series.joint_torque_nm[i] = h_dot - (moment_global.x() * g.y() - moment_global.y() * g.x());
        if (observer)
          (*observer)(n, eta, eta_dot, stepping_detail::forcingScalars(ms, sampled.valueAt(n)));
      });
  return series;
}

ModalDeploymentOptions deploymentOptionsFromConfig(const Config& config) {
  ModalDeploymentOptions o;
  o.end_time_s = config.simulation.end_time_s;
  o.step_s = outputInterval(config);
  return o;
}

}  // namespace mastrom::rom
