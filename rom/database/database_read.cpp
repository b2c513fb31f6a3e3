// Reading and verifying the database file (database_io.hpp): every refusal is an IoError of one
// line naming the file.
#include <optional>

#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "rom/database/database_io.hpp"
#include "rom/database/database_io_detail.hpp"
#include "rom/database/h5_arrays.hpp"
#include "rom/database/stress_arrays.hpp"

namespace mastrom::rom {

using namespace database_io_detail;

namespace {

[[noreturn]] void refuse(const std::string& path, const std::string& what) {
  throw IoError("ROM database '" + path + "' " + what);
}

}  // namespace

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
    db.exact_modulus =
        ExactModulus{file.readDoubleAttribute("/", "youngs_modulus_exact_reference")};
  db.estimate_from_probes = file.hasAttribute("/", "estimate_from_probes") &&
                            file.readIntAttribute("/", "estimate_from_probes") == 1;
  if (db.estimate_from_probes) {
    for (const char* name :
         {"/probes/parameters", "/probes/frequency_error", "/probes/response_error"})
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
      refuse(path, "is inconsistent: " + group +
                       "/values of a scattered database or an exactly "
                       "handled axis has shape " +
                       shapeText(dims) + ", expected the range [2] (lo < hi)");
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
    const std::string stress_rows = std::string("/affine/") + kAffineStressRows;
    if (file.exists(stress_rows)) {
      NamedArray x;
      x.name = kAffineStressRows;
      x.values = h5x::readDoubles(file, stress_rows, x.dims);
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
      if (!file.exists(path_in_file))
        refuse(path, "is incomplete: missing dataset " + path_in_file);
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
