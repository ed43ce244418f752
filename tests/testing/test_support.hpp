#pragma once
// Helpers shared by the test files of several directories: bad parameter
// values, catching a pradis::error, substring checks and scratch files. One copy
// here, so the files of a unity group (tests/CMakeLists.txt) do not collide.

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "pradis/core/error.hpp"
#include "pradis/integrators/options.hpp"

// Whether this build runs under a sanitizer (the asan-ubsan preset: -O0 with AddressSanitizer and UBSan,
// some 200x slower than the dev preset's -O1: 180x to 570x per test case, measured 2026-11-30).
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer) || __has_feature(thread_sanitizer)
#define PRADIS_TEST_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#ifndef PRADIS_TEST_SANITIZED
#define PRADIS_TEST_SANITIZED 1
#endif
#endif

namespace pradis_test {

#ifdef PRADIS_TEST_SANITIZED
inline constexpr bool sanitized = true;
#else
inline constexpr bool sanitized = false;
#endif

/// Bad parameter values for the code-100 tests.
inline constexpr double inf = std::numeric_limits<double>::infinity();
inline constexpr double not_a_number = std::numeric_limits<double>::quiet_NaN();

/// Runs f and returns the pradis::error it throws (nullopt if none).
template <class F>
std::optional<pradis::error> error_of(F&& f) {
  try {
    f();
  } catch (const pradis::error& e) {
    return e;
  }
  return std::nullopt;
}

/// Options of an error-controlled run to `end` with `outputs` output intervals and
/// DRLTX = DABSX = tol (the other options at their defaults).
inline pradis::run_options controlled_run(double end, double tol, int outputs) {
  pradis::run_options o;
  o.end = end;
  o.out = end / outputs;
  o.error_control = true;
  o.drltx = tol;
  o.dabsx = tol;
  return o;
}

/// Whether `s` contains `part`.
inline bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

/// The scratch directories made by scratch_dir; all are removed when the test program exits.
struct scratch_registry {
  std::vector<std::filesystem::path> dirs;
  scratch_registry() = default;
  scratch_registry(const scratch_registry&) = delete;
  scratch_registry& operator=(const scratch_registry&) = delete;
  ~scratch_registry() {
    for (const auto& d : dirs) {
      std::error_code ec;
      std::filesystem::remove_all(d, ec);  // best effort: a test may have made a file read-only
    }
  }
  static scratch_registry& instance() {
    static scratch_registry r;
    return r;
  }
};

/// A fresh scratch directory for tests that write files (removed at the program's exit).
inline std::filesystem::path scratch_dir(const std::string& tag) {
  std::random_device rd;
  auto p = std::filesystem::temp_directory_path() / ("pradis_" + tag + "_" + std::to_string(rd()));
  std::filesystem::create_directories(p);
  scratch_registry::instance().dirs.push_back(p);
  return p;
}

/// The whole content of a file (empty if it cannot be read).
inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream os;
  os << f.rdbuf();
  return os.str();
}

}  // namespace pradis_test
