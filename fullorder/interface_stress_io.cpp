// Interface stresses in result files (see interface_stress_io.hpp).
#include "fullorder/interface_stress_io.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "common/error.hpp"
#include "common/text_file.hpp"

namespace mastrom::fullorder {
namespace {

constexpr double kDegPerRad = 180.0 / 3.14159265358979323846;

void requireFiniteColumn(const std::string& what, const std::vector<Eigen::Vector3d>& rows) {
  for (std::size_t i = 0; i < rows.size(); ++i)
    MASTROM_REQUIRE(rows[i].allFinite(), NumericalError, "interface stresses: ", what,
                    " is not finite at index ", i);
}

constexpr const char* kForceComponents = "axial (> 0 tension), shear u, shear v";
constexpr const char* kMomentComponents = "torsion, bending about u, bending about v";

/// The edge's scalar resultants of one instant: axial force, shear force, torsion, bending.
std::array<double, 4> edgeScalars(const Eigen::Vector3d& force, const Eigen::Vector3d& moment) {
  return {force[0], std::hypot(force[1], force[2]), moment[0], std::hypot(moment[1], moment[2])};
}

void writeEdge(h5::File& file, const std::string& group, const std::vector<Eigen::Vector3d>& force,
               const std::vector<Eigen::Vector3d>& moment) {
  file.writeMatrix(group + "/force", force, "N");
  file.setStringAttribute(group + "/force", "components", kForceComponents);
  file.writeMatrix(group + "/moment", moment, "N*m");
  file.setStringAttribute(group + "/moment", "components", kMomentComponents);
  std::array<std::vector<double>, 4> scalars;
  for (std::size_t i = 0; i < force.size(); ++i) {
    const std::array<double, 4> s = edgeScalars(force[i], moment[i]);
    for (std::size_t c = 0; c < 4; ++c) scalars[c].push_back(s[c]);
  }
  file.writeDoubles(group + "/axial_force", scalars[0], "N");
  file.writeDoubles(group + "/shear_force", scalars[1], "N");
  file.writeDoubles(group + "/torsional_moment", scalars[2], "N*m");
  file.writeDoubles(group + "/bending_moment", scalars[3], "N*m");
}

/// The larger of the two walls' von Mises per point of a field (point-major, station fastest).
std::vector<double> wallMaximum(const std::vector<double>& field) {
  std::vector<double> walls(field.size() / kShellSurfaces);
  for (std::size_t p = 0; p < walls.size(); ++p)
    walls[p] = std::max(field[kShellSurfaces * p], field[kShellSurfaces * p + 2]);
  return walls;
}

/// Points, quads (2 × 2 per element between its 3 × 3 grid points, ξ fastest) and the larger wall
/// von Mises of the peak field, for ParaView.
void writePeakMesh(h5::File& file, const std::string& group, const InterfaceStressResult& r,
                   std::size_t k) {
  const std::size_t points = r.point_positions[k].size();
  file.writeMatrix(group + "/points", r.point_positions[k], "m");
  file.writeDoubles(group + "/von_mises_walls", wallMaximum(r.peak[k].field_von_mises_pa), "Pa");
  std::vector<double> cells;
  const std::size_t per_element = r.recovery_points.size();
  if (per_element == 9) {
    for (std::size_t e = 0; e < points / per_element; ++e)
      for (int j = 0; j < 2; ++j)
        for (int i = 0; i < 2; ++i) {
          const double base = static_cast<double>(e * per_element) + i + 3 * j;
          cells.insert(cells.end(), {base, base + 1, base + 4, base + 3});
        }
  }
  file.writeMatrix(group + "/cells", cells, cells.size() / 4, 4, "1");
}

}  // namespace

InterfaceStressMetrics interfaceStressMetrics(const InterfaceStressResult& result,
                                              std::optional<double> yield_strength_pa) {
  InterfaceStressMetrics m;
  for (const InterfaceStressPeak& p : result.peak) {
    m.peak_von_mises_pa.push_back(p.von_mises_pa);
    if (yield_strength_pa) {
      const double margin = marginOfSafety(*yield_strength_pa, p.von_mises_pa);
      m.margin_of_safety.push_back(margin);
      if (std::isfinite(margin))
        m.min_margin_of_safety = std::min(m.min_margin_of_safety.value_or(margin), margin);
    }
  }
  return m;
}

void writeInterfaceStresses(h5::File& file, const InterfaceStressResult& r, std::size_t time_count,
                            std::optional<double> yield_strength_pa) {
  MASTROM_REQUIRE(r.time_s.size() == time_count, UsageError, "interface stresses: ",
                  r.time_s.size(), " instants, /time has ", time_count);
  for (std::size_t k = 0; k < r.history.size(); ++k) {
    const InterfaceStressHistory& h = r.history[k];
    for (std::size_t i = 0; i < h.max_von_mises_pa.size(); ++i)
      MASTROM_REQUIRE(std::isfinite(h.max_von_mises_pa[i]), NumericalError,
                      "interface stresses: max von Mises of interface ", k + 1,
                      " is not finite at t = ", r.time_s[i], " s");
    requireFiniteColumn("base force", h.base_force_n);
    requireFiniteColumn("base moment", h.base_moment_nm);
    requireFiniteColumn("tip force", h.tip_force_n);
    requireFiniteColumn("tip moment", h.tip_moment_nm);
  }
  for (std::size_t k = 0; k < r.history.size(); ++k) {
    const std::string g = "/interfaces/" + std::to_string(k + 1);
    const InterfaceStressHistory& h = r.history[k];
    // A ROM result carries the history only when asked (rom eval --stress-history).
    if (!h.max_von_mises_pa.empty())
      file.writeDoubles(g + "/max_von_mises", h.max_von_mises_pa, "Pa");
    if (!h.base_force_n.empty()) {  // a ROM result carries no edge resultants
      writeEdge(file, g + "/base", h.base_force_n, h.base_moment_nm);
      writeEdge(file, g + "/tip", h.tip_force_n, h.tip_moment_nm);
    }
  }
  writeInterfaceStressResults(file, r, yield_strength_pa);
}

void writeInterfaceStressResults(h5::File& file, const InterfaceStressResult& r,
                                 std::optional<double> yield_strength_pa) {
  file.createGroup("/interfaces");
  file.setIntAttribute("/interfaces", "elements_axial", r.elements_axial);
  file.setIntAttribute("/interfaces", "elements_circumferential", r.elements_circumferential);
  std::vector<double> xi_eta;
  for (const auto& p : r.recovery_points) xi_eta.insert(xi_eta.end(), {p[0], p[1]});
  file.writeMatrix("/interfaces/recovery_points", xi_eta, r.recovery_points.size(), 2, "1");
  file.setStringAttribute("/interfaces", "surfaces",
                          "zeta = -h/2, 0, +h/2 along n = g_x x g_y (the inner wall is +h/2)");
  for (std::size_t k = 0; k < r.history.size(); ++k) {
    const std::string g = "/interfaces/" + std::to_string(k + 1);
    std::vector<double> coords;
    for (const auto& c : r.point_coordinates[k]) coords.insert(coords.end(), {c[0], c[1]});
    file.writeMatrix(g + "/points", coords, r.point_coordinates[k].size(), 2, "m, rad");
    const InterfaceStressPeak& p = r.peak[k];
    file.writeMatrix(g + "/peak/von_mises_field", p.field_von_mises_pa,
                     p.field_von_mises_pa.size() / kShellSurfaces, kShellSurfaces, "Pa");
    if (k < r.point_positions.size()) writePeakMesh(file, g + "/peak", r, k);
    file.setDoubleAttribute(g + "/peak", "von_mises_pa", p.von_mises_pa);
    file.setDoubleAttribute(g + "/peak", "time_s", p.time_s);
    file.setIntAttribute(g + "/peak", "element", p.element);
    file.setIntAttribute(g + "/peak", "point", p.point);
    file.setIntAttribute(g + "/peak", "surface", p.surface);
    file.setDoubleAttribute(g + "/peak", "axial_position_m", p.axial_position_m);
    file.setDoubleAttribute(g + "/peak", "angle_rad", p.angle_rad);
    for (std::size_t n = 0; n < r.snapshots.size(); ++n) {
      const InterfaceStressSnapshot& snap = r.snapshots[n];
      const std::string f = g + "/fields/" + std::to_string(n + 1);
      const std::vector<double>& field = snap.field_von_mises_pa[k];
      file.writeMatrix(f + "/von_mises_field", field, field.size() / kShellSurfaces,
                       kShellSurfaces, "Pa");
      file.writeDoubles(f + "/von_mises_walls", wallMaximum(field), "Pa");
      file.setDoubleAttribute(f, "requested_time_s", snap.requested_time_s);
      file.setDoubleAttribute(f, "time_s", snap.time_s);
    }
  }
  for (const auto& [name, value] : interfaceStressMetricAttributes(r, yield_strength_pa))
    file.setDoubleAttribute("/metrics", name, value);
}

std::vector<std::pair<std::string, double>> interfaceStressMetricAttributes(
    const InterfaceStressResult& r, std::optional<double> yield_strength_pa) {
  const InterfaceStressMetrics metrics = interfaceStressMetrics(r, yield_strength_pa);
  std::vector<std::pair<std::string, double>> out;
  for (std::size_t k = 0; k < r.peak.size(); ++k) {
    const std::string n = std::to_string(k + 1);
    out.emplace_back("peak_von_mises_interface_" + n, r.peak[k].von_mises_pa);
    if (yield_strength_pa && std::isfinite(metrics.margin_of_safety[k]))
      out.emplace_back("margin_of_safety_interface_" + n, metrics.margin_of_safety[k]);
  }
  if (yield_strength_pa) {
    out.emplace_back("yield_strength", *yield_strength_pa);
    if (metrics.min_margin_of_safety)
      out.emplace_back("min_margin_of_safety", *metrics.min_margin_of_safety);
  }
  return out;
}

void writeDeploymentFileWithStresses(const std::string& path, const DeploymentSeries& series,
                                     const DeploymentMetrics& metrics,
                                     const std::string& resolved_config_toml, double wall_time_s,
                                     const std::optional<InterfaceStressResult>& stresses,
                                     std::optional<double> yield_strength_pa, ResultSource source,
                                     std::optional<double> stopped_at_s,
                                     const std::function<void(h5::File&)>& extra) {
  series.checkConsistent();
  h5::AtomicH5Writer writer(path);
  writeDeployment(writer.file(), series, metrics, resolved_config_toml, wall_time_s, source);
  if (stresses) writeInterfaceStresses(writer.file(), *stresses, series.size(), yield_strength_pa);
  if (extra) extra(writer.file());
  if (stopped_at_s) markIncomplete(writer.file(), *stopped_at_s);
  writer.commit();
}

InterfaceStressAppender::InterfaceStressAppender(h5::File& file, std::size_t interfaces,
                                                 std::size_t block_rows, bool edge_resultants)
    : block_rows_(std::max<std::size_t>(1, block_rows)), edges_(edge_resultants) {
  using h5::AppendableDataset;
  using h5::AppendType;
  const auto edge = [&](const std::string& g) {
    Edge e{
        AppendableDataset(file, g + "/force", AppendType::Double, 3, block_rows_, "N"),
        AppendableDataset(file, g + "/moment", AppendType::Double, 3, block_rows_, "N*m"),
        AppendableDataset(file, g + "/axial_force", AppendType::Double, 0, block_rows_, "N"),
        AppendableDataset(file, g + "/shear_force", AppendType::Double, 0, block_rows_, "N"),
        AppendableDataset(file, g + "/torsional_moment", AppendType::Double, 0, block_rows_, "N*m"),
        AppendableDataset(file, g + "/bending_moment", AppendType::Double, 0, block_rows_, "N*m")};
    file.setStringAttribute(g + "/force", "components", kForceComponents);
    file.setStringAttribute(g + "/moment", "components", kMomentComponents);
    return e;
  };
  for (std::size_t k = 0; k < interfaces; ++k) {
    const std::string g = "/interfaces/" + std::to_string(k + 1);
    Interface itf;
    itf.max_von_mises =
        AppendableDataset(file, g + "/max_von_mises", AppendType::Double, 0, block_rows_, "Pa");
    if (edges_) {
      itf.base = edge(g + "/base");
      itf.tip = edge(g + "/tip");
    }
    datasets_.push_back(std::move(itf));
  }
  block_.reserve(block_rows_);
}

void InterfaceStressAppender::append(const InterfaceStressRow& row) {
  for (std::size_t k = 0; k < datasets_.size(); ++k) {
    MASTROM_REQUIRE(std::isfinite(row.max_von_mises_pa[k]), NumericalError,
                    "interface stresses: max von Mises of interface ", k + 1,
                    " is not finite at t = ", row.time_s, " s");
    MASTROM_REQUIRE(
        !edges_ || (row.base_force_n[k].allFinite() && row.base_moment_nm[k].allFinite() &&
                    row.tip_force_n[k].allFinite() && row.tip_moment_nm[k].allFinite()),
        NumericalError, "interface stresses: an edge resultant of interface ", k + 1,
        " is not finite at t = ", row.time_s, " s");
  }
  block_.push_back(row);
  if (block_.size() >= block_rows_) writeBlock();
}

void InterfaceStressAppender::writeBlock() {
  const std::size_t n = block_.size();
  std::vector<double> column(n);
  std::vector<Eigen::Vector3d> vectors(n);
  const auto put = [&](h5::AppendableDataset& d, auto value) {
    for (std::size_t i = 0; i < n; ++i) column[i] = value(block_[i]);
    d.append(column.data(), n);
  };
  const auto putVectors = [&](h5::AppendableDataset& d, auto value) {
    for (std::size_t i = 0; i < n; ++i) vectors[i] = value(block_[i]);
    static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double));
    d.append(vectors.data(), n);
  };
  const auto putEdge = [&](Edge& e, std::size_t k, bool base) {
    const auto force = [k, base](const InterfaceStressRow& r) {
      return base ? r.base_force_n[k] : r.tip_force_n[k];
    };
    const auto moment = [k, base](const InterfaceStressRow& r) {
      return base ? r.base_moment_nm[k] : r.tip_moment_nm[k];
    };
    putVectors(e.force, force);
    putVectors(e.moment, moment);
    h5::AppendableDataset* scalars[4] = {&e.axial, &e.shear, &e.torsion, &e.bending};
    for (std::size_t c = 0; c < 4; ++c)
      put(*scalars[c],
          [&](const InterfaceStressRow& r) { return edgeScalars(force(r), moment(r))[c]; });
  };
  for (std::size_t k = 0; k < datasets_.size(); ++k) {
    put(datasets_[k].max_von_mises,
        [k](const InterfaceStressRow& r) { return r.max_von_mises_pa[k]; });
    if (!edges_) continue;
    putEdge(datasets_[k].base, k, true);
    putEdge(datasets_[k].tip, k, false);
  }
  written_ += n;
  block_.clear();
}

