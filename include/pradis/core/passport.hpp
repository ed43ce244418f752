#pragma once
/// \file
/// The element passport: the constexpr aggregate that describes an element type to
/// the kernel, with every key of the PRADIS element developer's manual, section 3.3.

#include <string_view>

namespace pradis {

/// Passport of an element type (manual section 3.3), one constexpr aggregate.
///
/// | key  | member | meaning |
/// |------|--------|---------|
/// | name | name   | catalog (MODEL) name, e.g. "LINKD"; looked up by the model language |
/// | EXT  | ext    | external DOFs the user connects (> 0) |
/// | ENT  | ent    | internal DOFs, allocated by the model and hidden from the user |
/// | PAR  | par    | parameter count; with VPR the minimum count |
/// | VPR  | vpr    | 0 fixed count, 1 variable (>= PAR), 11 variable and odd, 21 variable and even |
/// | STR  | str    | fixed part of the state vector (NEW/OLD) |
/// | STP  | stp    | state entries per extra parameter |
/// | WRK  | wrk    | fixed part of the work vector |
/// | WRP  | wrp    | work entries per extra parameter |
/// | ADR  | adr    | 1: blocks by u, v, a; 2: by v, a ("written relative to velocities"); 3: by a only |
/// | IGN  | ign    | 2: velocity block zero; 3: acceleration block zero; 23: both |
///
/// From ADR/IGN the library derives at compile time which local Jacobian blocks
/// exist: K = dF/du, C = dF/dv, M = dF/da (see has_k(), has_c(), has_m()).
struct passport {
  std::string_view name{};
  int ext = 0;
  int ent = 0;
  int par = 1;
  int vpr = 0;
  int str = 0;
  int stp = 0;
  int wrk = 0;
  int wrp = 0;
  int adr = 1;
  int ign = 0;

  /// Total local DOFs N = EXT + ENT.
  constexpr int dofs() const noexcept { return ext + ent; }
  /// True when the stiffness block dF/du exists (ADR = 1).
  constexpr bool has_k() const noexcept { return adr == 1; }
  /// True when the viscosity block dF/dv exists (ADR <= 2 and IGN is not 2 or 23).
  constexpr bool has_c() const noexcept { return adr <= 2 && ign != 2 && ign != 23; }
  /// True when the inertia block dF/da exists (IGN is not 3 or 23).
  constexpr bool has_m() const noexcept { return ign != 3 && ign != 23; }
  /// True when the element accepts a variable parameter count.
  constexpr bool variable_parameters() const noexcept { return vpr != 0; }
  /// Whether `npar` parameters satisfy PAR/VPR.
  constexpr bool parameter_count_ok(int npar) const noexcept {
    if (vpr == 0) return npar == par;
    if (npar < par) return false;
    if (vpr == 11) return npar % 2 == 1;
    if (vpr == 21) return npar % 2 == 0;
    return true;
  }
  /// Length of the state vector for `npar` parameters: STR + (npar - PAR) * STP.
  constexpr int state_size(int npar) const noexcept { return str + (npar - par) * stp; }
  /// Length of the work vector for `npar` parameters: WRK + (npar - PAR) * WRP.
  constexpr int work_size(int npar) const noexcept { return wrk + (npar - par) * wrp; }
  /// A sentence describing the PAR/VPR rule, for error messages.
  constexpr std::string_view parameter_rule() const noexcept {
    switch (vpr) {
      case 0: return "exactly PAR";
      case 1: return "at least PAR";
      case 11: return "an odd number, at least PAR,";
      case 21: return "an even number, at least PAR,";
      default: return "?";
    }
  }

  friend constexpr bool operator==(const passport&, const passport&) = default;
};

/// Checks a passport; returns nullptr when it is valid, otherwise one sentence
/// saying what is wrong. Usable in constant expressions.
constexpr const char* passport_problem(const passport& p) noexcept {
  if (p.name.empty()) return "the passport has no catalog name";
  if (p.ext <= 0) return "EXT must be > 0";
  if (p.ent < 0) return "ENT must be >= 0";
  if (p.par < 0) return "PAR must be >= 0";
  if (p.vpr != 0 && p.vpr != 1 && p.vpr != 11 && p.vpr != 21) return "VPR must be 0, 1, 11 or 21";
  if (p.str < 0 || p.stp < 0) return "STR and STP must be >= 0";
  if (p.wrk < 0 || p.wrp < 0) return "WRK and WRP must be >= 0";
  if (p.vpr == 0 && (p.stp != 0 || p.wrp != 0)) return "STP and WRP need a variable parameter count (VPR != 0)";
  if (p.adr < 1 || p.adr > 3) return "ADR must be 1, 2 or 3";
  if (p.ign != 0 && p.ign != 2 && p.ign != 3 && p.ign != 23) return "IGN must be 0, 2, 3 or 23";
  if (p.adr == 2 && (p.ign == 2 || p.ign == 23)) return "ADR=2 allows IGN=0 or IGN=3 only";
  if (p.adr == 3 && p.ign != 0) return "ADR=3 allows IGN=0 only";
  return nullptr;
}

/// Help text of an element type (manual section 3.4), shown by `pradis help NAME`.
/// List fields hold one line per entry, separated by '\n', in DOF / PAR / WRK
/// order; the all-elements test checks their counts against the passport.
struct element_help {
  std::string_view title{};       ///< first line: what the element is, in a few words
  std::string_view name{};        ///< full name
  std::string_view field{};       ///< field of application
  std::string_view dofs{};        ///< one line per external DOF
  std::string_view parameters{};  ///< one line per parameter, with unit and admissible range
  std::string_view work{};        ///< one line per work-vector entry useful as output
  std::string_view special{};     ///< special situations (errors during the run, limits)
};

/// Number of '\n'-separated non-empty lines in a help list.
constexpr int help_lines(std::string_view s) noexcept {
  if (s.empty()) return 0;
  int n = 1;
  for (char c : s)
    if (c == '\n') ++n;
  if (s.back() == '\n') --n;
  return n;
}

}  // namespace pradis
