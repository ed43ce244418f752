// io::csv_file: rows written through a temporary file renamed at the end, every
// write and the close checked (a full disk is an error with the system's reason,
// never a silently truncated file), and io::table::write_csv on top of it.

#include <doctest/doctest.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <vector>

#include "pradis/io/table.hpp"
#include "testing/test_support.hpp"

namespace {
using pradis_test::slurp;
}  // namespace

TEST_SUITE("io/csv file") {
  TEST_CASE("rows go to <path>.part until commit renames it; 17 significant digits read back exactly") {
    const auto dir = pradis_test::scratch_dir("csv_commit");
    const auto path = (dir / "r.csv").string();
    {
      pradis::io::csv_file f(path, {"x", "a,b", "q\"t"});
      const std::vector<double> row{0.1, -2.5e-300, 1.0 / 3.0};
      f.add_row(0.0, row);
      CHECK(std::filesystem::exists(f.temporary_path()));
      CHECK_FALSE(std::filesystem::exists(path));
      f.commit();
      CHECK(f.rows() == 1);
    }
    const std::string text = slurp(path);
    CHECK(text.rfind("t,x,\"a,b\",\"q\"\"t\"\n0,", 0) == 0);
    std::istringstream is(text.substr(text.find('\n') + 1));
    std::string cell;
    std::vector<double> back;
    while (std::getline(is, cell, ',')) back.push_back(std::stod(cell));
    REQUIRE(back.size() == 4);
    CHECK(back[1] == 0.1);
    CHECK(back[2] == -2.5e-300);
    CHECK(back[3] == 1.0 / 3.0);
    CHECK_FALSE(std::filesystem::exists(path + ".part"));
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("a failed rename keeps the complete temporary file and names it") {
    // The final name is taken by a non-empty directory: rename(2) cannot replace it.
    const auto dir = pradis_test::scratch_dir("csv_rename");
    const auto path = dir / "r.csv";
    std::filesystem::create_directories(path / "occupied");
    {
      pradis::io::csv_file f(path.string(), {"x"});
      const std::vector<double> row{2.5};
      f.add_row(0.0, row);
      f.add_row(1.0, row);
      try {
        f.commit();
        FAIL("must throw");
      } catch (const pradis::error& e) {
        CHECK(e.code() == pradis::error_code::io_error);
        const std::string w = e.message();
        CHECK(w.rfind("cannot rename '" + f.temporary_path() + "' to '" + path.string() + "': ", 0) == 0);
        CHECK(w.find("the rows are kept in '" + f.temporary_path() + "'") != std::string::npos);
      }
    }  // the destructor must not remove the kept file
    CHECK(slurp(path.string() + ".part") == "t,x\n0,2.5\n1,2.5\n");
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("without commit (an exception unwinding) the temporary file is removed") {
    const auto dir = pradis_test::scratch_dir("csv_abandon");
    const auto path = (dir / "r.csv").string();
    {
      pradis::io::csv_file f(path, {"x"});
      f.add_row(0.0, std::vector<double>{1.0});
    }
    CHECK(std::filesystem::is_empty(dir));
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("a full disk (/dev/full) is an io_error with the system's reason, checked at flush and close") {
    if (!std::filesystem::exists("/dev/full")) {
      MESSAGE("no /dev/full on this system: checked on Linux only");
      return;
    }
    const auto dir = pradis_test::scratch_dir("csv_full");
    const auto path = (dir / "r.csv").string();
    std::filesystem::create_symlink("/dev/full", path + ".part");
    pradis::io::table t({"x"});
    for (int k = 0; k < 10; ++k) t.add_row(k, {1.0 * k});
    try {
      t.write_csv(path);
      FAIL("writing to /dev/full succeeded");
    } catch (const pradis::error& e) {
      CHECK(e.code() == pradis::error_code::io_error);
      CHECK(e.message() == "cannot write '" + path + "': " + std::strerror(ENOSPC));
    }
    CHECK_FALSE(std::filesystem::exists(path));
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("a file that cannot be created names the file and the reason") {
    const auto dir = pradis_test::scratch_dir("csv_nodir");
    const auto path = (dir / "missing" / "r.csv").string();
    try {
      pradis::io::csv_file f(path, {"x"});
      FAIL("a file in a missing directory was created");
    } catch (const pradis::error& e) {
      CHECK(e.message() == "cannot create '" + path + ".part': " + std::strerror(ENOENT));
    }
    CHECK_THROWS_AS(pradis::io::csv_file(path, {"x"}), pradis::error);
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("a row with the wrong number of values is refused") {
    const auto dir = pradis_test::scratch_dir("csv_count");
    pradis::io::csv_file f((dir / "r.csv").string(), {"x", "y"});
    CHECK_THROWS_AS(f.add_row(0.0, std::vector<double>{1.0}), pradis::error);
    f.abandon();
    std::filesystem::remove_all(dir);
  }
}
