#include "rom/database/database_io.hpp"

#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string_view>

#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "common/version.hpp"
#include "rom/database/h5_arrays.hpp"
#include "rom/model/modal_fields.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/database/stress_arrays.hpp"

namespace mastrom::rom {
namespace {

// --- the /samples datasets: one table drives writing, reading, shape checks and the checksum -----
enum class Shape { S, SP, SK, S3, S3K, SKK };

/// What a /samples dataset holds: a sample-level array, or one field of the modal model (which the
/// model's own field list, forEachModalField, describes).
enum class FieldId {
  Parameters,
  Model,
  Alignment,
  Tracking,
  TrackingSign,
  LooFrequency,
  LooResponse
};

struct Field {
  FieldId id;
  int model_field;  ///< index in forEachModalField order (FieldId::Model only)
  const char* name;
  Shape shape;
  const char* units;
  bool integer;
};

Shape shapeOf(ModalFieldShape shape) {
  switch (shape) {
    case ModalFieldShape::Scalar:
      return Shape::S;
    case ModalFieldShape::Vector3:
      return Shape::S3;
    case ModalFieldShape::PerMode:
      return Shape::SK;
    case ModalFieldShape::Vector3PerMode:
      return Shape::S3K;
    case ModalFieldShape::ModeByMode:
      return Shape::SKK;
  }
  return Shape::S;
}

/// Every /samples dataset, in file and checksum order: the parameters, the modal model's fields,
/// then the tracking data and the leave-one-out errors.
const std::vector<Field>& sampleFields() {
  static const std::vector<Field> fields = [] {
    std::vector<Field> f{{FieldId::Parameters, -1, "parameters", Shape::SP, "", false}};
    const std::vector<ModalFieldInfo> model = modalFieldList();
    for (std::size_t i = 0; i < model.size(); ++i)
      f.push_back({FieldId::Model, static_cast<int>(i), model[i].name, shapeOf(model[i].shape),
                   model[i].units, false});
    f.push_back({FieldId::Alignment, -1, "alignment", Shape::SKK, "1", false});
    f.push_back({FieldId::Tracking, -1, "tracking", Shape::SK, "1", true});
    f.push_back({FieldId::TrackingSign, -1, "tracking_sign", Shape::SK, "1", true});
    f.push_back({FieldId::LooFrequency, -1, "loo_frequency_error", Shape::S, "1", false});
    f.push_back({FieldId::LooResponse, -1, "loo_response_error", Shape::S, "1", false});
    return f;
  }();
  return fields;
}

struct Sizes {
  std::size_t s, p, k;
};

std::vector<std::size_t> dimsOf(Shape shape, const Sizes& n) {
  switch (shape) {
    case Shape::S:
      return {n.s};
    case Shape::SP:
      return {n.s, n.p};
    case Shape::SK:
      return {n.s, n.k};
    case Shape::S3:
      return {n.s, 3};
    case Shape::S3K:
      return {n.s, 3, n.k};
    case Shape::SKK:
      return {n.s, n.k, n.k};
  }
  return {};
}

std::string shapeText(const std::vector<std::size_t>& d) {
  std::string t = "[";
  for (std::size_t i = 0; i < d.size(); ++i) t += (i ? ", " : "") + std::to_string(d[i]);
  return t + "]";
}

/// One /samples dataset in memory (row-major).
struct Array {
  const Field* field;
  std::vector<std::size_t> dims;
  std::vector<double> d;
  std::vector<int> i;
};

Array flatten(const Field& f, const RomDatabase& db, const Sizes& n) {
  Array a{&f, dimsOf(f.shape, n), {}, {}};
  for (const RomSample& s : db.samples) {
    switch (f.id) {
      case FieldId::Parameters:
        a.d.insert(a.d.end(), s.parameters.begin(), s.parameters.end());
        break;
      case FieldId::Model: {
        int index = 0;
        forEachModalField(s.modal, [&](const ModalFieldInfo&, const auto& member) {
          if (index++ == f.model_field) appendRowMajor(a.d, member);
        });
        break;
      }
      case FieldId::Alignment:
        appendRowMajor(a.d, s.alignment);
        break;
      case FieldId::Tracking:
        a.i.insert(a.i.end(), s.tracking.begin(), s.tracking.end());
        break;
      case FieldId::TrackingSign:
        a.i.insert(a.i.end(), s.tracking_sign.begin(), s.tracking_sign.end());
        break;
      case FieldId::LooFrequency:
        a.d.push_back(s.loo_frequency_error);
        break;
      case FieldId::LooResponse:
        a.d.push_back(s.loo_response_error);
        break;
    }
  }
  return a;
}

void assign(const Array& a, RomDatabase& db, const Sizes& n) {
  const Eigen::Index k = static_cast<Eigen::Index>(n.k);
  const Field& f = *a.field;
  for (std::size_t s = 0; s < n.s; ++s) {
    RomSample& smp = db.samples[s];
    const std::size_t sk = s * n.k;
    switch (f.id) {
      case FieldId::Parameters:
        smp.parameters.assign(a.d.begin() + static_cast<long>(s * n.p),
                              a.d.begin() + static_cast<long>((s + 1) * n.p));
        break;
      case FieldId::Model: {
        int index = 0;
        forEachModalField(smp.modal, [&](const ModalFieldInfo& info, auto& member) {
          if (index++ != f.model_field) return;
          readRowMajor(member, info.shape, k, a.d.data() + s * modalFieldSize(info.shape, n.k));
        });
        break;
      }
      case FieldId::Alignment:
        readRowMajor(smp.alignment, ModalFieldShape::ModeByMode, k, a.d.data() + s * n.k * n.k);
        break;
      case FieldId::Tracking:
        smp.tracking.assign(a.i.begin() + static_cast<long>(sk),
                            a.i.begin() + static_cast<long>(sk + n.k));
        break;
      case FieldId::TrackingSign:
        smp.tracking_sign.assign(a.i.begin() + static_cast<long>(sk),
                                 a.i.begin() + static_cast<long>(sk + n.k));
        break;
      case FieldId::LooFrequency:
        smp.loo_frequency_error = a.d[s];
        break;
      case FieldId::LooResponse:
        smp.loo_response_error = a.d[s];
        break;
    }
  }
}

// --- checksum ------------------------------------------------------------------------------------
class Fnv1a {
public:
  void bytes(const unsigned char* p, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      h_ ^= p[i];
      h_ *= 1099511628211ULL;
    }
  }
  void u64(std::uint64_t v) {
    unsigned char b[8];
    for (int i = 0; i < 8; ++i) b[i] = static_cast<unsigned char>(v >> (8 * i));  // little-endian
    bytes(b, 8);
  }
  void i32(int v) {
    const auto u = static_cast<std::uint32_t>(v);
    unsigned char b[4];
    for (int i = 0; i < 4; ++i) b[i] = static_cast<unsigned char>(u >> (8 * i));
    bytes(b, 4);
  }
  void f64(double v) {
    std::uint64_t u;
    std::memcpy(&u, &v, sizeof u);
    u64(u);
  }
  void text(std::string_view s) {
    u64(s.size());
    bytes(reinterpret_cast<const unsigned char*>(s.data()), s.size());
  }
  std::string hex() const {
    char buf[40];
    std::snprintf(buf, sizeof buf, "fnv1a64:%016" PRIx64, h_);
    return buf;
  }

private:
  std::uint64_t h_ = 14695981039346656037ULL;
};

std::string checksum(const RomDatabase& db, const std::vector<Array>& arrays,
                     const std::vector<NamedArray>& stress) {
  Fnv1a h;
  h.text(kDatabaseFormat);
  h.i32(kDatabaseFormatVersion);
  h.text(db.base_config_toml);
  h.text(toString(db.default_method));
  h.i32(static_cast<int>(db.samples.size()));
  h.i32(static_cast<int>(db.axes.size()));
  h.i32(db.modes_per_sample);
  h.i32(db.reference_sample);
  // Absent from grid databases: their checksums stay what they were before scattered layouts.
  if (!db.isGrid()) h.text("scattered");
  for (const ParameterAxis& a : db.axes) {
    h.text(a.key);
    h.u64(a.values.size());
    for (const double v : a.values) h.f64(v);
  }
  if (db.exact_modulus) {  // absent from databases without it: their checksums stay as they were
    h.text("exact_modulus");
    h.f64(db.exact_modulus->reference_pa);
  }
  if (db.estimate_from_probes) {  // likewise
    h.text("estimate_from_probes");
    h.u64(db.probes.size());
    for (const ProbeError& e : db.probes) {
      for (const double v : e.parameters) h.f64(v);
      h.f64(e.frequency_error);
      h.f64(e.response_error);
    }
  }
  if (db.affine) {
    h.text("affine");
    for (const NamedArray& a : toArrays(*db.affine)) {
      h.text(a.name);
      h.u64(a.dims.size());
      for (const std::size_t d : a.dims) h.u64(d);
      for (const double v : a.values) h.f64(v);
    }
  }
  if (!stress.empty()) {  // absent from databases without stresses: their checksums stay as they were
    h.text("stress");
    for (const NamedArray& a : stress) {
      h.text(a.name);
      h.u64(a.dims.size());
      for (const std::size_t d : a.dims) h.u64(d);
      for (const double v : a.values) h.f64(v);
    }
  }
  for (const Array& a : arrays) {
    h.text(a.field->name);
    h.u64(a.dims.size());
    for (const std::size_t d : a.dims) h.u64(d);
    if (a.field->integer) {
      for (const int v : a.i) h.i32(v);
    } else {
      for (const double v : a.d) h.f64(v);
    }
  }
  return h.hex();
}

/// InputError unless the database can be laid out as the file's [S, …, k] arrays.
Sizes checkWritable(const RomDatabase& db) {
  const Sizes n{db.samples.size(), db.axes.size(), static_cast<std::size_t>(db.modes_per_sample)};
  MASTROM_REQUIRE(n.p >= 1 && n.s >= 1 && n.k >= 1, InputError, "rom database: ", n.s, " samples, ",
                  n.p, " axes, ", n.k, " modes per sample: nothing to write");
  const int exact_axis = db.exactModulusAxis();
  MASTROM_REQUIRE(!db.exact_modulus || exact_axis >= 0, InputError,
                  "rom database: Young's modulus is handled exactly but no axis is ",
                  kYoungsModulusKey);
  std::size_t grid = 1;
  for (std::size_t a = 0; a < db.axes.size(); ++a) {
    const ParameterAxis& x = db.axes[a];
    MASTROM_REQUIRE(!x.key.empty() && !x.values.empty(), InputError,
                    "rom database: an axis has no key or no values");
    const bool range = static_cast<int>(a) == exact_axis || !db.isGrid();
    MASTROM_REQUIRE(!range || (x.values.size() == 2 && x.values[0] < x.values[1]), InputError,
                    "rom database: scattered samples and an exactly handled axis need the range "
                    "{lo, hi} of axis ",
                    x.key);
    if (static_cast<int>(a) != exact_axis) grid *= x.values.size();
  }
  if (db.exact_modulus) {
    const std::vector<double>& box = db.axes[static_cast<std::size_t>(exact_axis)].values;
    const double e0 = db.exact_modulus->reference_pa;
    MASTROM_REQUIRE(std::isfinite(e0) && e0 >= box.front() && e0 <= box.back() && e0 > 0.0,
                    InputError, "rom database: the reference Young's modulus ", e0,
                    " Pa is outside its box");
    for (std::size_t s = 0; s < db.samples.size(); ++s)
      MASTROM_REQUIRE(db.samples[s].parameters.size() == db.axes.size() &&
                          db.samples[s].parameters[static_cast<std::size_t>(exact_axis)] == e0,
                      InputError, "rom database: sample ", s,
                      " is not at the reference Young's modulus of the exact scaling");
  }
  MASTROM_REQUIRE(!db.isGrid() || grid == n.s, InputError, "rom database: ", n.s,
                  " samples for a grid of ", grid);
  MASTROM_REQUIRE(db.reference_sample >= 0 && static_cast<std::size_t>(db.reference_sample) < n.s,
                  InputError, "rom database: reference sample ", db.reference_sample,
                  " out of range");
  const Eigen::Index k = db.modes_per_sample;
  for (std::size_t s = 0; s < n.s; ++s) {
    const RomSample& x = db.samples[s];
    const ModalModel& m = x.modal;
    MASTROM_REQUIRE(x.parameters.size() == n.p && m.modeCount() == k && m.coriolis.rows() == k &&
                        m.coriolis.cols() == k && x.alignment.rows() == k &&
                        x.alignment.cols() == k &&
                        static_cast<Eigen::Index>(x.tracking.size()) == k &&
                        static_cast<Eigen::Index>(x.tracking_sign.size()) == k,
                    InputError, "rom database: sample ", s, " does not have ", n.p,
                    " parameters and ", k, " modes with k x k Coriolis, alignment and tracking");
    m.validate();
  }
  if (db.affine) db.affine->validate();
  MASTROM_REQUIRE(db.default_method != InterpolationMethod::Affine || db.affine, InputError,
                  "rom database: default method affine without affine terms");
  return n;
}

[[noreturn]] void refuse(const std::string& path, const std::string& what) {
  throw IoError("ROM database '" + path + "' " + what);
}

}  // namespace

