// `mastrom study NAME|FILE… [-o DIR] [--set k=v]… [--model both|full|rom] [--case C]… [--modes K]`:
// the paper's parameter studies (configs/studies/*.toml, format in
// rom/studies/study_definition.hpp). Every case runs with the nonlinear full order (as `mastrom simulate`)
// and with the modal ROM solved at the case's own parameters (rom/offline/direct_modal_model.hpp: no
// database, so the ROM-vs-full difference is the modal model's own error, not interpolation's).
//
// NAME is a study file's stem looked up in $MASTROM_STUDY_DIR, ./configs/studies and the source
// tree's configs/studies; FILE is a study file or a plain run configuration (all plain
// configurations given together form one study named "configs", one case per file).
//
// Outputs, each written atomically: DIR/<study>/<case>_full.h5 and DIR/<study>/<case>_rom.h5 (the
// layout of `simulate` / `rom eval`, README.md "Outputs and units"), DIR/study.csv and
// DIR/study.h5 (the comparison table, rom/studies/study_run.hpp), and (unless --no-report) the report of
// each study, DIR/<study>/report/index.html: the paper-style overlays of its cases and the
// findings it tests (report/report_study.py). Every case is loaded and validated and every output
// path checked before the first run, so a bad name, key or path fails at once.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>

#include "cli/cli_common.hpp"
#include "cli/progress.hpp"
#include "cli/report_command.hpp"
#include "common/error.hpp"
#include "common/hdf5_file.hpp"
#include "fullorder/results_io.hpp"
#include "modes/slepc_session.hpp"
#include "rom/studies/study_definition.hpp"
#include "rom/studies/study_run.hpp"

#ifndef MASTROM_SOURCE_DIR
#error "MASTROM_SOURCE_DIR must be defined (cli/CMakeLists.txt)"
#endif

