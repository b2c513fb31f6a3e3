// TOML → Config: reading (types: SectionReader), overrides, the tabulated drive's path, then
// validation (config_validate.cpp). Reading and range checking are kept apart: SectionReader only
// converts TOML nodes to C++ types and rejects unknown keys and wrong types; validate() holds every
// range and cross-key rule, so a Config built in code is checked by exactly the same rules as one
// read from a file.
#include "common/config.hpp"


#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <system_error>
#include <tuple>

#include "common/drive_table.hpp"
#include "common/error.hpp"
#include "common/text_parsing.hpp"

#include "common/config_detail.hpp"

namespace mastrom {
using namespace config_detail;

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

  static bool isItemNumber(std::string_view k) {
    if (k.empty() || k.size() > 6 || k[0] < '1' || k[0] > '9') return false;
    return std::all_of(k.begin(), k.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
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

/// Table → Config (types only), then the derived values. validate() is the caller's next step.
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
  return c;
}

/// Offset of the first non-ASCII byte outside strings and comments, or npos. TOML 1.0 allows
/// non-ASCII text only inside strings and comments (bare keys, numbers, booleans and dates are
/// ASCII), so such a byte is always a syntax error — but toml++ 3.3.0 (Debian 12) reaches
/// __builtin_unreachable() on it wherever it skips whitespace (is_non_ascii_horizontal_whitespace,
/// code points U+00A1…U+0499 and others; upstream marzer/tomlplusplus#190), i.e. undefined
/// behaviour instead of an error. Found by fuzz/fuzz_config.cpp with UBSan ("a = 1 §"). The scan
/// follows TOML's lexical structure: # comments to the end of the line, "basic" strings with
/// backslash escapes, 'literal' strings and their triple-quoted multi-line forms. A quote opens a
/// string only where TOML lets a key or value start (after = [ , { . or at a line start): toml++
/// does not read `-9.8"""…` as a number and a string, and must not meet the text after it.
std::size_t firstBareNonAscii(std::string_view s) {
  enum class State { Normal, Comment, Basic, Literal, MultiBasic, MultiLiteral };
  State state = State::Normal;
  char previous = '\n';  // last significant character in the Normal state
  const auto at = [&s](std::size_t i, const char* three) { return s.compare(i, 3, three) == 0; };
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    switch (state) {
      case State::Normal: {
        if (static_cast<unsigned char>(c) >= 0x80) return i;
        if (c == ' ' || c == '\t' || c == '\r') break;
        const bool can_open = previous == '\n' || previous == '=' || previous == '[' ||
                              previous == ',' || previous == '{' || previous == '.';
        previous = c;
        if (c == '#') {
          state = State::Comment;
        } else if (!can_open) {
          break;
        } else if (at(i, "\"\"\"")) {
          state = State::MultiBasic;
          i += 2;
        } else if (at(i, "'''")) {
          state = State::MultiLiteral;
          i += 2;
        } else if (c == '"') {
          state = State::Basic;
        } else if (c == '\'') {
          state = State::Literal;
        }
        break;
      }
      case State::Comment:
        if (c == '\n') {
          state = State::Normal;
          previous = '\n';
        }
        break;
      case State::Basic:
        if (c == '\\')
          ++i;  // the escaped character cannot close the string
        else if (c == '"' || c == '\n')
          state = State::Normal;
        break;
      case State::Literal:
        if (c == '\'' || c == '\n') state = State::Normal;
        break;
      case State::MultiBasic:
        if (c == '\\') {
          ++i;
        } else if (at(i, "\"\"\"")) {
          state = State::Normal;
          i += 2;
        }
        break;
      case State::MultiLiteral:
        if (at(i, "'''")) {
          state = State::Normal;
          i += 2;
        }
        break;
    }
  }
  return std::string_view::npos;
}

toml::table parseToml(std::string_view text, std::string_view source_name) {
  if (const std::size_t bad = firstBareNonAscii(text); bad != std::string_view::npos) {
    const std::string_view before = text.substr(0, bad);
    const std::size_t line =
        1 + static_cast<std::size_t>(std::count(before.begin(), before.end(), '\n'));
    const std::size_t line_start = before.rfind('\n');
    const std::size_t column =
        bad - (line_start == std::string_view::npos ? 0 : line_start + 1) + 1;
    throw InputError(detail::concat(kPrefix, source_name, ":", line, ":", column,
                                    ": TOML syntax error: a non-ASCII character outside a string "
                                    "or comment (keys and non-string values are ASCII)"));
  }
  try {
    return toml::parse(text, source_name);
  } catch (const toml::parse_error& e) {
    std::string what(e.description());
    for (char& ch : what)
      if (ch == '\n' || ch == '\r') ch = ' ';
    throw InputError(detail::concat(kPrefix, source_name, ":", e.source().begin.line, ":",
                                    e.source().begin.column, ": TOML syntax error: ", what));
  }
}

std::string trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t");
  return std::string(s.substr(b, e - b + 1));
}

