// Modes result files (see modes_file.hpp).
#include "modes/modes_file.hpp"

#include <cmath>
#include <stdexcept>

#include "common/error.hpp"
#include "common/version.hpp"
#include "modes/h5_datasets.hpp"

namespace mastrom::modes {
namespace {

constexpr const char* kGroup = "/modes";
constexpr const char* kSource = "modes";

// Units of the datasets, one place for writing and documenting.
constexpr const char* kUnitsSqrtKgM = "kg^0.5*m";

struct VectorField {
  const char* path;
  const char* units;
  Eigen::VectorXd ModesData::*member;
};
struct MatrixField {
  const char* path;
  const char* units;
  Eigen::MatrixXd ModesData::*member;
};

const VectorField kVectors[] = {
    {"/modes/frequency_hz", "Hz", &ModesData::frequency_hz},
    {"/modes/damping_ratio", "1", &ModesData::damping_ratio},
    {"/modes/participation", kUnitsSqrtKgM, &ModesData::participation},
    {"/modes/effective_mass_fraction", "1", &ModesData::effective_mass_fraction},
    {"/modes/centrifugal_participation", kUnitsSqrtKgM, &ModesData::centrifugal_participation},
    {"/modes/residual", "1", &ModesData::residual},
    {"/modes/reference", "m (mixed: m for positions, 1 for slopes and direction vectors)",
     &ModesData::reference},
};
const MatrixField kMatrices[] = {
    {"/modes/translation_participation", "kg^0.5", &ModesData::translation_participation},
    {"/modes/coriolis", "1", &ModesData::coriolis},
    {"/modes/shapes",
     "kg^-0.5 (mixed: per unit modal coordinate [kg^0.5*m], m for positions, 1 for slopes)",
     &ModesData::shapes},
    {"/modes/end_rotation", "rad/(kg^0.5*m)", &ModesData::end_rotation},
    {"/modes/end_displacement", "kg^-0.5", &ModesData::end_displacement},
};
constexpr const char* kAnglePath = "/modes/angle_rad";
constexpr const char* kLabelsPath = "/modes/labels";

std::vector<double> toStd(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

}  // namespace

void ModesData::check(const std::string& file_path) const {
  const Eigen::Index k = frequency_hz.size();
  const auto requireSize = [&](const char* what, Eigen::Index rows, Eigen::Index cols,
                               Eigen::Index want_rows, Eigen::Index want_cols) {
    if (rows != want_rows || cols != want_cols)
      throw UsageError(::mastrom::detail::concat("modes data: ", what, " is ", rows,
                                                            " x ", cols, ", expected ", want_rows,
                                                            " x ", want_cols));
  };
  for (const VectorField& f : kVectors) {
    if (f.member == &ModesData::reference) continue;
    requireSize(f.path, (this->*f.member).size(), 1, k, 1);
  }
  const Eigen::Index ndof = reference.size();
  requireSize("/modes/translation_participation", translation_participation.rows(),
              translation_participation.cols(), k, 3);
  requireSize("/modes/coriolis", coriolis.rows(), coriolis.cols(), k, k);
  requireSize("/modes/shapes", shapes.rows(), shapes.cols(), k, ndof);
  requireSize("/modes/end_rotation", end_rotation.rows(), end_rotation.cols(), k, 3);
  requireSize("/modes/end_displacement", end_displacement.rows(), end_displacement.cols(), k, 3);
  if (static_cast<Eigen::Index>(labels.size()) != k)
    throw UsageError(
        ::mastrom::detail::concat("modes data: ", labels.size(), " labels for ", k, " modes"));

  const auto fail = [&](const std::string& what, double value) {
    throw NumericalError(::mastrom::detail::concat("refusing to write a non-finite value to '",
                                                   file_path, "': ", what, " = ", value));
  };
  for (const VectorField& f : kVectors) {
    const Eigen::VectorXd& v = this->*f.member;
    for (Eigen::Index i = 0; i < v.size(); ++i)
      if (!std::isfinite(v(i))) fail(::mastrom::detail::concat(f.path, "[", i, "]"), v(i));
  }
  for (const MatrixField& f : kMatrices) {
    const Eigen::MatrixXd& a = this->*f.member;
    for (Eigen::Index i = 0; i < a.rows(); ++i)
      for (Eigen::Index j = 0; j < a.cols(); ++j)
        if (!std::isfinite(a(i, j)))
          fail(::mastrom::detail::concat(f.path, "[", i, ", ", j, "]"), a(i, j));
  }
  if (!std::isfinite(angle_rad)) fail(kAnglePath, angle_rad);
  if (!std::isfinite(rotational_inertia_kg_m2))
    fail("/modes attribute rotational_inertia_kg_m2", rotational_inertia_kg_m2);
}

ModesData modesData(const ModalAnalysis& a, const Linearization& lin, double angle_rad) {
  ModesData d;
  d.angle_rad = angle_rad;
  d.backend = toString(a.eigen.backend);
  d.status = toString(a.eigen.status);
  d.requested = a.eigen.requested;
  d.frequency_hz = a.eigen.frequencies_hz;
  d.damping_ratio = a.damping_ratio;
  d.participation = a.participation;
  d.effective_mass_fraction = a.effective_mass_fraction;
  d.centrifugal_participation = a.centrifugal_participation;
  d.residual = a.residuals.size() == d.frequency_hz.size()
                   ? a.residuals
                   : Eigen::VectorXd::Zero(d.frequency_hz.size());
  d.translation_participation = a.translation_participation;
  d.coriolis = a.coriolis;
  d.shapes = a.eigen.modes.transpose();
  d.end_rotation = a.end_rotation;
  d.end_displacement = a.end_displacement;
  d.reference = lin.q;
  d.rotational_inertia_kg_m2 = a.rotational_inertia_kg_m2;
  d.labels = a.labels;
  return d;
}

void writeModes(h5::File& file, const ModesData& data, const std::string& resolved_config_toml,
                double wall_time_s) {
  data.check(file.path());
  MASTROM_REQUIRE(std::isfinite(wall_time_s), NumericalError,
                  "refusing to write a non-finite value to '", file.path(),
                  "': / attribute wall_time_s = ", wall_time_s);
  file.createGroup(kGroup);
  for (const VectorField& f : kVectors) file.writeDoubles(f.path, toStd(data.*f.member), f.units);
  for (const MatrixField& f : kMatrices) file.writeMatrix(f.path, data.*f.member, f.units);
  file.writeDoubles(kAnglePath, {data.angle_rad}, "rad");
  detail::writeStrings(file, kLabelsPath, data.labels, "1");
  file.setDoubleAttribute(kGroup, "rotational_inertia_kg_m2", data.rotational_inertia_kg_m2);
  file.setStringAttribute(kGroup, "backend", data.backend);
  file.setStringAttribute(kGroup, "status", data.status);
  file.setIntAttribute(kGroup, "requested", data.requested);
  file.setIntAttribute(kGroup, "stable", data.stability_checked ? (data.stable ? 1 : 0) : -1);
  file.setStringAttribute(kGroup, "instability", data.instability);

  file.setStringAttribute("/", "config", resolved_config_toml);
  file.setStringAttribute("/", "mastrom_version", kVersion);
  file.setStringAttribute("/", "source", kSource);
  file.setDoubleAttribute("/", "wall_time_s", wall_time_s);
}

void writeModesFile(const std::string& path, const ModesData& data,
                    const std::string& resolved_config_toml, double wall_time_s) {
  data.check(path);  // before any file exists
  h5::AtomicH5Writer writer(path);
  writeModes(writer.file(), data, resolved_config_toml, wall_time_s);
  writer.commit();
}

ModesFile readModesFile(const std::string& path) {
  const h5::File file = h5::File::open(path, h5::OpenMode::ReadOnly);
  std::string missing;
  const auto note = [&](const std::string& what) {
    missing += (missing.empty() ? "" : ", ") + what;
  };
  for (const VectorField& f : kVectors)
    if (!file.exists(f.path)) note(f.path);
  for (const MatrixField& f : kMatrices)
    if (!file.exists(f.path)) note(f.path);
  if (!file.exists(kAnglePath)) note(kAnglePath);
  if (!file.exists(kLabelsPath)) note(kLabelsPath);
  for (const char* name : {"rotational_inertia_kg_m2", "backend", "status", "requested"})
    if (file.exists(kGroup) && !file.hasAttribute(kGroup, name))
      note(std::string(kGroup) + " attribute " + name);
  for (const char* name : {"config", "mastrom_version", "source", "wall_time_s"})
    if (!file.hasAttribute("/", name)) note(std::string("/ attribute ") + name);
  MASTROM_REQUIRE(missing.empty(), IoError, "'", path, "' is not a mastrom modes file: missing ",
                  missing);

  ModesFile out;
  ModesData& d = out.modes;
  for (const VectorField& f : kVectors) {
    const std::vector<double> v = file.readDoubles(f.path);
    d.*f.member = Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
  }
  for (const MatrixField& f : kMatrices) {
    // A [k, 0] or [0, n] dataset reads back as an empty matrix; keep the shape consistent.
    d.*f.member = file.readMatrix(f.path);
  }
  const std::vector<double> angle = file.readDoubles(kAnglePath);
  MASTROM_REQUIRE(angle.size() == 1, IoError, "'", path, "': ", kAnglePath, " has ", angle.size(),
                  " entries, expected 1");
  d.angle_rad = angle[0];
  d.labels = detail::readStrings(file, kLabelsPath);
  d.rotational_inertia_kg_m2 = file.readDoubleAttribute(kGroup, "rotational_inertia_kg_m2");
  d.backend = file.readStringAttribute(kGroup, "backend");
  d.status = file.readStringAttribute(kGroup, "status");
  d.requested = file.readIntAttribute(kGroup, "requested");
  if (file.hasAttribute(kGroup, "stable")) {  // absent in files of earlier versions
    const int stable = file.readIntAttribute(kGroup, "stable");
    d.stability_checked = stable >= 0;
    d.stable = stable != 0;
    if (file.hasAttribute(kGroup, "instability"))
      d.instability = file.readStringAttribute(kGroup, "instability");
  }
  out.config_toml = file.readStringAttribute("/", "config");
  out.mastrom_version = file.readStringAttribute("/", "mastrom_version");
  out.source = file.readStringAttribute("/", "source");
  out.wall_time_s = file.readDoubleAttribute("/", "wall_time_s");
  MASTROM_REQUIRE(out.source == kSource, IoError, "'", path, "' has source '", out.source,
                  "', not a modes file");
  try {
    d.check(path);
  } catch (const std::exception& e) {
    throw IoError(::mastrom::detail::concat("'", path, "' is inconsistent: ", e.what()));
  }
  return out;
}

}  // namespace mastrom::modes
