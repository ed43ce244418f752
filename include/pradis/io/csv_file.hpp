#pragma once
/// \file
/// A CSV results file written safely and row by row: rows go to a temporary
/// file `<path>.part` as they are produced (flushed to the operating system at
/// least once a second), every write and the close are checked, and commit()
/// renames the temporary file to `<path>`. A failed write (a full disk, a
/// removed directory) throws pradis::error with code io_error and the system's
/// reason, and no truncated file is left under `<path>`.

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "pradis/core/error.hpp"

namespace pradis::io {

/// One CSV file: header `t,<names>`, then one line per row, full double precision (%.17g).
class csv_file {
 public:
  /// Creates `<path>.part` and writes the header: `first` (time, "t", unless
  /// given), then the names. Throws pradis::error (io_error) if the file cannot
  /// be created or written.
  csv_file(std::string path, const std::vector<std::string>& names, const std::string& first = "t")
      : path_(std::move(path)), temp_(path_ + ".part"), columns_(names.size()) {
    errno = 0;
    f_ = std::fopen(temp_.c_str(), "wb");
    if (!f_) fail("cannot create");
    std::string head = quote(first);
    for (const auto& n : names) head += ',' + quote(n);
    head += '\n';
    put(head);
    last_flush_ = std::chrono::steady_clock::now();
  }
  csv_file(const csv_file&) = delete;
  csv_file& operator=(const csv_file&) = delete;
  /// Removes the temporary file unless commit() was called.
  ~csv_file() { abandon(); }

  /// Appends one row: time and one value per column (throws if the count differs).
  void add_row(double t, std::span<const double> values) {
    check_count(values);
    line_.clear();
    append(t);
    finish_row(values);
    // At least once a second the rows reach the operating system, so that a
    // killed run (or a crash) leaves them in `<path>.part`.
    const auto now = std::chrono::steady_clock::now();
    if (now - last_flush_ > std::chrono::seconds(1)) {
      flush();
      last_flush_ = now;
    }
  }

  /// Appends one row whose first column is a text (a name) instead of a time.
  void add_row(const std::string& label, std::span<const double> values) {
    check_count(values);
    line_ = quote(label);
    finish_row(values);
  }

  /// Hands the buffered rows to the operating system (checked).
  void flush() {
    if (!f_) return;
    errno = 0;
    if (std::fflush(f_) != 0) fail("cannot write");
  }

  /// Flushes and closes the file (both checked) and renames it to path().
  /// Throws pradis::error (io_error) on failure: after removing the temporary
  /// file if writing or closing failed (it would be truncated); if only the
  /// rename failed, the complete temporary file is kept and the message names it.
  void commit() {
    if (!f_) throw error(error_code::io_error, "'" + path_ + "' was already closed");
    flush();
    errno = 0;
    const bool bad = std::ferror(f_) != 0;
    const int closed = std::fclose(f_);
    f_ = nullptr;
    if (bad || closed != 0) fail("cannot write");
    errno = 0;
    if (std::rename(temp_.c_str(), path_.c_str()) != 0) {
      // The rows are complete in the temporary file: keep it and say where it is.
      const int e = errno;
      committed_ = true;
      throw error(error_code::io_error, "cannot rename '" + temp_ + "' to '" + path_ + "': " +
                                            (e != 0 ? std::strerror(e) : "rename failed") + "; the rows are kept in '" +
                                            temp_ + "'");
    }
    committed_ = true;
  }

  /// Closes and removes the temporary file (no exception).
  void abandon() noexcept {
    if (f_) {
      std::fclose(f_);
      f_ = nullptr;
    }
    if (!committed_) std::remove(temp_.c_str());
  }

  /// Whether the file is open (false after commit(), abandon() or a failed write).
  bool is_open() const noexcept { return f_ != nullptr; }
  /// The final path of the file.
  const std::string& path() const noexcept { return path_; }
  /// The temporary file the rows are written to until commit().
  const std::string& temporary_path() const noexcept { return temp_; }
  /// Rows written so far.
  std::size_t rows() const noexcept { return rows_; }

  /// A CSV field: quoted (with "" for ") if it contains a comma or a quote.
  static std::string quote(const std::string& s) {
    if (s.find_first_of(",\"") == std::string::npos) return s;
    std::string o = "\"";
    for (char ch : s) o += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return o + "\"";
  }

 private:
  void check_count(std::span<const double> values) const {
    if (values.size() != columns_)
      throw error(error_code::invalid_option, "CSV row has " + std::to_string(values.size()) + " values for " +
                                                  std::to_string(columns_) + " columns");
  }
  /// Appends the values to the first column already in line_ and writes the row.
  void finish_row(std::span<const double> values) {
    for (double x : values) {
      line_ += ',';
      append(x);
    }
    line_ += '\n';
    put(line_);
    ++rows_;
  }
  [[noreturn]] void fail(const std::string& what) {
    const int e = errno;
    const std::string reason = e != 0 ? std::strerror(e) : "write error";
    const std::string target = what == "cannot create" ? temp_ : path_;
    abandon();
    throw error(error_code::io_error, what + " '" + target + "': " + reason);
  }
  void put(const std::string& s) {
    errno = 0;
    if (std::fwrite(s.data(), 1, s.size(), f_) != s.size()) fail("cannot write");
  }
  void append(double x) {
    char b[32];
    const int n = std::snprintf(b, sizeof b, "%.17g", x);
    line_.append(b, static_cast<std::size_t>(n));
  }

  std::string path_, temp_;
  std::size_t columns_ = 0, rows_ = 0;
  std::FILE* f_ = nullptr;
  bool committed_ = false;
  std::string line_;
  std::chrono::steady_clock::time_point last_flush_;
};

}  // namespace pradis::io
