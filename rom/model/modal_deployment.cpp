#include "rom/model/modal_deployment.hpp"

#include <algorithm>
#include <cstring>
#include <functional>
#include <utility>
#include <vector>

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
/// Rows per mode of the AVX2 layout: η's 6 rows, η̇'s 8 and η̈'s 10, each kind padded with zero rows
/// to whole packs of four (8 + 8 + 12), so that every pack multiplies one broadcast state.
constexpr int kPaddedRows = 28;

/// AVX2 + FMA: seven packs of four rows per mode, each one fused multiply-add by a broadcast of η,
/// η̇ or η̈. Against six packs where two straddle two kinds of state (and need their broadcasts
/// blended), one multiply-add more per mode but three broadcasts instead of five shuffles: 438 →
/// ≈ 280 instructions a sample for 20 modes (callgrind), the sums' order unchanged per row.
__attribute__((target("avx2,fma"))) void contractStatesAvx2(
    long modes, const double* __restrict rows, const double* __restrict eta,
    const double* __restrict eta_dot, const double* __restrict eta_ddot, double* __restrict y) {
  static_assert(kEtaRows == 6 && kRateRows == 8 && kAccRows == 10, "packs laid out for 6, 8, 10");
  Pack4 y0 = {0.0, 0.0, 0.0, 0.0}, y1 = y0, y2 = y0, y3 = y0, y4 = y0, y5 = y0, y6 = y0;
  for (long i = 0; i < modes; ++i) {
    const double e = eta[i], v = eta_dot[i], a = eta_ddot[i];
    const Pack4 m_e = {e, e, e, e}, m_v = {v, v, v, v}, m_a = {a, a, a, a};
    const double* col = rows + kPaddedRows * i;
    Pack4 c0, c1, c2, c3, c4, c5, c6;
    std::memcpy(&c0, col, sizeof(Pack4));
    std::memcpy(&c1, col + 4, sizeof(Pack4));
    std::memcpy(&c2, col + 8, sizeof(Pack4));
    std::memcpy(&c3, col + 12, sizeof(Pack4));
    std::memcpy(&c4, col + 16, sizeof(Pack4));
    std::memcpy(&c5, col + 20, sizeof(Pack4));
    std::memcpy(&c6, col + 24, sizeof(Pack4));
    y0 += c0 * m_e;
    y1 += c1 * m_e;
    y2 += c2 * m_v;
    y3 += c3 * m_v;
    y4 += c4 * m_a;
    y5 += c5 * m_a;
    y6 += c6 * m_a;
  }
  // Rows 0–5 (η), 6–13 (η̇), 14–23 (η̈): the padding lanes are overwritten or left out.
  std::memcpy(y, &y0, sizeof(Pack4));
  std::memcpy(y + 4, &y1, 2 * sizeof(double));
  std::memcpy(y + 6, &y2, sizeof(Pack4));
  std::memcpy(y + 10, &y3, sizeof(Pack4));
  std::memcpy(y + 14, &y4, sizeof(Pack4));
  std::memcpy(y + 18, &y5, sizeof(Pack4));
  std::memcpy(y + 22, &y6, 2 * sizeof(double));
}
#endif

/// The stacked rows [W_η; W_η̇; W_η̈] in this CPU's kernel's layout: the 24 × K column-major
/// matrix for the baseline, the padded columns of kPaddedRows for AVX2.
struct ContractionRows {
  std::vector<double> data;
  long modes = 0;
  bool padded = false;
};

ContractionRows contractionRows(const Eigen::Matrix<double, kRows, Eigen::Dynamic>& w) {
  ContractionRows r;
  r.modes = w.cols();
  r.data.assign(w.data(), w.data() + w.size());
#if MASTROM_HAVE_AVX2_KERNELS
  if (cpuHasAvx2Fma()) {
    r.padded = true;
    r.data.assign(static_cast<std::size_t>(kPaddedRows * r.modes), 0.0);
    for (long i = 0; i < r.modes; ++i) {
      double* col = r.data.data() + kPaddedRows * i;
      for (int row = 0; row < kEtaRows; ++row) col[row] = w(row, i);
      for (int row = 0; row < kRateRows; ++row) col[8 + row] = w(kEtaRows + row, i);
      for (int row = 0; row < kAccRows; ++row) col[16 + row] = w(kEtaRows + kRateRows + row, i);
    }
  }
#endif
  return r;
}

