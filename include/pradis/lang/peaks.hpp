#pragma once
/// \file
/// The 'PEAK display of the model language: per output, the peak and the
/// longest and total time at or above a threshold over a time window of the
/// results (io/post.hpp), as records, log lines and a CSV file.

#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "pradis/io/csv_file.hpp"
#include "pradis/io/post.hpp"
#include "pradis/io/table.hpp"
#include "pradis/lang/run_types.hpp"

namespace pradis::lang {

/// The summaries of the result columns `columns` (0-based output indices;
/// `labels` names every output) over the rows with start <= t <= end, for the
/// display named `display`. Without a threshold only the peak is found (longest
/// has duration 0, total is 0). Throws pradis::error: invalid_option if no row
/// is in the window; post.hpp's errors (a non-finite value) prefixed with the
/// output's label.
inline std::vector<peak_summary> peak_summaries(const io::table& results, const std::vector<std::string>& labels,
                                                const std::vector<int>& columns, double start, double end,
                                                std::optional<double> threshold, bool magnitude,
                                                const std::string& display) {
  std::vector<std::size_t> rows;
  std::vector<double> t;
  for (std::size_t r = 0; r < results.rows(); ++r)
    if (results.at(r, 0) >= start && results.at(r, 0) <= end) {
      rows.push_back(r);
      t.push_back(results.at(r, 0));
    }
  if (t.empty()) throw error(error_code::invalid_option, "no output row between START and END");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<peak_summary> out;
  for (int k : columns) {
    std::vector<double> y;
    for (std::size_t r : rows) y.push_back(results.at(r, static_cast<std::size_t>(k) + 1));
    peak_summary p{display, labels.at(static_cast<std::size_t>(k)), {}, threshold, {nan, nan, 0}, 0};
    try {
      p.peak = post::peak(t, y, magnitude ? post::peak_of::magnitude : post::peak_of::maximum);
      if (threshold) {
        p.longest = post::longest_above(t, y, *threshold);
        p.total = post::cumulative_above(t, y, *threshold);
      }
    } catch (const error& e) {
      throw error(e.code(), "output '" + p.output + "': " + e.message());
    }
    out.push_back(p);
  }
  return out;
}

/// One line for the log: "Label: peak P at t = T; at or above C: longest D (t = A .. B), total S".
inline std::string describe(const peak_summary& p) {
  const auto num = [](double x) { return to_text(x); };
  std::string s = p.output + ": peak " + num(p.peak.value) + " at t = " + num(p.peak.time);
  if (p.threshold) {
    s += "; at or above " + num(*p.threshold) + ": longest " + num(p.longest.duration);
    if (p.longest.found()) s += " (t = " + num(p.longest.start) + " .. " + num(p.longest.end) + ")";
    s += ", total " + num(p.total);
  }
  return s;
}

/// Writes the summaries as CSV: a row per output with the columns output, peak,
/// t_peak, threshold, longest, longest_start, longest_end, total_above (nan where
/// there is no threshold or the threshold is never reached). Throws io_error.
inline void write_peak_csv(const std::string& path, const std::vector<peak_summary>& found) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  io::csv_file f(path, {"peak", "t_peak", "threshold", "longest", "longest_start", "longest_end", "total_above"},
                 "output");
  for (const auto& p : found) {
    const double row[] = {p.peak.value,    p.peak.time,   p.threshold ? *p.threshold : nan,
                          p.threshold ? p.longest.duration : nan, p.longest.start, p.longest.end,
                          p.threshold ? p.total : nan};
    f.add_row(p.output, std::span<const double>(row));
  }
  f.commit();
}

}  // namespace pradis::lang
