#pragma once
/// \file
/// A one-line progress display for long runs on a terminal: simulated time,
/// percentage of the stage, current step size, Newton iterations, elapsed and
/// estimated remaining wall time. The line is redrawn in place with '\r' at most
/// every `interval` seconds (default 0.1 s, so at most about ten times per
/// second) and cleared when the stage ends. Whether to show it at all (only on
/// a terminal) is the caller's decision: `pradis run` writes it to stderr when
/// stderr is a terminal.
///
/// Usage:
///     pradis::io::progress_line p(std::cerr);
///     p.begin("Calculation SHTERM", t0, end);
///     sim.on_output([&](const auto& s) {
///       p.update(s.time(), s.statistics().last_step, s.statistics().last_iterations,
///                s.statistics().newton_iterations);
///     });
///     sim.run(...);
///     p.end();

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>

namespace pradis::io {

/// The figures one progress line shows.
struct progress_figures {
  std::string_view label;       ///< what runs (stage label and program); may be empty
  double t0 = 0;                ///< simulated time at the start of the stage
  double time = 0;              ///< current simulated time
  double end = 1;               ///< END of the stage
  double step = 0;              ///< size of the last accepted step (0: none yet)
  int iterations = 0;           ///< Newton iterations of the last accepted step
  long total_iterations = 0;    ///< Newton iterations of the whole run so far
  double elapsed = 0;           ///< wall-clock seconds since the stage began
};

/// A wall-clock duration for people: "12.3 s" below a minute, "4:05 min" below
/// an hour, "1:02:03 h" above; "?" when negative or not finite.
inline std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  char buf[48];
  if (seconds < 59.95) {
    std::snprintf(buf, sizeof buf, "%.1f s", seconds);
  } else if (seconds < 3599.5) {
    const long s = std::lround(seconds);
    std::snprintf(buf, sizeof buf, "%ld:%02ld min", s / 60, s % 60);
  } else if (seconds < 1e9) {
    const long s = std::lround(seconds);
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld h", s / 3600, (s / 60) % 60, s % 60);
  } else {
    return "> 30 years";
  }
  return buf;
}

/// The text of one progress line (without '\r'), for example
/// `Calc SHTERM  t = 0.25 of 1 (25.0%)  h = 0.001  Newton 2 (1234 total)  elapsed 1.5 s, left 4.5 s`.
/// The percentage is the fraction of the stage done, (time - t0) / (end - t0),
/// clamped to [0, 100]. The remaining time is estimated by assuming the rest of
/// the stage runs at the average rate so far: elapsed (end - time) / (time - t0);
/// it is "?" before the stage has advanced. A step of 0 (none taken yet) is shown
/// as "-".
inline std::string format_progress(const progress_figures& f) {
  const double span = f.end - f.t0, done = f.time - f.t0;
  double fraction = span > 0 ? done / span : 1.0;
  if (!(fraction >= 0)) fraction = 0;
  if (fraction > 1) fraction = 1;
  const double left = done > 0 && f.elapsed >= 0 ? f.elapsed * (f.end - f.time) / done : -1.0;
  char t[32], e[32], pct[16], h[32];
  std::snprintf(t, sizeof t, "%.6g", f.time);
  std::snprintf(e, sizeof e, "%.6g", f.end);
  std::snprintf(pct, sizeof pct, "%.1f%%", 100.0 * fraction);
  if (f.step > 0)
    std::snprintf(h, sizeof h, "%.3g", f.step);
  else
    std::snprintf(h, sizeof h, "-");
  std::string s;
  if (!f.label.empty()) {
    s.append(f.label.substr(0, 40));
    s += "  ";
  }
  s += "t = ";
  s += t;
  s += " of ";
  s += e;
  s += " (";
  s += pct;
  s += ")  h = ";
  s += h;
  s += "  Newton " + std::to_string(f.iterations) + " (" + std::to_string(f.total_iterations) + " total)";
  s += "  elapsed " + format_duration(f.elapsed) + ", left " + format_duration(left);
  return s;
}

/// Wall-clock seconds from a monotonic clock (the default clock of progress_line).
inline double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// A progress line redrawn in place on a stream (a terminal): begin() starts a
/// stage, update() redraws at most once per interval, end() clears the line.
class progress_line {
 public:
  /// A clock returning seconds (monotonic); replaceable for tests.
  using clock_function = std::function<double()>;

  /// Draws on `os`, at most once every `interval` seconds of `clock`.
  explicit progress_line(std::ostream& os, clock_function clock = steady_seconds, double interval = 0.1)
      : os_(os), clock_(std::move(clock)), interval_(interval) {}
  progress_line(const progress_line&) = delete;
  progress_line& operator=(const progress_line&) = delete;
  /// Clears the line if a stage is still shown.
  ~progress_line() { end(); }

  /// Starts a stage from simulated time t0 to `end`; the elapsed time counts from here.
  void begin(std::string label, double t0, double end) {
    this->end();
    label_ = std::move(label);
    t0_ = t0;
    end_ = end;
    start_ = clock_();
    active_ = true;
    drawn_once_ = false;
  }

  /// Reports the current state; redraws the line if it has not been drawn in
  /// this stage yet or `interval` seconds have passed since the last drawing.
  /// Does nothing outside begin() ... end().
  void update(double time, double step, int iterations, long total_iterations) {
    if (!active_) return;
    const double now = clock_();
    if (drawn_once_ && now - last_draw_ < interval_) return;
    const std::string line =
        format_progress({label_, t0_, time, end_, step, iterations, total_iterations, now - start_});
    // Blanks after a shorter line erase the rest of the previous one.
    os_ << '\r' << line << std::string(line.size() < width_ ? width_ - line.size() : 0, ' ');
    os_.flush();
    width_ = std::max(width_, line.size());
    last_draw_ = now;
    drawn_once_ = true;
    ++draws_;
  }

  /// Ends the stage: the line is cleared (overwritten with blanks), so that the
  /// next output starts at the beginning of an empty line.
  void end() {
    if (!active_) return;
    active_ = false;
    clear();
  }

  /// Erases the line for other output; the stage goes on and the next update()
  /// draws the line again at once.
  void clear() {
    if (width_ > 0) {
      os_ << '\r' << std::string(width_, ' ') << '\r';
      os_.flush();
    }
    width_ = 0;
    drawn_once_ = false;
  }

  /// True between begin() and end().
  bool active() const noexcept { return active_; }
  /// Number of times a line was drawn (all stages).
  long draws() const noexcept { return draws_; }

 private:
  std::ostream& os_;
  clock_function clock_;
  double interval_;
  std::string label_;
  double t0_ = 0, end_ = 1, start_ = 0, last_draw_ = 0;
  std::size_t width_ = 0;
  long draws_ = 0;
  bool active_ = false, drawn_once_ = false;
};

}  // namespace pradis::io