std::string databaseChecksum(const RomDatabase& db) {
  const Sizes n = checkWritable(db);
  std::vector<Array> arrays;
  for (const Field& f : sampleFields()) arrays.push_back(flatten(f, db, n));
  return checksum(db, arrays, stressArrays(db));
}

std::pair<double, double> databaseErrorEstimate(const RomDatabase& db) {
  double f = -1.0, r = -1.0;
  for (std::size_t i = 0; i < db.samples.size(); ++i) {
    const RomSample& s = db.samples[i];
    if (s.loo_frequency_error < 0) continue;
    // Affine: the errors at the samples themselves (nothing interpolated); probes: the errors
    // measured between samples; otherwise leave-one-out errors carried to the full grid
    // (rom/offline/leave_one_out.hpp).
    const double scale = db.estimate_from_probes
                             ? 1.0
                             : leaveOneOutScaleFor(db.axes, static_cast<int>(i), db.default_method);
    f = std::max(f, scale * s.loo_frequency_error);
    r = std::max(r, scale * s.loo_response_error);
  }
  return {f, r};
}

void writeDatabase(const std::string& path, const RomDatabase& db, const BuildReport* report) {
  const Sizes n = checkWritable(db);
  std::vector<Array> arrays;
  for (const Field& f : sampleFields()) arrays.push_back(flatten(f, db, n));
  const std::vector<NamedArray> stress = stressArrays(db);
  const std::string sum = checksum(db, arrays, stress);

  h5::AtomicH5Writer writer(path);
  h5::File& file = writer.file();
  file.setStringAttribute("/", "format", kDatabaseFormat);
  file.setIntAttribute("/", "format_version", kDatabaseFormatVersion);
  file.setStringAttribute("/", "mastrom_version",
                          db.mastrom_version.empty() ? std::string(kVersion) : db.mastrom_version);
  file.setStringAttribute("/", "source", "rom-database");
  file.setStringAttribute("/", "config", db.base_config_toml);
  file.setStringAttribute("/", "method", toString(db.default_method));
  file.setIntAttribute("/", "sample_count", static_cast<int>(n.s));
  file.setIntAttribute("/", "parameter_count", static_cast<int>(n.p));
  file.setIntAttribute("/", "modes_per_sample", static_cast<int>(n.k));
  file.setIntAttribute("/", "reference_sample", db.reference_sample);
  file.setStringAttribute("/", "layout", db.isGrid() ? "grid" : "scattered");
  file.setIntAttribute("/", "affine", db.affine ? 1 : 0);
  // Written only when present: a file without it reads as before (E, if an axis, sampled).
  if (db.exact_modulus)
    file.setDoubleAttribute("/", "youngs_modulus_exact_reference", db.exact_modulus->reference_pa);
  if (db.estimate_from_probes) {
    file.setIntAttribute("/", "estimate_from_probes", 1);
    file.createGroup("/probes");
    std::vector<double> parameters, frequency, response;
    for (const ProbeError& e : db.probes) {
      parameters.insert(parameters.end(), e.parameters.begin(), e.parameters.end());
      frequency.push_back(e.frequency_error);
      response.push_back(e.response_error);
    }
    h5x::writeDoubles(file, "/probes/parameters", {db.probes.size(), n.p}, parameters.data(),
                      "per column");
    h5x::writeDoubles(file, "/probes/frequency_error", {db.probes.size()}, frequency.data(), "1");
    h5x::writeDoubles(file, "/probes/response_error", {db.probes.size()}, response.data(), "1");
  }
  if (db.affine) {
    file.createGroup("/affine");
    for (const NamedArray& a : toArrays(*db.affine))
      h5x::writeDoubles(file, "/affine/" + a.name, a.dims, a.values.data(), "SI");
  }
  file.setIntAttribute("/", "stress", stress.empty() ? 0 : 1);
  if (!stress.empty()) {
    file.createGroup("/stress");
    file.setStringAttribute("/stress", "form", "mode-acceleration");
    for (const NamedArray& a : stress) {
      const std::string units = a.name == "damping" ? "s"
                                : a.name == "points" ? "m, rad"
                                : a.name == "interface_offsets" ? "1"
                                                                : "Pa";
      h5x::writeDoubles(file, "/stress/" + a.name, a.dims, a.values.data(), units);
    }
  }
  const auto [loo_f, loo_r] = databaseErrorEstimate(db);
  file.setDoubleAttribute("/", "loo_frequency_error", loo_f);
  file.setDoubleAttribute("/", "loo_response_error", loo_r);
  for (std::size_t a = 0; a < n.p; ++a) {
    const std::string group = "/axes/" + std::to_string(a);
    file.createGroup(group);
    file.setStringAttribute(group, "key", db.axes[a].key);
    file.writeDoubles(group + "/values", db.axes[a].values, configKeyUnits(db.axes[a].key));
  }
  std::vector<std::string> parameter_units;
  for (const ParameterAxis& a : db.axes) parameter_units.push_back(configKeyUnits(a.key));
  for (const Array& a : arrays) {
    const std::string name = std::string("/samples/") + a.field->name;
    if (a.field->integer) {
      h5x::writeInts(file, name, a.dims, a.i.data(), a.field->units);
    } else if (a.field->id == FieldId::Parameters) {
      h5x::writeDoubles(file, name, a.dims, a.d.data(), "per column");
      h5x::setStringArrayAttribute(file, name, "units", parameter_units);
    } else {
      h5x::writeDoubles(file, name, a.dims, a.d.data(), a.field->units);
    }
  }
  if (report) {
    const BuildTiming& t = report->timing;
    file.createGroup("/build");
    file.setIntAttribute("/build", "ranks", t.ranks);
    file.setIntAttribute("/build", "modal_solves", t.solves);
    file.setDoubleAttribute("/build", "assembly_time_s", t.assembly_s);
    file.setDoubleAttribute("/build", "eigensolve_time_s", t.eigensolve_s);
    file.setDoubleAttribute("/build", "extraction_tracking_time_s", t.extraction_s);
    file.setDoubleAttribute("/build", "communication_time_s", t.communication_s);
    file.setDoubleAttribute("/build", "leave_one_out_time_s", t.leave_one_out_s);
    file.setDoubleAttribute("/build", "probe_solve_time_s", t.probe_solves_s);
    file.setDoubleAttribute("/build", "wall_time_s", t.wall_s);
    file.setDoubleAttribute("/build", "min_tracking_mac", report->min_mac);
    file.setIntAttribute("/build", "min_tracking_mac_sample", report->min_mac_sample);
    file.setDoubleAttribute("/build", "min_tracking_mac_excited_modes", report->min_coupled_mac);
    file.setIntAttribute("/build", "min_tracking_mac_excited_modes_sample",
                         report->min_coupled_mac_sample);
    for (const LeaveOneOutResult& l : report->leave_one_out) {
      const std::string m = toString(l.method);
      file.setIntAttribute("/build", "loo_" + m + "_samples", l.estimated);
      file.setDoubleAttribute("/build", "loo_" + m + "_frequency_error", l.max_frequency_error);
      file.setDoubleAttribute("/build", "loo_" + m + "_response_error", l.max_response_error);
      file.setDoubleAttribute("/build", "loo_" + m + "_frequency_estimate", l.frequency_estimate);
      file.setDoubleAttribute("/build", "loo_" + m + "_response_estimate", l.response_estimate);
    }
  }
  file.setStringAttribute("/", "checksum", sum);
  writer.commit();
}

