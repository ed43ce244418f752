#pragma once
/// \file
/// Post-processing of a sampled time series (t_i, y_i): the peak, the longest
/// contiguous time the signal stays at or above a threshold, and the total time
/// above it. Pure functions over spans, so they serve C++ programs (an output
/// observer fills two vectors) and, later, the model language.
///
/// Between samples the signal is taken as the straight line through them (the
/// piecewise-linear interpolant): a crossing of the threshold between a sample
/// below and one at or above is interpolated linearly, so the durations are
/// exact for a piecewise-linear signal sampled at its corners, and for a smooth
/// signal the crossing time is off by at most h^2 max|y''| / (8 |y'|) (the error
/// of linear interpolation, h^2/8 max|y''|, over the slope at the crossing).
///
/// Bad input is a pradis::error: t and y of different lengths, or no sample, is
/// code 101 (wrong count); a time that does not increase strictly, or a value
/// (time, sample, threshold) that is not finite, is code 100 (invalid parameter).

#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <string>

#include "pradis/core/error.hpp"

namespace pradis::post {

/// Which extreme `peak` looks for.
enum class peak_of {
  maximum,    ///< the largest y
  magnitude,  ///< the largest |y| (the value is returned with its sign)
};

/// A sample where the peak occurs (the sample itself; no interpolation between samples).
struct peak_value {
  double value = 0;       ///< y at the peak (signed, also for peak_of::magnitude)
  double time = 0;        ///< t at the peak
  std::size_t index = 0;  ///< index of that sample (the first one if several are equal)
};

/// A time interval [start, end] of the piecewise-linear signal.
struct interval {
  double start = 0;     ///< start time (a threshold crossing, or the first sample's time)
  double end = 0;       ///< end time (a threshold crossing, or the last sample's time)
  double duration = 0;  ///< end - start; 0 and start = end = NaN when the signal never reaches the threshold
  /// Whether the signal reaches the threshold at all.
  bool found() const { return !std::isnan(start); }
};

namespace detail {

/// Checks a series (see the file comment for the codes); `what` names the function.
inline void check_series(std::span<const double> t, std::span<const double> y, const char* what) {
  const std::string f = std::string("post::") + what + ": ";
  if (t.size() != y.size())
    throw error(error_code::parameter_count,
                f + "the times have " + std::to_string(t.size()) + " samples, the values " + std::to_string(y.size()));
  if (t.empty()) throw error(error_code::parameter_count, f + "the series has no sample");
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (!std::isfinite(t[i]))
      throw error(error_code::invalid_parameter, f + "time t[" + std::to_string(i) + "] = " + to_text(t[i]) + " is not finite");
    if (!std::isfinite(y[i]))
      throw error(error_code::invalid_parameter,
                  f + "value y[" + std::to_string(i) + "] = " + to_text(y[i]) + " (t = " + to_text(t[i]) + ") is not finite");
    if (i > 0 && !(t[i] > t[i - 1]))
      throw error(error_code::invalid_parameter, f + "the times must increase strictly: t[" + std::to_string(i) +
                                                     "] = " + to_text(t[i]) + " follows t[" + std::to_string(i - 1) +
                                                     "] = " + to_text(t[i - 1]));
  }
}

inline void check_threshold(double threshold, const char* what) {
  if (!std::isfinite(threshold))
    throw error(error_code::invalid_parameter,
                std::string("post::") + what + ": the threshold " + to_text(threshold) + " is not finite");
}

/// Time where the line from (t0, y0) to (t1, y1) reaches the threshold c (y0 != y1).
inline double crossing(double t0, double y0, double t1, double y1, double c) {
  return t0 + (t1 - t0) * (c - y0) / (y1 - y0);
}

/// Calls f(interval) for every maximal interval where the interpolant is >= threshold.
template <class F>
void for_each_above(std::span<const double> t, std::span<const double> y, double c, F&& f) {
  const std::size_t n = t.size();
  std::size_t i = 0;
  while (i < n) {
    if (y[i] < c) {
      ++i;
      continue;
    }
    // Samples i .. j-1 are at or above: the interval starts at the crossing before i.
    const double start = i == 0 ? t[0] : crossing(t[i - 1], y[i - 1], t[i], y[i], c);
    std::size_t j = i;
    while (j < n && y[j] >= c) ++j;
    const double end = j == n ? t[n - 1] : crossing(t[j - 1], y[j - 1], t[j], y[j], c);
    f(interval{start, end, end - start});
    i = j;
  }
}

}  // namespace detail

/// The sample with the largest y (peak_of::maximum, the default) or the largest |y|
/// (peak_of::magnitude). Throws as described in the file comment.
inline peak_value peak(std::span<const double> t, std::span<const double> y, peak_of kind = peak_of::maximum) {
  detail::check_series(t, y, "peak");
  std::size_t best = 0;
  for (std::size_t i = 1; i < y.size(); ++i) {
    const bool larger = kind == peak_of::maximum ? y[i] > y[best] : std::abs(y[i]) > std::abs(y[best]);
    if (larger) best = i;
  }
  return {y[best], t[best], best};
}

/// The longest contiguous interval in which the piecewise-linear signal is at or above
/// `threshold`, with its start and end (crossings interpolated linearly between
/// samples; an interval open at either end of the series is cut there). Of equally
/// long intervals, the first. If no sample reaches the threshold: duration 0 and
/// start = end = NaN (interval::found() is false). Throws as described in the file comment.
inline interval longest_above(std::span<const double> t, std::span<const double> y, double threshold) {
  detail::check_series(t, y, "longest_above");
  detail::check_threshold(threshold, "longest_above");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  interval best{nan, nan, 0};
  detail::for_each_above(t, y, threshold, [&](const interval& s) {
    if (!best.found() || s.duration > best.duration) best = s;
  });
  return best;
}

/// The total time in which the piecewise-linear signal is at or above `threshold`
/// (the sum of the durations of all such intervals; 0 if it never is). Throws as
/// described in the file comment.
inline double cumulative_above(std::span<const double> t, std::span<const double> y, double threshold) {
  detail::check_series(t, y, "cumulative_above");
  detail::check_threshold(threshold, "cumulative_above");
  double total = 0;
  detail::for_each_above(t, y, threshold, [&](const interval& s) { total += s.duration; });
  return total;
}

}  // namespace pradis::post
