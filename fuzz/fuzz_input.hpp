#pragma once
// What both fuzz targets (fuzz_parser.cpp, fuzz_run.cpp) make of an input: its
// text, and the file loader of its $INCLUDEs, which serves one in-memory file
// (the fuzzer must not read the disk). tests/lang/test_fuzz_regressions.cpp
// replays fuzz/corpus/ and fuzz/regressions/ with the same loader.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "pradis/lang/parser.hpp"

namespace pradis_fuzz {

/// Inputs above this size are skipped.
inline constexpr std::size_t max_input = 64 * 1024;

/// The input as model text.
inline std::string input_text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// $INCLUDE 'inc.prd' gives a $DATA section; every other path is missing.
inline pradis::lang::file_loader loader() {
  return [](const std::string& path) -> std::optional<std::string> {
    if (path == "inc.prd") return std::string("$DATA\n  Included = 1, 2\n");
    return std::nullopt;
  };
}

}  // namespace pradis_fuzz
