// `mastrom compare FULL.h5 ROM.h5 [--tolerance T]`: the ROM-versus-full-order table of one case
// (rom/model/comparison.hpp definitions) from two deployment files sampled at the same instants, e.g. the
// output of `mastrom simulate` and `mastrom rom eval` with the same configuration. Exits 4 when an
// error exceeds the tolerance, so scripts and CI can gate on it.
#include <cmath>
#include <cstdio>
#include <algorithm>
#include <memory>
#include <optional>

#include "cli/cli_common.hpp"
#include "common/error.hpp"
#include "fullorder/deployment_result.hpp"
#include "fullorder/interface_stress_io.hpp"
#include "fullorder/results_io.hpp"
#include "rom/model/comparison.hpp"

namespace mastrom::cli {

void registerCompareCommand(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "compare", "Compare a ROM deployment file with a full-order one of the same case");
  auto full_path = std::make_shared<std::string>();
  auto rom_path = std::make_shared<std::string>();
  auto tolerance = std::make_shared<double>(-1.0);
  command->add_option("FULL", *full_path, "Full-order deployment file (mastrom simulate)")
      ->required();
  command->add_option("ROM", *rom_path, "ROM deployment file (mastrom rom eval)")->required();
  command->add_option("--tolerance", *tolerance,
                      "Fail (exit 4) when any relative error exceeds this, e.g. 0.03")
      ->check(numberInRange(NumberKind::kReal, 0));
  command->callback([full_path, rom_path, tolerance]() {
    using namespace fullorder;
    const DeploymentFile full = readDeploymentFile(*full_path);
    const DeploymentFile rom = readDeploymentFile(*rom_path);
    MASTROM_REQUIRE(full.source == ResultSource::FullOrder, InputError, "compare: ", *full_path,
                    " is a '", toString(full.source), "' file, expected a full-order deployment");
    MASTROM_REQUIRE(rom.source == ResultSource::Rom, InputError, "compare: ", *rom_path, " is a '",
                    toString(rom.source), "' file, expected a ROM deployment");
    // Like with like: a ROM file's /metrics hold the peaks of its continuous response
    // (rom/model/deployment_metrics.hpp); so do an adaptive full order's (its interpolant through every
    // step). An older or fixed-step full-order file has maxima over its samples, which under-read
    // fast ringing: then the ROM's metrics are taken over the same samples too.
    const bool full_continuous = full.metrics.peaks_resolved.rfind("continuous", 0) == 0;
    const DeploymentMetrics rom_metrics =
        full_continuous ? rom.metrics
                        : computeMetrics(rom.series, full.metrics.drive_end_time,
                                         full.metrics.settling_band);
    const rom::DeploymentComparison c =
        rom::compareDeployments(full.series, full.metrics, rom.series, rom_metrics);
    std::printf("ROM vs full order: %s vs %s (%zu samples)\n", rom_path->c_str(),
                full_path->c_str(), full.series.size());
    std::printf("  %-40s %12s\n", "quantity", "rel. error");
    const std::vector<std::string> names = rom::DeploymentComparison::names();
    const std::vector<double> values = c.values();
    for (std::size_t i = 0; i < names.size(); ++i)
      std::printf("  %-40s %11.3f%%\n", names[i].c_str(), 100.0 * values[i]);
    std::printf("  (NRMSE = |r_rom - r_full|_2 / |r_full|_2 of the relative end angular "
                "acceleration; metrics: |m_rom - m_full| / |m_full|; peaks: %s)\n",
                full_continuous ? "both continuous" : "both from the samples");
    // The interfaces' stresses, when both files carry them (docs/theory.md §6.5).
    double worst = c.worst();
    const std::optional<InterfaceStressSummary> full_stress = readInterfaceStressSummary(*full_path);
    const std::optional<InterfaceStressSummary> rom_stress = readInterfaceStressSummary(*rom_path);
    if (full_stress && rom_stress) {
      const rom::StressComparison sc = rom::compareInterfaceStresses(
          full_stress->max_von_mises_pa, full_stress->peak_von_mises_pa,
          rom_stress->max_von_mises_pa, rom_stress->peak_von_mises_pa);
      for (std::size_t k = 0; k < sc.peak_error.size(); ++k) {
        if (sc.histories)
          std::printf("  %-40s %11.3f%%\n",
                      ("nrmse_max_von_mises_interface_" + std::to_string(k + 1)).c_str(),
                      100.0 * sc.nrmse_max_von_mises[k]);
        std::printf("  %-40s %11.3f%%\n",
                    ("peak_von_mises_interface_" + std::to_string(k + 1)).c_str(),
                    100.0 * sc.peak_error[k]);
      }
      std::printf(
          "  (stresses: the largest von Mises of each interface over time, both on the "
          "same mesh; the ROM's by modal recovery%s)\n",
          sc.histories ? ""
                       : "; peaks only: a file without the history, e.g. rom eval "
                         "without --stress-history");
      worst = std::max(worst, sc.worst());
    } else if (full_stress || rom_stress) {
      std::printf("  stresses: only the %s file carries them; not compared\n",
                  full_stress ? "full-order" : "ROM");
    }
    if (std::isfinite(full.metrics.estimated_nrmse_rel_end_angular_acceleration)) {
      std::printf("  the full order's own estimated error: NRMSE %.3f%%, peak |rel| %.3f%% "
                  "(an error of the ROM near these is the reference's)\n",
                  100.0 * full.metrics.estimated_nrmse_rel_end_angular_acceleration,
                  100.0 * full.metrics.estimated_error_peak_rel_end_angular_acceleration);
    } else {
      std::printf("  the full order's own error: not estimated (run simulate with "
                  "--estimate-error)\n");
    }
    // The files' wall times are their whole commands' (rom eval's includes reading the database and
    // writing every output sample and the stress history): a ratio of commands, not the ROM's
    // speed-up, which rom eval's own timing line gives.
    std::printf("  whole-command wall time (reading, computing, writing its file): full order "
                "%.2f s, rom eval %.4f s, ratio %.0fx (the ROM's evaluation alone: rom eval's "
                "timing line)\n",
                full.wall_time_s, rom.wall_time_s,
                rom.wall_time_s > 0 ? full.wall_time_s / rom.wall_time_s : 0.0);
    if (*tolerance >= 0 && worst > *tolerance) {
      std::fprintf(stderr, "mastrom: error: compare: worst relative error %.3g exceeds the "
                   "tolerance %.3g\n", worst, *tolerance);
      std::fflush(stdout);
      std::exit(4);
    }
  });
}

}  // namespace mastrom::cli
