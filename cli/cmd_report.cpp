// `mastrom report FILE.h5… [--out DIR] [--screen-metric NAME]`: plots (PNG + SVG) and one
// self-contained index.html from result files (docs/report.md). The work is done by the
// Python program report/mastrom_report.py with Debian's matplotlib and h5py (a well-kept plotting
// library rather than a hand-written one); this file finds it, runs it with /usr/bin/python3 — no
// shell, posix_spawn gets the arguments as they are — and turns its outcome into mastrom's
// contract: one line `mastrom: error: report: …` and exit code 2 (bad input or file) or 1 (anything
// else).
//
// The script is $MASTROM_REPORT_SCRIPT when set, else <source tree>/report/mastrom_report.py
// (MASTROM_SOURCE_DIR, a compile definition set in cli/CMakeLists.txt).
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cli/cli_common.hpp"
#include "cli/report_command.hpp"
#include "cli/report_database.hpp"
#include "common/error.hpp"

#ifndef MASTROM_SOURCE_DIR
#error "MASTROM_SOURCE_DIR must be defined (cli/CMakeLists.txt)"
#endif

extern char** environ;

namespace mastrom::cli {
namespace {

/// Debian's interpreter: python3-h5py, python3-numpy and python3-matplotlib are visible only to it.
constexpr const char* kPython = "/usr/bin/python3";
/// The prefix of the Python program's one-line errors (report/mastrom_report.py, _fail).
constexpr const char* kScriptErrorPrefix = "mastrom report: error: ";

std::string reportScript() {
  const char* override_path = std::getenv("MASTROM_REPORT_SCRIPT");
  if (override_path != nullptr && *override_path != '\0') return override_path;
  return std::string(MASTROM_SOURCE_DIR) + "/report/mastrom_report.py";
}

/// The default of report/mastrom_report.py, computed here too so that this command can say where
/// index.html went: report/ next to the first input.
std::string defaultOutDir(const std::string& first_input) {
  const std::filesystem::path parent = std::filesystem::path(first_input).parent_path();
  return (parent / "report").string();
}

/// Outcome of one child process: exit code (or -signal) and everything it wrote to stderr.
struct ChildResult {
  int exit_code = 0;
  int signal = 0;
  std::string stderr_text;
};

/// Run argv[0] with argv (no shell), stdout inherited, stderr captured through a pipe.
ChildResult runCaptured(const std::vector<std::string>& args) {
  int fds[2];
  MASTROM_REQUIRE(::pipe(fds) == 0, Error, "report: cannot create a pipe: ", std::strerror(errno));
  // The parent's read end must not leak into the child.
  ::fcntl(fds[0], F_SETFD, FD_CLOEXEC);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, fds[1]);

  std::vector<char*> argv;
  argv.reserve(args.size() + 1);
  for (const std::string& arg : args) argv.push_back(const_cast<char*>(arg.c_str()));
  argv.push_back(nullptr);

