// Screen table conditions and order (see screen_filter.hpp).
#include "rom/studies/screen_filter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>

#include "common/error.hpp"

namespace mastrom::rom {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

/// Column c of row r (grid keys first, then metrics), or −1 when unknown.
int columnIndex(const ScreenTable& t, const std::string& name) {
  for (std::size_t a = 0; a < t.axes.size(); ++a)
    if (t.axes[a].key == name) return static_cast<int>(a);
  for (std::size_t m = 0; m < t.metric_names.size(); ++m)
    if (t.metric_names[m] == name) return static_cast<int>(t.axes.size() + m);
  return -1;
}

double cell(const ScreenTable& t, long row, int column) {
  const std::size_t p = t.axes.size(), q = t.metric_names.size();
  const auto c = static_cast<std::size_t>(column), r = static_cast<std::size_t>(row);
  return c < p ? t.parameters[r * p + c] : t.metrics[r * q + (c - p)];
}

bool holds(const ColumnCondition& c, double x) {
  if (std::isnan(x)) return false;
  switch (c.op) {
    case ColumnCondition::Op::Less: return x < c.value;
    case ColumnCondition::Op::LessEqual: return x <= c.value;
    case ColumnCondition::Op::Greater: return x > c.value;
    case ColumnCondition::Op::GreaterEqual: return x >= c.value;
    case ColumnCondition::Op::Equal: return x == c.value;
    case ColumnCondition::Op::NotEqual: return x != c.value;
  }
  return false;
}

std::string columnList(const ScreenTable& t) {
  std::string s;
  for (const ScreenAxis& a : t.axes) s += (s.empty() ? "" : ", ") + a.key;
  for (const std::string& m : t.metric_names) s += (s.empty() ? "" : ", ") + m;
  return s;
}

}  // namespace

ColumnCondition parseColumnCondition(const std::string& text, const std::string& option) {
  // ≤ and ≥ (UTF-8) as the mathematics writes them, beside the ASCII spellings.
  static const struct {
    const char* symbol;
    ColumnCondition::Op op;
  } kOps[] = {{"<=", ColumnCondition::Op::LessEqual}, {">=", ColumnCondition::Op::GreaterEqual},
              {"≤", ColumnCondition::Op::LessEqual},  {"≥", ColumnCondition::Op::GreaterEqual},
              {"==", ColumnCondition::Op::Equal},     {"!=", ColumnCondition::Op::NotEqual},
              {"<", ColumnCondition::Op::Less},       {">", ColumnCondition::Op::Greater}};
  // "=<" and "=>" would read as a column ending in '=' compared with < or >: say what was meant.
  for (const char* reversed : {"=<", "=>"}) {
    MASTROM_REQUIRE(text.find(reversed) == std::string::npos, InputError, option, " '", text,
                    "': '", reversed, "' is no operator; write ", reversed[1], "= (or ",
                    reversed[1] == '<' ? "≤" : "≥", "): OP one of < <= ≤ > >= ≥ == !=");
  }
  for (const auto& o : kOps) {
    const std::size_t at = text.find(o.symbol);
    if (at == std::string::npos) continue;
    ColumnCondition c;
    c.column = trim(text.substr(0, at));
    c.op = o.op;
    c.op_text = o.symbol;
    c.text = text;
    const std::string v = trim(text.substr(at + std::string(o.symbol).size()));
    char* end = nullptr;
    c.value = std::strtod(v.c_str(), &end);
    MASTROM_REQUIRE(
        !c.column.empty() && !v.empty() && end && *end == '\0' && std::isfinite(c.value),
        InputError, option, " '", text,
        "': expected COLUMN OP NUMBER with OP one of < <= ≤ > >= ≥ == != (e.g. "
        "\"min_margin_of_safety > 0.5\")");
    return c;
  }
  throw InputError(option + " '" + text +
                   "': no comparison; expected COLUMN OP NUMBER with OP one of < <= ≤ > >= "
                   "≥ == !=");
}

SortOrder parseSortOrder(const std::string& text) {
  SortOrder o;
  const std::size_t colon = text.rfind(':');
  o.column = trim(colon == std::string::npos ? text : text.substr(0, colon));
  const std::string dir = colon == std::string::npos ? "asc" : trim(text.substr(colon + 1));
  MASTROM_REQUIRE(!o.column.empty() && (dir == "asc" || dir == "desc"), InputError, "--sort-by '",
                  text, "': expected COLUMN, COLUMN:asc or COLUMN:desc");
  o.descending = dir == "desc";
  return o;
}

void checkColumns(const ScreenTable& table, const std::vector<ColumnCondition>& conditions,
                  const std::optional<SortOrder>& order) {
  for (const ColumnCondition& c : conditions)
    MASTROM_REQUIRE(columnIndex(table, c.column) >= 0, InputError, "--where '", c.text, "': ",
                    c.column, " is not a column of this screen (columns: ", columnList(table), ")");
  if (order)
    MASTROM_REQUIRE(columnIndex(table, order->column) >= 0, InputError, "--sort-by ",
                    order->column, " is not a column of this screen (columns: ", columnList(table),
                    ")");
}

long filterAndSort(ScreenTable& table, const std::vector<ColumnCondition>& conditions,
                   const std::optional<SortOrder>& order) {
  checkColumns(table, conditions, order);
  std::vector<long> rows;
  for (long r = 0; r < table.designs; ++r) {
    bool keep = true;
    for (const ColumnCondition& c : conditions)
      keep = keep && holds(c, cell(table, r, columnIndex(table, c.column)));
    if (keep) rows.push_back(r);
  }
  if (order) {
    const int col = columnIndex(table, order->column);
    std::stable_sort(rows.begin(), rows.end(), [&](long a, long b) {
      const double x = cell(table, a, col), y = cell(table, b, col);
      if (std::isnan(x) || std::isnan(y)) return !std::isnan(x) && std::isnan(y);
      return order->descending ? x > y : x < y;
    });
  }
  const std::size_t p = table.axes.size(), q = table.metric_names.size();
  std::vector<double> parameters, metrics;
  parameters.reserve(rows.size() * p);
  metrics.reserve(rows.size() * q);
  for (const long r : rows) {
    const auto ru = static_cast<std::size_t>(r);
    parameters.insert(parameters.end(), table.parameters.begin() + static_cast<long>(ru * p),
                      table.parameters.begin() + static_cast<long>((ru + 1) * p));
    metrics.insert(metrics.end(), table.metrics.begin() + static_cast<long>(ru * q),
                   table.metrics.begin() + static_cast<long>((ru + 1) * q));
  }
  const long removed = table.designs - static_cast<long>(rows.size());
  table.parameters = std::move(parameters);
  table.metrics = std::move(metrics);
  table.designs = static_cast<long>(rows.size());
  return removed;
}

}  // namespace mastrom::rom
