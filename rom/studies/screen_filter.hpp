// Filtering and ranking a screen's table (`mastrom screen --where … --sort-by …`, docs/user_guide.md
// §3): keep the designs whose columns satisfy every condition, then order them by one column.
// A column is a grid key or a metric (e.g. "min_margin_of_safety > 0.5",
// "peak_rel_end_angular_acceleration <= 5.2"); values are in the table's SI units. A NaN never
// satisfies a condition.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "rom/studies/screening.hpp"

namespace mastrom::rom {

struct ColumnCondition {
  enum class Op { Less, LessEqual, Greater, GreaterEqual, Equal, NotEqual };
  std::string column;
  Op op = Op::Less;
  double value = 0.0;
  std::string op_text;  ///< the operator as written ("<=", "≤", …), for messages and tables
  std::string text;     ///< as given, for messages
};

/// Parse "COLUMN OP VALUE" (OP one of < <= ≤ > >= ≥ == !=; spaces optional; "=<" and "=>"
/// refused by name). InputError naming the
/// option, the text and the expected form otherwise.
ColumnCondition parseColumnCondition(const std::string& text,
                                     const std::string& option = "--where");

struct SortOrder {
  std::string column;
  bool descending = false;
};

/// Parse "COLUMN" (ascending) or "COLUMN:desc" / "COLUMN:asc". InputError otherwise.
SortOrder parseSortOrder(const std::string& text);

/// InputError unless every condition's and the order's column is one of the table's (listing them).
void checkColumns(const ScreenTable& table, const std::vector<ColumnCondition>& conditions,
                  const std::optional<SortOrder>& order);

/// Keep the rows that satisfy every condition (in their order), then sort them stably by `order`
/// (NaN last). Returns the number of rows removed.
long filterAndSort(ScreenTable& table, const std::vector<ColumnCondition>& conditions,
                   const std::optional<SortOrder>& order);

}  // namespace mastrom::rom
