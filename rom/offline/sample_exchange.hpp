// One solved database sample as a flat run of doubles, for the MPI gather of a build
// (rom/offline/database_build.hpp): the rank that solved a sample packs it, every rank unpacks all of
// them. The layout is [index, k, k_t, the modal model's fields in forEachModalField order
// (row-major), alignment (k × k_t, row-major), tracking, signs, the two smallest MACs and their modes, the three
// timings]; packSample and unpackSamples are its only writer and reader.
#pragma once

#include <vector>

#include "rom/database/rom_database.hpp"

namespace mastrom::rom {

/// A sample as the rank that solved it reports it.
struct ExchangedSample {
  int index = 0;  ///< grid index
  RomSample sample;
  double mac_min[2] = {1.0, 1.0};  ///< smallest MAC: all tracked pairs, drive-excited modes
  int mac_min_mode[2] = {-1, -1};  ///< the reference mode of each (−1: none)
  double times[3] = {0, 0, 0};     ///< assembly, eigensolve, extraction + tracking [s]
};

/// Append `s` to `buffer`.
void packSample(std::vector<double>& buffer, const ExchangedSample& s);

/// Every sample in `buffer`, in order. Throws NumericalError when the buffer is truncated.
std::vector<ExchangedSample> unpackSamples(const std::vector<double>& buffer);

}  // namespace mastrom::rom
