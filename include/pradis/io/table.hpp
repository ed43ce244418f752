#pragma once
/// \file
/// A time-series table of named output variables, written as CSV and plotted
/// with gnuplot (the roles of PRADIS's 'TABL and 'DISP display programs).

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <string>
#include <vector>

#include "pradis/core/error.hpp"

namespace pradis::io {

/// Columns of named output variables sampled over time.
class table {
 public:
  /// Creates a table with the given column names (time is added as the first column "t").
  explicit table(std::vector<std::string> names) : names_(std::move(names)) {}

  /// Appends one row: time and one value per column (throws if the count differs).
  void add_row(double t, const std::vector<double>& values) {
    if (values.size() != names_.size())
      throw error(error_code::invalid_option, "table row has " + std::to_string(values.size()) + " values for " +
                                                  std::to_string(names_.size()) + " columns");
    rows_.push_back(t);
    rows_.insert(rows_.end(), values.begin(), values.end());
  }
  /// Number of rows.
  std::size_t rows() const noexcept { return rows_.size() / (names_.size() + 1); }
  /// Value at row r, column c (column 0 is time).
  double at(std::size_t r, std::size_t c) const { return rows_.at(r * (names_.size() + 1) + c); }
  /// Column names (without time).
  const std::vector<std::string>& names() const noexcept { return names_; }

  /// Writes the table as CSV with a header line; full double precision.
  void write_csv(const std::string& path) const {
    std::ofstream f(path);
    if (!f) throw error(error_code::io_error, "cannot write '" + path + "'");
    f << "t";
    for (const auto& n : names_) f << ',' << quote(n);
    f << '\n' << std::setprecision(17);
    const std::size_t w = names_.size() + 1;
    for (std::size_t r = 0; r < rows(); ++r) {
      for (std::size_t c = 0; c < w; ++c) f << (c ? "," : "") << rows_[r * w + c];
      f << '\n';
    }
    if (!f) throw error(error_code::io_error, "error while writing '" + path + "'");
  }

  /// Plots every column against time, one panel per column, into a PNG with
  /// gnuplot (which must be on PATH). Writes the gnuplot script next to the
  /// image (`<png>.gp`) and reads the data from `csv` (written by write_csv).
  void plot_png(const std::string& csv, const std::string& png, const std::string& title) const {
    // Paths go into a gnuplot script and a shell command in single quotes: refuse
    // characters that would end the quoting rather than escape them.
    for (const std::string* s : {&csv, &png})
      if (s->find_first_of("'\"\n\\`$") != std::string::npos)
        throw error(error_code::io_error, "cannot plot to or from '" + *s +
                                              "': the path contains a quote, backslash, $, backquote or newline");
    const std::string script = png + ".gp";
    {
      std::ofstream g(script);
      if (!g) throw error(error_code::io_error, "cannot write '" + script + "'");
      const std::size_t n = names_.size();
      g << "set datafile separator ','\n"
        << "set terminal pngcairo size 900," << 260 * n + 60 << " font 'sans,10'\n"
        << "set output '" << png << "'\n"
        << "set multiplot layout " << n << ",1 title '" << label(title) << "'\n"
        << "set grid\nset key off\n";
      for (std::size_t c = 0; c < n; ++c) {
        g << "set ylabel '" << label(names_[c]) << "'\n";
        if (c + 1 == n) g << "set xlabel 't [s]'\n";
        g << "plot '" << csv << "' using 1:" << c + 2 << " every ::1 with lines lw 2\n";
      }
      g << "unset multiplot\n";
    }
    const std::string cmd = "gnuplot '" + script + "'";
    if (std::system(cmd.c_str()) != 0)
      throw error(error_code::io_error, "gnuplot failed on '" + script + "' (is gnuplot installed?)");
  }

 private:
  /// A label safe inside single quotes in a gnuplot script.
  static std::string label(const std::string& s) {
    std::string o;
    for (char ch : s) o += (ch == '\'' || ch == '\n' || ch == '\\') ? ' ' : ch;
    return o;
  }
  static std::string quote(const std::string& s) {
    if (s.find_first_of(",\"") == std::string::npos) return s;
    std::string o = "\"";
    for (char ch : s) o += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return o + "\"";
  }
  std::vector<std::string> names_;
  std::vector<double> rows_;
};

}  // namespace pradis::io
