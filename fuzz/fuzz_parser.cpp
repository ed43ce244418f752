// libFuzzer target: the model-language lexer, parser and builder (no run).
// Any input must either build or throw pradis::lang::lang_error; every other
// outcome (crash, sanitizer report, other exception, hang) is a bug.
// Build and run: scripts/fuzz.sh [seconds]. Crashes go to fuzz/regressions/,
// which tests/lang/test_fuzz_regressions.cpp replays.

#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_input.hpp"
#include "pradis/lang/parser.hpp"
#include "pradis/lang/session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > pradis_fuzz::max_input) return 0;
  std::string text = pradis_fuzz::input_text(data, size);
  const pradis::lang::file_loader load = pradis_fuzz::loader();
  try {
    pradis::lang::session s(pradis::lang::parse_string(std::move(text), "fuzz.prd", load));
  } catch (const pradis::lang::lang_error&) {
  }
  return 0;
}
