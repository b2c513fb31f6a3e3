// The /stress arrays of a database (see stress_arrays.hpp).
#include "rom/database/stress_arrays.hpp"

#include <cmath>

#include "common/error.hpp"

namespace mastrom::rom {

const std::vector<const char*>& stressArrayNames() {
  static const std::vector<const char*> names{"interface_offsets", "modes", "loads", "preload",
                                              "points", "damping"};
  return names;
}

bool databaseHasStresses(const RomDatabase& db) {
  if (db.samples.empty() || db.samples.front().modal.stress.empty()) {
    for (const RomSample& s : db.samples)
      MASTROM_REQUIRE(s.modal.stress.empty(), InputError,
                      "rom database: some samples carry stresses and some do not");
    return false;
  }
  const ModalStress& first = db.samples.front().modal.stress;
  for (std::size_t n = 0; n < db.samples.size(); ++n) {
    const ModalStress& s = db.samples[n].modal.stress;
    MASTROM_REQUIRE(s.interface_offsets.size() == first.interface_offsets.size() &&
                        s.interface_offsets == first.interface_offsets,
                    InputError, "rom database: sample ", n,
                    " has its stresses on another mesh than sample 0");
  }
  return true;
}

std::vector<NamedArray> stressArrays(const RomDatabase& db) {
  std::vector<NamedArray> out;
  if (!databaseHasStresses(db)) return out;
  const ModalStress& first = db.samples.front().modal.stress;
  const std::size_t s = db.samples.size(), p = static_cast<std::size_t>(first.pointCount()),
                    r = kStressRowsPerPoint * p, k = static_cast<std::size_t>(db.modes_per_sample);
  NamedArray offsets{"interface_offsets", {static_cast<std::size_t>(first.interface_offsets.size())}, {}};
  for (Eigen::Index i = 0; i < first.interface_offsets.size(); ++i)
    offsets.values.push_back(first.interface_offsets[i]);
  NamedArray modes{"modes", {s, r, k}, {}}, loads{"loads", {s, r, kStressLoadCount}, {}};
  NamedArray preload{"preload", {s, r}, {}}, points{"points", {s, 2, p}, {}};
  NamedArray damping{"damping", {s}, {}};
  const auto append = [](std::vector<double>& v, const Eigen::MatrixXd& m) {
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      for (Eigen::Index j = 0; j < m.cols(); ++j) v.push_back(m(i, j));
  };
  for (const RomSample& x : db.samples) {
    const ModalStress& st = x.modal.stress;
    append(modes.values, st.modes);
    append(loads.values, st.loads);
    append(preload.values, st.preload);
    append(points.values, st.points);
    damping.values.push_back(st.damping_s);
  }
  out.push_back(std::move(offsets));
  out.push_back(std::move(modes));
  out.push_back(std::move(loads));
  out.push_back(std::move(preload));
  out.push_back(std::move(points));
  out.push_back(std::move(damping));
  return out;
}

void assignStressArrays(const std::vector<NamedArray>& arrays, RomDatabase& db) {
  const auto find = [&arrays](const char* name) -> const NamedArray& {
    for (const NamedArray& a : arrays)
      if (a.name == name) return a;
    throw InputError(std::string("missing stress array '") + name + "'");
  };
  const NamedArray& offsets = find("interface_offsets");
  MASTROM_REQUIRE(offsets.dims.size() == 1 && offsets.values.size() >= 2 &&
                      offsets.values.size() <= 1024,
                  InputError, "stress array 'interface_offsets' must hold 2 to 1024 values");
  // Whole, ascending point counts from 0 (a file is input: no cast of a NaN or a negative).
  for (std::size_t i = 0; i < offsets.values.size(); ++i) {
    const double o = offsets.values[i];
    MASTROM_REQUIRE(std::isfinite(o) && o == std::floor(o) && o >= 0.0 && o <= 1e7 &&
                        (i == 0 ? o == 0.0 : o > offsets.values[i - 1]),
                    InputError, "stress array 'interface_offsets' value ", i, " = ", o,
                    " is not a whole point offset in ascending order from 0");
  }
  const std::size_t p = static_cast<std::size_t>(offsets.values.back());
  const std::size_t s = db.samples.size(), r = kStressRowsPerPoint * p,
                    k = static_cast<std::size_t>(db.modes_per_sample);
  const auto shaped = [&](const char* name, std::vector<std::size_t> dims) -> const double* {
    const NamedArray& a = find(name);
    MASTROM_REQUIRE(a.dims == dims, InputError, "stress array '", name,
                    "' has the wrong shape for ", s, " samples, ", p, " points, ", k, " modes");
    return a.values.data();
  };
  const double* modes = shaped("modes", {s, r, k});
  const double* loads = shaped("loads", {s, r, kStressLoadCount});
  const double* preload = shaped("preload", {s, r});
  const double* points = shaped("points", {s, 2, p});
  const double* damping = shaped("damping", {s});
  const auto fill = [](Eigen::MatrixXd& m, Eigen::Index rows, Eigen::Index cols, const double* d) {
    m.resize(rows, cols);
    for (Eigen::Index i = 0; i < rows; ++i)
      for (Eigen::Index j = 0; j < cols; ++j) m(i, j) = d[i * cols + j];
  };
  const auto ri = static_cast<Eigen::Index>(r), ki = static_cast<Eigen::Index>(k),
             pi = static_cast<Eigen::Index>(p);
  for (std::size_t n = 0; n < s; ++n) {
    ModalStress& st = db.samples[n].modal.stress;
    st.interface_offsets.resize(static_cast<Eigen::Index>(offsets.values.size()));
    for (std::size_t i = 0; i < offsets.values.size(); ++i)
      st.interface_offsets[static_cast<Eigen::Index>(i)] = static_cast<int>(offsets.values[i]);
    fill(st.modes, ri, ki, modes + n * r * k);
    fill(st.loads, ri, kStressLoadCount, loads + n * r * kStressLoadCount);
    st.preload = Eigen::Map<const Eigen::VectorXd>(preload + n * r, ri);
    Eigen::MatrixXd pts;
    fill(pts, 2, pi, points + n * 2 * p);
    st.points = pts;
    st.damping_s = damping[n];
    st.validate(db.modes_per_sample);
  }
}

}  // namespace mastrom::rom
