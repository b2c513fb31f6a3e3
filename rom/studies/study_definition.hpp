// A study (the paper's §3 parameter studies, docs/theory.md §1): one named set of cases, each a
// complete run configuration. A study file is TOML:
//
//     [study]
//     description = "Paper §3.2: Scheme 3, shell thickness 0.5 / 1.0 / 1.5 mm"   # optional
//     base = "../scheme3.toml"        # run configuration, relative to the study file
//
//     [[case]]
//     name = "h0.5mm"                 # letters, digits, '.', '_', '-'; unique in the study
//     config = "../scheme1.toml"      # optional: replaces base for this case
//     set = ["interface.thickness=0.0005"]   # optional: --set-style overrides, in order
//
// The study's name is the file's stem (configs/studies/shell_thickness.toml → "shell_thickness").
// A case's configuration = its config (or base) file, then its `set` list, then the command line's
// --set overrides (so `--set simulation.end_time=1` shortens every case); every case is loaded and
// validated when the study is loaded, so a bad key fails before any run. Plain run configurations
// can be studied too: studyFromConfigs makes one case per file.
#pragma once

#include <string>
#include <vector>

#include "common/config.hpp"

namespace mastrom::rom {

struct StudyCase {
  std::string name;
  std::string source;                  ///< the run configuration file it came from
  std::vector<std::string> overrides;  ///< the case's own `set` list (without the command line's)
  Config config;                       ///< resolved and validated
};

struct Study {
  std::string name;
  std::string description;
  std::string path;  ///< the study file ("" for studyFromConfigs)
  std::vector<StudyCase> cases;
};

/// True when the TOML file at `path` has a [study] table. IoError when it cannot be read,
/// InputError on a TOML syntax error.
bool isStudyFile(const std::string& path);

/// Load a study file and resolve every case with `overrides` applied last. IoError when a file
/// cannot be read; InputError naming the study file and the case for an unknown key, a missing or
/// duplicate name, a bad override or a configuration out of range.
Study loadStudy(const std::string& path, const std::vector<std::string>& overrides);

/// A study named `name` with one case per run configuration file, named after the file's stem.
Study studyFromConfigs(const std::string& name, const std::vector<std::string>& paths,
                       const std::vector<std::string>& overrides);

/// The study file for NAME|PATH: an existing file is taken as it is; otherwise `<dir>/NAME.toml`
/// in the first directory of `search_dirs` that has it. InputError listing the studies found in
/// the search directories when there is none.
std::string resolveStudyPath(const std::string& name_or_path,
                             const std::vector<std::string>& search_dirs);

/// Names (file stems) of the study files in the search directories, sorted, without repeats.
std::vector<std::string> availableStudies(const std::vector<std::string>& search_dirs);

}  // namespace mastrom::rom