RomDatabase readDatabase(const std::string& path) {
  const h5::File file = h5::File::open(path, h5::OpenMode::ReadOnly);  // missing, not HDF5
  if (!file.hasAttribute("/", "format")) {
    std::string hint;
    if (file.hasAttribute("/", "source")) {
      try {
        hint = "; it is a '" + file.readStringAttribute("/", "source") + "' file";
      } catch (const IoError&) {
      }
    }
    refuse(path, "is not a mastrom ROM database (no root attribute 'format'" + hint + ")");
  }
  std::string format;
  try {
    format = file.readStringAttribute("/", "format");
  } catch (const IoError&) {
    format = "(not a string)";
  }
  if (format != kDatabaseFormat) {
    refuse(path, "is not a mastrom ROM database (format = '" + format + "', expected '" +
                     kDatabaseFormat + "')");
  }
  const auto need = [&](const char* name) {
    if (!file.hasAttribute("/", name))
      refuse(path, std::string("is incomplete: missing root attribute '") + name + "'");
  };
  need("format_version");
  const int version = file.readIntAttribute("/", "format_version");
  if (version != kDatabaseFormatVersion) {
    refuse(path, "has format_version " + std::to_string(version) +
                     ", which this mastrom does not read (it reads version " +
                     std::to_string(kDatabaseFormatVersion) + "; rebuild the database)");
  }
  for (const char* name : {"mastrom_version", "config", "method", "sample_count", "parameter_count",
                           "modes_per_sample", "reference_sample", "checksum"})
    need(name);

  RomDatabase db;
  db.mastrom_version = file.readStringAttribute("/", "mastrom_version");
  db.base_config_toml = file.readStringAttribute("/", "config");
  const std::string method = file.readStringAttribute("/", "method");
  const std::optional<InterpolationMethod> m = parseInterpolationMethod(method);
  if (!m) refuse(path, "is inconsistent: unknown interpolation method '" + method + "'");
  db.default_method = *m;
  const int s = file.readIntAttribute("/", "sample_count");
  const int p = file.readIntAttribute("/", "parameter_count");
  const int k = file.readIntAttribute("/", "modes_per_sample");
  db.reference_sample = file.readIntAttribute("/", "reference_sample");
  db.modes_per_sample = k;
  if (s < 1 || p < 1 || k < 1 || db.reference_sample < 0 || db.reference_sample >= s) {
    refuse(path, "is inconsistent: sample_count " + std::to_string(s) + ", parameter_count " +
                     std::to_string(p) + ", modes_per_sample " + std::to_string(k) +
                     ", reference_sample " + std::to_string(db.reference_sample));
  }
  const Sizes n{static_cast<std::size_t>(s), static_cast<std::size_t>(p),
                static_cast<std::size_t>(k)};
  // Files written before scattered layouts existed carry no layout: they are grids.
  if (file.hasAttribute("/", "layout")) {
    const std::string layout = file.readStringAttribute("/", "layout");
    if (layout != "grid" && layout != "scattered")
      refuse(path, "is inconsistent: unknown sample layout '" + layout + "' (grid or scattered)");
    db.layout = layout == "grid" ? SampleLayout::Grid : SampleLayout::Scattered;
  }

  if (file.hasAttribute("/", "youngs_modulus_exact_reference"))
    db.exact_modulus = ExactModulus{file.readDoubleAttribute("/", "youngs_modulus_exact_reference")};
  db.estimate_from_probes = file.hasAttribute("/", "estimate_from_probes") &&
                            file.readIntAttribute("/", "estimate_from_probes") == 1;
  if (db.estimate_from_probes) {
    for (const char* name : {"/probes/parameters", "/probes/frequency_error", "/probes/response_error"})
      if (!file.exists(name)) refuse(path, std::string("is incomplete: missing dataset ") + name);
    std::vector<std::size_t> dims_p, dims_f, dims_r;
    const std::vector<double> parameters = h5x::readDoubles(file, "/probes/parameters", dims_p);
    const std::vector<double> frequency = h5x::readDoubles(file, "/probes/frequency_error", dims_f);
    const std::vector<double> response = h5x::readDoubles(file, "/probes/response_error", dims_r);
    if (dims_p.size() != 2 || dims_p[1] != static_cast<std::size_t>(p) || dims_f.size() != 1 ||
        dims_r.size() != 1 || dims_f[0] != dims_p[0] || dims_r[0] != dims_p[0] || dims_p[0] == 0)
      refuse(path, "is inconsistent: /probes/* have shapes " + shapeText(dims_p) + ", " +
                       shapeText(dims_f) + ", " + shapeText(dims_r));
    for (std::size_t i = 0; i < dims_p[0]; ++i) {
      ProbeError e;
      e.parameters.assign(parameters.begin() + static_cast<std::ptrdiff_t>(i * dims_p[1]),
                          parameters.begin() + static_cast<std::ptrdiff_t>((i + 1) * dims_p[1]));
      e.frequency_error = frequency[i];
      e.response_error = response[i];
      db.probes.push_back(std::move(e));
    }
  }
  std::size_t grid = 1;
  for (int a = 0; a < p; ++a) {
    const std::string group = "/axes/" + std::to_string(a);
    if (!file.exists(group + "/values"))
      refuse(path, "is incomplete: missing dataset " + group + "/values");
    if (!file.hasAttribute(group, "key"))
      refuse(path, "is incomplete: missing attribute 'key' of " + group);
    ParameterAxis axis;
    axis.key = file.readStringAttribute(group, "key");
    std::vector<std::size_t> dims;
    axis.values = h5x::readDoubles(file, group + "/values", dims);
    if (dims.size() != 1 || axis.values.empty()) {
      refuse(path, "is inconsistent: " + group + "/values has shape " + shapeText(dims) +
                       ", expected [n] with n >= 1");
    }
    const bool exact = db.exact_modulus && axis.key == kYoungsModulusKey;
    if ((!db.isGrid() || exact) && !(axis.values.size() == 2 && axis.values[0] < axis.values[1])) {
      refuse(path, "is inconsistent: " + group + "/values of a scattered database or an exactly "
                       "handled axis has shape " + shapeText(dims) + ", expected the range [2] (lo < hi)");
    }
    if (!exact) grid *= axis.values.size();
    db.axes.push_back(std::move(axis));
  }
  if (db.isGrid() && grid != n.s) {
    refuse(path, "is inconsistent: the axes span a grid of " + std::to_string(grid) +
                     " samples, sample_count is " + std::to_string(s));
  }

  need("affine");
  if (file.readIntAttribute("/", "affine") != 0) {
    std::vector<NamedArray> affine;
    for (const NamedArray& a : toArrays(AffineReducedModel{})) {  // the names, in order
      const std::string name = "/affine/" + a.name;
      if (!file.exists(name)) refuse(path, "is incomplete: missing dataset " + name);
      NamedArray x;
      x.name = a.name;
      x.values = h5x::readDoubles(file, name, x.dims);
      affine.push_back(std::move(x));
    }
    try {
      db.affine = fromArrays(affine);
    } catch (const InputError& e) {
      refuse(path, std::string("is inconsistent: ") + e.what());
    }
  }
  if (db.default_method == InterpolationMethod::Affine && !db.affine)
    refuse(path, "is inconsistent: method affine without the /affine terms");

  std::vector<Array> arrays;
  for (const Field& f : sampleFields()) {
    const std::string name = std::string("/samples/") + f.name;
    if (!file.exists(name)) refuse(path, "is incomplete: missing dataset " + name);
    Array a{&f, dimsOf(f.shape, n), {}, {}};
    std::vector<std::size_t> dims;
    if (f.integer) {
      a.i = h5x::readInts(file, name, dims);
    } else {
      a.d = h5x::readDoubles(file, name, dims);
    }
    if (dims != a.dims) {
      refuse(path, "is inconsistent: " + name + " has shape " + shapeText(dims) + ", expected " +
                       shapeText(a.dims));
    }
    arrays.push_back(std::move(a));
  }
  std::vector<NamedArray> stress;
  if (file.hasAttribute("/", "stress") && file.readIntAttribute("/", "stress") != 0) {
    for (const char* name : stressArrayNames()) {
      const std::string path_in_file = std::string("/stress/") + name;
      if (!file.exists(path_in_file)) refuse(path, "is incomplete: missing dataset " + path_in_file);
      NamedArray x;
      x.name = name;
      x.values = h5x::readDoubles(file, path_in_file, x.dims);
      stress.push_back(std::move(x));
    }
  }
  db.samples.assign(n.s, RomSample{});
  const std::string stored = file.readStringAttribute("/", "checksum");
  const std::string computed = checksum(db, arrays, stress);
  if (stored != computed) {
    refuse(path,
           "is corrupted: its content checksum is " + computed + ", the file records " + stored);
  }
  for (const Array& a : arrays) assign(a, db, n);
  try {
    if (db.exact_modulus) checkWritable(db);  // the axis and every sample at the reference
    if (!stress.empty()) assignStressArrays(stress, db);
    for (const RomSample& x : db.samples) x.modal.validate();
  } catch (const InputError& e) {
    refuse(path, std::string("is inconsistent: ") + e.what());
  }
  return db;
}

}  // namespace mastrom::rom
