#pragma once
// Plotting of a results table with gnuplot: an application concern (it runs an
// external program), so it lives with the programs, not in the library. Used by
// the `pradis` program ('DISP) and the examples.

#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace pradis_apps {

/// A label safe inside single quotes in a gnuplot script.
inline std::string gnuplot_label(const std::string& s) {
  std::string o;
  for (char ch : s) o += (ch == '\'' || ch == '\n' || ch == '\\') ? ' ' : ch;
  return o;
}

/// Plots every column of the CSV file `csv` (written by pradis::io::table or
/// csv_file: time first, then one column per name) against time, one panel per
/// column, into the PNG `png` with gnuplot (which must be on PATH). Writes the
/// gnuplot script next to the image (`<png>.gp`). Returns "" on success, else
/// the reason of the failure (the caller reports it; a missing gnuplot is not
/// worth losing a run for).
inline std::string plot_png(const std::vector<std::string>& names, const std::string& csv, const std::string& png,
                            const std::string& title) {
  // Paths go into a gnuplot script and a shell command in single quotes: refuse
  // characters that would end the quoting rather than escape them.
  for (const std::string* s : {&csv, &png})
    if (s->find_first_of("'\"\n\\`$") != std::string::npos)
      return "cannot plot to or from '" + *s + "': the path contains a quote, backslash, $, backquote or newline";
  const std::string script = png + ".gp";
  {
    std::ofstream g(script);
    if (!g) return "cannot write '" + script + "'";
    const std::size_t n = names.size();
    g << "set datafile separator ','\n"
      << "set terminal pngcairo size 900," << 260 * n + 60 << " font 'sans,10'\n"
      << "set output '" << png << "'\n"
      << "set multiplot layout " << n << ",1 title '" << gnuplot_label(title) << "'\n"
      << "set grid\nset key off\n";
    for (std::size_t c = 0; c < n; ++c) {
      g << "set ylabel '" << gnuplot_label(names[c]) << "'\n";
      if (c + 1 == n) g << "set xlabel 't [s]'\n";
      g << "plot '" << csv << "' using 1:" << c + 2 << " every ::1 with lines lw 2\n";
    }
    g << "unset multiplot\n";
    g.close();
    if (!g) return "cannot write '" + script + "'";
  }
  const std::string cmd = "gnuplot '" + script + "' 2>/dev/null";
  if (std::system(cmd.c_str()) != 0) return "gnuplot failed on '" + script + "' (is gnuplot installed?)";
  return {};
}

}  // namespace pradis_apps
