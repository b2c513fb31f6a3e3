// Mode labels by circumferential harmonics (see mode_labels.hpp for the heuristic).
#include "modes/mode_labels.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <tuple>

#include "fullorder/block_rotation.hpp"

namespace mastrom::modes {
namespace {

/// Local frame of one shell node in the reference geometry.
struct NodeFrame {
  Eigen::Vector3d axis, normal, tangent;
  double angle = 0.0;  ///< circumferential angle φ
};

/// Nodes of one ring, with their frames.
using Ring = std::vector<int>;

}  // namespace

std::vector<std::string> labelModes(const fullorder::MultibodySystem& system,
                                    const Eigen::Ref<const Eigen::MatrixXd>& shapes,
                                    double frame_angle_rad) {
  const int nodes = system.nodeCount();
  const Eigen::Index k_modes = shapes.cols();
  std::vector<std::string> labels(static_cast<std::size_t>(k_modes), "rigid");
  if (nodes == 0 || shapes.rows() != system.dofCount()) return labels;

  // Reference frames of the nodes.
  std::vector<NodeFrame> frames(static_cast<std::size_t>(nodes));
  bool flat = true;
  const Eigen::Vector3d first_normal = system.nodeNormal(0).normalized();
  for (int i = 0; i < nodes; ++i) {
    NodeFrame& f = frames[static_cast<std::size_t>(i)];
    f.axis = system.nodeReference(i).segment<3>(3).normalized();
    f.normal = system.nodeNormal(i).normalized();
    f.tangent = f.axis.cross(f.normal);
    if (std::abs(f.normal.dot(first_normal)) < 1.0 - 1e-9) flat = false;
    // φ from the axis-perpendicular direction closest to global Y, towards axis × that.
    Eigen::Vector3d e1 = Eigen::Vector3d::UnitY() - f.axis * f.axis.y();
    if (e1.norm() < 1e-6) e1 = Eigen::Vector3d::UnitZ() - f.axis * f.axis.z();
    e1.normalize();
    const Eigen::Vector3d e2 = f.axis.cross(e1);
    f.angle = std::atan2(f.normal.dot(e2), f.normal.dot(e1));
  }

  // Rings: same axis (to 1e-6) and same axial coordinate (to 1 nm).
  std::map<std::tuple<long, long, long, long>, Ring> ring_map;
  for (int i = 0; i < nodes; ++i) {
    const NodeFrame& f = frames[static_cast<std::size_t>(i)];
    const Eigen::Vector3d r = system.nodeReference(i).head<3>();
    ring_map[{std::lround(f.axis.x() * 1e6), std::lround(f.axis.y() * 1e6),
              std::lround(f.axis.z() * 1e6), std::lround(r.dot(f.axis) * 1e9)}]
        .push_back(i);
  }

  // Displacements of every node in its own frame (axial, radial, tangential), per mode.
  const Eigen::Matrix3d back = fullorder::rotationAboutZ(-frame_angle_rad);
  std::vector<Eigen::MatrixXd> local(static_cast<std::size_t>(k_modes));
  std::vector<double> total(static_cast<std::size_t>(k_modes), 0.0),
      normal_part(static_cast<std::size_t>(k_modes), 0.0);
  for (Eigen::Index mode = 0; mode < k_modes; ++mode) {
    Eigen::MatrixXd& l = local[static_cast<std::size_t>(mode)];
    l.resize(3, nodes);
    for (int i = 0; i < nodes; ++i) {
      const NodeFrame& f = frames[static_cast<std::size_t>(i)];
      const Eigen::Vector3d u = back * shapes.col(mode).segment<3>(system.nodeDofOffset(i));
      l.col(i) = Eigen::Vector3d(u.dot(f.axis), u.dot(f.normal), u.dot(f.tangent));
      total[static_cast<std::size_t>(mode)] += u.squaredNorm();
      normal_part[static_cast<std::size_t>(mode)] += l(1, i) * l(1, i);
    }
  }
  if (flat) {
    for (Eigen::Index mode = 0; mode < k_modes; ++mode) {
      const std::size_t m = static_cast<std::size_t>(mode);
      if (total[m] > 0.0) labels[m] = normal_part[m] > 0.5 * total[m] ? "bending" : "in-plane";
    }
    return labels;
  }

  // Harmonic content: for every ring, the squared norms of the projections of each component onto
  // cos nφ and sin nφ (orthogonal projections, so uneven spacing is harmless; a basis function
  // that vanishes on the ring's nodes, e.g. sin nφ at n = N/2, contributes nothing). The tables of
  // cos nφ_j, sin nφ_j are built once per ring and used for every mode.
  int max_n = 0;
  for (const auto& entry : ring_map) max_n = std::max(max_n, int(entry.second.size()) / 2);
  Eigen::MatrixXd energy = Eigen::MatrixXd::Zero(k_modes, max_n + 1);
  Eigen::VectorXd axial0 = Eigen::VectorXd::Zero(k_modes), radial0 = axial0, torsion0 = axial0,
                  bend_y = axial0, bend_z = axial0;
  for (const auto& entry : ring_map) {
    const Ring& ring = entry.second;
    const int count = static_cast<int>(ring.size());
    const int ring_max_n = count / 2;
    Eigen::MatrixXd cos_table(count, ring_max_n + 1), sin_table(count, ring_max_n + 1);
    for (int j = 0; j < count; ++j) {
      const double phi = frames[static_cast<std::size_t>(ring[static_cast<std::size_t>(j)])].angle;
      for (int n = 0; n <= ring_max_n; ++n) {
        cos_table(j, n) = std::cos(n * phi);
        sin_table(j, n) = std::sin(n * phi);
      }
    }
    const double tiny = 1e-12 * count;
    Eigen::RowVectorXd inv_c = cos_table.colwise().squaredNorm();
    Eigen::RowVectorXd inv_s = sin_table.colwise().squaredNorm();
    for (int n = 0; n <= ring_max_n; ++n) {
      inv_c(n) = inv_c(n) > tiny ? 1.0 / inv_c(n) : 0.0;
      inv_s(n) = inv_s(n) > tiny ? 1.0 / inv_s(n) : 0.0;
    }
    Eigen::MatrixXd values(3, count);
    for (Eigen::Index mode = 0; mode < k_modes; ++mode) {
      for (int j = 0; j < count; ++j)
        values.col(j) =
            local[static_cast<std::size_t>(mode)].col(ring[static_cast<std::size_t>(j)]);
      // Rows: components (axial, radial, tangential); columns: harmonics.
      const Eigen::MatrixXd dot_c = values * cos_table, dot_s = values * sin_table;
      const Eigen::MatrixXd e_c = dot_c.array().square().rowwise() * inv_c.array();
      const Eigen::MatrixXd e_s = dot_s.array().square().rowwise() * inv_s.array();
      energy.row(mode).head(ring_max_n + 1) += (e_c + e_s).colwise().sum();
      axial0(mode) += e_c(0, 0);
      radial0(mode) += e_c(1, 0);
      torsion0(mode) += e_c(2, 0);
      if (ring_max_n >= 1) {
        bend_y(mode) += e_c(1, 1) + e_s(2, 1) + e_c(0, 1);
        bend_z(mode) += e_s(1, 1) + e_c(2, 1) + e_s(0, 1);
      }
    }
  }

  for (Eigen::Index mode = 0; mode < k_modes; ++mode) {
    std::string& label = labels[static_cast<std::size_t>(mode)];
    if (!(total[static_cast<std::size_t>(mode)] > 0.0)) continue;  // "rigid"
    Eigen::Index best = 0;
    energy.row(mode).maxCoeff(&best);
    if (best == 0) {
      if (axial0(mode) >= radial0(mode) && axial0(mode) >= torsion0(mode))
        label = "axial";
      else if (torsion0(mode) >= radial0(mode))
        label = "torsion";
      else
        label = "breathing";
    } else if (best == 1) {
      label = bend_y(mode) >= bend_z(mode) ? "bending-y" : "bending-z";
    } else {
      label = "shell n=" + std::to_string(best);
    }
  }
  return labels;
}

}  // namespace mastrom::modes
