// Error paths of the Matrix Market reader and writer (io/matrix_market.hpp) that
// tests/linalg/test_reduction.cpp does not reach: an unsupported format or
// symmetry in the header, a missing size line, a coordinate entry line without
// exactly three words, an array file that ends early or has two values on a
// line, and a file that cannot be opened or written. Malformed files are written
// to a per-test scratch directory and read back with read_matrix_market; each
// error is an io_error (table_csv_error) at the file, line and column expected.

#include <doctest/doctest.h>

#include <Eigen/Core>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <string>
#include <system_error>

#include "pradis/io/matrix_market.hpp"
#include "testing/test_support.hpp"

using namespace pradis;

namespace {

/// A per-test scratch directory, removed when the test ends.
struct mme_scratch {
  std::filesystem::path dir;
  mme_scratch() {
    std::random_device rd;
    dir = std::filesystem::temp_directory_path() / ("pradis_mm_errors_" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(dir);
  }
  mme_scratch(const mme_scratch&) = delete;
  mme_scratch& operator=(const mme_scratch&) = delete;
  ~mme_scratch() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  /// Writes `text` to the file `name` in the directory; its path.
  std::string file(const std::string& name, const std::string& text) const {
    const auto p = dir / name;
    std::ofstream f(p, std::ios::binary);
    f << text;
    f.close();
    REQUIRE(f);
    return p.string();
  }
};

/// The table_csv_error that reading `path` throws (nullopt if none).
std::optional<io::table_csv_error> mme_read_error(const std::string& path) {
  try {
    (void)io::read_matrix_market(path);
  } catch (const io::table_csv_error& e) {
    return e;
  }
  return std::nullopt;
}

/// Checks a reader error: code, file, line, column and the message (detail,
/// and what() located as file:line:column).
void mme_check(const std::optional<io::table_csv_error>& e, const std::string& path, int line, int column,
               const std::string& detail) {
  REQUIRE(e);
  CHECK(e->code() == error_code::io_error);
  CHECK(e->number() == 160);
  CHECK(e->file() == path);
  CHECK(e->line() == line);
  CHECK(e->column() == column);
  CHECK(e->detail() == detail);
  CHECK(pradis_test::contains(e->what(),
                              path + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + detail));
}

}  // namespace

TEST_SUITE("io/matrix market errors") {
  TEST_CASE("an unsupported format in the header is refused at its column") {
    const mme_scratch tmp;
    // "%%MatrixMarket matrix " is 22 characters: the format word starts at column 23.
    const std::string p = tmp.file("sparse.mtx", "%%MatrixMarket matrix sparse real general\n2 2 1\n1 1 4\n");
    mme_check(mme_read_error(p), p, 1, 23, "format 'sparse' is not supported (coordinate or array)");
    // Upper case is accepted (the check is case-insensitive), so only the word is wrong here.
    const std::string q = tmp.file("vector.mtx", "%%MATRIXMARKET MATRIX Vector REAL GENERAL\n2 2 1\n1 1 4\n");
    mme_check(mme_read_error(q), q, 1, 23, "format 'Vector' is not supported (coordinate or array)");
    const std::string ok = tmp.file("ok.mtx", "%%MATRIXMARKET MATRIX COORDINATE REAL GENERAL\n2 2 1\n1 1 4\n");
    const Eigen::MatrixXd a = io::read_matrix_market(ok);
    CHECK(a == (Eigen::Matrix2d() << 4, 0, 0, 0).finished());
  }

  TEST_CASE("an unsupported symmetry in the header is refused at its column") {
    const mme_scratch tmp;
    // "%%MatrixMarket matrix coordinate real " is 38 characters: column 39.
    const std::string p = tmp.file("skew.mtx", "%%MatrixMarket matrix coordinate real skew-symmetric\n2 2 1\n2 1 4\n");
    mme_check(mme_read_error(p), p, 1, 39, "symmetry 'skew-symmetric' is not supported (general or symmetric)");
    // "%%MatrixMarket matrix array real " is 33 characters: column 34.
    const std::string q = tmp.file("herm.mtx", "%%MatrixMarket matrix array real hermitian\n1 1\n4\n");
    mme_check(mme_read_error(q), q, 1, 34, "symmetry 'hermitian' is not supported (general or symmetric)");
  }

  TEST_CASE("a file without a size line: the error is at its end") {
    const mme_scratch tmp;
    SUBCASE("only the header") {
      // Two lines split at '\n': the header and the empty rest after it (line 2).
      const std::string p = tmp.file("header.mtx", "%%MatrixMarket matrix coordinate real general\n");
      mme_check(mme_read_error(p), p, 2, 1, "the size line is missing");
    }
    SUBCASE("the header, comments and blank lines") {
      const std::string p =
          tmp.file("comments.mtx", "%%MatrixMarket matrix array real general\n% a comment\n\n   \n%another\n");
      // Lines: header, comment, blank, blanks, comment, then the end (line 6).
      mme_check(mme_read_error(p), p, 6, 1, "the size line is missing");
    }
    SUBCASE("no final newline") {
      const std::string p = tmp.file("nonl.mtx", "%%MatrixMarket matrix coordinate real general\n% only a comment");
      mme_check(mme_read_error(p), p, 2, 1, "the size line is missing");
    }
  }

  TEST_CASE("a coordinate entry line without exactly row, column and value is refused at its line") {
    const mme_scratch tmp;
    const std::string h = "%%MatrixMarket matrix coordinate real general\n";
    SUBCASE("two words") {
      const std::string p = tmp.file("two.mtx", h + "2 2 2\n1 1 4\n2 2\n");
      mme_check(mme_read_error(p), p, 4, 1, "an entry line must be 'row column value'");
    }
    SUBCASE("four words, after a comment") {
      const std::string p = tmp.file("four.mtx", h + "% c\n2 2 1\n% c\n  2 1 4 5\n");
      mme_check(mme_read_error(p), p, 5, 1, "an entry line must be 'row column value'");
    }
    SUBCASE("symmetric file, one word") {
      const std::string p =
          tmp.file("one.mtx", "%%MatrixMarket matrix coordinate integer symmetric\n3 3 2\n1 1 4\n7\n");
      mme_check(mme_read_error(p), p, 4, 1, "an entry line must be 'row column value'");
    }
  }

  TEST_CASE("an array file that ends early or has more than one value on a line is refused") {
    const mme_scratch tmp;
    const std::string h = "%%MatrixMarket matrix array real general\n";
    SUBCASE("general: 3 of 4 values") {
      const std::string p = tmp.file("short.mtx", h + "2 2\n1\n2\n3\n");
      // Lines: header, size, three values, the end (line 6).
      mme_check(mme_read_error(p), p, 6, 1, "the file ends before all values of the array");
    }
    SUBCASE("symmetric: 2 of the 3 values of the lower triangle") {
      const std::string p = tmp.file("shortsym.mtx", "%%MatrixMarket matrix array real symmetric\n2 2\n4\n1\n");
      mme_check(mme_read_error(p), p, 5, 1, "the file ends before all values of the array");
    }
    SUBCASE("no value at all") {
      const std::string p = tmp.file("none.mtx", h + "1 3\n");
      mme_check(mme_read_error(p), p, 3, 1, "the file ends before all values of the array");
    }
    SUBCASE("two values on a line") {
      const std::string p = tmp.file("pair.mtx", h + "2 2\n1\n2 3\n4\n");
      mme_check(mme_read_error(p), p, 4, 1, "an array file has one value per line");
    }
    SUBCASE("a coordinate-style line in an array file") {
      const std::string p = tmp.file("coord.mtx", h + "% c\n2 1\n1 1 5\n");
      mme_check(mme_read_error(p), p, 4, 1, "an array file has one value per line");
    }
    SUBCASE("the size line of an array file has two words") {
      const std::string p = tmp.file("size.mtx", h + "2 2 4\n1\n2\n3\n4\n");
      mme_check(mme_read_error(p), p, 2, 1, "the size line must be 'rows columns'");
    }
    SUBCASE("the same values, well formed, are read column by column") {
      const std::string p = tmp.file("good.mtx", h + "2 2\n1\n2\n3\n4\n");
      CHECK(io::read_matrix_market(p) == (Eigen::Matrix2d() << 1, 3, 2, 4).finished());
    }
  }

  TEST_CASE("a matrix file that cannot be opened for writing: io_error naming the path, nothing created") {
    const mme_scratch tmp;
    const Eigen::Matrix2d a = (Eigen::Matrix2d() << 2, 1, 1, 3).finished();
    SUBCASE("in a directory that does not exist") {
      const std::string p = (tmp.dir / "missing" / "k.mtx").string();
      for (const bool symmetric : {true, false}) {
        CAPTURE(symmetric);
        const auto e = pradis_test::error_of([&] { io::write_matrix_market(p, a, symmetric); });
        REQUIRE(e);
        CHECK(e->code() == error_code::io_error);
        CHECK(e->number() == 160);
        CHECK(e->message() == "cannot write the matrix file '" + p + "'");
        CHECK(e->instance().empty());
        CHECK_FALSE(std::filesystem::exists(tmp.dir / "missing"));
      }
    }
    SUBCASE("a directory as the file") {
      const std::string p = tmp.dir.string();
      const auto e = pradis_test::error_of([&] { io::write_matrix_market(p, a, false); });
      REQUIRE(e);
      CHECK(e->code() == error_code::io_error);
      CHECK(e->message() == "cannot write the matrix file '" + p + "'");
      CHECK(std::filesystem::is_directory(tmp.dir));
    }
    SUBCASE("the same matrix to a valid path is written and read back") {
      const std::string p = (tmp.dir / "k.mtx").string();
      io::write_matrix_market(p, a, true);
      CHECK(io::read_matrix_market(p) == a);
    }
  }

#ifdef __linux__
  TEST_CASE("a matrix file that opens but whose writing fails: io_error 'writing ... failed'") {
    // /dev/full opens for writing, and every write to it fails (ENOSPC): the
    // buffered output fails when the file is closed.
    const std::string p = "/dev/full";
    REQUIRE(std::filesystem::is_character_file(p));
    const Eigen::MatrixXd a = Eigen::MatrixXd::Identity(3, 3);
    const auto e = pradis_test::error_of([&] { io::write_matrix_market(p, a, true); });
    REQUIRE(e);
    CHECK(e->code() == error_code::io_error);
    CHECK(e->number() == 160);
    CHECK(e->message() == "writing the matrix file '/dev/full' failed");
    CHECK(pradis_test::contains(e->what(), "pradis error 160 (I/O error): writing the matrix file"));
  }
#endif
}
