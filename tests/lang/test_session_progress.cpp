// The session feeds the progress line (io/progress.hpp) from the simulation's output observer, on the stream
// it is given and only there. The line's own text and throttle: tests/io/test_progress.cpp. (In tests/lang so
// that only this unit compiles the whole language.)

#include <doctest/doctest.h>

#include <sstream>
#include <string>

#include "pradis/lang/lang.hpp"

TEST_SUITE("lang/progress") {
  TEST_CASE("a session draws the line on the stream it is given, and only there") {
    const char* text =
        "$FRAGMENT\n#STRUCTURE\n  Body 'MASS (1; 1)\n  Spring 'SPRING (0 1; 1)\n  Start 'X0 (1; 1)\n"
        "#OUTPUT\n  U 'X (1; 1)\n$RUN\n  Calc 'GALPHA (END=0.5, SMAX=1E-3)\n$END\n";
    std::ostringstream progress, log;
    pradis::lang::session s(pradis::lang::parse_string(text, "p.prd"));
    s.run({.write_files = false, .log = &log, .progress = &progress});
    const std::string out = progress.str();
    // The first drawing is at the zero step (t = 0, no step yet).
    CHECK(out.rfind("\rCalc GALPHA  t = 0 of 0.5 (0.0%)  h = -  Newton 0 (0 total)  elapsed ", 0) == 0);
    // It ends blank, with the cursor at the start of the line.
    const std::size_t first = out.find('\r', 1);
    REQUIRE(first != std::string::npos);
    CHECK(out.back() == '\r');
    CHECK(out.find_first_not_of(' ', out.rfind('\r', out.size() - 2) + 1) == out.size() - 1);
    // The log has the stage line and no trace of the progress line.
    CHECK(log.str().find("stage 1 'Calc' GALPHA: t = 0 .. 0.5, ") != std::string::npos);
    CHECK(log.str().find('\r') == std::string::npos);
    // Without a progress stream nothing is drawn anywhere.
    std::ostringstream log2;
    pradis::lang::session q(pradis::lang::parse_string(text, "p.prd"));
    q.run({.write_files = false, .log = &log2});
    CHECK(log2.str() == log.str());
  }
}
