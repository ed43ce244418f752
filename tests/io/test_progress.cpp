// The progress line of long runs: its text for given figures, the redraw
// throttle (at most once per interval of the clock), clearing at the end of a
// stage. The session feeding it from the simulation's output observer:
// tests/lang/test_session_progress.cpp.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "pradis/io/progress.hpp"

using pradis::io::format_duration;
using pradis::io::format_progress;
using pradis::io::progress_figures;
using pradis::io::progress_line;

TEST_SUITE("io/progress") {
  TEST_CASE("the progress text for given figures") {
    // A quarter of the stage in 1.5 s: 4.5 s left at the same rate.
    CHECK(format_progress({"Calc SHTERM", 0, 0.25, 1, 1e-3, 2, 1234, 1.5}) ==
          "Calc SHTERM  t = 0.25 of 1 (25.0%)  h = 0.001  Newton 2 (1234 total)  elapsed 1.5 s, left 4.5 s");
    // A stage from t = 1 that has not advanced yet: no step, no estimate.
    CHECK(format_progress({"", 1, 1, 2, 0, 0, 0, 0}) ==
          "t = 1 of 2 (0.0%)  h = -  Newton 0 (0 total)  elapsed 0.0 s, left ?");
    // One tenth of the stage in 125 s: 1125 s = 18:45 min left.
    CHECK(format_progress({"B", 0, 1, 10, 2.5e-5, 3, 7, 125}) ==
          "B  t = 1 of 10 (10.0%)  h = 2.5e-05  Newton 3 (7 total)  elapsed 2:05 min, left 18:45 min");
    // The end of a stage: 100%, nothing left. Times beyond END are clamped to 100%.
    CHECK(format_progress({"", 0, 2, 2, 0.5, 1, 9, 3725}) ==
          "t = 2 of 2 (100.0%)  h = 0.5  Newton 1 (9 total)  elapsed 1:02:05 h, left 0.0 s");
    CHECK(format_progress({"", 0, 2.5, 2, 0.5, 1, 9, 1}).find("(100.0%)") != std::string::npos);
    // A long label is cut to 40 characters.
    const std::string label(60, 'x');
    CHECK(format_progress({label, 0, 0, 1, 0, 0, 0, 0}).rfind(std::string(40, 'x') + "  t = 0 of 1", 0) == 0);
  }

  TEST_CASE("durations: seconds, minutes, hours, unknown") {
    CHECK(format_duration(0) == "0.0 s");
    CHECK(format_duration(59.94) == "59.9 s");
    CHECK(format_duration(59.96) == "1:00 min");
    CHECK(format_duration(61) == "1:01 min");
    CHECK(format_duration(3599.4) == "59:59 min");
    CHECK(format_duration(3600) == "1:00:00 h");
    CHECK(format_duration(36000 + 61) == "10:01:01 h");
    CHECK(format_duration(2e9) == "> 30 years");
    CHECK(format_duration(-1) == "?");
    CHECK(format_duration(std::numeric_limits<double>::quiet_NaN()) == "?");
    CHECK(format_duration(std::numeric_limits<double>::infinity()) == "?");
  }

  TEST_CASE("the line is redrawn at most once per interval and cleared at the end of a stage") {
    std::ostringstream os;
    double now = 0;
    progress_line p(os, [&] { return now; }, 0.1);
    p.update(0.5, 1e-3, 1, 1);  // before begin(): nothing
    CHECK(os.str().empty());
    p.begin("S", 0, 1);
    CHECK(p.active());
    p.update(0.0, 0, 0, 0);  // the first update of a stage draws at once
    CHECK(p.draws() == 1);
    CHECK(os.str() == "\rS  t = 0 of 1 (0.0%)  h = -  Newton 0 (0 total)  elapsed 0.0 s, left ?");
    const std::size_t width = os.str().size() - 1;
    for (int k = 1; k <= 9; ++k) {  // 90 ms of updates: no redraw
      now = 0.01 * k;
      p.update(0.01 * k, 1e-3, 2, 2 * k);
    }
    CHECK(p.draws() == 1);
    now = 0.1;
    p.update(0.1, 1e-3, 2, 20);  // 100 ms after the first drawing
    CHECK(p.draws() == 2);
    CHECK(os.str().substr(os.str().rfind('\r')) ==
          "\rS  t = 0.1 of 1 (10.0%)  h = 0.001  Newton 2 (20 total)  elapsed 0.1 s, left 0.9 s");
    // A thousand updates within one second of the clock give at most ten drawings.
    for (int k = 0; k < 1000; ++k) {
      now = 0.1 + 0.001 * (k + 1);
      p.update(0.1 + 0.0009 * k, 1e-3, 2, 20 + k);
    }
    CHECK(p.draws() >= 2 + 9);
    CHECK(p.draws() <= 2 + 10);
    // The longest line drawn so far is blanked out at the end, and the cursor is back at column 0.
    std::size_t longest = 0;
    {
      const std::string s = os.str();
      std::size_t start = 0;
      while ((start = s.find('\r', start)) != std::string::npos) {
        const std::size_t next = s.find('\r', start + 1);
        longest = std::max(longest, (next == std::string::npos ? s.size() : next) - start - 1);
        start += 1;
      }
    }
    CHECK(longest >= width);
    p.end();
    CHECK_FALSE(p.active());
    const std::string tail = "\r" + std::string(longest, ' ') + "\r";
    REQUIRE(os.str().size() > tail.size());
    CHECK(os.str().substr(os.str().size() - tail.size()) == tail);
    // After the end nothing is drawn; a new stage draws at once again.
    const std::size_t size = os.str().size();
    p.update(0.9, 1e-3, 1, 1);
    CHECK(os.str().size() == size);
    p.begin("T", 1, 2);
    p.update(1.0, 1e-3, 1, 1);
    CHECK(os.str().substr(size) == "\rT  t = 1 of 2 (0.0%)  h = 0.001  Newton 1 (1 total)  elapsed 0.0 s, left ?");
  }

  TEST_CASE("a shorter line blanks out the rest of the longer one before it; clear() keeps the stage") {
    std::ostringstream os;
    double now = 0;
    progress_line p(os, [&] { return now; }, 0.1);
    p.begin(std::string(30, 'L'), 0, 1);
    p.update(0.5, 1e-3, 1, 1);
    const std::size_t first = os.str().size() - 1;
    p.begin("s", 0, 1);  // ends the stage (blanks) and starts another with a short label
    os.str("");
    p.update(0.5, 1e-3, 1, 1);
    const std::string line = format_progress({"s", 0, 0.5, 1, 1e-3, 1, 1, 0});
    CHECK(os.str() == "\r" + line);  // the previous line was cleared by the new begin()
    os.str("");
    p.begin(std::string(30, 'L'), 0, 1);
    p.update(0.5, 1e-3, 1, 1);
    now = 1;
    p.clear();  // e.g. for a message on the same terminal
    CHECK(os.str().substr(os.str().size() - first - 2) == "\r" + std::string(first, ' ') + "\r");
    CHECK(p.active());
    os.str("");
    p.update(0.6, 1e-3, 1, 1);
    CHECK(os.str().rfind("\r" + std::string(30, 'L') + "  t = 0.6 of 1 (60.0%)", 0) == 0);
    // Redrawing a shorter line over a longer one pads it with blanks.
    p.end();
    os.str("");
    p.begin("x", 0, 1);
    p.update(0.1, 1e-3, 1, 1);
    now = 2;
    p.update(0.123456, 1.23456e-3, 11, 111);
    now = 3;
    p.update(0.2, 1e-3, 1, 1);
    const std::string s = os.str();
    const std::string last = s.substr(s.rfind('\r') + 1);
    const std::string longer = format_progress({"x", 0, 0.123456, 1, 1.23456e-3, 11, 111, 1});
    const std::string shorter = format_progress({"x", 0, 0.2, 1, 1e-3, 1, 1, 2});
    REQUIRE(longer.size() > shorter.size());
    CHECK(last == shorter + std::string(longer.size() - shorter.size(), ' '));
  }
}
