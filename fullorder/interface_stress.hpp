// Strength of the interfaces over a deployment (docs/theory.md §6.2, §6.3): at the instants it is
// handed, the largest von Mises stress of each interface (over its elements, the 3 × 3 recovery
// points of fullorder/shell_stress.hpp and the three stations ζ = −h/2, 0, +h/2), the peak with
// where and when it occurred and the whole stress field at that instant, and the section
// resultants at the interface's two bonded edges.
//
// Edge resultants come from the bonded edges' reactions, recovered by the method of sections from
// the equations of motion of the free body beyond the edge (the modules and shells farther from the
// base): with g = Q_gravity − M q̈ per coordinate, the edge transmits the wrench Σ W_c(g) of that
// free body, where W_c maps a generalized force to a force and a moment about the ring centre c
// by the virtual work of a rigid motion (points: (r − c) × g_r; direction vectors and slopes:
// d × g_d). Every internal force (elastic, damping, the modules' own constraints) is
// self-equilibrated and drops out, so this equals Φ_qᵀλ of the edge's constraint rows at a
// converged step — which the integrator does not compute when the linear edge equations are
// eliminated (fullorder/eliminated_system.hpp). Sign: the wrench the part beyond the section
// exerts on the part towards the base (axial force > 0 in tension), in the axes of the module
// the edge is bonded to (x̂ along the mast axis, then its u, v): force = [axial, shear u, shear v],
// moment = [torsion, bending about u, bending about v].
//
// Adaptive runs: the monitor evaluates at the first state it is handed after each output instant
// k·Δ (and at every piece start and the end), so its cost is at most that of evaluating the output
// grid, and resample() interpolates its histories onto the output instants with the same
// piecewise cubic as the other outputs (fullorder/continuous_response.hpp). The peak is the largest
// value at the evaluated states. A streamed run (streamHistories) resamples while it goes instead
// and keeps no history (fullorder/interface_stress_stream.hpp).
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "fullorder/deployment.hpp"
#include "fullorder/interface_stress_stream.hpp"
#include "fullorder/mast_model.hpp"
#include "fullorder/shell_stress.hpp"

namespace mastrom::fullorder {

/// The time histories of one interface.
struct InterfaceStressHistory {
  std::vector<double> max_von_mises_pa;
  std::vector<Eigen::Vector3d> base_force_n, base_moment_nm;  ///< edge bonded to module k
  std::vector<Eigen::Vector3d> tip_force_n, tip_moment_nm;    ///< edge bonded to module k + 1
};

/// The peak von Mises stress of one interface, where and when it occurred, and the field then.
struct InterfaceStressPeak {
  double von_mises_pa = 0.0;
  double time_s = 0.0;
  int element = 0;  ///< within the interface: ring-major, i·N_circ + j (i axial, j circumferential)
  int point = 0;    ///< recovery point (ShellStressRecovery::gridPoints order)
  int surface = 0;  ///< ζ station: 0 = −h/2, 1 = mid-surface, 2 = +h/2 (along n = g_x × g_y)
  double axial_position_m = 0.0;  ///< of that point, from the base edge
  double angle_rad = 0.0;         ///< of that point about the axis, from the module's u axis
  /// von Mises at every element × point × surface at the peak instant (surface fastest).
  std::vector<double> field_von_mises_pa;
};

/// The von Mises field of every interface at one chosen instant.
struct InterfaceStressSnapshot {
  double requested_time_s = 0.0;
  double time_s = 0.0;  ///< the evaluated instant: the first at or after the requested one
  std::vector<std::vector<double>> field_von_mises_pa;  ///< per interface, as the peak's field
};

/// Everything the monitor found.
struct InterfaceStressResult {
  std::vector<double> time_s;                  ///< instants of the histories
  std::vector<InterfaceStressHistory> history;  ///< per interface
  std::vector<InterfaceStressPeak> peak;        ///< per interface
  std::vector<InterfaceStressSnapshot> snapshots;  ///< fields at the requested instants
  /// Per interface, per element × point: axial position [m] and angle [rad] in the reference
  /// configuration (the cylinder unrolled), for fields.
  std::vector<std::vector<std::array<double, 2>>> point_coordinates;
  /// The same points' reference positions in the stowed mast (global frame) [m], for fields.
  std::vector<std::vector<Eigen::Vector3d>> point_positions;
  std::vector<std::array<double, 2>> recovery_points;  ///< (ξ, η) of the recovery points
  int elements_axial = 0, elements_circumferential = 0;
  bool empty() const { return time_s.empty(); }
};

class InterfaceStressMonitor {
public:
  /// @param evaluation_interval_s  evaluate at the first state on or after each multiple of it
  ///                               (0: at every state handed)
  /// @param end_time_s             the run's end: its last state is always evaluated
  InterfaceStressMonitor(const MastModel& model, double evaluation_interval_s = 0.0,
                         double end_time_s = 0.0);

