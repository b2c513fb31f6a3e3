// The parts of the database file that writing and reading share (database_io_detail.hpp): the
// /samples table and its arrays, the content checksum, and the check that a database fits the
// layout.
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string_view>

#include "common/error.hpp"
#include "rom/database/database_io.hpp"
#include "rom/database/database_io_detail.hpp"
#include "rom/model/modal_fields.hpp"

namespace mastrom::rom::database_io_detail {
namespace {

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

}  // namespace

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

std::vector<Array> sampleArrays(const RomDatabase& db, const Sizes& n) {
  std::vector<Array> arrays;
  for (const Field& f : sampleFields()) arrays.push_back(flatten(f, db, n));
  return arrays;
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
  // Absent from databases without stresses: their checksums stay as they were.
  if (!stress.empty()) {
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

}  // namespace mastrom::rom::database_io_detail