void InterfaceStressAppender::close() {
  if (!block_.empty()) writeBlock();
  for (Interface& itf : datasets_) {
    itf.max_von_mises.close();
    if (!edges_) continue;
    for (Edge* e : {&itf.base, &itf.tip})
      for (h5::AppendableDataset* d :
           {&e->force, &e->moment, &e->axial, &e->shear, &e->torsion, &e->bending})
        d->close();
  }
}

void writeInterfaceStressXdmf(const std::string& xdmf_path, const std::string& h5_reference,
                              const InterfaceStressResult& r) {
  std::ostringstream x;
  // One grid per interface: the quads of /interfaces/K/peak, the wall von Mises of `field`.
  const auto grid = [&](std::size_t k, const std::string& field, double time_s) {
    const std::string g = h5_reference + ":/interfaces/" + std::to_string(k + 1);
    const std::size_t points = r.point_positions[k].size();
    const std::size_t cells = points / 9 * 4;
    x << "        <Grid Name=\"interface " << k + 1 << "\" GridType=\"Uniform\">\n"
      << "          <Information Name=\"time_s\" Value=\"" << time_s << "\" />\n"
      << "          <Topology TopologyType=\"Quadrilateral\" NumberOfElements=\"" << cells
      << "\">\n            <DataItem Dimensions=\"" << cells << " 4\" NumberType=\"Float\" "
      << "Precision=\"8\" Format=\"HDF\">" << g << "/peak/cells</DataItem>\n"
      << "          </Topology>\n          <Geometry GeometryType=\"XYZ\">\n"
      << "            <DataItem Dimensions=\"" << points << " 3\" NumberType=\"Float\" "
      << "Precision=\"8\" Format=\"HDF\">" << g << "/peak/points</DataItem>\n"
      << "          </Geometry>\n"
      << "          <Attribute Name=\"von_mises_pa\" AttributeType=\"Scalar\" Center=\"Node\">\n"
      << "            <DataItem Dimensions=\"" << points << "\" NumberType=\"Float\" "
      << "Precision=\"8\" Format=\"HDF\">" << g << "/" << field << "/von_mises_walls</DataItem>\n"
      << "          </Attribute>\n        </Grid>\n";
  };
  x << "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"2.0\">\n  <Domain>\n"
    << "    <Grid Name=\"interface stresses\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  // Step 0: every interface at its own peak; then the requested instants in time order.
  x << "      <Grid Name=\"peaks\" GridType=\"Collection\" CollectionType=\"Spatial\">\n"
    << "        <Time Value=\"0\" />\n";
  for (std::size_t k = 0; k < r.peak.size(); ++k) grid(k, "peak", r.peak[k].time_s);
  x << "      </Grid>\n";
  for (std::size_t n = 0; n < r.snapshots.size(); ++n) {
    x << "      <Grid Name=\"t = " << r.snapshots[n].time_s << " s\" GridType=\"Collection\" "
      << "CollectionType=\"Spatial\">\n        <Time Value=\"" << n + 1 << "\" />\n";
    for (std::size_t k = 0; k < r.peak.size(); ++k)
      grid(k, "fields/" + std::to_string(n + 1), r.snapshots[n].time_s);
    x << "      </Grid>\n";
  }
  x << "    </Grid>\n  </Domain>\n</Xdmf>\n";
  writeTextFileAtomically(xdmf_path, x.str());
}

