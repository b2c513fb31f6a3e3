// The ROM database file (docs/theory.md §4.3, §5.3): HDF5, versioned, self-describing, written
// atomically, verified on reading. Layout (S samples, p parameters, k modes per sample; row-major):
//
//   / attributes  format = "mastrom-rom-database", format_version = 2 (int), mastrom_version,
//                 source = "rom-database", config (base configuration, TOML), method (default
//                 interpolation: "tracked" | "manifold"), sample_count, parameter_count,
//                 modes_per_sample, reference_sample, affine (0/1) (ints), layout ("grid" |
//                 "scattered"; absent in files from before scattered layouts: grid), loo_frequency_error,
//                 loo_response_error (the database's error estimate between samples: max over
//                 samples of ρ_s × the sample's leave-one-out error, rom/offline/leave_one_out.hpp; −1 =
//                 none),
//                 checksum = "fnv1a64:<16 hex digits>"
//   /axes/<a>     attribute key (config key); dataset values [n_a] (units of the key); of a
//                 scattered database the range [2] = {lo, hi}
//   /samples/parameters [S, p]                        units: one per column
//   /samples/omega [S, k] rad/s          /samples/damping_ratio [S, k] 1
//   /samples/rotation_participation [S, k], /samples/centrifugal_participation [S, k]  kg^0.5*m
//   /samples/end_rotation [S, 3, k] rad/(kg^0.5*m)   /samples/end_translation [S, 3, k] kg^-0.5
//   /samples/momentum_participation [S, 3, k] kg^0.5 /samples/coriolis [S, k, k] 1
//   /samples/inertia_z [S] kg*m^2   /samples/total_mass [S] kg   /samples/centroid [S, 3] m
//   /samples/end_position [S, 3] m  /samples/reference_angle [S] rad  /samples/gravity [S, 3] m/s^2
//   /samples/alignment [S, k, k] 1  /samples/tracking, /samples/tracking_sign [S, k] int32
//   /samples/loo_frequency_error, /samples/loo_response_error [S] 1 (−1 = not estimated): relative
//                 error of ω₁ and NRMSE of the relative end angular acceleration of the sample
//                 interpolated from the grid without it
// Version history: 2 added method "affine" and /affine; 1 stored the relative error of the peak
// response as loo_response_error and the
// unscaled maxima as the estimate; version 2 (NRMSE, scaled estimate) refuses version 1 files.
//   /affine/<name> (when the root attribute affine = 1): the exact affine terms of method (c),
//                 rom/database/affine_reduced.hpp toArrays (each [rows, cols], SI); part of the checksum
//   /build        attributes only (informational, outside the checksum): timing split, ranks,
//                 smallest tracking MAC, leave-one-out maxima per method
//
// The checksum is 64-bit FNV-1a over, in this order: the format name and version, the config text,
// the method, the four integer attributes, the text "scattered" for a scattered layout (nothing
// for a grid), the affine arrays when present ("affine", then each
// array's name, shape and values), every axis (key, then its values) and every /samples
// dataset in the order above (its name, its shape, then its elements as little-endian IEEE doubles
// or int32). It detects any change of the content, on purpose or by accident, that HDF5 itself
// would not notice.
//
// Reading refuses, with IoError and one line naming the file: a missing file, a non-HDF5 file, an
// HDF5 file of another kind (no or another `format`), an unsupported format_version, a missing
// dataset or attribute (named), inconsistent sizes (named, with the expected shape) and a checksum
// mismatch ("corrupted").
#pragma once

#include <string>
#include <vector>

#include "rom/database/build_report.hpp"
#include "rom/database/rom_database.hpp"

namespace mastrom::rom {

inline constexpr const char* kDatabaseFormat = "mastrom-rom-database";
inline constexpr int kDatabaseFormatVersion = 2;

/// Write the database atomically (temporary name, renamed when complete). `report`, if given, is
/// stored under /build. Throws InputError for an inconsistent database (checked before any file is
/// created), IoError when the file cannot be written.
void writeDatabase(const std::string& path, const RomDatabase& db,
                   const BuildReport* report = nullptr);

/// Read and verify a database file (see the header for what is refused).
RomDatabase readDatabase(const std::string& path);

/// The content checksum of a database, "fnv1a64:<16 hex digits>" (what the file stores).
std::string databaseChecksum(const RomDatabase& db);

/// The database's own error estimate between samples (frequency, response NRMSE): the largest
/// leave-one-out errors over its samples, each scaled by leaveOneOutScale; −1 each when no sample
/// was estimated.
std::pair<double, double> databaseErrorEstimate(const RomDatabase& db);

}  // namespace mastrom::rom
