// io::read_table_csv / parse_table_csv: two-column tables for tabular laws,
// with an optional header, comma or blank separators and # comments; every bad
// file is an io_error located at file:line:column with the offending text.

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "pradis/io/csv_file.hpp"
#include "pradis/io/table_csv.hpp"
#include "testing/test_support.hpp"

using pradis::io::parse_table_csv;
using pradis::io::read_table_csv;
using pradis::io::table_csv_error;

namespace {
std::optional<table_csv_error> parse_error(const std::string& text) {
  try {
    parse_table_csv(text, "t.csv");
  } catch (const table_csv_error& e) {
    return e;
  }
  return std::nullopt;
}
void check_parse_error(const std::string& text, int line, int column, const std::string& mention) {
  CAPTURE(text);
  const auto e = parse_error(text);
  REQUIRE(e.has_value());
  INFO("what(): ", std::string(e->what()));
  CHECK(e->code() == pradis::error_code::io_error);
  CHECK(e->line() == line);
  CHECK(e->column() == column);
  CHECK(e->detail().find(mention) != std::string::npos);
  const std::string where = line > 0 ? "t.csv:" + std::to_string(line) + ":" + std::to_string(column) + ": " : "t.csv: ";
  CHECK(std::string(e->what()).find(where) != std::string::npos);
}
}  // namespace

TEST_SUITE("io/table csv") {
  TEST_CASE("comma, blank and tab separators, a header, comments, blank lines and CR LF give the flat pair list") {
    const std::vector<double> want{0.0, 0.0, 0.1, 12.5, 0.25, -3e-3, 1.0, 40.0};
    CHECK(parse_table_csv("0,0\n0.1,12.5\n0.25,-3e-3\n1,40\n", "a") == want);
    CHECK(parse_table_csv("# deformation [m], force [N]\nd, F   # header\n\n 0 , 0\n0.1,\t12.5\r\n0.25 , -3E-3\r1,+40",
                          "b") == want);
    CHECK(parse_table_csv("d F\n0 0\n0.1\t12.5\n   0.25   -0.003  # comment\n1 40\n", "c") == want);
  }

  TEST_CASE("a table written by io::csv_file reads back exactly (17 significant digits)") {
    const auto dir = pradis_test::scratch_dir("tcsv_round");
    const auto path = (dir / "curve.csv").string();
    std::vector<double> want;
    {
      pradis::io::csv_file f(path, {"F"});  // header t,F: the abscissa is the first column
      for (int i = 0; i <= 20; ++i) {
        const double d = -0.1 + 0.01 * i, F = 1000 * d + 1e5 * d * d * d + 1.0 / 3.0;
        const double row[1] = {F};
        f.add_row(d, row);
        want.insert(want.end(), {d, F});
      }
      f.commit();
    }
    CHECK(read_table_csv(path) == want);
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("bad table files are io errors at file:line:column naming the offending text") {
    check_parse_error("0,0\n0.1,abc\n", 2, 5, "'abc' is not a finite number");
    check_parse_error("d,F\n0,0\nx,y\n", 3, 1, "'x' is not a finite number (only the first line may be a header)");
    check_parse_error("0 0\n0.1 1e999\n", 2, 5, "'1e999' is not a finite number");
    check_parse_error("0 0\n0.1 nan\n", 2, 5, "'nan' is not a finite number");
    check_parse_error("0 0\n0.1 1.5.2\n", 2, 5, "'1.5.2' is not a finite number");
    check_parse_error("0,0\n0.1, 2, 3\n", 2, 9, "expected 2 columns (x, y), found 3 in '0.1, 2, 3'");
    check_parse_error("0,0\n  0.5\n", 2, 6, "expected 2 columns (x, y), found 1");
    check_parse_error("0,0\n0.5,\n", 2, 5, "empty cell");
    check_parse_error("0,0\n,1\n", 2, 1, "empty cell");
    check_parse_error("# only a comment\n\nd, F\n", 0, 0, "no data lines");
    check_parse_error("", 0, 0, "no data lines");
    // The first line as a header must be all text: a half-numeric first line is an error.
    check_parse_error("0, F\n1, 2\n", 1, 4, "'F' is not a finite number");
  }

  TEST_CASE("a missing table file or a directory is an io error naming the path and the reason") {
    const auto dir = pradis_test::scratch_dir("tcsv_missing");
    const std::string path = (dir / "nowhere.csv").string();
    try {
      read_table_csv(path);
      FAIL("no error");
    } catch (const table_csv_error& e) {
      CHECK(e.code() == pradis::error_code::io_error);
      CHECK(e.line() == 0);
      CHECK(std::string(e.what()).find(path + ": cannot read the table file: No such file") != std::string::npos);
    }
    try {
      read_table_csv(dir.string());
      FAIL("no error");
    } catch (const table_csv_error& e) {
      CHECK(e.detail() == "cannot read the table file: it is a directory");
    }
    std::filesystem::remove_all(dir);
  }
}