std::optional<InterfaceStressSummary> readInterfaceStressSummary(const std::string& path) {
  const h5::File file = h5::File::open(path, h5::OpenMode::ReadOnly);
  if (!file.exists("/interfaces")) return std::nullopt;
  InterfaceStressSummary s;
  for (int k = 1; file.exists("/interfaces/" + std::to_string(k)); ++k) {
    const std::string g = "/interfaces/" + std::to_string(k);
    s.max_von_mises_pa.push_back(file.exists(g + "/max_von_mises")
                                     ? file.readDoubles(g + "/max_von_mises")
                                     : std::vector<double>{});
    s.peak_von_mises_pa.push_back(file.readDoubleAttribute(g + "/peak", "von_mises_pa"));
  }
  return s;
}

void printInterfaceStressSummary(const InterfaceStressResult& r,
                                 std::optional<double> yield_strength_pa) {
  static const char* const kSurface[kShellSurfaces] = {"outer", "mid", "inner"};
  const InterfaceStressMetrics m = interfaceStressMetrics(r, yield_strength_pa);
  for (std::size_t k = 0; k < r.peak.size(); ++k) {
    const InterfaceStressPeak& p = r.peak[k];
    std::printf("  interface %zu: peak von Mises %.4g MPa at t = %.4f s, element %d, x = %.4g mm, "
                "angle %.1f deg, %s wall",
                k + 1, p.von_mises_pa * 1e-6, p.time_s, p.element,
                // a point on the base edge sits at round-off from 0 (no "-4.988e-14 mm")
                std::abs(p.axial_position_m) < 1e-12 ? 0.0 : p.axial_position_m * 1e3,
                p.angle_rad * kDegPerRad, kSurface[p.surface]);
    if (yield_strength_pa) std::printf("; margin of safety %.3g", m.margin_of_safety[k]);
    std::printf("\n");
  }
  if (m.min_margin_of_safety) std::printf("  min margin of safety %.3g\n", *m.min_margin_of_safety);
}

}  // namespace mastrom::fullorder
