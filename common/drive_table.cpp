#include "common/drive_table.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "common/error.hpp"
#include "common/text_parsing.hpp"

namespace mastrom {
namespace {

constexpr double kRadPerDeg = 3.14159265358979323846 / 180.0;
constexpr double kDegPerRad = 180.0 / 3.14159265358979323846;

/// "t, angle" → two numbers; false when the line is not exactly that.
bool parseRow(const std::string& line, double& t, double& angle_deg) {
  const auto comma = line.find(',');
  if (comma == std::string::npos || line.find(',', comma + 1) != std::string::npos) return false;
  return parseStrictNumber(line.substr(0, comma), t) &&
         parseStrictNumber(line.substr(comma + 1), angle_deg);
}

/// Slope at x0 of the quadratic through (x0, y0), (x1, y1), (x2, y2) (Newton divided differences).
double quadraticSlope(double x0, double y0, double x1, double y1, double x2, double y2) {
  const double d01 = (y1 - y0) / (x1 - x0);
  const double d12 = (y2 - y1) / (x2 - x1);
  return d01 + (d12 - d01) / (x2 - x0) * (x0 - x1);
}

}  // namespace

DriveTable readDriveTable(const std::string& path) {
  const std::string source = "drive.table = \"" + path + "\"";
  std::ifstream in(path);
  MASTROM_REQUIRE(static_cast<bool>(in), IoError, "config: ", source, ": cannot read the file: ",
                  std::strerror(errno));
  DriveTable table;
  std::string line;
  int row = 0;
  bool first_content = true;
  while (std::getline(in, line)) {
    ++row;
    if (!line.empty() && line.back() == '\r') line.pop_back();  // a file written on Windows
    const std::string text = trimBlanks(line);
    if (text.empty() || text[0] == '#') continue;
    double t = 0, a = 0;
    const bool ok = parseRow(text, t, a);
    if (!ok && first_content) {  // a header line
      first_content = false;
      continue;
    }
    first_content = false;
    MASTROM_REQUIRE(ok, InputError, "config: ", source, ": line ", row, " = \"", text,
                    "\" is not a row: expected two finite numbers, time [s], angle [deg]");
    table.time_s.push_back(t);
    table.angle_rad.push_back(a * kRadPerDeg);
  }
  validateDriveTable(table, source);
  return table;
}

void validateDriveTable(const DriveTable& table, const std::string& source) {
  const std::vector<double>& t = table.time_s;
  const std::vector<double>& a = table.angle_rad;
  const std::size_t n = t.size();
  MASTROM_REQUIRE(n == a.size() && n >= kDriveTableMinRows, InputError, "config: ", source,
                  " has ", n, " rows: a drive profile needs at least ", kDriveTableMinRows,
                  " (time [s], angle [deg])");
  for (std::size_t i = 0; i < n; ++i) {
    MASTROM_REQUIRE(std::isfinite(t[i]) && std::isfinite(a[i]), InputError, "config: ", source,
                    ": row ", i + 1, " is not finite");
  }
  MASTROM_REQUIRE(t[0] == 0.0, InputError, "config: ", source, ": the first time is ", t[0],
                  " s: the profile must start at time 0");
  for (std::size_t i = 1; i < n; ++i) {
    MASTROM_REQUIRE(t[i] > t[i - 1], InputError, "config: ", source, ": row ", i + 1, ": time ",
                    t[i], " s does not exceed the previous row's ", t[i - 1],
                    " s (times must increase strictly)");
  }
  MASTROM_REQUIRE(a[0] == 0.0, InputError, "config: ", source, ": the first angle is ",
                  a[0] * kDegPerRad, " deg: the profile must start from the stowed angle 0");
  const double last_deg = a[n - 1] * kDegPerRad;
  MASTROM_REQUIRE(last_deg > 0.0 && last_deg <= 360.0, InputError, "config: ", source,
                  ": the last angle is ", last_deg, " deg: must satisfy 0 < angle <= 360");
  double peak = 0.0;
  for (std::size_t i = 1; i < n; ++i) peak = std::max(peak, std::abs(a[i] - a[i - 1]) / (t[i] - t[i - 1]));
  const double start = quadraticSlope(t[0], a[0], t[1], a[1], t[2], a[2]);
  const double end =
      quadraticSlope(t[n - 1], a[n - 1], t[n - 2], a[n - 2], t[n - 3], a[n - 3]);
  const double limit = kDriveTableRestFraction * peak;
  MASTROM_REQUIRE(std::abs(start) <= limit, InputError, "config: ", source,
                  " does not start at rest: rate at t = 0 from its first three rows ",
                  start * kDegPerRad, " deg/s, allowed at most ", kDriveTableRestFraction * 100,
                  " % of its peak rate (", limit * kDegPerRad, " deg/s)");
  MASTROM_REQUIRE(std::abs(end) <= limit, InputError, "config: ", source,
                  " does not end at rest: rate at t = ", t[n - 1], " s from its last three rows ",
                  end * kDegPerRad, " deg/s, allowed at most ", kDriveTableRestFraction * 100,
                  " % of its peak rate (", limit * kDegPerRad, " deg/s)");
}

}  // namespace mastrom