/// Offset of the first byte where `s` stops being well-formed UTF-8 (RFC 3629 §4: no overlong
/// forms, no surrogates, nothing above U+10FFFF), or npos. TOML text is UTF-8 by definition, so a
/// bare `--set` string that is not could never be written back into a config file (found by
/// fuzz/fuzz_config.cpp: the resolved config of `--set output.file=<0xff>` failed to re-read).
std::size_t invalidUtf8Offset(std::string_view s) {
  std::size_t i = 0;
  while (i < s.size()) {
    const auto lead = static_cast<unsigned char>(s[i]);
    if (lead < 0x80) {
      ++i;
      continue;
    }
    std::size_t length = 0;
    unsigned char lo = 0x80, hi = 0xBF;  // allowed range of the second byte
    if (lead >= 0xC2 && lead <= 0xDF) {
      length = 2;
    } else if (lead >= 0xE0 && lead <= 0xEF) {
      length = 3;
      if (lead == 0xE0) lo = 0xA0;  // overlong
      if (lead == 0xED) hi = 0x9F;  // UTF-16 surrogates
    } else if (lead >= 0xF0 && lead <= 0xF4) {
      length = 4;
      if (lead == 0xF0) lo = 0x90;  // overlong
      if (lead == 0xF4) hi = 0x8F;  // above U+10FFFF
    } else {
      return i;
    }
    if (i + length > s.size()) return i;
    for (std::size_t k = 1; k < length; ++k) {
      const auto b = static_cast<unsigned char>(s[i + k]);
      if (k == 1 ? (b < lo || b > hi) : (b < 0x80 || b > 0xBF)) return i;
    }
    i += length;
  }
  return std::string_view::npos;
}

