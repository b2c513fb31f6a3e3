// Interface stresses over a deployment (see interface_stress.hpp; docs/theory.md §6.2–6.3).
#include "fullorder/interface_stress.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "common/error.hpp"
#include "fullorder/continuous_response.hpp"
#include "fullorder/interface_stress_stream.hpp"

namespace mastrom::fullorder {
namespace {

Vec36 gatherElement(const std::array<int, 36>& dofs, const Eigen::VectorXd& v) {
  Vec36 e;
  for (int c = 0; c < 36; ++c) e[c] = v[dofs[static_cast<size_t>(c)]];
  return e;
}

/// Module axes [x̂, u, v] (columns) from its NCF coordinates [r_i, r_j, u, v].
Eigen::Matrix3d moduleAxes(const Eigen::VectorXd& q, int offset) {
  Eigen::Matrix3d axes;
  axes.col(0) = (q.segment<3>(offset + 3) - q.segment<3>(offset)).normalized();
  axes.col(1) = q.segment<3>(offset + 6).normalized();
  axes.col(2) = q.segment<3>(offset + 9).normalized();
  return axes;
}

Eigen::Vector3d ringCentre(const MultibodySystem& sys, const std::vector<int>& ring,
                           const Eigen::VectorXd& q) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int node : ring) c += q.segment<3>(sys.nodeDofOffset(node));
  return c / static_cast<double>(ring.size());
}

}  // namespace

