// XDMF + HDF5 output of mode shapes (see xdmf_writer.hpp).
#include "modes/xdmf_writer.hpp"


#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "common/error.hpp"
#include "common/text_file.hpp"
#include "modes/h5_datasets.hpp"

namespace mastrom::modes {
namespace {

namespace fs = std::filesystem;

/// Corner signs of a hexahedron in VTK/XDMF order: the bottom face (−z) counter-clockwise seen from
/// +z, then the top face in the same order.
constexpr int kHexCorners[8][3] = {{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                   {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};

std::string modeName(int k) {
  char buffer[16];
  std::snprintf(buffer, sizeof buffer, "mode_%03d", k + 1);
  return buffer;
}

std::string escapeXml(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

/// Row-major copy of a list of 3-vectors.
std::vector<double> rowMajor(const std::vector<Eigen::Vector3d>& rows) {
  std::vector<double> out;
  out.reserve(3 * rows.size());
  for (const Eigen::Vector3d& r : rows) out.insert(out.end(), {r.x(), r.y(), r.z()});
  return out;
}

}  // namespace

VisualizationLayout writeModeVisualization(h5::File& file, const fullorder::MultibodySystem& system,
                                           const Eigen::Ref<const Eigen::VectorXd>& q,
                                           const Eigen::Ref<const Eigen::MatrixXd>& shapes,
                                           double relative_amplitude) {
  const int n = system.dofCount();
  MASTROM_REQUIRE(q.size() == n && shapes.rows() == n, InputError, "mode visualization: q has ",
                  q.size(), " entries and the shapes ", shapes.rows(), " rows for a system of ", n,
                  " DOFs");
  MASTROM_REQUIRE(std::isfinite(relative_amplitude) && relative_amplitude > 0.0, InputError,
                  "mode visualization: relative_amplitude = ", relative_amplitude, " must be > 0");
  VisualizationLayout layout;
  layout.modes = static_cast<int>(shapes.cols());
  layout.shell_points = system.nodeCount();
  layout.shell_cells = system.elementCount();
  layout.module_cells = system.bodyCount();
  layout.module_points = 8 * system.bodyCount();

  // Reference points and the corner maps of the modules.
  std::vector<Eigen::Vector3d> shell_points, module_points;
  for (int i = 0; i < system.nodeCount(); ++i)
    shell_points.push_back(q.segment<3>(system.nodeDofOffset(i)));
  std::vector<fullorder::Mat3x12> corner_maps;
  for (int b = 0; b < system.bodyCount(); ++b) {
    const fullorder::RigidModule& body = system.body(b);
    const double half = 0.5 * body.axisLength();
    const fullorder::Vec12 q_body = q.segment<12>(system.bodyDofOffset(b));
    for (const auto& s : kHexCorners) {
      corner_maps.push_back(body.pointMap(Eigen::Vector3d(s[0] * half, s[1] * half, s[2] * half)));
      module_points.push_back(corner_maps.back() * q_body);
    }
  }
  Eigen::Vector3d low = Eigen::Vector3d::Constant(1e300), high = -low;
  for (const auto* list : {&shell_points, &module_points})
    for (const Eigen::Vector3d& p : *list) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
  const double size = (shell_points.empty() && module_points.empty()) ? 1.0 : (high - low).norm();
  const double target = relative_amplitude * (size > 0.0 ? size : 1.0);

  const std::string shell = layout.group + "/shell", modules = layout.group + "/modules";
  if (layout.shell_cells > 0) {
    file.writeMatrix(shell + "/points", rowMajor(shell_points), shell_points.size(), 3, "m");
    std::vector<int> connectivity;
    for (int e = 0; e < system.elementCount(); ++e) {
      const std::array<int, 36>& dofs = system.elementDofs(e);
      for (int c = 0; c < 4; ++c)  // node id from the corner's first DOF
        connectivity.push_back((dofs[static_cast<size_t>(9 * c)] - system.nodeDofOffset(0)) / 9);
    }
    detail::writeIntMatrix(file, shell + "/connectivity", connectivity,
                           static_cast<std::size_t>(layout.shell_cells), 4, "1");
  }
  if (layout.module_cells > 0) {
    file.writeMatrix(modules + "/points", rowMajor(module_points), module_points.size(), 3, "m");
    std::vector<int> connectivity(static_cast<std::size_t>(layout.module_points));
    for (int i = 0; i < layout.module_points; ++i) connectivity[static_cast<size_t>(i)] = i;
    detail::writeIntMatrix(file, modules + "/connectivity", connectivity,
                           static_cast<std::size_t>(layout.module_cells), 8, "1");
  }

  for (int k = 0; k < layout.modes; ++k) {
    std::vector<Eigen::Vector3d> shell_u, module_u;
    double largest = 0.0;
    if (layout.shell_cells > 0)
      for (int i = 0; i < system.nodeCount(); ++i) {
        shell_u.push_back(shapes.col(k).segment<3>(system.nodeDofOffset(i)));
        largest = std::max(largest, shell_u.back().norm());
      }
    for (int b = 0; b < system.bodyCount(); ++b) {
      const fullorder::Vec12 d_body = shapes.col(k).segment<12>(system.bodyDofOffset(b));
      for (int c = 0; c < 8; ++c) {
        module_u.push_back(corner_maps[static_cast<size_t>(8 * b + c)] * d_body);
        largest = std::max(largest, module_u.back().norm());
      }
    }
    const double scale = largest > 0.0 ? target / largest : 1.0;
    layout.scales.push_back(scale);
    for (auto* list : {&shell_u, &module_u})
      for (Eigen::Vector3d& u : *list) u *= scale;
    if (layout.shell_cells > 0) {
      const std::string path = shell + "/" + modeName(k);
      file.writeMatrix(path, rowMajor(shell_u), shell_u.size(), 3, "m");
      file.setDoubleAttribute(path, "scale", scale);
    }
    if (layout.module_cells > 0) {
      const std::string path = modules + "/" + modeName(k);
      file.writeMatrix(path, rowMajor(module_u), module_u.size(), 3, "m");
      file.setDoubleAttribute(path, "scale", scale);
    }
  }
  file.setDoubleAttribute(layout.group, "relative_amplitude", relative_amplitude);
  return layout;
}

void writeXdmf(const std::string& xdmf_path, const std::string& h5_reference,
               const VisualizationLayout& layout,
               const Eigen::Ref<const Eigen::VectorXd>& frequencies_hz,
               const std::vector<std::string>& labels) {
  MASTROM_REQUIRE(
      frequencies_hz.size() == layout.modes && static_cast<int>(labels.size()) == layout.modes,
      InputError, "xdmf: ", layout.modes, " modes but ", frequencies_hz.size(), " frequencies and ",
      labels.size(), " labels");
  const std::string h5 = escapeXml(h5_reference);
  std::ostringstream x;
  x.precision(10);
  const auto data = [&](const std::string& path, int rows, int cols, bool integer) {
    x << "          <DataItem Dimensions=\"" << rows << " " << cols << "\" NumberType=\""
      << (integer ? "Int" : "Float") << "\" Precision=\"" << (integer ? 4 : 8)
      << "\" Format=\"HDF\">" << h5 << ":" << escapeXml(path) << "</DataItem>\n";
  };
  const auto grid = [&](const char* name, const char* topology, int corners, int points, int cells,
                        int mode) {
    const std::string base = layout.group + "/" + name;
    x << "      <Grid Name=\"" << name << "\" GridType=\"Uniform\">\n"
      << "        <Topology TopologyType=\"" << topology << "\" NumberOfElements=\"" << cells
      << "\">\n";
    data(base + "/connectivity", cells, corners, true);
    x << "        </Topology>\n        <Geometry GeometryType=\"XYZ\">\n";
    data(base + "/points", points, 3, false);
    x << "        </Geometry>\n"
      << "        <Attribute Name=\"mode_shape\" AttributeType=\"Vector\" Center=\"Node\">\n";
    data(base + "/" + modeName(mode), points, 3, false);
    x << "        </Attribute>\n      </Grid>\n";
  };

  x << "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
    << "<!-- mastrom mode shapes: one time step per mode (Time = mode number). In ParaView apply\n"
    << "     Warp By Vector (mode_shape); animate a mode with a sinusoidal key frame on the\n"
    << "     warp's Scale Factor. Displacements are scaled per mode (attribute 'scale' of the\n"
    << "     HDF5 datasets); the mass-normalised shapes are /modes/shapes. -->\n"
    << "<Xdmf Version=\"2.0\">\n  <Domain>\n"
    << "    <Grid Name=\"modes\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (int k = 0; k < layout.modes; ++k) {
    x << "    <Grid Name=\"mode " << k + 1 << "\" GridType=\"Collection\" "
      << "CollectionType=\"Spatial\">\n"
      << "      <Time Value=\"" << k + 1 << "\" />\n"
      << "      <Information Name=\"frequency_hz\" Value=\"" << frequencies_hz(k) << "\" />\n"
      << "      <Information Name=\"label\" Value=\"" << escapeXml(labels[static_cast<size_t>(k)])
      << "\" />\n"
      << "      <Information Name=\"scale\" Value=\"" << layout.scales[static_cast<size_t>(k)]
      << "\" />\n";
    if (layout.shell_cells > 0)
      grid("shell", "Quadrilateral", 4, layout.shell_points, layout.shell_cells, k);
    if (layout.module_cells > 0)
      grid("modules", "Hexahedron", 8, layout.module_points, layout.module_cells, k);
    x << "    </Grid>\n";
  }
  x << "    </Grid>\n  </Domain>\n</Xdmf>\n";

  writeTextFileAtomically(xdmf_path, x.str());
}

std::string xdmfPathFor(const std::string& h5_path) {
  fs::path p(h5_path);
  p.replace_extension(".xdmf");
  return p.string();
}

}  // namespace mastrom::modes