/// Apply one "section.key=value" override to the parsed file. Keys are checked later, by the same
/// reader as the file's keys, so an unknown key gets the same message either way.
void applyOverride(toml::table& root, const std::string& text, std::set<std::string>& overridden) {
  const auto malformed = [&text]() {
    return InputError(detail::concat(kPrefix, "--set ", tomlString(text),
                                     " is malformed: expected section.key=value (or "
                                     "module.K.key / interface.K.key for item K), e.g. "
                                     "interface.thickness=0.001"));
  };
  const auto eq = text.find('=');
  if (eq == std::string::npos) throw malformed();
  const std::string key = trim(std::string_view(text).substr(0, eq));
  const std::string value = trim(std::string_view(text).substr(eq + 1));
  // section.key, or section.K.key for item K of [module] / [interface].
  const std::vector<std::string> parts = splitAt(key, '.');
  for (const std::string& p : parts)
    if (p.empty()) throw malformed();
  const bool item_key = parts.size() == 3 && (parts[0] == "module" || parts[0] == "interface") &&
                        SectionReader::isItemNumber(parts[1]);
  if (parts.size() != 2 && !item_key) throw malformed();
  const std::string section = parts.front();
  const std::string leaf = parts.back();

  // The value is TOML ("0.001", "[0, 0, -9.81]", "\"cubic\"", "true"); anything that is not a
  // single TOML value is taken as a bare string ("cubic", "run 1.h5").
  toml::table parsed;
  bool is_toml_value = false;
  // Non-ASCII outside a TOML string cannot be a TOML value, and must not reach toml++ (see
  // firstBareNonAscii): such a value is a bare string.
  const std::string as_toml = "v = " + value;
  if (firstBareNonAscii(as_toml) == std::string_view::npos) {
    try {
      parsed = toml::parse(as_toml);
      is_toml_value = parsed.size() == 1 && parsed.contains("v");
    } catch (const toml::parse_error&) {
      is_toml_value = false;
    }
  }

  toml::table* table = &root;
  std::string path;
  for (std::size_t p = 0; p + 1 < parts.size(); ++p) {
    path += (p ? "." : "") + parts[p];
    toml::node* sub = table->get(parts[p]);
    if (!sub) sub = table->insert_or_assign(parts[p], toml::table{}).first->second.as_table();
    if (!sub->is_table()) {
      throw InputError(detail::concat(kPrefix, "--set ", tomlString(text), ": ", path, " = ",
                                      formatNode(*sub), " is not a table [", path, "]"));
    }
    table = sub->as_table();
  }
  if (is_toml_value) {
    table->insert_or_assign(leaf, *parsed.get("v"));
  } else {
    if (const std::size_t bad = invalidUtf8Offset(value); bad != std::string_view::npos) {
      char byte[8];
      std::snprintf(byte, sizeof byte, "0x%02x",
                    static_cast<unsigned>(static_cast<unsigned char>(value[bad])));
      throw InputError(detail::concat(kPrefix, "--set ", key,
                                      ": the value is not valid UTF-8 (byte ", byte, " at offset ",
                                      bad, "): text values must be UTF-8"));
    }
    table->insert_or_assign(leaf, value);
  }

  // radius and inner_diameter are two ways to give one quantity: on the command line the override
  // replaces the file's choice; both given as overrides stays an error.
  const std::string other = leaf == "radius"           ? "inner_diameter"
                            : leaf == "inner_diameter" ? "radius"
                                                       : "";
  if (section == "interface" && !other.empty() &&
      overridden.count(path + "." + other) == 0) {
    table->erase(other);
  }
  overridden.insert(key);
}

/// law = "table": the table's path made absolute against `base_dir`, its rows read and checked,
/// and T, Θ taken from its last row.
void resolveDriveTable(DriveConfig& d, const std::filesystem::path& base_dir) {
  if (d.law != DriveLawKind::Table) {
    d.table_time_s.clear();
    d.table_angle_rad.clear();
    return;
  }
  if (d.table.empty()) {
    throw InputError(detail::concat(kPrefix, "drive.table = \"\" is out of range: drive.law = "
                                             "\"table\" needs the path of a CSV file (time [s], "
                                             "angle [deg])"));
  }
  const std::filesystem::path given(d.table);
  d.table = (given.is_absolute() ? given : std::filesystem::absolute(base_dir / given))
                .lexically_normal()
                .string();
  const DriveTable table = readDriveTable(d.table);
  d.table_time_s = table.time_s;
  d.table_angle_rad = table.angle_rad;
  d.duration_s = table.time_s.back();
  d.angle_deg = table.angle_rad.back() * 180.0 / kPi;
}

Config parseApplyValidate(std::string_view text, std::string_view source_name,
                          const std::vector<std::string>& overrides,
                          const std::filesystem::path& base_dir = {}) {
  toml::table root = parseToml(text, source_name);
  std::set<std::string> overridden;
  for (const std::string& o : overrides) applyOverride(root, o, overridden);
  Config c = fromTable(root);
  validate(c);  // the table is read only for an otherwise valid configuration
  resolveDriveTable(c.drive, base_dir);
  return c;
}

}  // namespace

Config parseConfigText(std::string_view toml, std::string_view source_name) {
  return parseApplyValidate(toml, source_name, {});
}

Config applyConfigOverrides(const Config& base, const std::vector<std::string>& overrides) {
  if (overrides.empty()) return base;
  return parseApplyValidate(toToml(base), "configuration with overrides", overrides);
}

Config loadConfig(const std::string& path, const std::vector<std::string>& overrides) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw IoError(detail::concat(kPrefix, "cannot read ", path, ": it is a directory"));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw IoError(detail::concat(kPrefix, "cannot read ", path, ": ", std::strerror(errno)));
  }
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw IoError(detail::concat(kPrefix, "cannot read ", path, ": read error"));
  return parseApplyValidate(text.str(), path, overrides, std::filesystem::path(path).parent_path());
}

}  // namespace mastrom
