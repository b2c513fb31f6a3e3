#include "rom/database/parameter_space.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>

#include "common/error.hpp"
#include "common/option_names.hpp"
#include "rom/database/axis_lookup.hpp"
#include "common/text_parsing.hpp"

namespace mastrom::rom {
namespace {

constexpr const char* kParamExample = "e.g. interface.thickness=0.001:0.002:3";
constexpr const char* kRangeExample = "e.g. interface.thickness=0.001:0.002";

/// What the ROM knows about one configuration key (common/config.hpp lists them all).
struct KeyInfo {
  const char* key;
  KeyRole role;
  const char* units;
  const char* why_fixed;  ///< for Fixed keys: why a database cannot span them
};

constexpr const char* kTopology =
    "an integer key changes the model's size and cannot be interpolated";

// modes.angle_deg is listed as a parameter; keyRole() demotes it without gravity.
const KeyInfo kKeys[] = {
    {"mast.modules", KeyRole::Fixed, "1", kTopology},
    {"module.side", KeyRole::DatabaseParameter, "m", ""},
    {"module.mass", KeyRole::DatabaseParameter, "kg", ""},
    {"module.inertia", KeyRole::Fixed, "kg*m^2", "an array key cannot span an axis"},
    {"module.centroid_offset", KeyRole::Fixed, "m", "an array key cannot span an axis"},
    {"interface.length", KeyRole::DatabaseParameter, "m", ""},
    {"interface.radius", KeyRole::DatabaseParameter, "m", ""},
    {"interface.inner_diameter", KeyRole::DatabaseParameter, "m", ""},
    {"interface.thickness", KeyRole::DatabaseParameter, "m", ""},
    {"interface.elements_axial", KeyRole::Fixed, "1", kTopology},
    {"interface.elements_circumferential", KeyRole::Fixed, "1", kTopology},
    {"material.youngs_modulus", KeyRole::DatabaseParameter, "Pa", ""},
    {"material.poisson_ratio", KeyRole::DatabaseParameter, "1", ""},
    {"material.density", KeyRole::DatabaseParameter, "kg/m^3", ""},
    {"material.damping", KeyRole::DatabaseParameter, "s", ""},
    // The yield strength enters no modal quantity, only the margin of safety of the stresses.
    {"material.yield_strength", KeyRole::Free, "Pa", ""},
    {"drive.law", KeyRole::Free, "1", ""},
    {"drive.angle_deg", KeyRole::Free, "deg", ""},
    {"drive.duration", KeyRole::Free, "s", ""},
    {"drive.ramp", KeyRole::Free, "s", ""},
    {"drive.table", KeyRole::Free, "1", ""},
    {"simulation.end_time", KeyRole::Free, "s", ""},
    {"simulation.time_step", KeyRole::Free, "s", ""},
    {"simulation.adaptive", KeyRole::Free, "1", ""},
    {"simulation.tolerance", KeyRole::Free, "1", ""},
    {"simulation.min_time_step", KeyRole::Free, "s", ""},
    {"simulation.max_time_step", KeyRole::Free, "s", ""},
    {"simulation.rho_inf", KeyRole::Free, "1", ""},
    {"simulation.accelerations", KeyRole::Free, "1", ""},
    {"simulation.gravity", KeyRole::Fixed, "m/s^2",
     "gravity sets every sample's preload; build one database per gravity vector"},
    {"modes.count", KeyRole::Fixed, "1", "the mode count is given by "},
    {"modes.angle_deg", KeyRole::DatabaseParameter, "deg", ""},
    {"modes.backend", KeyRole::Fixed, "1", "the backend is given by "},
    {"output.file", KeyRole::Free, "1", ""},
    {"output.every", KeyRole::Free, "1", ""},
    {"output.step", KeyRole::Free, "s", ""},
};

/// "section.key" of an item's key "section.K.key" (module or interface item K), else `key`.
std::string genericKey(const std::string& key) {
  const auto first = key.find('.');
  const auto last = key.rfind('.');
  if (first == std::string::npos || first == last) return key;
  const std::string section = key.substr(0, first);
  const std::string item = key.substr(first + 1, last - first - 1);
  if ((section != "module" && section != "interface") || item.empty() ||
      item.find_first_not_of("0123456789") != std::string::npos) {
    return key;
  }
  return section + key.substr(last);
}

/// The key's entry; an item's key "module.K.mass" has the entry of "module.mass".
const KeyInfo* findKey(const std::string& key) {
  const std::string generic = genericKey(key);
  for (const KeyInfo& k : kKeys)
    if (generic == k.key) return &k;
  return nullptr;
}

bool gravityOn(const Config& c) {
  const auto& g = c.simulation.gravity_m_s2;
  return g[0] != 0.0 || g[1] != 0.0 || g[2] != 0.0;
}

std::string shortest(double v) { return shortestText(v); }

std::string trim(const std::string& s) { return trimBlanks(s); }
bool parseNumber(const std::string& text, double& out) { return parseStrictNumber(text, out); }

std::string keyOf(const std::string& override_text) {
  const auto eq = override_text.find('=');
  return trim(eq == std::string::npos ? override_text : override_text.substr(0, eq));
}

}  // namespace

KeyRole keyRole(const std::string& key, const Config& base) {
  const KeyInfo* info = findKey(key);
  if (!info) return KeyRole::Fixed;
  if (key == "modes.angle_deg" && !gravityOn(base)) return KeyRole::Fixed;
  return info->role;
}

std::string configKeyUnits(const std::string& key) {
  const KeyInfo* info = findKey(key);
  return info ? info->units : "1";
}

std::string formatOverride(const std::string& key, double value) {
  std::string v = shortest(value);
  if (v.find_first_of(".eEn") == std::string::npos) v += ".0";  // a float, not an integer literal
  return key + "=" + v;
}

Config applyOverrides(const Config& base, const std::vector<std::string>& overrides) {
  return applyConfigOverrides(base, overrides);
}

double configValue(const Config& config, const std::string& key) {
  const toml::table root = toml::parse(toToml(config));
  // An item's key absent from its table [section.K] has the value of [section].
  toml::node_view<const toml::node> node = root.at_path(key);
  if (!node) node = root.at_path(genericKey(key));
  const KeyInfo* info = findKey(key);
  MASTROM_REQUIRE(info != nullptr || node, InputError, "config: unknown key ", key);
  MASTROM_REQUIRE(node, InputError, "config: ", key, " is not set in this configuration",
                  key == "interface.inner_diameter" ? " (it gives interface.radius)"
                  : key == "interface.radius"       ? " (it gives interface.inner_diameter)"
                                                    : "");
  const auto* f = node.as_floating_point();
  MASTROM_REQUIRE(f != nullptr, InputError, "config: ", key,
                  " is not a floating-point key (a ROM parameter is a continuous number)");
  return f->get();
}

ParameterAxis parseParameterAxis(const std::string& text, const Config& base, AxisForm form) {
  const bool grid = form == AxisForm::Grid;
  const char* expected = grid ? "KEY=LO:HI:N" : "KEY=LO:HI (an adaptive build places its samples)";
  const char* example = grid ? kParamExample : kRangeExample;
  // The argument as the front end's user gave it (--param '…' / params '…').
  const std::string given = detail::concat(optionName(Option::Param), " '", text, "'");
  const auto eq = text.find('=');
  MASTROM_REQUIRE(eq != std::string::npos, InputError, given, " is malformed: expected ", expected,
                  ", ", example);
  const std::string key = trim(text.substr(0, eq));
  const std::string range = trim(text.substr(eq + 1));
  const std::vector<std::string> parts = splitAt(range, ':');
  MASTROM_REQUIRE(!key.empty() && parts.size() == (grid ? 3u : 2u), InputError, given,
                  " is malformed: expected ", expected, ", ", example);
  double lo = 0, hi = 0, n_value = 2;
  MASTROM_REQUIRE(parseNumber(parts[0], lo) && parseNumber(parts[1], hi), InputError, given,
                  ": LO and HI must be finite numbers, ", example);
  MASTROM_REQUIRE(
      !grid || (parseNumber(parts[2], n_value) && n_value == std::floor(n_value) && n_value >= 2 &&
                n_value <= 10000),
      InputError, given,
      ": N must be an integer in [2, 10000] (the number of samples, LO and HI included)");
  MASTROM_REQUIRE(lo < hi, InputError, given, ": LO = ", parts[0],
                  " must be less than HI = ", parts[1]);

  const std::string named = detail::concat(optionName(Option::Param), " ", key);
  const KeyInfo* info = findKey(key);
  if (info != nullptr) {
    const std::string section = key.substr(0, key.find('.'));
    MASTROM_REQUIRE(info->role != KeyRole::Free, InputError, named, ": ", section,
                    " keys are not database parameters; they are free when the ROM is evaluated "
                    "(give them to each evaluation or screen with ",
                    optionName(Option::Set), ")");
    MASTROM_REQUIRE(!(key == "modes.angle_deg" && !gravityOn(base)), InputError, named,
                    ": without gravity the modes at another angle are the same modes rotated; "
                    "modes.angle_deg is a database parameter only when simulation.gravity is "
                    "non-zero");
    MASTROM_REQUIRE(info->role != KeyRole::Fixed, InputError, named,
                    " cannot be a database parameter: ", info->why_fixed,
                    key == "modes.count"     ? optionName(Option::Modes)
                    : key == "modes.backend" ? optionName(Option::Backend)
                                             : "");
  }
  // The key must exist and accept both ends of the range: the configuration's own checks decide.
  for (const double v : {lo, hi}) {
    try {
      (void)applyOverrides(base, {formatOverride(key, v)});
    } catch (const InputError& e) {
      throw InputError(detail::concat(given, ": ", e.what()));
    }
  }
  MASTROM_REQUIRE(info != nullptr, InputError, named, " is not a key the ROM knows how to sample");

  ParameterAxis axis;
  axis.key = key;
  const int n = static_cast<int>(n_value);
  axis.values.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    axis.values[static_cast<std::size_t>(i)] = lo + (hi - lo) * i / (n - 1);
  axis.values.front() = lo;
  axis.values.back() = hi;
  return axis;
}

Config databaseBaseConfig(const Config& base, const std::vector<ParameterAxis>& axes) {
  std::set<std::string> keys;
  for (const ParameterAxis& a : axes) {
    MASTROM_REQUIRE(keys.insert(a.key).second, InputError, optionName(Option::Param), " ", a.key,
                    " is given twice: one axis per key");
  }
  MASTROM_REQUIRE(!(keys.count("interface.radius") && keys.count("interface.inner_diameter")),
                  InputError, optionName(Option::Param),
                  " interface.radius and interface.inner_diameter are two ways to give one "
                  "quantity: sample one of them");
  std::vector<std::string> switch_to;
  const InterfaceConfig& f = base.interface;
  if (keys.count("interface.inner_diameter") && !f.inner_diameter_m) {
    switch_to.push_back(
        formatOverride("interface.inner_diameter", 2.0 * f.radius_m - f.thickness_m));
  }
  if (keys.count("interface.radius") && f.inner_diameter_m) {
    switch_to.push_back(formatOverride("interface.radius", f.radius_m));
  }
  return applyOverrides(base, switch_to);
}

std::vector<std::string> parameterOverrides(const std::vector<ParameterAxis>& axes,
                                            const std::vector<double>& parameters) {
  MASTROM_REQUIRE(parameters.size() == axes.size(), InputError, "rom: ", parameters.size(),
                  " parameter values for ", axes.size(), " axes");
  std::vector<std::string> out;
  for (std::size_t a = 0; a < axes.size(); ++a)
    out.push_back(formatOverride(axes[a].key, parameters[a]));
  return out;
}

std::vector<double> parameterPoint(const RomDatabase& db, const Config& config) {
  std::vector<double> p;
  p.reserve(db.axes.size());
  for (const ParameterAxis& a : db.axes) p.push_back(configValue(config, a.key));
  return p;
}

Config evaluationConfig(const RomDatabase& db, const std::vector<std::string>& overrides) {
  const Config base = parseConfigText(db.base_config_toml, "ROM database base configuration");
  const Config config = applyOverrides(base, overrides);  // unknown keys, types, ranges
  for (const std::string& o : overrides) {
    const std::string key = keyOf(o);
    bool is_axis = false;
    for (const ParameterAxis& a : db.axes) is_axis = is_axis || a.key == key;
    if (is_axis || keyRole(key, base) == KeyRole::Free) continue;
    throw InputError(
        detail::concat("rom: ", optionName(Option::Set), " ", key,
                       " is not a parameter of this database (parameters: ", axisKeys(db),
                       "; free keys: drive.*, simulation.* of the full order's steps, output.*, "
                       "material.yield_strength): the ROM "
                       "holds it at the value it was built with"));
  }
  return config;
}

void requireInsideBox(const RomDatabase& db, const std::vector<double>& parameters,
                      BoxPolicy policy) {
  MASTROM_REQUIRE(parameters.size() == db.axes.size(), InputError, "rom: ", parameters.size(),
                  " parameter values for ", db.axes.size(), " database axes");
  for (std::size_t a = 0; a < db.axes.size(); ++a) {
    MASTROM_REQUIRE(std::isfinite(parameters[a]), InputError, "rom: ", db.axes[a].key, " = ",
                    parameters[a], " is not finite");
  }
  if (policy == BoxPolicy::Extrapolate || db.contains(parameters)) return;
  for (std::size_t a = 0; a < db.axes.size(); ++a) {
    const ParameterAxis& axis = db.axes[a];
    std::vector<double> probe(db.axes.size());
    for (std::size_t b = 0; b < db.axes.size(); ++b) probe[b] = db.axes[b].values.front();
    probe[a] = parameters[a];
    if (db.contains(probe)) continue;
    throw InputError(detail::concat(
        "rom: ", axis.key, " = ", shortest(parameters[a]), " lies outside the database's range [",
        shortest(axis.values.front()), ", ", shortest(axis.values.back()),
        "] (evaluating outside the sampled box needs ", optionName(Option::Extrapolate), ")"));
  }
}

}  // namespace mastrom::rom
