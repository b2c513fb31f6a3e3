// What `mastrom report` shows of a ROM database that the Python report cannot compute itself: the
// database's own interpolation (rom/interpolation/interpolator.hpp, its default method) evaluated along each
// parameter axis and, for a database of two or more axes, over the plane of the first two. The
// samples themselves the report reads from the database file; these curves go to a small HDF5 file
// in the report's directory, `rom_database_N.h5` (N = the position of the database on the command
// line, 1-based), which the page refers to. Layout (k = modes per sample, n = kPointsPerAxis):
//
//   / attributes  source = "rom-database-curves", database (the file as given), method, axes (int),
//                 mastrom_version
//   /axis_A/values [n]                           units of the key   A = 0 … p−1; the other axes at
//   /axis_A/frequency_hz [n, k]                  Hz                 the reference sample's values
//   /axis_A/participation [n, k]                 kg^0.5*m           (/axis_A/held [p])
//   /plane/values_0 [n], /plane/values_1 [n]     the first two axes (others at the reference)
//   /plane/frequency_hz [n*n, k], /plane/participation [n*n, k]   row i*n + j = (values_0[i],
//                                                                  values_1[j])
// Every axis key is an attribute `key` of its group.
#pragma once

#include <string>

namespace mastrom::cli {

/// Points per axis of the sampled curves (and per side of the plane).
inline constexpr int kPointsPerAxis = 41;

/// True when `path` is a ROM database (root attribute source = "rom-database"); false for any
/// other file, readable or not (the report itself then says what is wrong with it).
bool isRomDatabaseFile(const std::string& path);

/// Evaluate the database at `database_path` as the header says and write `out_path` atomically.
/// IoError / InputError from reading the database.
void writeDatabaseCurves(const std::string& database_path, const std::string& out_path);

}  // namespace mastrom::cli
