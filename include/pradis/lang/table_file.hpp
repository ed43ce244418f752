#pragma once
/// \file
/// `FILE("table.csv")` in a $DATA value list: the numbers of a two-column table
/// file (io::parse_table_csv) as value items, with errors located in the table
/// file (file:line:column, its line and a caret) and naming the FILE call.

#include <memory>
#include <string>
#include <vector>

#include "pradis/io/table_csv.hpp"
#include "pradis/lang/ast.hpp"
#include "pradis/lang/source.hpp"

namespace pradis::lang {

/// Appends x1, y1, x2, y2, ... of the table `text` (read from `file`) to `out` as
/// number items located at `where` (the FILE call). Throws lang_error at the bad
/// cell of the table file, or at `path_loc` if the file has no data lines.
inline void table_file_items(std::string text, const std::string& file, const location& where,
                             const location& path_loc, std::vector<ast::item>& out) {
  std::vector<double> numbers;
  try {
    numbers = io::parse_table_csv(text, file);
  } catch (const io::table_csv_error& e) {
    const std::string msg = e.detail() + " (in the table file read by FILE at " + where.str() + ")";
    if (e.line() <= 0) throw lang_error(path_loc, msg);
    auto csv = std::make_shared<const source_file>(source_file{file, std::move(text)});
    throw lang_error(location{csv, e.line(), e.column()}, msg);
  }
  for (const double x : numbers) {
    ast::item v;
    v.loc = where;
    v.number = x;
    out.push_back(std::move(v));
  }
}

}  // namespace pradis::lang
