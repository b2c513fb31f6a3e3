// The parsed TOML table → Config, types only (SectionReader), and the derived values: the first
// step after parsing (config_read.cpp). Reading and range checking are kept apart: SectionReader
// only converts TOML nodes to C++ types and rejects unknown keys and wrong types; validate()
// (config_validate.cpp) holds every range and cross-key rule, so a Config built in code is checked
// by exactly the same rules as one read from a file.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "common/config.hpp"
#include "common/config_detail.hpp"
#include "common/error.hpp"

namespace mastrom::config_detail {

bool isItemNumber(std::string_view k) {
  if (k.empty() || k.size() > 6 || k[0] < '1' || k[0] > '9') return false;
  return std::all_of(k.begin(), k.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
}

namespace {

// ---------------------------------------------------------------------------------------------
// Reading one section: types only. Every read registers its key, so the list of allowed keys in
// the "unknown key" message can never drift from what is actually read.

class SectionReader {
public:
  SectionReader(std::string_view section, const toml::table* table)
      : section_(section), table_(table) {}

  void read(std::string_view key, double& out) {
    if (const toml::node* n = find(key)) out = number(key, *n);
  }

  void read(std::string_view key, std::optional<double>& out) {
    if (const toml::node* n = find(key)) out = number(key, *n);
  }

  void read(std::string_view key, int& out) {
    const toml::node* n = find(key);
    if (!n) return;
    const auto* i = n->as_integer();
    if (!i) {
      wrongType(key, *n,
                n->is_floating_point() ? "an integer (a float is not accepted for a count)"
                                       : "an integer");
    }
    const std::int64_t v = i->get();
    if (v > std::numeric_limits<int>::max() || v < std::numeric_limits<int>::min()) {
      throw InputError(detail::concat(kPrefix, name(key), " = ", v,
                                      " is out of range: must be at most ",
                                      std::numeric_limits<int>::max()));
    }
    out = static_cast<int>(v);
  }

  void read(std::string_view key, std::optional<int>& out) {
    if (!has(key)) {
      (void)find(key);
      return;
    }
    int value = 0;
    read(key, value);
    out = value;
  }

  void read(std::string_view key, bool& out) {
    const toml::node* n = find(key);
    if (!n) return;
    if (!n->is_boolean()) wrongType(key, *n, "a boolean (true or false)");
    out = n->as_boolean()->get();
  }

  void read(std::string_view key, std::string& out) {
    const toml::node* n = find(key);
    if (!n) return;
    if (!n->is_string()) wrongType(key, *n, "a string");
    out = n->as_string()->get();
  }

  void read(std::string_view key, std::array<double, 3>& out) {
    if (const toml::node* n = find(key)) out = vec3(key, *n);
  }

  void read(std::string_view key, std::optional<std::array<double, 3>>& out) {
    if (const toml::node* n = find(key)) out = vec3(key, *n);
  }

  /// An enum given by name; parse returns nullopt for an unknown name.
  template <typename Kind, typename Parse>
  void readKind(std::string_view key, Kind& out, Parse parse, std::string_view what,
                const std::string& allowed) {
    std::string text;
    read(key, text);
    if (!has(key)) return;
    const std::optional<Kind> kind = parse(text);
    if (!kind) {
      throw InputError(detail::concat(kPrefix, name(key), " = ", tomlString(text),
                                      " is not a known ", what, ": allowed: ", allowed));
    }
    out = *kind;
  }

  bool has(std::string_view key) const { return table_ && table_->get(key) != nullptr; }

  /// The per-item sub-tables [section.K] (K a positive integer written without leading zeros),
  /// by number. A key of that form whose value is not a table is a type error.
  std::vector<std::pair<int, const toml::table*>> items() {
    items_allowed_ = true;
    std::vector<std::pair<int, const toml::table*>> out;
    if (!table_) return out;
    for (auto&& [key, value] : *table_) {
      const std::string k(key.str());
      if (!isItemNumber(k)) continue;
      if (!value.is_table()) {
        wrongType(k, value, detail::concat("a table [", section_, ".", k, "] of item ", k, "'s keys"));
      }
      known_.insert(k);
      out.emplace_back(std::stoi(k), value.as_table());
    }
    return out;
  }

  std::string name(std::string_view key) const { return section_ + "." + std::string(key); }

  /// The number at key, if the table has it (for messages about values already read).
  std::optional<double> number(std::string_view key) const {
    const toml::node* n = table_ ? table_->get(key) : nullptr;
    if (!n || !n->is_number()) return std::nullopt;
    return number(key, *n);
  }

  /// Reject every key of the table that no read() asked for.
  void rejectUnknownKeys() const {
    if (!table_) return;
    for (auto&& [key, value] : *table_) {
      if (known_.count(std::string(key.str())) != 0) continue;
      std::vector<std::string> allowed(order_.begin(), order_.end());
      throw InputError(detail::concat(
          kPrefix, "unknown key ", name(key.str()), " = ", formatNode(value), ": allowed keys of [",
          section_, "]: ", joinKeys(allowed),
          items_allowed_ ? detail::concat(", and tables [", section_, ".K] for item K") : ""));
    }
  }

private:
  const toml::node* find(std::string_view key) {
    if (known_.insert(std::string(key)).second) order_.emplace_back(key);
    return table_ ? table_->get(key) : nullptr;
  }

  [[noreturn]] void wrongType(std::string_view key, const toml::node& n,
                              std::string_view expected) const {
    throw InputError(detail::concat(kPrefix, name(key), " = ", formatNode(n),
                                    " has the wrong type: expected ", expected));
  }

  double number(std::string_view key, const toml::node& n) const {
    if (const auto* f = n.as_floating_point()) return f->get();
    if (const auto* i = n.as_integer()) return static_cast<double>(i->get());
    wrongType(key, n, "a number");
  }

  std::array<double, 3> vec3(std::string_view key, const toml::node& n) const {
    const auto* a = n.as_array();
    if (!a || a->size() != 3) wrongType(key, n, "an array of 3 numbers [x, y, z]");
    std::array<double, 3> v{};
    for (std::size_t k = 0; k < 3; ++k) {
      const toml::node& e = *a->get(k);
      if (!e.is_number()) wrongType(key, n, "an array of 3 numbers [x, y, z]");
      v[k] = number(key, e);
    }
    return v;
  }

  std::string section_;
  const toml::table* table_;
  std::set<std::string> known_;
  std::vector<std::string> order_;
  bool items_allowed_ = false;
};

// The keys of a module and of an interface, read alike into the [section] defaults and into an
// item's optional overrides (SectionReader::read has an overload for each).
template <typename Module>
void readModuleKeys(SectionReader& r, Module& m) {
  r.read("side", m.side_m);
  r.read("mass", m.mass_kg);
  r.read("inertia", m.inertia_kg_m2);
  r.read("centroid_offset", m.centroid_offset_m);
  r.rejectUnknownKeys();
}

template <typename Interface>
void readInterfaceKeys(SectionReader& r, Interface& f) {
  r.read("length", f.length_m);
  r.read("radius", f.radius_m);
  r.read("inner_diameter", f.inner_diameter_m);
  r.read("thickness", f.thickness_m);
  r.read("elements_axial", f.elements_axial);
  r.read("elements_circumferential", f.elements_circumferential);
  r.rejectUnknownKeys();
  if (r.has("radius") && r.has("inner_diameter")) {
    throw InputError(detail::concat(kPrefix, r.name("radius"), " = ", formatDouble(*r.number("radius")),
                                    " and ", r.name("inner_diameter"), " = ",
                                    formatDouble(*r.number("inner_diameter")),
                                    " are both given: give one of them (radius = (inner_diameter "
                                    "+ thickness)/2)"));
  }
}

/// The sub-table of one section, or nullptr when the section is absent.
const toml::table* sectionTable(const toml::table& root, std::string_view section) {
  const toml::node* n = root.get(section);
  if (!n) return nullptr;
  if (!n->is_table()) {
    throw InputError(detail::concat(kPrefix, section, " = ", formatNode(*n),
                                    " has the wrong type: expected a table [", section, "]"));
  }
  return n->as_table();
}

void rejectUnknownSections(const toml::table& root) {
  for (auto&& [key, value] : root) {
    const std::string_view k = key.str();
    bool known = false;
    for (const std::string_view s : kSections) known = known || s == k;
    if (known) continue;
    if (value.is_table()) {
      throw InputError(detail::concat(kPrefix, "unknown section [", k, "] = ", formatNode(value),
                                      ": allowed sections: ", allowedSections()));
    }
    throw InputError(detail::concat(kPrefix, "unknown key ", k, " = ", formatNode(value),
                                    " at top level: every key belongs to a section; allowed "
                                    "sections: ",
                                    allowedSections()));
  }
}

}  // namespace

std::map<std::string, UncertainInput> readUncertainty(const toml::table* section) {
  std::map<std::string, UncertainInput> inputs;
  if (!section) return inputs;
  for (auto&& [key, value] : *section) {
    const std::string k(key.str());
    const std::string at = "uncertainty." + k;
    if (!value.is_table()) {
      throw InputError(detail::concat(kPrefix, at, " = ", formatNode(value),
                                      " has the wrong type: expected a table [uncertainty.",
                                      tomlString(k), "] with distribution = \"",
                                      allowedDistributionNames(), "\" and its parameters"));
    }
    SectionReader r(at, value.as_table());
    UncertainInput& in = inputs[k];
    r.readKind("distribution", in.distribution, parseDistributionKind, "distribution",
               allowedDistributionNames());
    r.read("mean", in.mean);
    r.read("std", in.std_dev);
    r.read("lower", in.lower);
    r.read("upper", in.upper);
    r.rejectUnknownKeys();
    if (!r.has("distribution")) {
      throw InputError(detail::concat(kPrefix, at, ".distribution is missing: give one of ",
                                      allowedDistributionNames()));
    }
  }
  return inputs;
}

Config fromTable(const toml::table& root) {
  rejectUnknownSections(root);
  Config c;

  SectionReader mast("mast", sectionTable(root, "mast"));
  mast.read("modules", c.mast.modules);
  mast.rejectUnknownKeys();

  SectionReader module("module", sectionTable(root, "module"));
  for (const auto& [k, table] : module.items()) {
    SectionReader item("module." + std::to_string(k), table);
    readModuleKeys(item, c.module_items[k]);
  }
  readModuleKeys(module, c.module);

  SectionReader iface("interface", sectionTable(root, "interface"));
  for (const auto& [k, table] : iface.items()) {
    SectionReader item("interface." + std::to_string(k), table);
    readInterfaceKeys(item, c.interface_items[k]);
  }
  readInterfaceKeys(iface, c.interface);
  // docs/theory.md §1: the inner diameter maps to the mid-surface radius R = (D_in + h)/2.
  if (c.interface.inner_diameter_m) {
    c.interface.radius_m = 0.5 * (*c.interface.inner_diameter_m + c.interface.thickness_m);
  }

  SectionReader material("material", sectionTable(root, "material"));
  material.read("youngs_modulus", c.material.youngs_modulus_pa);
  material.read("poisson_ratio", c.material.poisson_ratio);
  material.read("density", c.material.density_kg_m3);
  material.read("damping", c.material.damping_s);
  material.read("yield_strength", c.material.yield_strength_pa);
  material.rejectUnknownKeys();

  SectionReader drive("drive", sectionTable(root, "drive"));
  drive.readKind("law", c.drive.law, parseDriveLawKind, "drive law", allowedDriveLawNames());
  drive.read("angle_deg", c.drive.angle_deg);
  drive.read("duration", c.drive.duration_s);
  drive.read("ramp", c.drive.ramp_s);
  drive.read("table", c.drive.table);
  drive.rejectUnknownKeys();

  SectionReader sim("simulation", sectionTable(root, "simulation"));
  sim.read("end_time", c.simulation.end_time_s);
  sim.read("time_step", c.simulation.time_step_s);
  sim.read("adaptive", c.simulation.adaptive);
  sim.read("tolerance", c.simulation.tolerance);
  sim.read("min_time_step", c.simulation.min_time_step_s);
  sim.read("max_time_step", c.simulation.max_time_step_s);
  sim.read("rho_inf", c.simulation.rho_inf);
  sim.read("gravity", c.simulation.gravity_m_s2);
  sim.readKind("accelerations", c.simulation.accelerations, parseAccelerationOutputKind,
               "acceleration output", allowedAccelerationOutputNames());
  sim.rejectUnknownKeys();

  SectionReader modes("modes", sectionTable(root, "modes"));
  modes.read("count", c.modes.count);
  modes.read("angle_deg", c.modes.angle_deg);
  modes.readKind("backend", c.modes.backend, parseEigenBackendKind, "eigensolver backend",
                 allowedEigenBackendNames());
  modes.rejectUnknownKeys();

  SectionReader output("output", sectionTable(root, "output"));
  output.read("file", c.output.file);
  output.read("every", c.output.every);
  output.read("step", c.output.step_s);
  output.rejectUnknownKeys();

  c.uncertainty = readUncertainty(sectionTable(root, "uncertainty"));
  return c;
}

}  // namespace mastrom::config_detail
