// TOML → Config: the file's text parsed (config_toml.cpp), the overrides applied
// (config_overrides.cpp), the table read (config_from_table.cpp), the result validated
// (config_validate.cpp), and the tabulated drive's path resolved and its table read.
#include "common/config.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "common/config_detail.hpp"
#include "common/drive_table.hpp"
#include "common/error.hpp"

namespace mastrom {
using namespace config_detail;

namespace {

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
