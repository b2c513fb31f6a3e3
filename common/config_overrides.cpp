// `--set section.key=value` overrides, applied to the parsed TOML table before it is read, so an
// override meets the same reader, types and messages as a key of the file (config_read.cpp).
#include "common/config_detail.hpp"

#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "common/option_names.hpp"
#include "common/text_parsing.hpp"

namespace mastrom::config_detail {
namespace {

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

}  // namespace

/// Apply one "section.key=value" override to the parsed file. Keys are checked later, by the same
/// reader as the file's keys, so an unknown key gets the same message either way.
void applyOverride(toml::table& root, const std::string& text, std::set<std::string>& overridden) {
  const auto malformed = [&text]() {
    return InputError(detail::concat(kPrefix, optionName(Option::Set), " ", tomlString(text),
                                     " is malformed: expected section.key=value (or "
                                     "module.K.key / interface.K.key for item K, "
                                     "uncertainty.KEY.param for an uncertain input), e.g. "
                                     "interface.thickness=0.001"));
  };
  const auto eq = text.find('=');
  if (eq == std::string::npos) throw malformed();
  const std::string key = trimBlanks(text.substr(0, eq));
  const std::string value = trimBlanks(text.substr(eq + 1));
  // section.key, or section.K.key for item K of [module] / [interface].
  std::vector<std::string> parts = splitAt(key, '.');
  for (const std::string& p : parts)
    if (p.empty()) throw malformed();
  const bool item_key = parts.size() == 3 && (parts[0] == "module" || parts[0] == "interface") &&
                        isItemNumber(parts[1]);
  // uncertainty.KEY.param: KEY (itself dotted, "interface.thickness") names one table
  // [uncertainty."KEY"].
  const bool uncertainty_key = parts.size() >= 4 && parts[0] == "uncertainty";
  if (uncertainty_key) {
    std::string input = parts[1];
    for (std::size_t p = 2; p + 1 < parts.size(); ++p) input += "." + parts[p];
    parts = {parts.front(), input, parts.back()};
  }
  if (parts.size() != 2 && !item_key && !uncertainty_key) throw malformed();
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
      throw InputError(detail::concat(kPrefix, optionName(Option::Set), " ", tomlString(text), ": ",
                                      path, " = ", formatNode(*sub), " is not a table [", path,
                                      "]"));
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
      throw InputError(detail::concat(kPrefix, optionName(Option::Set), " ", key,
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
  // A new distribution replaces the input: the file's parameters of the old one are dropped, the
  // new ones come from the command line too (--set uncertainty.KEY.distribution=uniform
  // --set uncertainty.KEY.lower=... --set uncertainty.KEY.upper=...).
  if (uncertainty_key && leaf == "distribution") {
    for (const char* p : {"mean", "std", "lower", "upper"})
      if (overridden.count(path + "." + p) == 0) table->erase(p);
  }
  overridden.insert(key);
}

}  // namespace mastrom::config_detail
