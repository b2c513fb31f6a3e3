// The files of `mastrom uq` (docs/user_guide.md "mastrom uq"). HDF5, every array in SI units
// (R rows = ROM evaluations, k inputs, q metrics, L limits, T tail checks, 5 quantile levels):
//   /uq/input_names [k]   /uq/inputs [R, k] (attribute units per column)
//   /uq/metric_names [q]  /uq/metrics [R, q] (units per column)
//   /uq/rom_error [R, 2] (relative error estimates: ω₁, response NRMSE upper value; −1 = none)
//   /uq/metric_error [R, q] (the absolute bound taken against the limits; 0 = none)
//   /uq/statistic_rows [S] (the rows the statistics use: A and B of Saltelli's design, or all)
//   /uq/summary/{mean,std}{,_lower,_upper} [q], /uq/summary/quantile_levels [5],
//   /uq/summary/quantiles{,_lower,_upper} [q, 5]
//   /uq/limits/text [L], probability{,_lower,_upper} [L], conservative{,_lower,_upper} [L],
//   /uq/limits/critical_row [L]
//   /uq/sobol/{first,total}{,_lower,_upper} [q, k] (NaN-free: rows of a metric without indices
//   are −1), /uq/sobol/variance [q]
//   /uq/tails/{limit,row} [T] int, label [T], rom_value, rom_error_bound, full_value,
//   full_error_estimate, full_wall_time [T] (NaN written as −1 with attribute note)
//   / attributes source = "uq", mastrom_version, config, database_checksum, sampling, seed,
//   base_samples, rows, confidence, rom_step_s, ranks, wall_time_s
// CSV summary, one estimate a line: kind,name,statistic,estimate,lower,upper with kind one of
// metric (mean, std, q01 … q99), limit (probability, conservative), sobol_first / sobol_total
// (name = METRIC:INPUT), tail (name = LIMIT:LABEL; statistic rom / full, lower/upper = value ∓ its
// error estimate).
#pragma once

#include <string>
#include <vector>

#include "rom/studies/uncertainty_study.hpp"
#include "rom/studies/uncertainty_tails.hpp"

namespace mastrom::rom {

void writeUqH5(const std::string& path, const UqResult& result,
               const std::vector<TailCheck>& tails);
std::string uqCsvSummary(const UqResult& result, const std::vector<TailCheck>& tails);
void writeUqCsv(const std::string& path, const UqResult& result,
                const std::vector<TailCheck>& tails);

}  // namespace mastrom::rom
