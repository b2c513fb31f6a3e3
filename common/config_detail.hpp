// Internals shared by the implementation files of common/config.hpp: config_text.cpp (values as
// text, for messages and for toToml), config_read.cpp (TOML → Config, overrides),
// config_validate.cpp (ranges), config_write.cpp (Config → TOML) and config.cpp (derived values).
// Not part of the library's interface.
#pragma once

#include <toml++/toml.h>

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace mastrom::config_detail {

inline constexpr std::string_view kPrefix = "config: ";
inline constexpr double kPi = 3.14159265358979323846;
inline constexpr std::array<std::string_view, 8> kSections{
    "mast", "module", "interface", "material", "drive", "simulation", "modes", "output"};

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

}  // namespace mastrom::config_detail
