// libFuzzer target: the model-language lexer, parser and builder (no run).
// Any input must either build or throw pradis::lang::lang_error; every other
// outcome (crash, sanitizer report, other exception, hang) is a bug.
// Build and run: scripts/fuzz.sh [seconds]. Crashes go to fuzz/regressions/,
// which tests/lang/test_fuzz_regressions.cpp replays.

#include <cstddef>
#include <cstdint>
#include <string>

#include "pradis/lang/parser.hpp"
#include "pradis/lang/session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 64 * 1024) return 0;
  std::string text(reinterpret_cast<const char*>(data), size);
  // $INCLUDE resolves to an in-memory file (the fuzzer must not read the disk).
  const pradis::lang::file_loader load = [](const std::string& path) -> std::optional<std::string> {
    if (path == "inc.prd") return std::string("$DATA\n  Included = 1, 2\n");
    return std::nullopt;
  };
  try {
    pradis::lang::session s(pradis::lang::parse_string(std::move(text), "fuzz.prd", load));
  } catch (const pradis::lang::lang_error&) {
  }
  return 0;
}
