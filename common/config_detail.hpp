// Internals shared by the implementation files of common/config.hpp: config_text.cpp (values as
// text, for messages and for toToml), config_read.cpp (TOML → Config: the steps below, in order),
// config_toml.cpp (text → TOML table), config_overrides.cpp (--set on the table),
// config_from_table.cpp (table → Config, types only), config_validate.cpp (ranges),
// config_write.cpp (Config → TOML) and config.cpp (derived values). Not part of the library's
// interface.
#pragma once

#include <toml++/toml.h>

#include <array>
#include <cstddef>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "common/config.hpp"

namespace mastrom::config_detail {

inline constexpr std::string_view kPrefix = "config: ";
inline constexpr double kPi = 3.14159265358979323846;
inline constexpr std::array<std::string_view, 9> kSections{"mast",     "module", "interface",
                                                           "material", "drive",  "simulation",
                                                           "modes",    "output", "uncertainty"};

/// Shortest text that reads back to the same double (std::to_chars round-trip guarantee).
std::string formatDouble(double v);
/// A double as a TOML float literal ("2700.0", not "2700", which would read back as an integer).
std::string tomlFloat(double v);
/// A TOML basic string literal with the needed escapes.
std::string tomlString(std::string_view text);
/// A double for people: %g with 6 significant digits.
std::string formatShort(double v);
std::string tomlVec3(const std::array<double, 3>& v);
std::string formatVec3(const std::array<double, 3>& v);
/// A TOML node's value as text, for messages.
std::string formatNode(const toml::node& node);
std::string joinKeys(const std::vector<std::string>& keys);
/// "mast, module, …": the sections a file may have.
std::string allowedSections();

/// Offset of the first non-ASCII byte outside TOML strings and comments, or npos (config_toml.cpp
/// says why toml++ must not meet one).
std::size_t firstBareNonAscii(std::string_view s);
/// The TOML text parsed; InputError (source:line:column) on a syntax error.
toml::table parseToml(std::string_view text, std::string_view source_name);

/// Apply one "section.key=value" override to the parsed file (`overridden`: the keys overridden so
/// far, for the radius / inner_diameter rule).
void applyOverride(toml::table& root, const std::string& text, std::set<std::string>& overridden);

/// Whether a table key names an item [section.K]: a positive integer without leading zeros.
bool isItemNumber(std::string_view k);
/// [uncertainty]: the inputs' tables read (types only, config_uncertainty.cpp), their ranges
/// checked, and their TOML text (nothing when there are none).
std::map<std::string, UncertainInput> readUncertainty(const toml::table* section);
void validateUncertainty(const std::map<std::string, UncertainInput>& inputs);
std::string uncertaintyToml(const std::map<std::string, UncertainInput>& inputs);

/// Table → Config (types only), then the derived values. validate() is the caller's next step.
Config fromTable(const toml::table& root);

}  // namespace mastrom::config_detail
