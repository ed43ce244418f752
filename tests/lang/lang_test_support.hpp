#pragma once
// Helpers for the model-language tests: parse and build from strings, expect
// located errors, find the example models next to the sources.

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <string>

#include "pradis/lang/lang.hpp"
#include "testing/test_support.hpp"

namespace lang_test {

/// Column of a results table by label (1-based: column 0 is the time).
inline std::size_t column(const pradis::io::table& t, const std::string& label) {
  for (std::size_t c = 0; c < t.names().size(); ++c)
    if (t.names()[c] == label) return c + 1;
  FAIL("no column " << label);
  return 0;
}

/// examples/models of this source tree (found from this file's path).
inline std::filesystem::path models_dir() {
  return std::filesystem::path(__FILE__).parent_path().parent_path().parent_path() / "examples" / "models";
}

/// A fresh scratch directory for tests that write files.
inline std::filesystem::path scratch_dir(const std::string& tag) { return pradis_test::scratch_dir("lang_" + tag); }

using pradis_test::slurp;

/// A loader over in-memory files (for $INCLUDE tests).
inline pradis::lang::file_loader memory_loader(std::map<std::string, std::string> files) {
  return [files = std::move(files)](const std::string& p) -> std::optional<std::string> {
    auto it = files.find(p);
    if (it == files.end()) return std::nullopt;
    return it->second;
  };
}

/// Parses and builds (no run).
inline std::unique_ptr<pradis::lang::session> build(const std::string& text,
                                                    const pradis::lang::file_loader& load = pradis::lang::read_file) {
  return std::make_unique<pradis::lang::session>(pradis::lang::parse_string(text, "test.prd", load));
}

/// Parses, builds and runs without writing files.
inline std::unique_ptr<pradis::lang::session> run(const std::string& text) {
  auto s = build(text);
  s->run({.write_files = false});
  return s;
}

/// The message of the lang_error that parsing, building and running `text`
/// throws (and checks that it is one); empty if none was thrown.
inline std::string error_of(const std::string& text, const pradis::lang::file_loader& load = pradis::lang::read_file) {
  try {
    auto s = build(text, load);
    s->run({.write_files = false});
  } catch (const pradis::lang::lang_error& e) {
    return e.what();
  }
  return {};
}

/// Expects `text` to fail with a located error: the message starts with
/// `test.prd:<where>: error: ` and contains every one of `parts`. `line` is the
/// caller's (__builtin_LINE(), known to GCC and clang: clang 14 has no
/// std::source_location with libstdc++).
inline void expect_error(const std::string& text, const std::string& where, std::initializer_list<const char*> parts,
                         int line = __builtin_LINE()) {
  const std::string e = error_of(text);
  CAPTURE(line);
  CAPTURE(text);
  CAPTURE(e);
  REQUIRE_FALSE(e.empty());
  CHECK(e.rfind("test.prd:" + where + ": error: ", 0) == 0);
  for (const char* p : parts) CHECK(e.find(p) != std::string::npos);
}

/// A valid small model (mass on a spring, constant force) with placeholders
/// replaced by the caller through simple string substitution.
inline const char* small_model =
    "$DATA\n"
    "  Mass = 2\n"
    "  Stiffness = 100\n"
    "  Load = 10\n"
    "$FRAGMENT\n"
    "#STRUCTURE\n"
    "  Body 'MASS (1; Mass)\n"
    "  Spring 'SPRING (0 1; Stiffness)\n"
    "  Push 'F (1; Load)\n"
    "#OUTPUT\n"
    "  Position 'X (1; 1)\n"
    "  Spring force 'X (W:Spring(1); 1)\n"
    "$RUN\n"
    "  Calc 'SHTERM (END=0.1, SMAX=1E-3)\n"
    "$END\n";

/// small_model with the first occurrence of `from` replaced by `to` (which must exist).
inline std::string small_with(const std::string& from, const std::string& to) {
  std::string s = small_model;
  const auto p = s.find(from);
  REQUIRE_MESSAGE(p != std::string::npos, from);
  s.replace(p, from.size(), to);
  return s;
}

}  // namespace lang_test