  /// Offer the full-coordinate state at time t (q, q̇ and q̈ — the index-1 accelerations where
  /// available); `piece_start` marks the first state after a drive breakpoint. Evaluated when due.
  void offer(double time_s, const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
             const Eigen::VectorXd& qddot, bool piece_start);
  /// Also keep the whole field at these instants (each at the first evaluated state at or after
  /// it; instants past the last evaluation are dropped). InputError for a non-finite time.
  void requestFields(std::vector<double> times_s);
  /// Evaluate at this state unconditionally (the last state of a run).
  void evaluate(double time_s, const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                const Eigen::VectorXd& qddot);

  /// The stresses at every recovery point of interface k (0-based; element-major, points in
  /// ShellStressRecovery::gridPoints order) for full coordinates q and velocities q̇ (may be null:
  /// elastic part only). The order of InterfaceStressResult::point_coordinates.
  std::vector<ShellPointStress> pointStresses(int k, const Eigen::VectorXd& q,
                                              const Eigen::VectorXd* qdot) const;
  /// Linearised at q: the stresses per unit of the direction d in coordinate space (a mode shape
  /// at the locked configuration gives the modal stresses a modal ROM stores; docs/theory.md
  /// §6.1). von_mises_pa is left zero.
  std::vector<ShellPointStress> linearizedPointStresses(int k, const Eigen::VectorXd& q,
                                                        const Eigen::VectorXd& d) const;

  /// Hand the histories to `sink` resampled onto the output instants (outputInstant) as soon as
  /// each is final, instead of keeping them: result() then holds no history (time_s and history
  /// stay empty), and memory does not grow with the horizon. Before the first evaluation.
  void streamHistories(InterfaceStressRowSink sink);
  /// The next output instant (ascending) of a streamed run; its row reaches the sink once the
  /// evaluations that fix it are made.
  void outputInstant(double time_s);
  /// The run is over: the output instants still pending go to the sink (streamed runs).
  void finishHistories();

  /// Wall time spent evaluating so far [s] (the monitor's cost in a run).
  double evaluationSeconds() const { return evaluation_seconds_; }
  /// States evaluated so far, and the time of the last [s] (valid when evaluationCount() > 0).
  std::size_t evaluationCount() const { return evaluations_; }
  double lastEvaluatedTime() const { return last_time_s_; }
  /// Evaluated instants held in memory (all of them, or a streamed run's few).
  std::size_t heldEvaluations() const;
  /// The result at the evaluated instants (peaks and fields only, when streamed).
  const InterfaceStressResult& result() const { return result_; }
  /// The histories interpolated onto `times` (within the evaluated span) by the piecewise cubic
  /// through the four nearest evaluated instants of the same piece; peaks are copied.
  InterfaceStressResult resample(const std::vector<double>& times) const;

private:
  struct Interface {
    std::vector<int> elements;                  ///< system element indices
    std::vector<ShellStressRecovery> recovery;  ///< one per element
    int base_module = 0, tip_module = 0;
    std::vector<int> base_ring, tip_ring;       ///< global node ids
    int first_dof = 0, dof_count = 0;
  };
  void evaluateState(double time_s, const Eigen::VectorXd& q, const Eigen::VectorXd& qdot,
                     const Eigen::VectorXd& qddot, bool piece_start);
  /// row_ into the histories, or to the resampler of a streamed run.
  void storeRow(bool piece_start);
  /// Force and moment about the global origin of the generalized force g on module m / interface k.
  void moduleWrench(int module, const Eigen::VectorXd& q, const Eigen::VectorXd& g,
                    Eigen::Vector3d& force, Eigen::Vector3d& moment) const;
  void shellWrench(const Interface& itf, const Eigen::VectorXd& q, const Eigen::VectorXd& g,
                   Eigen::Vector3d& force, Eigen::Vector3d& moment) const;

  const MastModel& model_;
  double interval_s_ = 0.0;
  double end_time_s_ = 0.0;
  double next_due_s_ = 0.0;
  std::vector<Interface> interfaces_;
  std::vector<long> piece_starts_;
  InterfaceStressResult result_;
  Eigen::VectorXd generalized_force_;
  double evaluation_seconds_ = 0.0;
  std::vector<double> field_requests_;  ///< sorted
  std::size_t next_request_ = 0;
  std::size_t evaluations_ = 0;
  double last_time_s_ = 0.0;
  InterfaceStressRow row_;  ///< the instant being evaluated
  std::unique_ptr<InterfaceStressResampler> stream_;
};

/// The monitor of a run with `options`: on the output grid (fixed steps: every recorded state;
/// adaptive: the first step point on or after each output instant, and the end).
InterfaceStressMonitor stressMonitorFor(const MastModel& model, const DeploymentOptions& options);

/// The DeploymentOptions::state_observer that offers every recorded state to `monitor` (borrowed:
/// it must outlive the run).
DeploymentStateObserver observeInterfaceStresses(InterfaceStressMonitor& monitor);

/// Margin of safety yield / peak − 1 (NaN when the peak is zero).
double marginOfSafety(double yield_strength_pa, double peak_von_mises_pa);

}  // namespace mastrom::fullorder
