// Writing the database file (database_io.hpp): the checks and the checksum first, then every
// group and attribute, committed atomically.
#include <algorithm>

#include "common/hdf5_file.hpp"
#include "common/version.hpp"
#include "rom/database/database_io.hpp"
#include "rom/database/database_io_detail.hpp"
#include "rom/database/h5_arrays.hpp"
#include "rom/database/parameter_space.hpp"
#include "rom/database/stress_arrays.hpp"

namespace mastrom::rom {

using namespace database_io_detail;

std::string databaseChecksum(const RomDatabase& db) {
  const Sizes n = checkWritable(db);
  return checksum(db, sampleArrays(db, n), stressArrays(db));
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
  const std::vector<Array> arrays = sampleArrays(db, n);
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
      const std::string units = a.name == "damping"             ? "s"
                                : a.name == "points"            ? "m, rad"
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

}  // namespace mastrom::rom
