#pragma once
/// \file
/// Matrices in the Matrix Market exchange format (the text format that finite
/// element programs export stiffness and mass matrices in), read into and
/// written from dense Eigen matrices, for condensed elastic parts
/// (linalg/reduction.hpp).
///
/// Read: `%%MatrixMarket matrix coordinate real|integer general|symmetric` (one
/// `i j value` line per entry, 1-based; a symmetric file lists the lower
/// triangle, i >= j) and `%%MatrixMarket matrix array real general|symmetric`
/// (the values column by column; symmetric: the lower triangle of each column).
/// `%` lines after the header are comments; blank lines are skipped. Every
/// defect is an io::table_csv_error (pradis::error, code io_error) located at
/// file:line:column with the offending text: a missing or unsupported header,
/// a bad size line, a bad or non-finite number, an index out of range, an
/// entry above the diagonal of a symmetric file, an entry given twice, too
/// few or too many entries.

#include <Eigen/Core>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "pradis/io/table_csv.hpp"

namespace pradis::io {

namespace detail {
/// The words of a line with their 1-based columns.
struct mm_word {
  std::string_view text;
  int column = 0;
};
inline std::vector<mm_word> mm_words(std::string_view line) {
  std::vector<mm_word> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const std::size_t b = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > b) out.push_back({line.substr(b, i - b), static_cast<int>(b) + 1});
  }
  return out;
}
inline std::string mm_lower(std::string_view s) {
  std::string o(s);
  for (char& c : o) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return o;
}
}  // namespace detail

/// Parses the Matrix Market text `text` (named `file` in messages) into a dense
/// matrix; a symmetric file gives the full symmetric matrix. Throws
/// table_csv_error (code io_error) at the first defect (see the file comment),
/// also for more than `max_size` rows or columns, before anything is allocated
/// (dense storage: the default, 10000 x 10000, is 800 MB).
inline Eigen::MatrixXd parse_matrix_market(std::string_view text, const std::string& file, long max_size = 10000) {
  std::vector<std::string_view> lines;
  for (std::size_t b = 0; b <= text.size();) {
    std::size_t e = text.find('\n', b);
    if (e == std::string_view::npos) e = text.size();
    lines.push_back(text.substr(b, e - b));
    b = e + 1;
  }
  const auto fail = [&](int line, int column, const std::string& what) -> void {
    throw table_csv_error(file, line, column, what);
  };
  const auto words0 = lines.empty() ? std::vector<detail::mm_word>{} : detail::mm_words(lines[0]);
  if (words0.size() != 5 || detail::mm_lower(words0[0].text) != "%%matrixmarket" ||
      detail::mm_lower(words0[1].text) != "matrix")
    fail(1, 1, "not a Matrix Market file: the first line must be '%%MatrixMarket matrix <format> <field> <symmetry>'");
  const std::string format = detail::mm_lower(words0[2].text), field = detail::mm_lower(words0[3].text),
                    symmetry = detail::mm_lower(words0[4].text);
  if (format != "coordinate" && format != "array")
    fail(1, words0[2].column, "format '" + std::string(words0[2].text) + "' is not supported (coordinate or array)");
  if (field != "real" && field != "integer" && field != "double")
    fail(1, words0[3].column, "field '" + std::string(words0[3].text) + "' is not supported (real or integer)");
  if (symmetry != "general" && symmetry != "symmetric")
    fail(1, words0[4].column, "symmetry '" + std::string(words0[4].text) + "' is not supported (general or symmetric)");
  const bool coordinate = format == "coordinate", symmetric = symmetry == "symmetric";

  std::size_t k = 1;  // next line index
  const auto next_data = [&]() -> int {  // 1-based line number of the next data line, or 0 at the end
    while (k < lines.size()) {
      const std::string_view l = lines[k++];
      const auto w = detail::mm_words(l);
      if (w.empty() || w[0].text[0] == '%') continue;
      return static_cast<int>(k);
    }
    return 0;
  };
  const auto number = [&](int line, const detail::mm_word& w) {
    const auto x = detail::csv_number(w.text);
    if (!x) fail(line, w.column, "'" + detail::csv_show(w.text) + "' is not a finite number");
    return *x;
  };
  const auto index = [&](int line, const detail::mm_word& w, long n, const char* what) {
    const double x = number(line, w);
    if (!(x >= 1 && x <= static_cast<double>(n) && x == std::floor(x)))
      fail(line, w.column, std::string(what) + " '" + detail::csv_show(w.text) + "' is not a whole number in 1.." +
                               std::to_string(n));
    return static_cast<long>(x);
  };

  const int size_line = next_data();
  if (size_line == 0) fail(static_cast<int>(lines.size()), 1, "the size line is missing");
  const auto sw = detail::mm_words(lines[static_cast<std::size_t>(size_line - 1)]);
  if (sw.size() != (coordinate ? 3u : 2u))
    fail(size_line, 1, coordinate ? "the size line must be 'rows columns entries'" : "the size line must be 'rows columns'");
  const long rows = index(size_line, sw[0], max_size, "the row count");
  const long cols = index(size_line, sw[1], max_size, "the column count");
  if (symmetric && rows != cols) fail(size_line, 1, "a symmetric matrix must be square");
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(rows, cols);
  if (coordinate) {
    const long nnz = sw[2].text == "0" ? 0 : index(size_line, sw[2], rows * cols, "the entry count");
    std::vector<char> seen(static_cast<std::size_t>(rows * cols), 0);
    for (long e = 0; e < nnz; ++e) {
      const int ln = next_data();
      if (ln == 0)
        fail(static_cast<int>(lines.size()), 1,
             "the file ends after " + std::to_string(e) + " of its " + std::to_string(nnz) + " entries");
      const auto w = detail::mm_words(lines[static_cast<std::size_t>(ln - 1)]);
      if (w.size() != 3) fail(ln, 1, "an entry line must be 'row column value'");
      const long i = index(ln, w[0], rows, "the row index"), j = index(ln, w[1], cols, "the column index");
      const double x = number(ln, w[2]);
      if (symmetric && i < j)
        fail(ln, w[0].column, "entry (" + std::to_string(i) + ", " + std::to_string(j) +
                                  ") is above the diagonal: a symmetric file lists the lower triangle (row >= column)");
      char& s = seen[static_cast<std::size_t>((i - 1) * cols + (j - 1))];
      if (s) fail(ln, w[0].column, "entry (" + std::to_string(i) + ", " + std::to_string(j) + ") is given twice");
      s = 1;
      a(i - 1, j - 1) = x;
      if (symmetric) a(j - 1, i - 1) = x;
    }
  } else {
    for (long j = 0; j < cols; ++j)
      for (long i = symmetric ? j : 0; i < rows; ++i) {
        const int ln = next_data();
        if (ln == 0) fail(static_cast<int>(lines.size()), 1, "the file ends before all values of the array");
        const auto w = detail::mm_words(lines[static_cast<std::size_t>(ln - 1)]);
        if (w.size() != 1) fail(ln, 1, "an array file has one value per line");
        a(i, j) = number(ln, w[0]);
        if (symmetric) a(j, i) = a(i, j);
      }
  }
  if (const int extra = next_data(); extra != 0) fail(extra, 1, "more entries than the size line announces");
  return a;
}