double marginOfSafety(double yield_strength_pa, double peak_von_mises_pa) {
  if (!(peak_von_mises_pa > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  return yield_strength_pa / peak_von_mises_pa - 1.0;
}

InterfaceStressMonitor stressMonitorFor(const MastModel& model, const DeploymentOptions& options) {
  return InterfaceStressMonitor(model, options.adaptive ? options.output_step_s : 0.0,
                                options.end_time_s);
}

DeploymentStateObserver observeInterfaceStresses(InterfaceStressMonitor& monitor) {
  return [&monitor](const DaeState& s, const Eigen::VectorXd& qdot, bool piece_start) {
    const Eigen::VectorXd& qddot = s.qddot_index1.size() == s.q.size() ? s.qddot_index1 : s.qddot;
    monitor.offer(s.time_s, s.q, qdot, qddot, piece_start);
  };
}

InterfaceStressMonitor::InterfaceStressMonitor(const MastModel& model, double evaluation_interval_s,
                                               double end_time_s)
    : model_(model), interval_s_(evaluation_interval_s), end_time_s_(end_time_s) {
  MASTROM_REQUIRE(std::isfinite(interval_s_) && interval_s_ >= 0.0, InputError,
                  "interface stresses: evaluation interval = ", interval_s_, " s must be >= 0");
  const MultibodySystem& sys = model.system();
  const Eigen::VectorXd& q0 = sys.referenceCoordinates();
  const int node_base = sys.nodeDofOffset(0);
  result_.recovery_points = ShellStressRecovery::gridPoints();
  result_.elements_axial = model.parameters().elements_axial;
  result_.elements_circumferential = model.parameters().elements_circumferential;
  for (int k = 0; k < model.interfaceCount(); ++k) {
    const MastModel::InterfaceRange& range = model.interfaceRange(k);
    Interface itf;
    itf.base_module = k;
    itf.tip_module = k + 1;
    itf.base_ring = range.ring0_nodes;
    itf.tip_ring = range.ring1_nodes;
    itf.first_dof = range.first_dof;
    itf.dof_count = range.dof_count;
    // The interface's elements are those whose nodes are its nodes (in the order they were added).
    for (int e = 0; e < sys.elementCount(); ++e) {
      const int node = (sys.elementDofs(e)[0] - node_base) / 9;
      if (node >= range.first_node && node < range.first_node + range.node_count)
        itf.elements.push_back(e);
    }
    // Reference frame of the cylinder: origin at the base ring's centre, axes of module k.
    const Eigen::Vector3d origin = ringCentre(sys, itf.base_ring, q0);
    const Eigen::Matrix3d axes = moduleAxes(q0, model.moduleDofOffset(k));
    std::vector<std::array<double, 2>> coords;
    std::vector<Eigen::Vector3d> positions;
    for (int e : itf.elements) {
      itf.recovery.emplace_back(sys.element(e), result_.recovery_points);
      const ShellStressRecovery& rec = itf.recovery.back();
      for (int p = 0; p < rec.pointCount(); ++p) {
        const Eigen::Vector3d local = axes.transpose() * (rec.referencePosition(p) - origin);
        double angle = std::atan2(local.z(), local.y());
        // [0, 2π), with the round-off of points on the u axis (atan2 of ∓1e-18) mapped to 0.
        if (std::abs(angle) < 1e-9) angle = 0.0;
        if (angle < 0.0) angle += 2.0 * 3.14159265358979323846;
        coords.push_back({local.x(), angle});
        positions.push_back(rec.referencePosition(p));
      }
    }
    result_.point_coordinates.push_back(std::move(coords));
    result_.point_positions.push_back(std::move(positions));
    interfaces_.push_back(std::move(itf));
  }
  result_.history.resize(interfaces_.size());
  result_.peak.resize(interfaces_.size());
}

void InterfaceStressMonitor::requestFields(std::vector<double> times_s) {
  for (double t : times_s)
    MASTROM_REQUIRE(std::isfinite(t), InputError, "interface stresses: field time ", t,
                    " s is not finite");
  std::sort(times_s.begin(), times_s.end());
  field_requests_ = std::move(times_s);
  next_request_ = 0;
  while (next_request_ < field_requests_.size() && evaluations_ > 0 &&
         field_requests_[next_request_] <= last_time_s_)
    ++next_request_;
}

void InterfaceStressMonitor::offer(double time_s, const Eigen::VectorXd& q,
                                   const Eigen::VectorXd& qdot, const Eigen::VectorXd& qddot,
                                   bool piece_start) {
  if (evaluations_ > 0 && time_s <= last_time_s_) return;  // not a later state
  const bool due = evaluations_ == 0 || piece_start || time_s >= next_due_s_ ||
                   (interval_s_ > 0.0 && time_s >= end_time_s_ - 1e-3 * interval_s_);
  if (!due) return;
  evaluateState(time_s, q, qdot, qddot, piece_start || evaluations_ == 0);
}

void InterfaceStressMonitor::evaluate(double time_s, const Eigen::VectorXd& q,
                                      const Eigen::VectorXd& qdot, const Eigen::VectorXd& qddot) {
  evaluateState(time_s, q, qdot, qddot, evaluations_ == 0);
}

void InterfaceStressMonitor::streamHistories(InterfaceStressRowSink sink) {
  MASTROM_REQUIRE(evaluations_ == 0, UsageError,
                  "interface stresses: streamHistories after the first evaluation");
  stream_ = std::make_unique<InterfaceStressResampler>(interfaces_.size(), std::move(sink));
}

void InterfaceStressMonitor::outputInstant(double time_s) {
  MASTROM_REQUIRE(stream_ != nullptr, UsageError,
                  "interface stresses: outputInstant without streamHistories");
  stream_->addOutputInstant(time_s);
}

void InterfaceStressMonitor::finishHistories() {
  if (stream_) stream_->finish();
}

std::size_t InterfaceStressMonitor::heldEvaluations() const {
  return stream_ ? stream_->heldEvaluations() : result_.time_s.size();
}

void InterfaceStressMonitor::evaluateState(double time_s, const Eigen::VectorXd& q,
                                           const Eigen::VectorXd& qdot,
                                           const Eigen::VectorXd& qddot, bool piece_start) {
  if (evaluations_ > 0 && time_s <= last_time_s_) return;  // already evaluated
  const auto started = std::chrono::steady_clock::now();
  if (interval_s_ > 0.0)
    next_due_s_ = interval_s_ * (std::floor(time_s / interval_s_ + 1e-3) + 1.0) - 1e-3 * interval_s_;
  ++evaluations_;
  last_time_s_ = time_s;
  row_.resize(interfaces_.size());
  row_.time_s = time_s;
  const MultibodySystem& sys = model_.system();

  // Stresses: the largest von Mises of each interface, and the field when it is a new peak or a
  // requested instant has been reached.
  std::vector<double> field;
  const bool snapshot_due =
      next_request_ < field_requests_.size() && field_requests_[next_request_] <= time_s;
  InterfaceStressSnapshot snapshot;
  if (snapshot_due) {
    snapshot.requested_time_s = field_requests_[next_request_];
    snapshot.time_s = time_s;
    while (next_request_ < field_requests_.size() && field_requests_[next_request_] <= time_s)
      ++next_request_;
  }
  for (std::size_t k = 0; k < interfaces_.size(); ++k) {
    InterfaceStressPeak& peak = result_.peak[k];
    double largest = 0.0;
    int where = 0;
    field.clear();
    for (const ShellPointStress& s : pointStresses(static_cast<int>(k), q, &qdot)) {
      for (int z = 0; z < kShellSurfaces; ++z) {
        const double vm = s.von_mises_pa[static_cast<size_t>(z)];
        MASTROM_REQUIRE(std::isfinite(vm), NumericalError,
                        "interface stresses: non-finite stress at t = ", time_s, " s");
        if (vm > largest) largest = vm, where = static_cast<int>(field.size());
        field.push_back(vm);
      }
    }
    row_.max_von_mises_pa[k] = largest;
    if (largest > peak.von_mises_pa || evaluations_ == 1) {
      const int per_element = static_cast<int>(result_.recovery_points.size()) * kShellSurfaces;
      peak.von_mises_pa = largest;
      peak.time_s = time_s;
      peak.element = where / per_element;
      peak.point = (where % per_element) / kShellSurfaces;
      peak.surface = where % kShellSurfaces;
      const std::array<double, 2>& xy =
          result_.point_coordinates[k][static_cast<size_t>(where / kShellSurfaces)];
      peak.axial_position_m = xy[0];
      peak.angle_rad = xy[1];
      peak.field_von_mises_pa = field;
    }
    if (snapshot_due) snapshot.field_von_mises_pa.push_back(field);
  }
  if (snapshot_due) result_.snapshots.push_back(std::move(snapshot));

  // Edge resultants by the method of sections (header): g = Q_gravity − M q̈.
  generalized_force_ = sys.gravityForce();
  generalized_force_.noalias() -= sys.massMatrix() * qddot;
  const int n = model_.moduleCount();
  std::vector<Eigen::Vector3d> body_force(static_cast<size_t>(n)), body_moment(static_cast<size_t>(n));
  for (int m = 0; m < n; ++m)
    moduleWrench(m, q, generalized_force_, body_force[static_cast<size_t>(m)],
                 body_moment[static_cast<size_t>(m)]);
  // From the top down: what lies beyond the tip edge of interface k, then beyond its base edge.
  Eigen::Vector3d beyond_force = Eigen::Vector3d::Zero(), beyond_moment = Eigen::Vector3d::Zero();
  for (int k = static_cast<int>(interfaces_.size()) - 1; k >= 0; --k) {
    const Interface& itf = interfaces_[static_cast<size_t>(k)];
    beyond_force += body_force[static_cast<size_t>(itf.tip_module)];
    beyond_moment += body_moment[static_cast<size_t>(itf.tip_module)];
    const std::size_t kk = static_cast<size_t>(k);
    const auto record = [&](int module, const std::vector<int>& ring, Eigen::Vector3d& force,
                            Eigen::Vector3d& moment) {
      const Eigen::Vector3d c = ringCentre(sys, ring, q);
      const Eigen::Matrix3d axes = moduleAxes(q, model_.moduleDofOffset(module));
      force = axes.transpose() * beyond_force;
      moment = axes.transpose() * (beyond_moment - c.cross(beyond_force));
    };
    record(itf.tip_module, itf.tip_ring, row_.tip_force_n[kk], row_.tip_moment_nm[kk]);
    Eigen::Vector3d f, m;
    shellWrench(itf, q, generalized_force_, f, m);
    beyond_force += f;
    beyond_moment += m;
    record(itf.base_module, itf.base_ring, row_.base_force_n[kk], row_.base_moment_nm[kk]);
  }
  storeRow(piece_start);
  evaluation_seconds_ +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
}

std::vector<ShellPointStress> InterfaceStressMonitor::pointStresses(
    int k, const Eigen::VectorXd& q, const Eigen::VectorXd* qdot) const {
  const Interface& itf = interfaces_.at(static_cast<size_t>(k));
  const MultibodySystem& sys = model_.system();
  std::vector<ShellPointStress> out;
  out.reserve(itf.elements.size() * result_.recovery_points.size());
  Vec36 edot;
  for (std::size_t i = 0; i < itf.elements.size(); ++i) {
    const std::array<int, 36>& dofs = sys.elementDofs(itf.elements[i]);
    const Vec36 e = gatherElement(dofs, q);
    if (qdot) edot = gatherElement(dofs, *qdot);
    const ShellStressRecovery& rec = itf.recovery[i];
    for (int p = 0; p < rec.pointCount(); ++p) out.push_back(rec.stress(p, e, qdot ? &edot : nullptr));
  }
  return out;
}

std::vector<ShellPointStress> InterfaceStressMonitor::linearizedPointStresses(
    int k, const Eigen::VectorXd& q, const Eigen::VectorXd& d) const {
  const Interface& itf = interfaces_.at(static_cast<size_t>(k));
  const MultibodySystem& sys = model_.system();
  std::vector<ShellPointStress> out;
  out.reserve(itf.elements.size() * result_.recovery_points.size());
  for (std::size_t i = 0; i < itf.elements.size(); ++i) {
    const std::array<int, 36>& dofs = sys.elementDofs(itf.elements[i]);
    const Vec36 e = gatherElement(dofs, q), de = gatherElement(dofs, d);
    const ShellStressRecovery& rec = itf.recovery[i];
    for (int p = 0; p < rec.pointCount(); ++p) out.push_back(rec.linearizedStress(p, e, de));
  }
  return out;
}

void InterfaceStressMonitor::moduleWrench(int module, const Eigen::VectorXd& q,
                                          const Eigen::VectorXd& g, Eigen::Vector3d& force,
                                          Eigen::Vector3d& moment) const {
  const int o = model_.moduleDofOffset(module);
  // δW of a rigid motion (δu, δθ) about the origin: δr = δu + δθ × r for r_i, r_j; δθ × d for u, v.
  force = g.segment<3>(o) + g.segment<3>(o + 3);
  moment = Eigen::Vector3d(q.segment<3>(o)).cross(Eigen::Vector3d(g.segment<3>(o)));
  for (int b = 1; b < 4; ++b)
    moment += Eigen::Vector3d(q.segment<3>(o + 3 * b)).cross(Eigen::Vector3d(g.segment<3>(o + 3 * b)));
}

void InterfaceStressMonitor::shellWrench(const Interface& itf, const Eigen::VectorXd& q,
                                         const Eigen::VectorXd& g, Eigen::Vector3d& force,
                                         Eigen::Vector3d& moment) const {
  force.setZero();
  moment.setZero();
  // Node blocks [r, r_x, r_y]: r is a point, r_x and r_y turn with the body.
  for (int o = itf.first_dof; o < itf.first_dof + itf.dof_count; o += 9) {
    force += g.segment<3>(o);
    for (int b = 0; b < 3; ++b)
      moment += Eigen::Vector3d(q.segment<3>(o + 3 * b)).cross(Eigen::Vector3d(g.segment<3>(o + 3 * b)));
  }
}

void InterfaceStressMonitor::storeRow(bool piece_start) {
  if (stream_) {
    stream_->addEvaluation(row_, piece_start);
    return;
  }
  if (piece_start) piece_starts_.push_back(static_cast<long>(result_.time_s.size()));
  result_.time_s.push_back(row_.time_s);
  appendStressRow(row_, result_.history);
}

InterfaceStressResult InterfaceStressMonitor::resample(const std::vector<double>& times) const {
  InterfaceStressResult out = result_;
  if (result_.time_s.empty()) return out;
  out.time_s.clear();
  for (InterfaceStressHistory& h : out.history) h = InterfaceStressHistory{};
  const std::vector<double>& t = result_.time_s;
  const long total = static_cast<long>(t.size());
  InterfaceStressRow row;
  for (double tau : times) {
    if (tau < t.front() - 1e-12 || tau > t.back() + 1e-12) continue;
    // The piece holding τ (by start times), then the cubic through its nearest points.
    std::size_t piece = 0;
    while (piece + 1 < piece_starts_.size() &&
           t[static_cast<size_t>(piece_starts_[piece + 1])] <= tau)
      ++piece;
    const long begin = piece_starts_[piece];
    const long end = piece + 1 < piece_starts_.size() ? piece_starts_[piece + 1] : total;
    interpolateStressRow(t, result_.history, begin, end, tau, row);
    out.time_s.push_back(tau);
    appendStressRow(row, out.history);
  }
  return out;
}

}  // namespace mastrom::fullorder