  std::fflush(stdout);
  std::cout.flush();
  pid_t pid = 0;
  const int spawned = ::posix_spawn(&pid, args[0].c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  ::close(fds[1]);
  if (spawned != 0) {
    ::close(fds[0]);
    throw Error(detail::concat("report: cannot run ", args[0], ": ", std::strerror(spawned)));
  }

  ChildResult result;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n > 0) {
      result.stderr_text.append(buffer, static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  ::close(fds[0]);

  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    MASTROM_REQUIRE(errno == EINTR, Error, "report: waitpid failed: ", std::strerror(errno));
  }
  if (WIFSIGNALED(status)) {
    result.signal = WTERMSIG(status);
    result.exit_code = 1;
  } else {
    result.exit_code = WEXITSTATUS(status);
  }
  return result;
}

/// The last non-empty line of a text.
std::string lastLine(const std::string& text) {
  std::size_t end = text.find_last_not_of("\r\n \t");
  if (end == std::string::npos) return "";
  const std::size_t begin = text.rfind('\n', end);
  return text.substr(begin == std::string::npos ? 0 : begin + 1,
                     end + 1 - (begin == std::string::npos ? 0 : begin + 1));
}

}  // namespace

void writeReport(const ReportRequest& args) {
  MASTROM_REQUIRE(::access(kPython, X_OK) == 0, Error, "report: ", kPython,
                  " is missing: install the Debian packages python3, python3-h5py and "
                  "python3-matplotlib");
  const std::string script = reportScript();
  MASTROM_REQUIRE(::access(script.c_str(), R_OK) == 0, Error,
                  "report: cannot read the report program '", script,
                  "': set MASTROM_REPORT_SCRIPT to the path of report/mastrom_report.py");
  const std::string out_dir =
      args.out_dir.empty() ? defaultOutDir(args.files.front()) : args.out_dir;

  // --no-index-line: this command prints where index.html is itself, after checking the outcome.
  std::vector<std::string> command{kPython, script, "--out", out_dir, "--no-index-line"};
  command.push_back("--mastrom-version");
  command.push_back(std::string(kVersion));
  if (!args.screen_metric.empty()) {
    command.push_back("--screen-metric");
    command.push_back(args.screen_metric);
  }
  if (!args.study.empty()) {
    command.push_back("--study");
    command.push_back(args.study);
  }
  // A ROM database's interpolation lives in C++: evaluate it here for the Python report.
  for (std::size_t i = 0; i < args.files.size(); ++i) {
    if (!isRomDatabaseFile(args.files[i])) continue;
    std::error_code ec;
    std::filesystem::create_directories(out_dir, ec);
    MASTROM_REQUIRE(!ec, IoError, "report: cannot create the output directory '", out_dir,
                    "': ", ec.message());
    const std::string curves =
        (std::filesystem::path(out_dir) / ("rom_database_" + std::to_string(i + 1) + ".h5"))
            .string();
    writeDatabaseCurves(args.files[i], curves);
    command.push_back("--database-curves");
    command.push_back(std::to_string(i) + ":" + curves);
  }
  command.push_back("--");  // every file name stays a file name, even one starting with '-'
  command.insert(command.end(), args.files.begin(), args.files.end());

  const ChildResult result = runCaptured(command);
  if (result.exit_code == 0) {
    std::cerr << result.stderr_text;  // warnings, if any
    const std::filesystem::path index = std::filesystem::path(out_dir) / "index.html";
    MASTROM_REQUIRE(std::filesystem::is_regular_file(index), Error, "report: ", script,
                    " succeeded but wrote no ", index.string());
    std::printf("wrote %s\n", index.c_str());
    return;
  }
  // The Python program ends a handled failure with one line carrying kScriptErrorPrefix; anything
  // else (a traceback) is a bug in it, reported by its last line.
  const std::string line = lastLine(result.stderr_text);
  if (line.rfind(kScriptErrorPrefix, 0) == 0) {
    const std::string message = "report: " + line.substr(std::strlen(kScriptErrorPrefix));
    if (result.exit_code == kExitInput) throw IoError(message);
    throw Error(message);
  }
  if (result.signal != 0) {
    throw Error(
        detail::concat("report: ", kPython, " ", script, " was killed by signal ", result.signal));
  }
  throw Error(detail::concat("report: ", script, " failed (exit code ", result.exit_code,
                             "): ", line.empty() ? "no message" : line));
}

void registerReportCommand(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "report",
      "Plots (PNG + SVG) and one self-contained index.html from result files: deployment "
      "(full-order, rom), modes, screen, ROM database and study files; needs python3-h5py and "
      "python3-matplotlib");
  auto args = std::make_shared<ReportRequest>();
  command->add_option("FILE", args->files, "mastrom HDF5 result files (one or more)")
      ->required()
      ->type_name("FILE.h5");
  command
      ->add_option("--out", args->out_dir,
                   "Output directory for index.html and the figures (default: report/ next "
                   "to the first FILE)")
      ->type_name("DIR");
  command
      ->add_option("--screen-metric", args->screen_metric,
                   "For screen files: heat map of this metric only (default: every metric)")
      ->type_name("NAME");
  command
      ->add_option("--study", args->study,
                   "With a study.h5 among the files: the report of this study only (mastrom study "
                   "writes one per study itself)")
      ->type_name("NAME");
  command->footer("See docs/report.md for what every figure and table shows.");
  command->callback([args]() { writeReport(*args); });
}

}  // namespace mastrom::cli