namespace mastrom::cli {
namespace {

namespace fs = std::filesystem;
constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

struct StudyArguments {
  std::vector<std::string> studies;
  std::vector<std::string> overrides;
  std::string output = "results/studies";
  std::string model = "both";
  std::vector<std::string> cases;
  int modes = 0;
  bool quiet = false;
  bool list = false;
  bool no_report = false;
};

std::vector<std::string> searchDirectories() {
  std::vector<std::string> dirs;
  if (const char* env = std::getenv("MASTROM_STUDY_DIR"); env != nullptr && *env != '\0')
    dirs.emplace_back(env);
  dirs.emplace_back("configs/studies");
  dirs.emplace_back(std::string(MASTROM_SOURCE_DIR) + "/configs/studies");
  return dirs;
}

/// The studies named on the command line, cases resolved with the overrides.
std::vector<rom::Study> loadStudies(const StudyArguments& args) {
  std::vector<rom::Study> studies;
  std::vector<std::string> plain;
  std::error_code ec;
  for (const std::string& a : args.studies) {
    if (fs::is_regular_file(a, ec) && !rom::isStudyFile(a)) {
      plain.push_back(a);
      continue;
    }
    studies.push_back(
        rom::loadStudy(rom::resolveStudyPath(a, searchDirectories()), args.overrides));
  }
  if (!plain.empty()) studies.push_back(rom::studyFromConfigs("configs", plain, args.overrides));
  std::set<std::string> names;
  for (const rom::Study& s : studies)
    MASTROM_REQUIRE(names.insert(s.name).second, InputError, "study: '", s.name,
                    "' is given twice");
  return studies;
}

/// Keep only the cases --case names ("case" or "study/case"); every name must match one.
void selectCases(std::vector<rom::Study>& studies, const std::vector<std::string>& wanted) {
  if (wanted.empty()) return;
  std::set<std::string> unused(wanted.begin(), wanted.end());
  std::string available;
  for (rom::Study& s : studies) {
    std::vector<rom::StudyCase> kept;
    for (rom::StudyCase& c : s.cases) {
      available += (available.empty() ? "" : ", ") + s.name + "/" + c.name;
      const std::string full_name = s.name + "/" + c.name;
      const bool hit = std::count(wanted.begin(), wanted.end(), c.name) > 0 ||
                       std::count(wanted.begin(), wanted.end(), full_name) > 0;
      unused.erase(c.name);
      unused.erase(full_name);
      if (hit) kept.push_back(std::move(c));
    }
    s.cases = std::move(kept);
  }
  MASTROM_REQUIRE(unused.empty(), InputError, "--case = '", *unused.begin(),
                  "' is not a case of the studies given (available: ", available, ")");
}

std::string caseFile(const std::string& dir, const rom::Study& s, const rom::StudyCase& c,
                     const char* model) {
  return (fs::path(dir) / s.name / (c.name + "_" + model + ".h5")).string();
}

void printTable(const std::vector<rom::StudyRow>& rows) {
  std::printf("\n%-32s %-6s %11s %11s %11s %11s %9s %10s %10s %8s %8s\n", "study/case", "model",
              "peak|abs|", "peak|rel|", "rms rel", "residual", "settle", "F_joint", "tau_drive",
              "f1", "NRMSE");
  std::printf("%-32s %-6s %11s %11s %11s %11s %9s %10s %10s %8s %8s\n", "", "", "deg/s^2",
              "deg/s^2", "deg/s^2", "deg/s^2", "s", "N", "N*m", "Hz", "");
  for (const rom::StudyRow& r : rows) {
    const std::string id = r.study + "/" + r.name;
    auto line = [&id](const char* model, const std::vector<double>& v, const std::string& tail) {
      std::printf("%-32s %-6s %11.4g %11.4g %11.4g %11.4g %9.4g %10.4g %10.4g%s\n", id.c_str(),
                  model, v[0] * kRadToDeg, v[1] * kRadToDeg, v[2] * kRadToDeg, v[3] * kRadToDeg,
                  v[4], v[5], v[6], tail.c_str());
    };
    std::vector<double> full, rom;
    if (r.full) line("full", full = rom::studyMetricValues(r.full->metrics), "");
    if (r.rom) {
      char tail[48];
      std::snprintf(tail, sizeof tail, " %8.2f", r.rom->first_bending_hz);
      line("rom", rom = rom::studyMetricValues(r.rom->metrics), tail);
    }
    if (r.full && r.rom) {
      std::printf("%-32s %-6s", id.c_str(), "diff");
      const int widths[] = {11, 11, 11, 11, 9, 10, 10};
      for (std::size_t j = 0; j < full.size(); ++j) {
        if (full[j] != 0.0)
          std::printf(" %*.2f%%", widths[j] - 1, 100.0 * (rom[j] - full[j]) / std::abs(full[j]));
        else
          std::printf(" %*s", widths[j], "-");
      }
      std::printf(" %8s %7.2f%%\n", "", 100.0 * r.comparison->nrmse_relative_acceleration);
    }
  }
  std::printf(
      "(diff = (rom - full)/|full|; NRMSE of the relative end angular acceleration, "
      "RMS-normalised; f1 = first drive-excited (in-plane bending) mode of the ROM)\n");
}

void runStudy(const StudyArguments& args) {
  if (args.list) {
    for (const std::string& n : rom::availableStudies(searchDirectories()))
      std::printf("%s\n", n.c_str());
    return;
  }
  MASTROM_REQUIRE(!args.studies.empty(), InputError,
                  "study: no study given (a NAME, a study file or run configurations; "
                  "'mastrom study --list' lists the names)");
  MASTROM_REQUIRE(args.model == "both" || args.model == "full" || args.model == "rom", InputError,
                  "--model = '", args.model, "' is not a model (allowed: both, full, rom)");
  MASTROM_REQUIRE(args.modes >= 0, InputError, "--modes = ", args.modes,
                  " is out of range (>= 1, or 0 for modes.count of the configuration)");
  const bool run_full = args.model != "rom", run_rom = args.model != "full";

  std::vector<rom::Study> studies = loadStudies(args);
  selectCases(studies, args.cases);
  std::size_t total = 0;
  for (const rom::Study& s : studies) total += s.cases.size();

  // Every output path is checked before the first run (minutes of work).
  std::error_code ec;
  for (const rom::Study& s : studies) {
    fs::create_directories(fs::path(args.output) / s.name, ec);
    MASTROM_REQUIRE(!ec, IoError, "-o: cannot create directory '",
                    (fs::path(args.output) / s.name).string(), "': ", ec.message());
    for (const rom::StudyCase& c : s.cases) {
      if (run_full) h5::checkWritable(caseFile(args.output, s, c, "full"));
      if (run_rom) h5::checkWritable(caseFile(args.output, s, c, "rom"));
    }
  }
  const std::string csv = (fs::path(args.output) / "study.csv").string();
  const std::string table = (fs::path(args.output) / "study.h5").string();
  h5::checkWritable(csv);
  h5::checkWritable(table);

  std::optional<modes::SlepcSession> session;
  if (run_rom) session.emplace();  // PETSc/SLEPc for the modal solves (any backend works under it)

  std::printf("mastrom study: %zu case%s, model%s %s, output %s\n", total, total == 1 ? "" : "s",
              args.model == "both" ? "s" : "",
              args.model == "both" ? "full + rom" : args.model.c_str(), args.output.c_str());
  for (const rom::Study& s : studies)
    std::printf("  %s: %s (%zu case%s)\n", s.name.c_str(), s.description.c_str(), s.cases.size(),
                s.cases.size() == 1 ? "" : "s");
  std::fflush(stdout);

  std::vector<rom::StudyRow> rows;
  std::size_t done = 0;
  for (const rom::Study& s : studies) {
    for (const rom::StudyCase& c : s.cases) {
      ++done;
      rom::StudyRow row;
      row.study = s.name;
      row.name = c.name;
      row.config = c.config;
      const std::string id = s.name + "/" + c.name;
      if (!args.quiet) std::fprintf(stderr, "study: case %zu / %zu: %s\n", done, total, id.c_str());
      const std::string config_toml = toToml(c.config);
      if (run_full) {
        ProgressReporter reporter("study " + id + " full order", 2.0, !args.quiet);
        row.full = rom::runFullOrderCase(c.config, [&reporter](double t, double end, double it) {
          char detail[96];
          std::snprintf(detail, sizeof detail, "t = %.4f / %.4f s, %.2f Newton it/step", t, end,
                        it);
          reporter.update(t, end, detail);
        });
        fullorder::writeDeploymentFile(caseFile(args.output, s, c, "full"), row.full->series,
                                       row.full->metrics, config_toml, row.full->wall_s,
                                       fullorder::ResultSource::FullOrder);
      }
      if (run_rom) {
        row.rom = rom::runRomCase(c.config, args.modes);
        fullorder::writeDeploymentFile(caseFile(args.output, s, c, "rom"), row.rom->series,
                                       row.rom->metrics, config_toml, row.rom->wall_s,
                                       fullorder::ResultSource::Rom);
      }
      rom::compareRow(row);
      if (!args.quiet) {
        std::fprintf(stderr, "study: case %zu / %zu: %s done (", done, total, id.c_str());
        if (row.full) std::fprintf(stderr, "full order %.2f s", row.full->wall_s);
        if (row.rom)
          std::fprintf(stderr, "%sROM %.3f s, %d modes", row.full ? ", " : "", row.rom->wall_s,
                       row.rom->modes);
        std::fprintf(stderr, ")\n");
      }
      rows.push_back(std::move(row));
    }
  }

  printTable(rows);
  rom::writeStudyCsv(csv, rows);
  rom::writeStudyH5(table, rows);
  std::printf("wrote %s, %s and %zu deployment file%s under %s/\n", csv.c_str(), table.c_str(),
              total * (run_full + run_rom), total * (run_full + run_rom) == 1 ? "" : "s",
              args.output.c_str());
  std::fflush(stdout);
  if (args.no_report) return;
  // The paper-style page of each study: the overlays of its cases and the findings it tests.
  for (const rom::Study& s : studies) {
    ReportRequest request;
    request.files.push_back(table);
    for (const rom::StudyCase& c : s.cases) {
      if (run_full) request.files.push_back(caseFile(args.output, s, c, "full"));
      if (run_rom) request.files.push_back(caseFile(args.output, s, c, "rom"));
    }
    request.out_dir = (fs::path(args.output) / s.name / "report").string();
    request.study = s.name;
    try {
      writeReport(request);
    } catch (const Error& e) {
      throw Error(detail::concat("the study's results are written (", csv, ", ", table,
                                 "); its report is not: ", e.what()));
    }
  }
}

}  // namespace

void registerStudyCommand(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "study",
      "Run a parameter study (paper 3.1-3.3) with the full order and the ROM, and "
      "tabulate both");
  auto args = std::make_shared<StudyArguments>();
  command
      ->add_option("STUDY", args->studies,
                   "Study name (e.g. shell_thickness; see --list), study file, or run "
                   "configuration files (together one study, one case per file)")
      ->type_name("NAME|FILE");
  command
      ->add_option("--set", args->overrides,
                   "Override one key in every case, after the case's own settings, e.g. --set "
                   "simulation.end_time=1 (repeatable)")
      ->type_name("SECTION.KEY=VALUE")
      ->allow_extra_args(false);
  command
      ->add_option("-o,--output", args->output,
                   "Output directory (created): <study>/<case>_{full,rom}.h5, study.csv, "
                   "study.h5 (default results/studies)")
      ->type_name("DIR");
  command->add_option("--model", args->model, "Which models to run: both (default), full or rom")
      ->type_name("NAME");
  command
      ->add_option("--case", args->cases,
                   "Run only this case, CASE or STUDY/CASE (repeatable; default: every case)")
      ->type_name("CASE")
      ->allow_extra_args(false);
  command->add_option("--modes", args->modes, "ROM modes per case (default: [modes] count)")
      ->check(numberInRange(NumberKind::kWhole, 1));
  command->add_flag("-q,--quiet", args->quiet, "No progress lines on stderr");
  command->add_flag("--list", args->list, "List the study names found and exit");
  command->add_flag("--no-report", args->no_report,
                    "Do not write <study>/report/index.html (figures and findings; needs "
                    "python3-matplotlib and python3-h5py)");
  command->footer(
      "Studies are looked up in $MASTROM_STUDY_DIR, ./configs/studies and the source tree's "
      "configs/studies. Shorten runs for a try-out with e.g. --set drive.duration=0.5 --set "
      "simulation.end_time=1.");
  command->callback([args]() { runStudy(*args); });
}

}  // namespace mastrom::cli