/// The variant for this CPU.
void contractStates(const ContractionRows& rows, const double* eta, const double* eta_dot,
                    const double* eta_ddot, double* y) {
#if MASTROM_HAVE_AVX2_KERNELS
  if (rows.padded)
    return contractStatesAvx2(rows.modes, rows.data.data(), eta, eta_dot, eta_ddot, y);
#endif
  contractStatesBaseline(rows.modes, rows.data.data(), eta, eta_dot, eta_ddot, y);
}

/// Size every column of `series` to `rows` (shrinking keeps the storage, and with it the
/// pointers the stepping writes through).
void resizeSeries(fullorder::DeploymentSeries& series, std::size_t rows) {
  series.time_s.resize(rows);
  series.drive_angle_rad.resize(rows);
  series.drive_rate_rad_s.resize(rows);
  series.drive_acceleration_rad_s2.resize(rows);
  series.end_angular_acceleration_rad_s2.resize(rows);
  series.end_relative_angular_acceleration_rad_s2.resize(rows);
  series.end_position_m.resize(rows);
  series.end_acceleration_m_s2.resize(rows);
  series.joint_force_n.resize(rows);
  series.joint_torque_nm.resize(rows);
  series.newton_iterations.resize(rows, 0);
  series.constraint_residual.resize(rows, 0.0);
}

