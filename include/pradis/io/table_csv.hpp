#pragma once
/// \file
/// Reading a two-column table (x, y per line) from a CSV file, for tabular laws
/// such as TSPRING: read_table_csv(path) returns the flat list x1, y1, x2, y2, ...
///
/// Format: one point per line; the two cells are separated by a comma (blanks
/// around it are ignored) or, on a line without a comma, by blanks or tabs;
/// `#` starts a comment to the end of the line; blank lines are skipped; the
/// first non-blank line may be a header whose cells are all non-numeric
/// (`d, F`). Lines end with LF, CR LF or CR. Numbers are decimal or scientific
/// (`1.5`, `-2e-3`, `+4`) and must be finite.

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "pradis/core/error.hpp"

namespace pradis::io {

/// A table file that cannot be read or parsed: pradis::error with code io_error
/// whose what() and message() start with `file:line:column: `; line() and
/// column() (1-based, 0 when the file could not be opened) and detail() (the
/// message without the location) let a caller re-locate it.
class table_csv_error : public error {
 public:
  /// The error at `file`:`line`:`column` (0, 0: the file could not be opened) with the message `detail`.
  table_csv_error(const std::string& file, int line, int column, const std::string& detail)
      : error(error_code::io_error, locate(file, line, column) + detail),
        file_(file),
        line_(line),
        column_(column),
        detail_(detail) {}
  /// The file name as given.
  const std::string& file() const noexcept { return file_; }
  /// Line (1-based; 0 if the file could not be read).
  int line() const noexcept { return line_; }
  /// Column (1-based byte column; 0 if the file could not be read).
  int column() const noexcept { return column_; }
  /// The message without `file:line:column: `.
  const std::string& detail() const noexcept { return detail_; }

 private:
  static std::string locate(const std::string& f, int l, int c) {
    return l > 0 ? f + ":" + std::to_string(l) + ":" + std::to_string(c) + ": " : f + ": ";
  }
  std::string file_;
  int line_ = 0, column_ = 0;
  std::string detail_;
};

namespace detail {
inline bool csv_blank(char c) { return c == ' ' || c == '\t'; }
/// A cell as a finite double (the whole cell), or nothing.
inline std::optional<double> csv_number(std::string_view s) {
  if (!s.empty() && s[0] == '+') s.remove_prefix(1);
  if (s.empty() || s[0] == '+') return std::nullopt;
  double x = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), x, std::chars_format::general);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(x)) return std::nullopt;
  return x;
}
/// A cell's text for a message: at most 40 bytes, control bytes as '?'.
inline std::string csv_show(std::string_view s) {
  std::string o;
  for (char c : s.substr(0, 40)) o += (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) ? '?' : c;
  if (s.size() > 40) o += "...";
  return o;
}
}  // namespace detail

/// Parses table text (the contents of a CSV file; `name` is used in messages).
/// Returns x1, y1, x2, y2, ... in file order (at least one point). Throws
/// table_csv_error for a line without exactly two cells, an empty or non-numeric
/// cell, a non-finite number, or a file without data lines. It does not check
/// that x increases: the element that uses the table does (code 100).
inline std::vector<double> parse_table_csv(std::string_view text, const std::string& name) {
  std::vector<double> out;
  bool seen_content = false;
  int line_no = 0;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    ++line_no;
    std::size_t end = text.find_first_of("\r\n", pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = text.substr(pos, end - pos);
    const std::size_t next = end >= text.size() ? text.size() + 1
                             : (text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n') ? end + 2
                                                                                                       : end + 1;
    pos = next;
    // Cells: [begin, end) byte ranges within the line, comment removed.
    std::string_view body = line.substr(0, std::min(line.find('#'), line.size()));
    struct cell {
      std::size_t at;
      std::string_view text;
    };
    std::vector<cell> cells;
    const bool comma = body.find(',') != std::string_view::npos;
    std::size_t i = 0;
    if (comma) {
      for (;;) {
        const std::size_t stop = std::min(body.find(',', i), body.size());
        std::size_t a = i, b = stop;
        while (a < b && detail::csv_blank(body[a])) ++a;
        while (b > a && detail::csv_blank(body[b - 1])) --b;
        cells.push_back({a, body.substr(a, b - a)});
        if (stop >= body.size()) break;
        i = stop + 1;
      }
    } else {
      while (i < body.size()) {
        while (i < body.size() && detail::csv_blank(body[i])) ++i;
        if (i >= body.size()) break;
        const std::size_t a = i;
        while (i < body.size() && !detail::csv_blank(body[i])) ++i;
        cells.push_back({a, body.substr(a, i - a)});
      }
    }
    if (cells.empty()) continue;  // blank or comment line
    const auto col = [](std::size_t at) { return static_cast<int>(at) + 1; };
    const bool all_text = [&] {
      for (const cell& c : cells)
        if (c.text.empty() || detail::csv_number(c.text)) return false;
      return true;
    }();
    const bool header = all_text && !seen_content;
    seen_content = true;
    if (cells.size() != 2)
      throw table_csv_error(name, line_no, col(cells.size() > 2 ? cells[2].at : body.size()),
                            "expected 2 columns (x, y), found " + std::to_string(cells.size()) + " in '" +
                                detail::csv_show(line) + "'");
    if (header) continue;
    for (const cell& c : cells) {
      if (c.text.empty()) throw table_csv_error(name, line_no, col(c.at), "empty cell in '" + detail::csv_show(line) + "'");
      const auto x = detail::csv_number(c.text);
      if (!x)
        throw table_csv_error(name, line_no, col(c.at),
                              "'" + detail::csv_show(c.text) + "' is not a finite number" +
                                  (all_text ? " (only the first line may be a header)" : ""));
      out.push_back(*x);
    }
  }
  if (out.empty()) throw table_csv_error(name, 0, 0, "the table file has no data lines");
  return out;
}

/// Reads a two-column table from the CSV file `path` (format above). Throws
/// table_csv_error (code io_error) if the file cannot be read, with the
/// system's reason, or if its contents are not a table.
inline std::vector<double> read_table_csv(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw table_csv_error(path, 0, 0, "cannot read the table file: it is a directory");
  errno = 0;
  std::ifstream f(path, std::ios::binary);
  if (!f) {
    const int e = errno;
    throw table_csv_error(path, 0, 0, std::string("cannot read the table file") + (e ? ": " + std::string(std::strerror(e)) : ""));
  }
  std::ostringstream os;
  os << f.rdbuf();
  if (f.bad()) throw table_csv_error(path, 0, 0, "cannot read the table file");
  return parse_table_csv(os.str(), path);
}

}  // namespace pradis::io
