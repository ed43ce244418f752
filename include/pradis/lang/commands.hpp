#pragma once
/// \file
/// What the `pradis` program prints: the catalog (`pradis list`), the reference
/// of an element or program (`pradis help NAME`, generated from E::passport and
/// E::help) and the finite-difference Jacobian check of an element (`pradis
/// check NAME`, the manual's section 3.6.8 harness at random admissible states).
/// Kept in the library so that tests can call them without the executable.

#include <iomanip>
#include <optional>
#include <ostream>
#include <random>
#include <string>
#include <string_view>

#include "pradis/elements/library.hpp"
#include "pradis/lang/catalog.hpp"
#include "pradis/lang/source.hpp"
#include "pradis/testing/jacobian_check.hpp"

namespace pradis::lang {

namespace detail {
inline void indented_lines(std::ostream& os, std::string_view text, std::string_view indent = "  ") {
  while (!text.empty()) {
    const auto nl = text.find('\n');
    os << indent << text.substr(0, nl) << '\n';
    if (nl == std::string_view::npos) break;
    text.remove_prefix(nl + 1);
  }
}
inline void program_list(std::ostream& os, const char* title, const std::vector<program_info>& v) {
  os << title << '\n';
  for (const auto& p : v) os << "  " << std::left << std::setw(8) << p.name << ' ' << p.purpose << '\n';
}
}  // namespace detail

/// `pradis list`: elements, integration, output and display programs, one line each.
inline void print_catalog(std::ostream& os) {
  os << "Element models (#STRUCTURE: Name 'MODEL (nodes; parameters)):\n";
  library_model::for_each_type([&]<class E>(std::type_identity<E>) {
    os << "  " << std::left << std::setw(8) << E::passport.name << ' ' << E::help.title << " (EXT=" << E::passport.ext
       << ", PAR=" << E::passport.par << ")\n";
  });
  detail::program_list(os, "Nodes with an equation (#STRUCTURE: Name 'NODE (nodes; parameters)):", node_programs());
  detail::program_list(os, "Integration programs ($RUN: Label 'PROGRAM (END=..., ...)):", integration_programs());
  detail::program_list(os, "Output programs (#OUTPUT: Label 'PROGRAM (...)):", output_programs());
  detail::program_list(os, "Display programs ($PRINT: Label 'PROGRAM (...)):", display_programs());
  os << "`pradis help NAME` prints the full reference of one of them.\n";
}

/// The full reference of element type E, from its passport and help text.
template <class E>
void print_element_reference(std::ostream& os) {
  constexpr passport p = E::passport;
  constexpr element_help h = E::help;
  os << p.name << " - " << h.title << "\n\n" << h.name << "\nField: " << h.field << "\n\n";
  os << "Passport: EXT=" << p.ext << " ENT=" << p.ent << " PAR=" << p.par << " VPR=" << p.vpr << " STR=" << p.str
     << " STP=" << p.stp << " WRK=" << p.wrk << " WRP=" << p.wrp << " ADR=" << p.adr << " IGN=" << p.ign << '\n';
  os << "Jacobian blocks:" << (p.has_k() ? " dF/du" : "") << (p.has_c() ? " dF/dv" : "") << (p.has_m() ? " dF/da" : "")
     << "\n\n";
  os << "Usage: Name '" << p.name << " (";
  for (int k = 1; k <= p.ext; ++k) os << (k > 1 ? " " : "") << "n" << k;
  os << "; ";
  for (int k = 1; k <= p.par; ++k) os << (k > 1 ? ", " : "") << "p" << k;
  if (p.vpr != 0) os << ", ...";
  os << ")\n\nNodes (" << p.ext << "):\n";
  detail::indented_lines(os, h.dofs);
  os << "Parameters (" << p.parameter_rule() << " = " << p.par << "):\n";
  detail::indented_lines(os, h.parameters);
  if (p.wrk + p.wrp > 0) {
    os << "Work vector (output with 'X (W:Name(k); 1)):\n";
    if (h.work.empty())
      os << "  (internal use)\n";
    else
      detail::indented_lines(os, h.work);
  }
  os << "Special situations:\n";
  detail::indented_lines(os, h.special);
}

/// The reference of a non-element program.
inline void print_program_reference(std::ostream& os, const program_info& p, std::string_view kind) {
  os << p.name << " - " << p.purpose << "\n\n" << kind << "\nUsage: " << p.usage << '\n';
  if (kind == "integration program") {
    os << "Keys:\n";
    detail::indented_lines(os, common_run_keys());
    if (!p.keys.empty()) detail::indented_lines(os, p.keys);
    os << "Not implemented yet (an error if given):";
    for (const auto& k : unimplemented_run_keys()) os << ' ' << k;
    os << '\n';
  } else if (kind == "node program") {
    detail::indented_lines(os, p.keys);
  } else if (!p.keys.empty()) {
    os << "Keys:\n";
    detail::indented_lines(os, p.keys);
  }
}

/// Every name `pradis help` knows (for suggestions).
inline std::vector<std::string> help_names() {
  std::vector<std::string> v = element_names();
  for (const auto* l : {&node_programs(), &integration_programs(), &output_programs(), &display_programs()})
    for (const auto& p : *l) v.emplace_back(p.name);
  return v;
}

/// `pradis help NAME` (NAME case-insensitive). Returns false if NAME is unknown
/// (and prints a message with the nearest name to `err`).
inline bool print_reference(std::ostream& os, std::ostream& err, std::string_view name) {
  const std::string n = upper(name);
  bool found = false;
  library_model::for_each_type([&]<class E>(std::type_identity<E>) {
    if (!found && E::passport.name == n) {
      print_element_reference<E>(os);
      found = true;
    }
  });
  if (found) return true;
  if (auto* np = find_program(node_programs(), n))
    print_program_reference(os, *np, "node program");
  else if (auto* p = find_program(integration_programs(), n))
    print_program_reference(os, *p, "integration program");
  else if (auto* q = find_program(output_programs(), n))
    print_program_reference(os, *q, "output program");
  else if (auto* r = find_program(display_programs(), n))
    print_program_reference(os, *r, "display program");
  else {
    err << "pradis: error: no element or program named '" << printable(name) << "'" << did_you_mean(n, help_names())
        << "; `pradis list` shows the catalog\n";
    return false;
  }
  return true;
}

/// Options of `pradis check`.
struct check_options {
  int points = 3;          ///< random admissible states to check
  unsigned seed = 12345;   ///< random seed
  double amplitude = 0.3;  ///< displacements up to +-amplitude; velocities and accelerations up to +-10
  bool verbose = true;     ///< print the table at every point (otherwise only failing points)
};

/// Checks element type E with its example parameters. Returns true if every point passes.
template <class E>
bool check_element_jacobian(std::ostream& os, const check_options& o) {
  constexpr passport p = E::passport;
  testing::jacobian_checker<E> chk{E(E::example())};
  std::mt19937 rng(o.seed);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  os << "Finite-difference check of the Jacobian of " << p.name << " (" << E::help.title
     << "), example parameters, central differences\n";
  int checked = 0, failed = 0;
  for (int attempt = 0; checked < o.points && attempt < 1000 * o.points; ++attempt) {
    local_input<E> in;
    for (int k = 0; k < element_traits<E>::n; ++k) {
      in.u(k) = o.amplitude * uni(rng);
      in.v(k) = 10 * uni(rng);
      in.a(k) = 10 * uni(rng);
    }
    in.t = 1.0 + uni(rng);
    if constexpr (requires(const E& e) { e.admissible(in); })
      if (!chk.element().admissible(in)) continue;
    ++checked;
    const auto r = chk.check(in);
    if (!r.ok) ++failed;
    if (!o.verbose && r.ok) continue;
    os << "\npoint " << checked << ": t = " << in.t << '\n' << std::scientific << std::setprecision(5);
    for (int k = 0; k < element_traits<E>::n; ++k)
      os << "  DOF " << k + 1 << ": u = " << std::setw(12) << in.u(k) << "  v = " << std::setw(12) << in.v(k)
         << "  a = " << std::setw(12) << in.a(k) << '\n';
    const auto f = chk.flows(in);
    os << "flows at the point:\n";
    for (int k = 0; k < element_traits<E>::n; ++k) os << "  F" << k + 1 << " = " << std::setw(13) << f(k) << '\n';
    os << std::defaultfloat;
    r.print(os);
  }
  os << '\n'
     << p.name << ": " << checked << " point" << (checked == 1 ? "" : "s") << " checked, "
     << (failed == 0 ? "Jacobian OK" : std::to_string(failed) + " with a WRONG Jacobian") << '\n';
  return failed == 0 && checked > 0;
}

/// `pradis check NAME`: the exit status of the command. Returns 0 if the
/// Jacobian is right, 1 if it is wrong or NAME is not an element (then with a
/// message and the nearest name on `err`), as docs/language.md states.
inline int check_by_name(std::ostream& os, std::ostream& err, std::string_view name, const check_options& o) {
  const std::string n = upper(name);
  std::optional<bool> ok;  // empty: no element of that name
  library_model::for_each_type([&]<class E>(std::type_identity<E>) {
    if (!ok && E::passport.name == n) ok = check_element_jacobian<E>(os, o);
  });
  if (!ok && find_program(node_programs(), n))
    err << "pradis: error: " << n << " is a node program, not an element: `pradis check` checks elements (the "
        << "node's equation and its carry are checked by finite differences in the test suite)\n";
  else if (!ok)
    err << "pradis: error: no element named '" << printable(name) << "'" << did_you_mean(n, element_names())
        << "; `pradis list` shows the catalog\n";
  return ok && *ok ? 0 : 1;
}

}  // namespace pradis::lang
