#include "rom/database/affine_reduced.hpp"

#include <cmath>
#include <functional>

#include "common/error.hpp"

namespace mastrom::rom {
namespace {

/// One entry of the fixed array list: its name and the model member it views (any Eigen dense
/// object is read and written through a Map of its storage; scalars are 1 × 1).
struct Member {
  const char* name;
  std::function<Eigen::Map<Eigen::MatrixXd>(AffineReducedModel&, Eigen::Index rows,
                                            Eigen::Index cols)>
      view;
  std::function<std::pair<Eigen::Index, Eigen::Index>(const AffineReducedModel&)> shape;
};

template <typename M>
Member matrixMember(const char* name, M AffineReducedModel::*field) {
  return {name,
          [field](AffineReducedModel& m, Eigen::Index r, Eigen::Index c) {
            (m.*field).resize(r, c);
            return Eigen::Map<Eigen::MatrixXd>((m.*field).data(), r, c);
          },
          [field](const AffineReducedModel& m) {
            return std::make_pair((m.*field).rows(), (m.*field).cols());
          }};
}

Member vector3Member(const char* name, Eigen::Vector3d AffineReducedModel::*field) {
  return {name,
          [field](AffineReducedModel& m, Eigen::Index, Eigen::Index) {
            return Eigen::Map<Eigen::MatrixXd>((m.*field).data(), 3, 1);
          },
          [](const AffineReducedModel&) {
            return std::make_pair(Eigen::Index{3}, Eigen::Index{1});
          }};
}

Member scalarMember(const char* name, double AffineReducedModel::*field) {
  return {name,
          [field](AffineReducedModel& m, Eigen::Index, Eigen::Index) {
            return Eigen::Map<Eigen::MatrixXd>(&(m.*field), 1, 1);
          },
          [](const AffineReducedModel&) {
            return std::make_pair(Eigen::Index{1}, Eigen::Index{1});
          }};
}

const std::vector<Member>& members() {
  using R = AffineReducedModel;
  static const std::vector<Member> list = {
      scalarMember("thickness_min", &R::thickness_min_m),
      scalarMember("thickness_max", &R::thickness_max_m),
      scalarMember("youngs_modulus_min", &R::youngs_modulus_min_pa),
      scalarMember("youngs_modulus_max", &R::youngs_modulus_max_pa),
      scalarMember("density_min", &R::density_min_kg_m3),
      scalarMember("density_max", &R::density_max_kg_m3),
      scalarMember("damping", &R::damping_s),
      scalarMember("reference_angle", &R::reference_angle_rad),
      matrixMember("k_membrane", &R::k_membrane),
      matrixMember("k_bending", &R::k_bending),
      matrixMember("m_rigid", &R::m_rigid),
      matrixMember("m_shell", &R::m_shell),
      matrixMember("gamma_rigid", &R::gamma_rigid),
      matrixMember("gamma_shell", &R::gamma_shell),
      matrixMember("gamma_c_rigid", &R::gamma_c_rigid),
      matrixMember("gamma_c_shell", &R::gamma_c_shell),
      matrixMember("momentum_rigid", &R::momentum_rigid),
      matrixMember("momentum_shell", &R::momentum_shell),
      matrixMember("coriolis_rigid", &R::coriolis_rigid),
      matrixMember("coriolis_shell", &R::coriolis_shell),
      matrixMember("end_rotation", &R::end_rotation),
      matrixMember("end_translation", &R::end_translation),
      scalarMember("inertia_rigid", &R::inertia_rigid),
      scalarMember("inertia_shell", &R::inertia_shell),
      scalarMember("mass_rigid", &R::mass_rigid),
      scalarMember("mass_shell", &R::mass_shell),
      vector3Member("first_moment_rigid", &R::first_moment_rigid),
      vector3Member("first_moment_shell", &R::first_moment_shell),
      vector3Member("end_position", &R::end_position),
  };
  return list;
}

}  // namespace

void AffineReducedModel::validate() const {
  const Eigen::Index r = k_membrane.rows();
  MASTROM_REQUIRE(r >= 1, InputError, "affine model: empty reduced basis");
  const auto square = [r](const Eigen::MatrixXd& m) { return m.rows() == r && m.cols() == r; };
  MASTROM_REQUIRE(square(k_membrane) && square(k_bending) && square(m_rigid) && square(m_shell) &&
                      square(coriolis_rigid) && square(coriolis_shell) &&
                      gamma_rigid.size() == r && gamma_shell.size() == r &&
                      gamma_c_rigid.size() == r && gamma_c_shell.size() == r &&
                      momentum_rigid.cols() == r && momentum_shell.cols() == r &&
                      end_rotation.cols() == r && end_translation.cols() == r,
                  InputError, "affine model: the reduced terms are not all of basis size ", r);
  MASTROM_REQUIRE(modes >= 1 && modes <= r, InputError, "affine model: ", modes,
                  " modes for a basis of ", r);
  const bool finite = k_membrane.allFinite() && k_bending.allFinite() && m_rigid.allFinite() &&
                      m_shell.allFinite() && coriolis_rigid.allFinite() &&
                      coriolis_shell.allFinite() && gamma_rigid.allFinite() &&
                      gamma_shell.allFinite() && gamma_c_rigid.allFinite() &&
                      gamma_c_shell.allFinite() && momentum_rigid.allFinite() &&
                      momentum_shell.allFinite() && end_rotation.allFinite() &&
                      end_translation.allFinite() && first_moment_rigid.allFinite() &&
                      first_moment_shell.allFinite() && end_position.allFinite() &&
                      std::isfinite(inertia_rigid) && std::isfinite(inertia_shell) &&
                      std::isfinite(mass_rigid) && std::isfinite(mass_shell) &&
                      std::isfinite(damping_s) && std::isfinite(reference_angle_rad);
  MASTROM_REQUIRE(finite, InputError, "affine model: a reduced term is not finite");
  MASTROM_REQUIRE(
      stress_rows.size() == 0 ||
          (stress_rows.cols() == r && stress_rows.rows() % 6 == 0 && stress_rows.allFinite()),
      InputError, "affine model: the stress rows are not finite 6P × ", r);
}

std::vector<NamedArray> toArrays(const AffineReducedModel& model) {
  AffineReducedModel copy = model;  // the views need non-const storage
  std::vector<NamedArray> out;
  for (const Member& m : members()) {
    const auto [rows, cols] = m.shape(copy);
    const Eigen::Map<Eigen::MatrixXd> v = m.view(copy, rows, cols);
    NamedArray a;
    a.name = m.name;
    a.dims = {static_cast<std::size_t>(rows), static_cast<std::size_t>(cols)};
    for (Eigen::Index i = 0; i < rows; ++i)
      for (Eigen::Index j = 0; j < cols; ++j) a.values.push_back(v(i, j));  // row-major
    out.push_back(std::move(a));
  }
  NamedArray modes{"modes", {1, 1}, {static_cast<double>(model.modes)}};
  out.push_back(std::move(modes));
  if (model.stress_rows.size() > 0) {  // optional: only a database built with stresses
    const Eigen::MatrixXd& st = model.stress_rows;
    NamedArray a{kAffineStressRows,
                 {static_cast<std::size_t>(st.rows()), static_cast<std::size_t>(st.cols())},
                 {}};
    a.values.reserve(static_cast<std::size_t>(st.size()));
    for (Eigen::Index i = 0; i < st.rows(); ++i)
      for (Eigen::Index j = 0; j < st.cols(); ++j) a.values.push_back(st(i, j));  // row-major
    out.push_back(std::move(a));
  }
  return out;
}

AffineReducedModel fromArrays(const std::vector<NamedArray>& arrays) {
  const auto find = [&arrays](const std::string& name) -> const NamedArray& {
    for (const NamedArray& a : arrays)
      if (a.name == name) return a;
    throw InputError("affine model: missing array '" + name + "'");
  };
  AffineReducedModel model;
  for (const Member& m : members()) {
    const NamedArray& a = find(m.name);
    MASTROM_REQUIRE(a.dims.size() == 2 && a.values.size() == a.dims[0] * a.dims[1], InputError,
                    "affine model: array '", m.name, "' is not a matrix of its stated shape");
    const auto rows = static_cast<Eigen::Index>(a.dims[0]);
    const auto cols = static_cast<Eigen::Index>(a.dims[1]);
    Eigen::Map<Eigen::MatrixXd> v = m.view(model, rows, cols);
    MASTROM_REQUIRE(v.rows() == rows && v.cols() == cols, InputError, "affine model: array '",
                    m.name, "' has shape [", rows, ", ", cols, "], expected [", v.rows(), ", ",
                    v.cols(), "]");
    for (Eigen::Index i = 0; i < rows; ++i)
      for (Eigen::Index j = 0; j < cols; ++j)
        v(i, j) = a.values[static_cast<std::size_t>(i * cols + j)];
  }
  const NamedArray& modes = find("modes");
  MASTROM_REQUIRE(modes.values.size() == 1, InputError,
                  "affine model: array 'modes' is not [1, 1]");
  model.modes = static_cast<int>(modes.values[0]);
  for (const NamedArray& a : arrays) {
    if (a.name != kAffineStressRows) continue;
    MASTROM_REQUIRE(a.dims.size() == 2 && a.values.size() == a.dims[0] * a.dims[1], InputError,
                    "affine model: array '", a.name, "' is not a matrix of its stated shape");
    model.stress_rows.resize(static_cast<Eigen::Index>(a.dims[0]),
                             static_cast<Eigen::Index>(a.dims[1]));
    for (Eigen::Index i = 0; i < model.stress_rows.rows(); ++i)
      for (Eigen::Index j = 0; j < model.stress_rows.cols(); ++j)
        model.stress_rows(i, j) =
            a.values[static_cast<std::size_t>(i * model.stress_rows.cols() + j)];
  }
  model.validate();
  return model;
}

}  // namespace mastrom::rom
