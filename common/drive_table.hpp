// A measured drive profile: the CSV file behind `drive.law = "table"` (docs/theory.md §1.5).
//
// Format: one row per instant, two comma-separated columns, time [s] and joint angle [deg]. Blank
// lines and lines starting with '#' are skipped; a first line that is not two numbers is a header.
// The profile must describe a deployment from rest to rest, so that the interpolated θ(t)
// (fullorder/drive_law.hpp, a clamped C² cubic spline) joins the stowed and the held state without
// a jump of θ or θ̇:
//  * at least kMinRows rows, every value finite;
//  * times start at 0 and increase strictly;
//  * the angle starts at 0 and ends in (0, 360] deg;
//  * at rest at both ends: the rate of the quadratic through the first (last) three rows is at most
//    kRestFraction of the table's peak secant rate.
// Every violation is an InputError with one line naming drive.table, the file, the row and the rule.
#pragma once

#include <string>
#include <vector>

namespace mastrom {

struct DriveTable {
  std::vector<double> time_s;
  std::vector<double> angle_rad;
};

/// Fewest rows a table may have (the rest checks need three at each end).
inline constexpr std::size_t kDriveTableMinRows = 4;
/// Largest end rate a table may have, relative to its peak secant rate, and still be "at rest".
/// The three-row estimate of a rest start is not exact: for the cubic law sampled every h it reads
/// (8/3)(h/T)² of the peak rate (4 % with 9 rows), while a profile that starts moving reads its
/// starting rate — a quarter separates the two down to tables of 5 rows.
inline constexpr double kDriveTableRestFraction = 0.25;

/// Read and check the table at `path` (see the header). IoError when the file cannot be read.
DriveTable readDriveTable(const std::string& path);

/// The checks of the header on rows already read; `source` names them in messages.
void validateDriveTable(const DriveTable& table, const std::string& source);

}  // namespace mastrom
