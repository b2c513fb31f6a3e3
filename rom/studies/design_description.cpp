// Mass and natural frequencies of a design (see design_description.hpp).
#include "rom/studies/design_description.hpp"

#include <cmath>

#include "common/error.hpp"
#include "fullorder/mast_config.hpp"

namespace mastrom::rom {
namespace {

constexpr double kTwoPi = 2.0 * 3.14159265358979323846;

/// Sets `key` (a database parameter's key) to `value` in `c` when it changes a mass (docs/theory.md
/// (1.12)); false, and `c` untouched, for any other key. The inner diameter moves the radius as
/// the configuration derives it, R = (D_in + h)/2 (1.1).
bool setMassKey(Config& c, const std::string& key, double value) {
  if (key == "material.density") {
    c.material.density_kg_m3 = value;
    return true;
  }
  const auto first = key.find('.'), last = key.rfind('.');
  if (first == std::string::npos) return false;
  const std::string section = key.substr(0, first), name = key.substr(last + 1);
  const std::string item = first == last ? "" : key.substr(first + 1, last - first - 1);
  if (!item.empty() && item.find_first_not_of("0123456789") != std::string::npos) return false;
  const int k = item.empty() ? 0 : std::stoi(item);
  if (section == "module" && name == "mass") {
    if (item.empty())
      c.module.mass_kg = value;
    else
      c.module_items[k].mass_kg = value;
    return true;
  }
  if (section != "interface") return false;
  if (name != "length" && name != "thickness" && name != "radius" && name != "inner_diameter")
    return false;
  if (item.empty()) {
    InterfaceConfig& f = c.interface;
    if (name == "length") f.length_m = value;
    if (name == "thickness") f.thickness_m = value;
    if (name == "radius") {
      f.radius_m = value;
      f.inner_diameter_m.reset();
    }
    if (name == "inner_diameter") f.inner_diameter_m = value;
    if (f.inner_diameter_m) f.radius_m = 0.5 * (*f.inner_diameter_m + f.thickness_m);
  } else {
    InterfaceItemConfig& f = c.interface_items[k];
    if (name == "length") f.length_m = value;
    if (name == "thickness") f.thickness_m = value;
    if (name == "radius") {
      f.radius_m = value;
      f.inner_diameter_m.reset();
    }
    if (name == "inner_diameter") {
      f.inner_diameter_m = value;
      f.radius_m.reset();
    }
  }
  return true;
}

int axisOf(const std::vector<ParameterAxis>& axes, const std::string& key) {
  for (std::size_t a = 0; a < axes.size(); ++a)
    if (axes[a].key == key) return static_cast<int>(a);
  return -1;
}

}  // namespace

fullorder::MastMass configuredMass(const Config& config) {
  return fullorder::mastMass(fullorder::mastParametersFromConfig(config));
}

DesignDescriber::DesignDescriber(const RomDatabase& db, const Config& base,
                                 const FrequencyRequest& request,
                                 const std::vector<double>& deployed_angles_deg, BoxPolicy box)
    : base_(base), axes_(db.axes), deployed_deg_(deployed_angles_deg) {
  base_mass_ = configuredMass(base_);
  for (std::size_t a = 0; a < axes_.size(); ++a) {
    Config probe = base_;  // only asks whether the key moves a mass
    if (setMassKey(probe, axes_[a].key, 1.0)) mass_axes_.push_back(static_cast<int>(a));
  }

  MASTROM_REQUIRE(request.count >= 0 && request.count <= db.modes_per_sample, InputError,
                  request.option, " ", request.count, ": the database holds ", db.modes_per_sample,
                  " modes per sample (allowed 0 … ", db.modes_per_sample, ")");
  // Where the database holds modes at the deployed angle (see the header).
  const bool in_plane_gravity =
      base_.simulation.gravity_m_s2[0] != 0.0 || base_.simulation.gravity_m_s2[1] != 0.0;
  std::string why_not;
  if (in_plane_gravity) {
    angle_axis_ = axisOf(axes_, "modes.angle_deg");
    source_ = AngleSource::AngleAxis;
    for (const double theta : deployed_deg_) {
      if (angle_axis_ >= 0) {
        const ParameterAxis& axis = axes_[static_cast<std::size_t>(angle_axis_)];
        std::vector<double> p = parameterPoint(db, base_);
        p[static_cast<std::size_t>(angle_axis_)] = theta;
        if (box == BoxPolicy::Refuse && !db.contains(p))
          why_not = detail::concat("the deployed angle drive.angle_deg = ", theta,
                                   " deg lies outside the database's modes.angle_deg axis [",
                                   axis.values.front(), ", ", axis.values.back(), "] deg");
      } else if (base_.modes.angle_deg != theta) {
        why_not = detail::concat(
            "simulation.gravity has a component in the plane of the deployment, so the modes "
            "depend on the locked angle, and the database holds them only at modes.angle_deg = ",
            base_.modes.angle_deg, " deg, not at the deployed angle drive.angle_deg = ", theta,
            " deg (build it with modes.angle_deg = ", theta,
            " or over a modes.angle_deg axis that spans it)");
      }
      if (!why_not.empty()) break;
    }
    if (angle_axis_ < 0 && why_not.empty()) source_ = AngleSource::Invariant;  // θ₀ = Θ
  }
  if (request.count == 0) {
    no_frequency_reason_ = detail::concat(request.option, " 0");
    return;
  }
  if (!why_not.empty()) {
    MASTROM_REQUIRE(!request.explicit_request, InputError, request.option, " ", request.count, ": ",
                    why_not);
    no_frequency_reason_ = why_not;
    return;
  }
  frequencies_ = request.count;
  estimate_ = std::make_shared<const FrequencyErrorEstimate>(db, frequencies_);
}

MetricColumns DesignDescriber::columns(int stress_interfaces, bool margin,
                                       const std::string& no_stress_reason) const {
  MetricColumns c;
  c.stress_interfaces = stress_interfaces;
  c.margin = margin;
  if (!no_stress_reason.empty()) c.no_stress_reason = no_stress_reason;
  c.modules = base_.mast.modules;
  c.frequencies = frequencies_;
  if (!no_frequency_reason_.empty()) c.no_frequency_reason = no_frequency_reason_;
  return c;
}

fullorder::MastMass DesignDescriber::massAt(const std::vector<double>& point) const {
  if (mass_axes_.empty()) return base_mass_;
  Config c = base_;
  for (const int a : mass_axes_)
    setMassKey(c, axes_[static_cast<std::size_t>(a)].key, point[static_cast<std::size_t>(a)]);
  return configuredMass(c);
}

void DesignDescriber::describe(const ModalInterpolator& interpolator, const ModalModel& model,
                               const std::vector<double>& point, std::size_t free_case,
                               DesignValues& out) const {
  out.mass = massAt(point);
  out.frequency_hz.clear();
  out.frequency_error.clear();
  if (frequencies_ == 0) return;
  std::vector<double> at = point;
  const ModalModel* locked = &model;
  ModalModel turned;
  if (source_ == AngleSource::AngleAxis) {
    const auto a = static_cast<std::size_t>(angle_axis_);
    at[a] = deployed_deg_.at(free_case);
    if (at[a] != point[a]) {
      turned = interpolator.evaluate(at);
      locked = &turned;
    }
  }
  MASTROM_REQUIRE(locked->modeCount() >= frequencies_, NumericalError,
                  "frequencies: the model has ", locked->modeCount(), " modes, ", frequencies_,
                  " asked for");
  for (int k = 0; k < frequencies_; ++k)
    out.frequency_hz.push_back(locked->omega_rad_s[k] / kTwoPi);
  out.frequency_error = estimate_->at(at);
}

}  // namespace mastrom::rom
