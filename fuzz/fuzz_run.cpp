// libFuzzer target: model files built and run (lexer, parser, builder, the
// elements' checks, the zero step and the integrators), from the example models.
// Any input must either build and run, or throw pradis::lang::lang_error
// (located), or be stopped by the fuzzer's CPU budget (lang::interrupted); a
// run that ends must leave only finite outputs. Every other outcome (crash,
// sanitizer report, other exception, a NaN or infinite output, a step that
// hangs past libFuzzer's -timeout) is a bug.
//
// The budget: a CPU-time timer (ITIMER_VIRTUAL, PRADIS_FUZZ_RUN_MS, default
// 300 ms per input) sets run_settings::stop, which the session checks after
// every step, so long but healthy runs end as interrupted. Inputs with $SAVE
// or $RESTORE are skipped (a mutated path could name any file), and no
// results file is written.
// Build and run: scripts/fuzz.sh [seconds] [build dir] run. Crashes go to
// fuzz/regressions-run/; `fuzz_run FILE` replays one (the test suite does not:
// these inputs need the budget, so a fix gets a test of its own).

#include <sys/time.h>

#include <cmath>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <string>

#include "fuzz_input.hpp"
#include "pradis/lang/parser.hpp"
#include "pradis/lang/session.hpp"

namespace {

volatile std::sig_atomic_t stop_flag = 0;

extern "C" void on_budget(int) { stop_flag = 1; }

long budget_ms() {
  const char* v = std::getenv("PRADIS_FUZZ_RUN_MS");
  const long ms = v ? std::strtol(v, nullptr, 10) : 300;
  return ms > 0 ? ms : 300;
}

void arm(long ms) {
  itimerval t{};
  t.it_value.tv_sec = ms / 1000;
  t.it_value.tv_usec = (ms % 1000) * 1000;
  setitimer(ITIMER_VIRTUAL, &t, nullptr);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  std::signal(SIGVTALRM, on_budget);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > pradis_fuzz::max_input) return 0;
  std::string text = pradis_fuzz::input_text(data, size);
  const pradis::lang::file_loader load = pradis_fuzz::loader();
  pradis::lang::run_settings rs;
  rs.stem = "fuzz";
  rs.plot = false;
  rs.write_files = false;
  rs.stop = &stop_flag;
  rs.max_rows = 1e5;
  stop_flag = 0;
  arm(budget_ms());
  bool ended = false;
  std::optional<pradis::lang::session> s;
  try {
    auto prog = pradis::lang::parse_string(std::move(text), "fuzz.prd", load);
    for (const auto& a : prog.actions)  // no checkpoint files: a mutated path could name any file
      if (a.what == pradis::lang::ast::action::kind::save || a.what == pradis::lang::ast::action::kind::restore) {
        arm(0);
        return 0;
      }
    s.emplace(std::move(prog));
    s->run(rs);
    ended = true;
  } catch (const pradis::lang::lang_error& e) {
    if (std::string(e.what()).rfind("fuzz.prd", 0) != 0) std::abort();  // an error without its location
  } catch (const pradis::lang::interrupted&) {
  }
  arm(0);
  if (ended) {
    const auto& r = s->results();
    for (std::size_t i = 0; i < r.rows(); ++i)
      for (std::size_t j = 0; j <= r.names().size(); ++j)
        if (!std::isfinite(r.at(i, j))) std::abort();  // a silent NaN or infinity in the results
  }
  return 0;
}
