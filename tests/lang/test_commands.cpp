// What `pradis list`, `pradis help NAME` and `pradis check NAME` print, tested
// through the library functions the program calls.

#include <doctest/doctest.h>

#include <sstream>

#include "pradis/lang/commands.hpp"

using namespace pradis;

namespace {
template <class E>
void check_reference() {
  std::ostringstream os, err;
  REQUIRE(lang::print_reference(os, err, E::passport.name));
  const std::string s = os.str();
  CAPTURE(s);
  // Every help line appears, generated from the element's own help text.
  for (std::string_view field : {E::help.title, E::help.name, E::help.field}) CHECK(s.find(field) != std::string::npos);
  for (std::string_view list : {E::help.dofs, E::help.parameters, E::help.work, E::help.special}) {
    std::size_t from = 0;
    while (from < list.size()) {
      const auto nl = list.find('\n', from);
      const std::string_view line =
          list.substr(from, nl == std::string_view::npos ? std::string_view::npos : nl - from);
      CHECK(s.find(line) != std::string::npos);
      if (nl == std::string_view::npos) break;
      from = nl + 1;
    }
  }
  CHECK(s.find("EXT=" + std::to_string(E::passport.ext)) != std::string::npos);
  CHECK(s.find("PAR=" + std::to_string(E::passport.par)) != std::string::npos);
}
template <class... Es>
void check_all_references(type_list<Es...>) {
  (check_reference<Es>(), ...);
}
template <class... Es>
void check_all_jacobians(type_list<Es...>) {
  (
      [] {
        std::ostringstream os, err;
        CAPTURE(Es::passport.name);
        CHECK(lang::check_by_name(os, err, Es::passport.name, {.points = 2}) == 0);
        CHECK(os.str().find("2 points checked, Jacobian OK") != std::string::npos);
      }(),
      ...);
}
}  // namespace

TEST_SUITE("lang/commands") {
  TEST_CASE("`pradis list` names every element and program") {
    std::ostringstream os;
    lang::print_catalog(os);
    const std::string s = os.str();
    for (const auto& n : lang::help_names()) CHECK(s.find("  " + n + " ") != std::string::npos);
    CHECK(s.find("LINKD    ideal elastic axial link for plane motion (EXT=4, PAR=5)") != std::string::npos);
    // The four integration programs, one line each with their purpose.
    CHECK(s.find("  SHTERM   Stoermer scheme") != std::string::npos);
    CHECK(s.find("  NEWMARK  Newmark scheme") != std::string::npos);
    CHECK(s.find("  HHT      Hilber-Hughes-Taylor alpha scheme: second order") != std::string::npos);
    CHECK(s.find("  GALPHA   generalized-alpha scheme: second order") != std::string::npos);
  }

  TEST_CASE("`pradis help NAME` prints the passport and every help line of every element") {
    check_all_references(elements::library_elements{});
  }

  TEST_CASE("`pradis help` knows programs, is case-insensitive and suggests names") {
    std::ostringstream os, err;
    CHECK(lang::print_reference(os, err, "newmark"));
    CHECK(os.str().find("BETA") != std::string::npos);
    CHECK(os.str().find("Not implemented yet (an error if given): WEIGHT CHECKM") != std::string::npos);
    CHECK(os.str().find("DRLTX - error control") != std::string::npos);
    CHECK(os.str().find("SAVE - write a checkpoint <stem>.t<time>.chk") != std::string::npos);
    std::ostringstream hht, galpha;
    CHECK(lang::print_reference(hht, err, "hht"));
    CHECK(hht.str().find("ALPHA - -1/3 <= ALPHA <= 0") != std::string::npos);
    CHECK(lang::print_reference(galpha, err, "GAlpha"));
    CHECK(galpha.str().find("RHOINF - spectral radius at infinite frequency, 0 <= RHOINF <= 1") != std::string::npos);
    CHECK_FALSE(lang::print_reference(os, err, "LINKDD"));
    CHECK(err.str().find("no element or program named 'LINKDD' (did you mean 'LINKD'?)") != std::string::npos);
  }

  TEST_CASE("`pradis check NAME` passes for every library element and prints the harness table") {
    check_all_jacobians(elements::library_elements{});
    std::ostringstream os, err;
    CHECK(lang::check_by_name(os, err, "LINKD", {.points = 1}) == 0);
    CHECK(os.str().find("flows at the point:") != std::string::npos);
    CHECK(os.str().find("numerical     analytical") != std::string::npos);
    CHECK(lang::check_by_name(os, err, "SPRNG", {}) == 1);  // docs/language.md: an unknown NAME exits 1
    CHECK(err.str().find("did you mean 'SPRING'?") != std::string::npos);
  }
}
