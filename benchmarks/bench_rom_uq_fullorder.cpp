// `mastrom uq` against the full order itself (benchmarks/README.md "Uncertainty: ROM against the
// full order"; docs/theory.md §7.6). Plain Monte Carlo with the full order: FULL samples of the
// study's inputs, each one nonlinear full-order deployment; their mean, standard deviation and
// 95 % quantile with 95 % intervals from the sample size (common/statistics/sample_statistics.hpp).
// The ROM's own study (randomised Sobol, ROM samples) must fall inside those intervals for every
// metric printed; the same FULL inputs through the ROM give the paired differences too (ROM −
// full order at each sample: the ROM's error, apart from the sampling error).
//
//   bench_rom_uq_fullorder DB CONFIG FULL ROM [--set k=v]...
//   → a table per metric, then "within: yes|no" for each of mean, std, q95.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "common/config.hpp"
#include "common/statistics/sample_statistics.hpp"
#include "modes/slepc_session.hpp"
#include "rom/database/database_io.hpp"
#include "rom/studies/uncertainty_study.hpp"
#include "rom/studies/uncertainty_tails.hpp"

int main(int argc, char** argv) {
  using namespace mastrom;
  if (argc < 5) {
    std::fprintf(stderr, "usage: bench_rom_uq_fullorder DB CONFIG FULL ROM [--set k=v]...\n");
    return 2;
  }
  std::vector<std::string> overrides;
  for (int i = 5; i + 1 < argc; i += 2) overrides.push_back(argv[i + 1]);
  // MPI and PETSc for the life of the program, as `mastrom uq` holds them: the full-order runs'
  // drive compliance and the modal solves need them.
  const modes::SlepcSession session;
  try {
    const rom::RomDatabase db = rom::readDatabase(argv[1]);
    const Config config = loadConfig(argv[2], overrides);
    const long full_samples = std::atol(argv[3]), rom_samples = std::atol(argv[4]);
    const std::vector<std::string> metrics{"peak_rel_end_angular_acceleration",
                                           "rms_rel_end_angular_acceleration", "peak_joint_force",
                                           "max_peak_von_mises"};

    // The full order's Monte Carlo sample: the inputs of a plain Monte Carlo study (the ROM's
    // values at them come along), then one full-order run per sample.
    rom::UqOptions mc;
    mc.sampling = stats::SamplingKind::MonteCarlo;
    mc.samples = full_samples;
    mc.sensitivity = false;
    mc.seed = 12345;
    const rom::UqResult paired = rom::runUncertaintyStudy(db, config, mc);
    std::vector<rom::TailCheck> runs;
    for (long row = 0; row < paired.rows; ++row)
      for (const std::string& m : metrics) {
        rom::TailCheck c;
        c.row = row;
        c.metric = m;
        runs.push_back(c);
      }
    const auto start = std::chrono::steady_clock::now();
    rom::runTailChecks(db, config, paired, runs, [](long done, long total) {
      if (done % 20 == 0 || done == total)
        std::fprintf(stderr, "full order %ld / %ld\n", done, total);
    });
    const double full_wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    // The ROM's own study: randomised Sobol points.
    rom::UqOptions sobol;
    sobol.samples = rom_samples;
    sobol.sensitivity = false;
    const rom::UqResult rom = rom::runUncertaintyStudy(db, config, sobol);

    std::printf(
        "full order: %ld Monte Carlo runs in %.1f s (%.2f s each); ROM: %ld Sobol samples "
        "in %.2f s\n",
        paired.rows, full_wall, full_wall / static_cast<double>(paired.rows), rom.rows, rom.wall_s);
    bool all_within = true;
    for (const std::string& m : metrics) {
      std::vector<double> full, diff;
      std::size_t mi = 0;
      while (mi < rom.metric_names.size() && rom.metric_names[mi] != m) ++mi;
      if (mi == rom.metric_names.size()) continue;
      for (const rom::TailCheck& c : runs) {
        if (c.metric != m) continue;
        full.push_back(c.full_value);
        diff.push_back(paired.metric(c.row, mi) - c.full_value);
      }
      const stats::SampleSummary f = stats::summarize(full, {0.95}, 0.95);
      const stats::SampleSummary r = rom.summaries[mi];
      const stats::SampleSummary d = stats::summarize(diff, {0.5}, 0.95);
      const bool mean_in = f.mean.contains(r.mean.estimate);
      const bool sd_in = f.std_dev.contains(r.std_dev.estimate);
      const bool q95_in = f.quantiles[0].contains(r.quantiles[3].estimate);
      all_within = all_within && mean_in && sd_in && q95_in;
      std::printf("%s\n", m.c_str());
      std::printf("  mean  full %.6g [%.6g, %.6g]  ROM %.6g  within: %s\n", f.mean.estimate,
                  f.mean.lower, f.mean.upper, r.mean.estimate, mean_in ? "yes" : "no");
      std::printf("  std   full %.6g [%.6g, %.6g]  ROM %.6g  within: %s\n", f.std_dev.estimate,
                  f.std_dev.lower, f.std_dev.upper, r.std_dev.estimate, sd_in ? "yes" : "no");
      std::printf("  q95   full %.6g [%.6g, %.6g]  ROM %.6g  within: %s\n", f.quantiles[0].estimate,
                  f.quantiles[0].lower, f.quantiles[0].upper, r.quantiles[3].estimate,
                  q95_in ? "yes" : "no");
      std::printf(
          "  paired ROM - full at the same inputs: mean %.3g (%.3g %% of the full mean), "
          "std %.3g\n",
          d.mean.estimate, 100.0 * d.mean.estimate / f.mean.estimate, d.std_dev.estimate);
    }
    std::printf("all within the full order's 95 %% intervals: %s\n", all_within ? "yes" : "no");
    return all_within ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_rom_uq_fullorder: %s\n", e.what());
    return 2;
  }
}
