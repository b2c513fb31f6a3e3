// The up-front estimates of the commands other than `simulate` (whose estimate,
// fullorder/run_footprint.hpp, also serves the full-order runs of `validate`): what each holds in
// memory and writes, counted from the configuration, the grid or the database file before any
// work; common/resource_budget.hpp checks them against the machine and words the refusal.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "common/config.hpp"
#include "common/resource_budget.hpp"

namespace mastrom::cli {

/// `modes`: the locked mast's model and factorisation (sparse backends) or its dense matrices
/// (dense backend: about 2.5 n × n matrices of doubles at the peak, n the DOFs), and the shapes
/// written (modes.count × DOFs doubles, twice: HDF5 and the XDMF's data).
ResourceEstimate modesEstimate(const Config& config);

/// `rom build`: one sample's modal solve at a time per rank, and the database: per sample and
/// mode the per-mode quantities and the stress modes (a row per recovery point and station).
ResourceEstimate romBuildEstimate(const Config& config, double samples, int modes,
                                  const std::vector<ResourceDriver>& grid);

/// `rom eval`: the database read into memory and the metrics' pass over one deployment of
/// `eval_config`, stepped at `metrics_step_s` (its drive samples and, with stresses, the states
/// the stress peaks' refinement keeps); the output series and stress histories are streamed into
/// the file, one block in memory.
ResourceEstimate romEvalEstimate(const Config& eval_config, double metrics_step_s,
                                 double database_bytes, bool stresses);

/// `screen`: the database and the table of `designs` rows × `columns` numbers.
ResourceEstimate screenEstimate(double designs, double columns, double database_bytes,
                                const std::vector<ResourceDriver>& grid);

/// `validate`: the database, and one full-order run of `eval_config` at a time with its series in
/// memory (compared with the ROM's).
ResourceEstimate validateEstimate(const Config& eval_config, int points, double database_bytes);

/// The --allow-large flag, the same on every command.
void addAllowLargeFlag(CLI::App& command, bool& allow_large);

/// Check `estimate` against this machine (memory, and the free space where `output_path` goes;
/// "" for none) and print the "large run" line first when there is one; InputError (one line)
/// when it does not fit and allow_large is false.
void requireResources(const ResourceEstimate& estimate, const std::string& output_path,
                      bool allow_large);

/// Size of a file [bytes], 0 when it cannot be read (the reader then says why).
double fileBytes(const std::string& path);

}  // namespace mastrom::cli
