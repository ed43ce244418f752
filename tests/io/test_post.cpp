// post.hpp: peak, longest_above and cumulative_above of a sampled series, against
// closed forms:
// - a triangle pulse (and a pair of them) on non-uniform times: the crossings of a
//   piecewise-linear signal sampled at its corners are exact by linear interpolation
//   (the interpolant is the signal), so the durations must agree to rounding;
// - a sampled sine: sin t >= 1/2 on [pi/6, 5 pi/6] (length 2 pi / 3); the linear
//   interpolant is off by at most h^2 max|y''| / 8 = h^2 / 8 (the error bound of linear
//   interpolation, e.g. Burden and Faires, Numerical Analysis, Theorem 3.3), so the
//   interpolated crossing is off by at most (h^2 / 8) / |cos(pi/6)| to first order;
// - every bad input is an error with its code (101 for the counts, 100 for the values).

#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "pradis/io/post.hpp"

using namespace pradis;

namespace {
/// The error a call throws: its code and message (code 0 if it does not throw).
struct thrown {
  int code = 0;
  std::string message;
};
thrown catch_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const error& e) {
    return {e.number(), e.message()};
  }
  return {};
}
}  // namespace

TEST_SUITE("io/post") {
  TEST_CASE("a triangle pulse sampled at its corners: the crossings are exact") {
    // y rises linearly from 0 at t = 0.5 to 100 at t = 2.0 and falls to 0 at t = 4.5;
    // the samples include the corners, the times are not uniform.
    const std::vector<double> t{0.0, 0.5, 1.1, 2.0, 2.3, 3.7, 4.5, 5.0};
    std::vector<double> y;
    for (double x : t) y.push_back(x <= 0.5 ? 0.0 : x <= 2.0 ? 100 * (x - 0.5) / 1.5 : x <= 4.5 ? 100 * (4.5 - x) / 2.5 : 0.0);
    // y >= 80 from 0.5 + 0.8 * 1.5 = 1.7 to 4.5 - 0.8 * 2.5 = 2.5.
    const post::interval s = post::longest_above(t, y, 80);
    REQUIRE(s.found());
    CHECK(s.start == doctest::Approx(1.7).epsilon(1e-14));
    CHECK(s.end == doctest::Approx(2.5).epsilon(1e-14));
    CHECK(s.duration == doctest::Approx(0.8).epsilon(1e-13));
    CHECK(post::cumulative_above(t, y, 80) == doctest::Approx(0.8).epsilon(1e-13));
    const post::peak_value p = post::peak(t, y);
    CHECK(p.value == 100);
    CHECK(p.time == 2.0);
    CHECK(p.index == 3);
    // A threshold above the peak: never reached.
    const post::interval none = post::longest_above(t, y, 100.5);
    CHECK_FALSE(none.found());
    CHECK(none.duration == 0);
    CHECK(post::cumulative_above(t, y, 100.5) == 0);
    // The threshold equal to the peak: a single point, found, of zero length.
    const post::interval touch = post::longest_above(t, y, 100);
    CHECK(touch.found());
    CHECK(touch.start == 2.0);
    CHECK(touch.duration == 0);
  }

  TEST_CASE("two pulses: the longest interval is the wider one, the cumulative time is the sum") {
    // Pulse 1: 0 at t = 0, 10 at t = 1, 0 at t = 2: y >= 6 on [0.6, 1.4] (0.8).
    // Pulse 2: 0 at t = 3, 10 at t = 5, 0 at t = 7: y >= 6 on [4.2, 5.8] (1.6).
    const std::vector<double> t{0, 1, 2, 3, 5, 7};
    const std::vector<double> y{0, 10, 0, 0, 10, 0};
    const post::interval s = post::longest_above(t, y, 6);
    CHECK(s.start == doctest::Approx(4.2).epsilon(1e-14));
    CHECK(s.end == doctest::Approx(5.8).epsilon(1e-14));
    CHECK(post::cumulative_above(t, y, 6) == doctest::Approx(2.4).epsilon(1e-14));
    // Of two equal maxima the first.
    CHECK(post::peak(t, y).time == 1);
  }

  TEST_CASE("a signal above the threshold at either end of the series: the interval is cut there") {
    const std::vector<double> t{0, 1, 2, 3, 4};
    const std::vector<double> y{5, 3, 0, 2, 4};
    // y >= 2.5 from t = 0 to the crossing 1 + (2.5 - 3) / (0 - 3) = 1 + 1/6,
    // and from 3 + 0.5 / 2 = 3.25 to the end 4.
    const post::interval s = post::longest_above(t, y, 2.5);
    CHECK(s.start == 0);
    CHECK(s.end == doctest::Approx(1 + 1.0 / 6).epsilon(1e-14));
    CHECK(post::cumulative_above(t, y, 2.5) == doctest::Approx(1 + 1.0 / 6 + 0.75).epsilon(1e-14));
    // Everything above: the whole series.
    const post::interval all = post::longest_above(t, y, -1);
    CHECK(all.start == 0);
    CHECK(all.end == 4);
    CHECK(all.duration == 4);
  }

  TEST_CASE("peak by magnitude returns the signed value of the largest |y|") {
    const std::vector<double> t{0.0, 0.1, 0.2, 0.3};
    const std::vector<double> y{1.0, 2.0, -3.0, 2.5};
    CHECK(post::peak(t, y).value == 2.5);
    const post::peak_value p = post::peak(t, y, post::peak_of::magnitude);
    CHECK(p.value == -3.0);
    CHECK(p.time == 0.2);
    CHECK(p.index == 2);
    // A single sample is its own peak.
    CHECK(post::peak(std::vector<double>{7.0}, std::vector<double>{-1.0}).time == 7.0);
  }

  TEST_CASE("a sampled sine: the time above 1/2 is 2 pi / 3 within the interpolation bound") {
    const double pi = std::numbers::pi;
    for (int n : {50, 200, 800}) {
      const double h = pi / n;
      std::vector<double> t, y;
      for (int i = 0; i <= n; ++i) {
        t.push_back(i * h);
        y.push_back(std::sin(i * h));
      }
      const post::interval s = post::longest_above(t, y, 0.5);
      const double bound = h * h / 8 / std::cos(pi / 6) * 1.01;  // 1 %: the second-order term of the bound
      CHECK(std::abs(s.start - pi / 6) <= bound);
      CHECK(std::abs(s.end - 5 * pi / 6) <= bound);
      CHECK(std::abs(s.duration - 2 * pi / 3) <= 2 * bound);
      // The interpolant lies below the concave sine: the interval is too short, never too long.
      CHECK(s.duration <= 2 * pi / 3);
      CHECK(post::cumulative_above(t, y, 0.5) == s.duration);
      const post::peak_value p = post::peak(t, y);
      CHECK(std::abs(p.time - pi / 2) <= h / 2);
    }
  }

  TEST_CASE("bad series and thresholds are refused with their codes") {
    const std::vector<double> t{0, 1, 2}, y{0, 1, 0};
    const std::vector<double> short_y{0, 1}, empty;
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    // Different lengths and no sample: code 101, for each function.
    thrown e = catch_error([&] { post::peak(t, short_y); });
    CHECK(e.code == 101);
    CHECK(e.message == "post::peak: the times have 3 samples, the values 2");
    CHECK(catch_error([&] { post::longest_above(t, short_y, 0.5); }).code == 101);
    CHECK(catch_error([&] { post::cumulative_above(t, short_y, 0.5); }).code == 101);
    e = catch_error([&] { post::peak(empty, empty); });
    CHECK(e.code == 101);
    CHECK(e.message == "post::peak: the series has no sample");
    // Times that repeat or go back: code 100.
    e = catch_error([&] { post::longest_above(std::vector<double>{0, 1, 1}, y, 0.5); });
    CHECK(e.code == 100);
    CHECK(e.message == "post::longest_above: the times must increase strictly: t[2] = 1 follows t[1] = 1");
    CHECK(catch_error([&] { post::cumulative_above(std::vector<double>{0, 2, 1}, y, 0.5); }).code == 100);
    // Values that are not finite: code 100, naming the sample.
    e = catch_error([&] { post::peak(t, std::vector<double>{0, nan, 0}); });
    CHECK(e.code == 100);
    CHECK(e.message == "post::peak: value y[1] = nan (t = 1) is not finite");
    e = catch_error([&] { post::cumulative_above(std::vector<double>{0, 1, inf}, y, 0.5); });
    CHECK(e.code == 100);
    CHECK(e.message == "post::cumulative_above: time t[2] = inf is not finite");
    // A threshold that is not finite: code 100.
    e = catch_error([&] { post::longest_above(t, y, nan); });
    CHECK(e.code == 100);
    CHECK(e.message == "post::longest_above: the threshold nan is not finite");
    CHECK(catch_error([&] { post::cumulative_above(t, y, -inf); }).code == 100);
  }
}
