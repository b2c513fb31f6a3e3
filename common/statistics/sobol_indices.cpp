#include "common/statistics/sobol_indices.hpp"

#include <gsl/gsl_rng.h>
#include <gsl/gsl_sort.h>
#include <gsl/gsl_statistics_double.h>

#include <algorithm>
#include <memory>

#include "common/error.hpp"

namespace mastrom::stats {
namespace {

/// Point estimates of every index from the base samples listed in `rows` (repeats allowed).
void estimate(const std::vector<double>& f, int k, const std::vector<std::size_t>& rows,
              std::vector<double>& first, std::vector<double>& total, double& variance) {
  const std::size_t stride = static_cast<std::size_t>(k) + 2;
  std::vector<double> ab;
  ab.reserve(2 * rows.size());
  for (const std::size_t j : rows) {
    ab.push_back(f[stride * j]);
    ab.push_back(f[stride * j + 1]);
  }
  variance = gsl_stats_variance(ab.data(), 1, ab.size());
  first.assign(static_cast<std::size_t>(k), 0.0);
  total.assign(static_cast<std::size_t>(k), 0.0);
  if (!(variance > 0.0)) return;
  const double scale = 1.0 / (2.0 * static_cast<double>(rows.size()) * variance);
  for (int i = 0; i < k; ++i) {
    double d_first = 0.0, d_total = 0.0;
    for (const std::size_t j : rows) {
      const double* v = &f[stride * j];
      const double fab = v[2 + i];
      d_first += (v[1] - fab) * (v[1] - fab);
      d_total += (v[0] - fab) * (v[0] - fab);
    }
    first[static_cast<std::size_t>(i)] = 1.0 - scale * d_first;
    total[static_cast<std::size_t>(i)] = scale * d_total;
  }
}

}  // namespace

void saltelliRows(const double* u, int k, double* rows) {
  const std::size_t n = static_cast<std::size_t>(k);
  std::copy(u, u + n, rows);              // A
  std::copy(u + n, u + 2 * n, rows + n);  // B
  for (std::size_t i = 0; i < n; ++i) {   // AB_i
    double* row = rows + (2 + i) * n;
    std::copy(u, u + n, row);
    row[i] = u[n + i];
  }
}

double SobolIndices::widestInterval() const {
  double w = 0.0;
  for (const Interval& s : first) w = std::max(w, s.width());
  for (const Interval& s : total) w = std::max(w, s.width());
  return w;
}

SobolIndices jansenIndices(const std::vector<double>& f, int k, const BootstrapOptions& options) {
  const std::size_t stride = static_cast<std::size_t>(k) + 2;
  MASTROM_REQUIRE(k >= 1 && f.size() % stride == 0 && f.size() / stride >= 2, UsageError,
                  "jansenIndices: ", f.size(), " values for ", k, " inputs");
  MASTROM_REQUIRE(options.resamples >= 2, UsageError, "jansenIndices: ", options.resamples,
                  " bootstrap resamples");
  const std::size_t n = f.size() / stride;
  std::vector<std::size_t> rows(n);
  for (std::size_t j = 0; j < n; ++j) rows[j] = j;
  SobolIndices out;
  std::vector<double> first, total;
  estimate(f, k, rows, first, total, out.variance);

  // Bootstrap: the same redrawn base samples for every index (their intervals are joint draws).
  const std::size_t ki = static_cast<std::size_t>(k);
  const std::size_t r_count = static_cast<std::size_t>(options.resamples);
  std::vector<double> first_draws(ki * r_count), total_draws(ki * r_count);
  std::unique_ptr<gsl_rng, void (*)(gsl_rng*)> rng(gsl_rng_alloc(gsl_rng_mt19937), gsl_rng_free);
  gsl_rng_set(rng.get(), options.seed);
  std::vector<double> bf, bt;
  double bv = 0.0;
  for (std::size_t r = 0; r < r_count; ++r) {
    for (std::size_t& j : rows) j = gsl_rng_uniform_int(rng.get(), n);
    estimate(f, k, rows, bf, bt, bv);
    for (std::size_t i = 0; i < ki; ++i) {
      first_draws[i * r_count + r] = bf[i];
      total_draws[i * r_count + r] = bt[i];
    }
  }
  const double tail = 0.5 * (1.0 - options.confidence);
  const auto interval = [&](double estimate_value, double* draws) {
    gsl_sort(draws, 1, r_count);
    return Interval{estimate_value, gsl_stats_quantile_from_sorted_data(draws, 1, r_count, tail),
                    gsl_stats_quantile_from_sorted_data(draws, 1, r_count, 1.0 - tail)};
  };
  for (std::size_t i = 0; i < ki; ++i) {
    out.first.push_back(interval(first[i], &first_draws[i * r_count]));
    out.total.push_back(interval(total[i], &total_draws[i * r_count]));
  }
  return out;
}

}  // namespace mastrom::stats