/// Reads a Matrix Market file (see parse_matrix_market, also for `max_size`). A
/// file that cannot be read is a table_csv_error at line 0 naming the path.
inline Eigen::MatrixXd read_matrix_market(const std::string& path, long max_size = 10000) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw table_csv_error(path, 0, 0, "cannot read the matrix file");
  std::ostringstream s;
  s << f.rdbuf();
  return parse_matrix_market(s.str(), path, max_size);
}

/// Writes `a` as a Matrix Market coordinate file (real; `symmetric`: the lower
/// triangle of a symmetric matrix, which must then be square), every entry with
/// 17 significant digits, zeros left out. Throws pradis::error (io_error) if the
/// file cannot be written, invalid_option if `symmetric` and `a` is not square.
inline void write_matrix_market(const std::string& path, const Eigen::MatrixXd& a, bool symmetric) {
  if (symmetric && a.rows() != a.cols())
    throw error(error_code::invalid_option, "write_matrix_market: a symmetric matrix must be square");
  std::ostringstream body;
  long nnz = 0;
  char buf[64];
  for (Eigen::Index j = 0; j < a.cols(); ++j)
    for (Eigen::Index i = symmetric ? j : 0; i < a.rows(); ++i)
      if (a(i, j) != 0) {
        std::snprintf(buf, sizeof buf, "%.17g", a(i, j));
        body << i + 1 << ' ' << j + 1 << ' ' << buf << '\n';
        ++nnz;
      }
  std::ofstream f(path, std::ios::binary);
  if (!f) throw error(error_code::io_error, "cannot write the matrix file '" + path + "'");
  f << "%%MatrixMarket matrix coordinate real " << (symmetric ? "symmetric" : "general") << '\n'
    << a.rows() << ' ' << a.cols() << ' ' << nnz << '\n'
    << body.str();
  f.close();
  if (!f) throw error(error_code::io_error, "writing the matrix file '" + path + "' failed");
}

}  // namespace pradis::io
