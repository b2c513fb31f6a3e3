#include "python/src/arrays.hpp"

#include <cmath>
#include <cstring>
#include <utility>

namespace py = pybind11;

namespace mastrom::python {
namespace {

static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double),
              "the (N, 3) views assume unpadded 3-vectors");

/// A 1-D view of `v` kept alive by `owner`.
template <typename T>
py::array_t<T> view(const std::vector<T>& v, const py::capsule& owner) {
  return py::array_t<T>({static_cast<py::ssize_t>(v.size())}, {static_cast<py::ssize_t>(sizeof(T))},
                        v.data(), owner);
}

/// An (N, 3) view of a vector of 3-vectors, kept alive by `owner`.
py::array_t<double> view3(const std::vector<Eigen::Vector3d>& v, const py::capsule& owner) {
  const auto n = static_cast<py::ssize_t>(v.size());
  const auto row = static_cast<py::ssize_t>(sizeof(Eigen::Vector3d));
  return py::array_t<double>({n, py::ssize_t{3}}, {row, static_cast<py::ssize_t>(sizeof(double))},
                             v.empty() ? nullptr : v.front().data(), owner);
}

}  // namespace

py::array_t<double> copyVector(const Eigen::Ref<const Eigen::VectorXd>& v) {
  py::array_t<double> out(static_cast<py::ssize_t>(v.size()));
  if (v.size() > 0) std::memcpy(out.mutable_data(), v.data(), sizeof(double) * v.size());
  return out;
}

py::array_t<double> copyMatrix(const Eigen::Ref<const Eigen::MatrixXd>& m) {
  py::array_t<double> out({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  auto w = out.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) w(i, j) = m(i, j);
  return out;
}

py::array_t<double> copyRows(const std::vector<double>& data, std::size_t rows, std::size_t cols) {
  py::array_t<double> out({static_cast<py::ssize_t>(rows), static_cast<py::ssize_t>(cols)});
  if (!data.empty()) std::memcpy(out.mutable_data(), data.data(), sizeof(double) * rows * cols);
  return out;
}

py::dict metricsDict(const fullorder::DeploymentMetrics& m) {
  py::dict d;
  d["peak_abs_end_angular_acceleration"] = m.peak_abs_end_angular_acceleration;
  d["peak_rel_end_angular_acceleration"] = m.peak_rel_end_angular_acceleration;
  d["rms_rel_end_angular_acceleration"] = m.rms_rel_end_angular_acceleration;
  d["residual_rel_end_angular_acceleration"] = m.residual_rel_end_angular_acceleration;
  d["settling_time"] = m.settling_time;
  d["settled"] = m.settled;
  d["peak_joint_force"] = m.peak_joint_force;
  d["peak_drive_torque"] = m.peak_drive_torque;
  d["drive_end_time"] = m.drive_end_time;
  d["settling_band"] = m.settling_band;
  // As in the result file: the full order's own error estimates only when made, the notes only
  // when there is something to say (metrics not available are NaN here, absent from files).
  const std::pair<const char*, double> estimates[] = {
      {"estimated_nrmse_rel_end_angular_acceleration",
       m.estimated_nrmse_rel_end_angular_acceleration},
      {"estimated_error_peak_rel_end_angular_acceleration",
       m.estimated_error_peak_rel_end_angular_acceleration},
      {"estimated_error_peak_abs_end_angular_acceleration",
       m.estimated_error_peak_abs_end_angular_acceleration},
      {"estimated_error_peak_joint_force", m.estimated_error_peak_joint_force}};
  for (const auto& [name, value] : estimates)
    if (std::isfinite(value)) d[name] = value;
  if (!m.not_available.empty()) d["not_available"] = m.not_available;
  if (!m.peaks_resolved.empty()) d["peaks_resolved"] = m.peaks_resolved;
  return d;
}

py::dict seriesDict(fullorder::DeploymentSeries series) {
  auto* owned = new fullorder::DeploymentSeries(std::move(series));
  const py::capsule owner(owned,
                          [](void* p) { delete static_cast<fullorder::DeploymentSeries*>(p); });
  const fullorder::DeploymentSeries& s = *owned;
  py::dict d;
  d["time"] = view(s.time_s, owner);
  d["drive/angle"] = view(s.drive_angle_rad, owner);
  d["drive/rate"] = view(s.drive_rate_rad_s, owner);
  d["drive/acceleration"] = view(s.drive_acceleration_rad_s2, owner);
  d["end/angular_acceleration"] = view3(s.end_angular_acceleration_rad_s2, owner);
  d["end/relative_angular_acceleration"] = view(s.end_relative_angular_acceleration_rad_s2, owner);
  d["end/position"] = view3(s.end_position_m, owner);
  d["end/acceleration"] = view3(s.end_acceleration_m_s2, owner);
  const std::vector<double> tangential = s.endTangentialAccelerations();  // derived: a copy
  d["end/tangential_acceleration"] =
      py::array_t<double>(static_cast<py::ssize_t>(tangential.size()), tangential.data());
  d["joint/force"] = view3(s.joint_force_n, owner);
  d["joint/torque"] = view(s.joint_torque_nm, owner);
  static_assert(sizeof(int) == 4, "newton_iterations is handed over as int32");
  d["solver/newton_iterations"] = view(s.newton_iterations, owner);
  d["solver/constraint_residual"] = view(s.constraint_residual, owner);
  return d;
}

}  // namespace mastrom::python
