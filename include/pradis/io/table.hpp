#pragma once
/// \file
/// A time-series table of named output variables, written as CSV (the data of
/// PRADIS's 'TABL and 'DISP display programs; plotting is the application's
/// business: apps/common/gnuplot.hpp).

#include <span>
#include <string>
#include <vector>

#include "pradis/core/error.hpp"
#include "pradis/io/csv_file.hpp"

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

  /// Writes the table as CSV with a header line, full double precision, through
  /// a temporary file renamed at the end (io::csv_file: every write checked; a
  /// failure throws pradis::error with code io_error and leaves no truncated file).
  void write_csv(const std::string& path) const {
    csv_file f(path, names_);
    const std::size_t w = names_.size() + 1;
    for (std::size_t r = 0; r < rows(); ++r)
      f.add_row(rows_[r * w], std::span<const double>(rows_.data() + r * w + 1, names_.size()));
    f.commit();
  }

 private:
  std::vector<std::string> names_;
  std::vector<double> rows_;
};

}  // namespace pradis::io
