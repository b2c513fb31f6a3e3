#include "rom/interpolation/affine_interpolation.hpp"

#include "common/config.hpp"
#include "common/error.hpp"
#include "rom/interpolation/tracked_interpolation.hpp"

namespace mastrom::rom {
namespace {

constexpr const char* kAffineKeys[3] = {"interface.thickness", "material.youngs_modulus",
                                        "material.density"};

int affineIndex(const std::string& key) {
  for (int i = 0; i < 3; ++i)
    if (key == kAffineKeys[i]) return i;
  return -1;
}

}  // namespace

bool affineApplicable(const Config& base, const std::vector<ParameterAxis>& axes,
                      std::string* why) {
  const auto no = [why](const std::string& reason) {
    if (why) *why = reason;
    return false;
  };
  for (const ParameterAxis& a : axes) {
    if (affineIndex(a.key) < 0) return no(a.key + " does not enter K and M affinely");
    if (a.key == "interface.thickness" && base.interface.inner_diameter_m)
      return no("the interface is given by its inner diameter, so R = (D_in + h)/2 moves with h");
  }
  if (!base.interface_items.empty())
    return no("interfaces differ ([interface.K] tables): the affine terms assume one shell section");
  for (const double g : base.simulation.gravity_m_s2)
    if (g != 0.0) return no("gravity is on (the preload's geometric stiffness is not affine)");
  return true;
}

AffineInterpolator::AffineInterpolator(const RomDatabase& db)
    : model_([&db] {
        MASTROM_REQUIRE(db.affine.has_value(), InputError,
                        "rom: this database carries no affine terms (built over parameters that "
                        "do not all enter affinely)");
        return AffineModalModel::fromReduced(*db.affine);
      }()) {
  const AffineReducedModel& r = *db.affine;
  fixed_ = {r.thickness_min_m, r.youngs_modulus_min_pa, r.density_min_kg_m3};
  for (std::size_t a = 0; a < db.axes.size(); ++a) {
    const int i = affineIndex(db.axes[a].key);
    MASTROM_REQUIRE(i >= 0, InputError, "rom database: axis ", db.axes[a].key,
                    " is not an affine parameter, yet the database carries affine terms");
    axis_of_[static_cast<std::size_t>(i)] = static_cast<int>(a);
  }
  const bool samples_have_stresses =
      !db.samples.empty() && !db.samples.front().modal.stress.empty();
  if (model_.hasStresses() && samples_have_stresses && db.isGrid())
    sampled_stress_ = std::make_unique<TrackedInterpolator>(db, AxisWeighting::Logarithmic, 3);
}

std::array<double, 3> AffineInterpolator::affineValues(
    const std::vector<double>& parameters) const {
  std::size_t axes = 0;
  for (const int a : axis_of_) axes += a >= 0 ? 1 : 0;
  MASTROM_REQUIRE(parameters.size() == axes, InputError, "rom: ", parameters.size(),
                  " parameter values for ", axes, " database axes");
  std::array<double, 3> v{};
  for (std::size_t i = 0; i < 3; ++i)
    v[i] = axis_of_[i] >= 0 ? parameters[static_cast<std::size_t>(axis_of_[i])] : fixed_[i];
  return v;
}

ModalModel AffineInterpolator::evaluate(const std::vector<double>& parameters) const {
  const std::array<double, 3> v = affineValues(parameters);
  return model_.evaluate(v[0], v[1], v[2]);
}

ModalModel AffineInterpolator::evaluateWithStresses(const std::vector<double>& parameters) const {
  if (!sampled_stress_) return evaluate(parameters);
  const std::array<double, 3> v = affineValues(parameters);
  AffineSolution solution;
  ModalModel m = model_.evaluate(v[0], v[1], v[2], solution);
  // The samples' static-correction rows S_res and preload σ̄ are plain fields (no mode order or
  // sign to track), smooth in the parameters; only they are taken from the interpolation.
  m.stress = sampled_stress_->evaluateWithStresses(parameters).stress;
  m.stress.modes = model_.stressModes(v[0], v[1], solution.coefficients);
  m.stress.validate(m.modeCount(), false);
  return m;
}

}  // namespace mastrom::rom
