// The outputs of one deployment (docs/theory.md §1 "Outputs of a deployment"): the time series the
// full-order integrator and the ROM both produce, and the scalar metrics derived from them for
// screening and tests. The series map one-to-one onto the HDF5 layout of docs/user_guide.md §5
// (fullorder/results_io.hpp writes and reads them). Everything is SI; names carry their units.
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace mastrom::fullorder {

/// A metric that is not available (DeploymentMetrics::not_available says why).
inline constexpr double kNotAvailable = std::numeric_limits<double>::quiet_NaN();

/// Default settling band of docs/theory.md §1: 1 °/s² in rad/s².
inline constexpr double kDefaultSettlingBandRadS2 = 3.14159265358979323846 / 180.0;

/// Everything recorded at one output instant. Vectors are in the global frame.
struct DeploymentSample {
  double time_s = 0.0;
  double drive_angle_rad = 0.0;            ///< θ(t) of the drive law
  double drive_rate_rad_s = 0.0;           ///< θ̇(t)
  double drive_acceleration_rad_s2 = 0.0;  ///< θ̈(t)
  /// Angular acceleration of the last module; its Z component is the "absolute" one ([LW24] Fig.
  /// 7).
  Eigen::Vector3d end_angular_acceleration_rad_s2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d end_position_m = Eigen::Vector3d::Zero();        ///< last module's centroid
  Eigen::Vector3d end_acceleration_m_s2 = Eigen::Vector3d::Zero();  ///< of that centroid
  Eigen::Vector3d joint_force_n = Eigen::Vector3d::Zero();  ///< base-joint reaction on module 1
  double joint_torque_nm = 0.0;                             ///< drive torque about Z
  int newton_iterations = 0;                                ///< of the step that reached time_s
  double constraint_residual = 0.0;                         ///< norm, after convergence
};

/// Time series of one deployment, one entry per output instant (columns of equal length).
/// Fill with append(); the columns are public so that a reader or the ROM can fill them directly, in
/// which case checkConsistent() states the invariant.
struct DeploymentSeries {
  std::vector<double> time_s;
  std::vector<double> drive_angle_rad;
  std::vector<double> drive_rate_rad_s;
  std::vector<double> drive_acceleration_rad_s2;
  std::vector<Eigen::Vector3d> end_angular_acceleration_rad_s2;
  /// Z component of end_angular_acceleration minus θ̈ of the drive: the vibration ([LW24] Fig. 14).
  std::vector<double> end_relative_angular_acceleration_rad_s2;
  std::vector<Eigen::Vector3d> end_position_m;
  std::vector<Eigen::Vector3d> end_acceleration_m_s2;
  std::vector<Eigen::Vector3d> joint_force_n;
  std::vector<double> joint_torque_nm;
  std::vector<int> newton_iterations;
  std::vector<double> constraint_residual;

  /// Append one instant; computes the relative angular acceleration (Z minus θ̈).
  /// Throws UsageError when sample.time_s does not exceed the previous time.
  void append(const DeploymentSample& sample);
  void reserve(std::size_t n);
  /// Row i as a sample (the relative angular acceleration is derived again by append()).
  DeploymentSample sample(std::size_t i) const;
  /// Remove the first n rows (a sliding window over a long run).
  void dropFront(std::size_t n);
  std::size_t size() const { return time_s.size(); }
  bool empty() const { return time_s.empty(); }
  /// Throws UsageError naming the column when the columns differ in length, or when time
  /// does not increase strictly.
  void checkConsistent() const;
  /// The end point's tangential acceleration at every instant [m/s²] (endTangentialAcceleration),
  /// derived from end_position_m and end_acceleration_m_s2.
  std::vector<double> endTangentialAccelerations() const;
};

/// The tangential linear acceleration an accelerometer on the last module measures
/// (docs/theory.md (1.11)): the component of the end point's acceleration a along
/// t̂ = Z × p / |Z × p|, the direction in which the joint's rotation moves the end point p
/// (positive towards increasing θ). 0 when p lies on the joint axis (t̂ undefined).
double endTangentialAcceleration(const Eigen::Vector3d& position_m,
                                 const Eigen::Vector3d& acceleration_m_s2);

/// Scalar metrics of docs/theory.md §1, SI units. With r_i the relative end angular acceleration at
/// t_i, a_i the Z component of the end angular acceleration, t_d the drive end time and b the band.
/// computeMetrics (the full order, and any series) takes the peaks from the samples as written
/// below; the ROM's metrics path (rom/model/deployment_metrics.hpp: `rom eval`, `screen`) fills the same
/// struct with the peaks and residual of its continuous response instead, RMS and settling as here.
struct DeploymentMetrics {
  /// max_i |a_i| over the whole record [rad/s²].
  double peak_abs_end_angular_acceleration = 0.0;
  /// max_i |r_i| over the whole record [rad/s²].
  double peak_rel_end_angular_acceleration = 0.0;
  /// Time-weighted RMS of r over the whole record [rad/s²]:
  /// sqrt( ∫ r² dt / (t_last − t_first) ), the integral by the trapezoidal rule on r², so unequal
  /// output steps are weighted by their length; |r_0| for a single sample.
  double rms_rel_end_angular_acceleration = 0.0;
  /// Residual vibration amplitude after the drive stops: max |r_i| over t_i ≥ t_d [rad/s²].
  double residual_rel_end_angular_acceleration = 0.0;
  /// Settling time [s]: the first time t_s ≥ t_d after which |r| stays within b for the rest of the
  /// record. With j the last sample where |r_j| > b, t_s = max(t_d, t_c), where t_c ∈ (t_j, t_{j+1}]
  /// is where r, interpolated linearly between samples, returns to the band edge. No such j: t_s = t_d.
  /// j the last sample (the record ends outside the band): settled = false and t_s = t_last.
  double settling_time = 0.0;
  /// False when the record ends with |r| outside the band (settling_time is then the record end).
  bool settled = false;
  /// max_i ‖F_i‖₂ of the joint reaction force [N].
  double peak_joint_force = 0.0;
  /// max_i |τ_i| of the drive torque [N·m].
  double peak_drive_torque = 0.0;
  /// The inputs the metrics were computed with, recorded so a file says what its numbers mean.
  double drive_end_time = 0.0;  ///< t_d [s]
  double settling_band = 0.0;   ///< b [rad/s²]
  /// Metrics that could not be computed are NaN here and absent from files; this says which and
  /// why (e.g. a record that ends before the drive has no residual vibration). Empty: all are.
  std::string not_available;
  /// How the peaks were found: "samples" (the output samples), "continuous" (the response
  /// between the samples too: the full order's interpolant through every step, the ROM's exact
  /// modal solution). Empty when not said (older files).
  std::string peaks_resolved;
  /// The full order's own discretisation error, estimated from its local error estimates
  /// (fullorder/deployment_accuracy.hpp; adaptive runs only, else NaN): NRMSE of the relative end
  /// angular acceleration against the exact solution of the same model, and relative errors of
  /// the peaks.
  double estimated_nrmse_rel_end_angular_acceleration = kNotAvailable;
  double estimated_error_peak_rel_end_angular_acceleration = kNotAvailable;
  double estimated_error_peak_abs_end_angular_acceleration = kNotAvailable;
  double estimated_error_peak_joint_force = kNotAvailable;
};

/// Metrics of a deployment whose drive stops at drive_end_time_s (the drive law's duration T).
/// A record that ends before the drive does has no residual vibration and no settling time: those
/// are then kNotAvailable and not_available says why. Throws InputError when the band is not
/// finite and > 0 or drive_end_time_s is not finite; NumericalError when a column used is
/// non-finite (naming it, the index and the time); UsageError for an empty or
/// inconsistent series.
DeploymentMetrics computeMetrics(const DeploymentSeries& series, double drive_end_time_s,
                                 double settling_band_rad_s2 = kDefaultSettlingBandRadS2);

}  // namespace mastrom::fullorder
