// libFuzzer target for the configuration layer (common/config.hpp): TOML text and `--set`
// overrides (docs/user_guide.md §4).
//
// Input: the TOML text, optionally followed by NUL-separated override strings
// ("<toml>\0section.key=value\0…"). What must hold for every input:
//  * the only failure is mastrom::InputError (a one-line message); any other exception, a crash or
//  a
//    sanitizer report is a finding;
//  * a configuration that is accepted survives the documented round trip
//    parseConfigText(toToml(c)) == c (config.hpp), before and after the overrides.
// Overrides are applied to the parsed file when it is valid, else to the defaults, so the override
// parser sees arbitrary text either way.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/config.hpp"
#include "common/error.hpp"

namespace {

/// The accepted configuration, or nullopt when `parse` refuses it with InputError (the one allowed
/// failure; anything else propagates and is a finding).
template <typename Parse>
std::optional<mastrom::Config> accepted(Parse parse) {
  try {
    return parse();
  } catch (const mastrom::InputError&) {
    return std::nullopt;
  }
}

/// Abort (a libFuzzer crash) when an accepted configuration does not read back to itself; an
/// InputError here is a finding too (toToml wrote something its own parser refuses).
void requireRoundTrip(const mastrom::Config& c) {
  const mastrom::Config back = mastrom::parseConfigText(mastrom::toToml(c), "round trip");
  if (back != c) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const std::size_t nul = input.find('\0');
  const std::string_view toml = input.substr(0, nul);
  std::vector<std::string> overrides;
  if (nul != std::string_view::npos) {
    std::string_view rest = input.substr(nul + 1);
    while (true) {
      const std::size_t next = rest.find('\0');
      overrides.emplace_back(rest.substr(0, next));
      if (next == std::string_view::npos) break;
      rest = rest.substr(next + 1);
    }
  }

  const std::optional<mastrom::Config> parsed =
      accepted([&] { return mastrom::parseConfigText(toml, "fuzz.toml"); });
  if (parsed) requireRoundTrip(*parsed);
  const mastrom::Config base = parsed.value_or(mastrom::Config{});  // defaults: text refused
  if (overrides.empty()) return 0;
  const std::optional<mastrom::Config> changed =
      accepted([&] { return mastrom::applyConfigOverrides(base, overrides); });
  if (changed) requireRoundTrip(*changed);
  return 0;
}
