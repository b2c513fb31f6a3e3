#include "rom/studies/study_definition.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "common/error.hpp"

namespace mastrom::rom {
namespace fs = std::filesystem;
namespace {

toml::table parseFile(const std::string& path) {
  std::ifstream in(path);
  MASTROM_REQUIRE(in.good(), IoError, "study: cannot read '", path, "'");
  std::ostringstream text;
  text << in.rdbuf();
  try {
    return toml::parse(text.str(), path);
  } catch (const toml::parse_error& e) {
    const toml::source_position at = e.source().begin;
    throw InputError(detail::concat(path, ":", at.line, ":", at.column, ": ", e.description()));
  }
}

bool validCaseName(const std::string& name) {
  if (name.empty()) return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
  });
}

/// Run configuration `config_path` with `own` then `extra` overrides; errors name the case.
StudyCase resolveCase(const std::string& where, std::string name, const std::string& config_path,
                      std::vector<std::string> own, const std::vector<std::string>& extra) {
  StudyCase c;
  c.name = std::move(name);
  c.source = config_path;
  c.overrides = own;
  std::vector<std::string> all = std::move(own);
  all.insert(all.end(), extra.begin(), extra.end());
  try {
    c.config = loadConfig(config_path, all);
  } catch (const InputError& e) {
    throw InputError(detail::concat(where, ", case '", c.name, "': ", e.what()));
  } catch (const IoError& e) {
    throw IoError(detail::concat(where, ", case '", c.name, "': ", e.what()));
  }
  return c;
}

std::string relativeTo(const std::string& study_path, const std::string& file) {
  const fs::path p(file);
  return p.is_absolute() ? file
                         : (fs::path(study_path).parent_path() / p).lexically_normal().string();
}

void requireKeys(const toml::table& t, const std::set<std::string>& allowed,
                 const std::string& where) {
  for (const auto& [key, value] : t) {
    (void)value;
    const std::string k(key.str());
    if (allowed.count(k)) continue;
    std::string list;
    for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
    throw InputError(detail::concat(where, ": unknown key '", k, "' (allowed: ", list, ")"));
  }
}

}  // namespace

bool isStudyFile(const std::string& path) {
  const toml::table t = parseFile(path);
  return t.contains("study");
}

Study loadStudy(const std::string& path, const std::vector<std::string>& overrides) {
  const toml::table t = parseFile(path);
  Study s;
  s.path = path;
  s.name = fs::path(path).stem().string();
  const std::string where = "study '" + path + "'";
  requireKeys(t, {"study", "case"}, where);
  const toml::table* head = t["study"].as_table();
  MASTROM_REQUIRE(head != nullptr, InputError, where, ": no [study] table");
  requireKeys(*head, {"description", "base"}, where + " [study]");
  s.description = head->get("description") ? (*head)["description"].value_or(std::string()) : "";
  std::optional<std::string> base;
  if (head->get("base")) {
    base = (*head)["base"].value<std::string>();
    MASTROM_REQUIRE(base.has_value(), InputError, where, ": study.base must be a string (a path)");
  }
  const toml::array* cases = t["case"].as_array();
  MASTROM_REQUIRE(cases != nullptr && !cases->empty(), InputError, where,
                  ": no [[case]] (a study needs at least one case)");
  std::set<std::string> names;
  for (std::size_t i = 0; i < cases->size(); ++i) {
    const toml::table* ct = (*cases)[i].as_table();
    const std::string cwhere = detail::concat(where, ", case ", i + 1);
    MASTROM_REQUIRE(ct != nullptr, InputError, cwhere, ": must be a table ([[case]])");
    requireKeys(*ct, {"name", "config", "set"}, cwhere);
    const std::optional<std::string> name = (*ct)["name"].value<std::string>();
    MASTROM_REQUIRE(name.has_value() && validCaseName(*name), InputError, cwhere, ": name = '",
                    name.value_or(""),
                    "' must be a non-empty string of letters, "
                    "digits, '.', '_', '-'");
    MASTROM_REQUIRE(names.insert(*name).second, InputError, cwhere, ": name '", *name,
                    "' is used twice");
    std::string config = base.value_or("");
    if (ct->get("config")) {
      const std::optional<std::string> c = (*ct)["config"].value<std::string>();
      MASTROM_REQUIRE(c.has_value(), InputError, cwhere, " ('", *name,
                      "'): config must be a string (a path)");
      config = *c;
    }
    MASTROM_REQUIRE(!config.empty(), InputError, cwhere, " ('", *name,
                    "'): no configuration: give study.base or the case's config");
    std::vector<std::string> own;
    if (ct->get("set")) {
      const toml::array* list = (*ct)["set"].as_array();
      MASTROM_REQUIRE(list != nullptr, InputError, cwhere, " ('", *name,
                      "'): set must be an array of \"section.key=value\" strings");
      for (const toml::node& item : *list) {
        const std::optional<std::string> v = item.value<std::string>();
        MASTROM_REQUIRE(v.has_value(), InputError, cwhere, " ('", *name,
                        "'): set must be an array of \"section.key=value\" strings");
        own.push_back(*v);
      }
    }
    s.cases.push_back(resolveCase(where, *name, relativeTo(path, config), own, overrides));
  }
  return s;
}

Study studyFromConfigs(const std::string& name, const std::vector<std::string>& paths,
                       const std::vector<std::string>& overrides) {
  Study s;
  s.name = name;
  s.description = "run configurations given on the command line";
  std::set<std::string> names;
  for (const std::string& p : paths) {
    const std::string stem = fs::path(p).stem().string();
    MASTROM_REQUIRE(names.insert(stem).second, InputError, "study: two configurations named '",
                    stem, "' (case names are the file stems and must differ)");
    s.cases.push_back(resolveCase("study", stem, p, {}, overrides));
  }
  return s;
}

std::string resolveStudyPath(const std::string& name_or_path,
                             const std::vector<std::string>& search_dirs) {
  std::error_code ec;
  if (fs::is_regular_file(name_or_path, ec)) return name_or_path;
  for (const std::string& dir : search_dirs) {
    const fs::path candidate = fs::path(dir) / (name_or_path + ".toml");
    if (fs::is_regular_file(candidate, ec)) return candidate.string();
  }
  std::string list;
  for (const std::string& n : availableStudies(search_dirs)) list += (list.empty() ? "" : ", ") + n;
  throw InputError(detail::concat("study: '", name_or_path,
                                  "' is neither a file nor a known study (available: ",
                                  list.empty() ? "none found" : list, ")"));
}

std::vector<std::string> availableStudies(const std::vector<std::string>& search_dirs) {
  std::set<std::string> names;
  for (const std::string& dir : search_dirs) {
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
      if (it->is_regular_file(ec) && it->path().extension() == ".toml")
        names.insert(it->path().stem().string());
  }
  return {names.begin(), names.end()};
}

}  // namespace mastrom::rom