/// The stepping of the series, its rows written into one block of `block_rows` rows (the last
/// one shorter) that is handed to `full` each time it is filled, then reused. The values do not
/// depend on the block size: each row is computed from the state at its sample alone.
void stepModalSeries(const ModalModel& m, const SampledDrive& sampled, bool coriolis_coupling,
                     const ModalSampleObserver* observer, std::size_t block_rows,
                     const std::function<void(fullorder::DeploymentSeries&)>& full) {
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

  const std::size_t samples = sampled.samples.size();
  const std::size_t block = std::min(std::max<std::size_t>(block_rows, 1), samples);
  fullorder::DeploymentSeries series;
  resizeSeries(series, block);
  long block_first = 0;  // the sample of the block's first row

  const double m_tot = m.total_mass_kg;
  const Eigen::Vector3d first_moment_ref = m_tot * m.centroid_m;
  const Eigen::Vector3d& g = m.gravity_m_s2;
  // The outputs in scalars, written through pointers taken once: the same operations in the same
  // order as the vector expressions of the formulas (R commutes with Z×; Z×v = (−v_y, v_x, 0),
  // Z×(Z×v) = −(v_x, v_y, 0)), but without reloading ten vectors' storage at every sample.
  //   α = θ̈ Z + R (ψη̈ + θ̇ Z × ψη̇);  p = R(p̄ + Tη);
  //   a = R[Tη̈ + θ̈ Z×p' + θ̇² Z×(Z×p') + 2θ̇ Z×Tη̇];
  //   joint force = Ṗ − m g, P = R[θ̇ Z × (m c̄ + Lη) + Lη̇] ((m c̄ + Lη)_z enters no output);
  //   drive torque = Ḣ − τ_g, H = θ̇ (J − 2Γ_cᵀη) + Γᵀη̇, τ_g = ((R s) × g)_z.
  const ContractionRows rows = contractionRows(w);
  double* const time_out = series.time_s.data();
  double* const angle_out = series.drive_angle_rad.data();
  double* const rate_out = series.drive_rate_rad_s.data();
  double* const drive_acc_out = series.drive_acceleration_rad_s2.data();
  Eigen::Vector3d* const alpha_out = series.end_angular_acceleration_rad_s2.data();
  double* const rel_out = series.end_relative_angular_acceleration_rad_s2.data();
  Eigen::Vector3d* const position_out = series.end_position_m.data();
  Eigen::Vector3d* const end_acc_out = series.end_acceleration_m_s2.data();
  Eigen::Vector3d* const force_out = series.joint_force_n.data();
  double* const torque_out = series.joint_torque_nm.data();
  const double end_x = m.end_position_m.x(), end_y = m.end_position_m.y(),
               end_z = m.end_position_m.z();
  const double moment_x = first_moment_ref.x(), moment_y = first_moment_ref.y();
  const double weight_x = m_tot * g.x(), weight_y = m_tot * g.y(), weight_z = m_tot * g.z();
  const double inertia_z = m.inertia_z_kg_m2, step_s = sampled.step_s;
  const SampledDrive::Sample* const drive_samples = sampled.samples.data();
  runModalStepping(
      m, ms, sampled,
      [&](long sample, const Eigen::VectorXd& eta, const Eigen::VectorXd& eta_dot,
          const Eigen::VectorXd& eta_ddot) {
        const SampledDrive::Sample& d = drive_samples[sample];
        const long n = sample - block_first;  // the row in the block
        double y[kRows];
        contractStates(rows, eta.data(), eta_dot.data(), eta_ddot.data(), y);
        const double* ye = y;                         // η rows
        const double* yr = y + kEtaRows;              // η̇ rows
        const double* ya = y + kEtaRows + kRateRows;  // η̈ rows
        double c = 1.0, s = 0.0;
        ms.rotation(d.sin_angle, d.cos_angle, c, s);
        const double th_d = d.rate_rad_s, th_dd = d.acceleration_rad_s2, th_d2 = th_d * th_d;
        const double two_th_d = 2.0 * th_d;
        time_out[n] = static_cast<double>(sample) * step_s;
        angle_out[n] = d.angle_rad;
        rate_out[n] = th_d;
        drive_acc_out[n] = th_dd;
        // α
        const double ax = ya[0] + th_d * -yr[1], ay = ya[1] + th_d * yr[0];
        alpha_out[n] = Eigen::Vector3d(c * ax - s * ay, s * ax + c * ay, ya[2] + th_dd);
        rel_out[n] = ya[2];  // (ψη̈)_z, R keeps z
        // End centroid.
        const double px = end_x + ye[0], py = end_y + ye[1], pz = end_z + ye[2];
        position_out[n] = Eigen::Vector3d(c * px - s * py, s * px + c * py, pz);
        const double ex = ((ya[3] + th_dd * -py) - th_d2 * px) + two_th_d * -yr[3];
        const double ey = ((ya[4] + th_dd * px) - th_d2 * py) + two_th_d * yr[2];
        end_acc_out[n] = Eigen::Vector3d(c * ex - s * ey, s * ex + c * ey, ya[5]);
        // Joint force.
        const double mx = moment_x + ye[3], my = moment_y + ye[4];
        const double fx = ((ya[6] + th_dd * -my) - th_d2 * mx) + two_th_d * -yr[5];
        const double fy = ((ya[7] + th_dd * mx) - th_d2 * my) + two_th_d * yr[4];
        force_out[n] = Eigen::Vector3d((c * fx - s * fy) - weight_x, (s * fx + c * fy) - weight_y,
                                       ya[8] - weight_z);
        // Drive torque.
        const double h_dot = (th_dd * (inertia_z - 2.0 * ye[5]) - two_th_d * yr[6]) + ya[9];
        const double gx = c * mx - s * my, gy = s * mx + c * my;
        torque_out[n] = h_dot - (gx * g.y() - gy * g.x());
        if (observer)
          (*observer)(sample, eta, eta_dot,
                      stepping_detail::forcingScalars(ms, sampled.valueAt(sample)));
        if (static_cast<std::size_t>(n) + 1 == series.time_s.size()) {
          full(series);
          block_first = sample + 1;
          const std::size_t left = samples - static_cast<std::size_t>(block_first);
          if (left > 0 && left < series.time_s.size()) resizeSeries(series, left);
        }
      });
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
  fullorder::DeploymentSeries whole;
  stepModalSeries(m, sampled, coriolis_coupling, observer, sampled.samples.size(),
                  [&whole](fullorder::DeploymentSeries& block) { whole = std::move(block); });
  return whole;
}

void streamModalDeployment(const ModalModel& m, const SampledDrive& sampled, bool coriolis_coupling,
                           const ModalSeriesBlockSink& sink, std::size_t block_rows,
                           const ModalSampleObserver* observer) {
  stepModalSeries(m, sampled, coriolis_coupling, observer, block_rows,
                  [&sink](fullorder::DeploymentSeries& block) { sink(block); });
}

ModalDeploymentOptions deploymentOptionsFromConfig(const Config& config) {
  ModalDeploymentOptions o;
  o.end_time_s = config.simulation.end_time_s;
  o.step_s = outputInterval(config);
  return o;
}

}  // namespace mastrom::rom
