// Kernel error paths that no other test reaches:
// - a NaN or infinite viscosity (dF/dv) or inertia (dF/da) Jacobian entry is code
//   150 naming the element type and instance and the block (the dF/du case is in
//   test_bad_input.cpp), with NEWMARK and with BDF, at the zero step and during
//   a step, for an element with all three blocks and for one with that block only;
// - run_options with SMIN <= 0, a negative DRLTU, DABSI or DRLTI, or both Newton
//   tolerances of a pair zero are code 120 naming the option, in
//   pradis::simulation and pradis::bdf_simulation (check_options is shared), and
//   the run does not start;
// - a diagnostics file that cannot be opened is code 160 naming the path.

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>

#include "pradis/core/diagnostics.hpp"
#include "pradis/elements/library.hpp"
#include "pradis/integrators/bdf/bdf_simulation.hpp"
#include "pradis/integrators/newmark.hpp"
#include "pradis/integrators/simulation.hpp"
#include "testing/test_support.hpp"

using namespace pradis;
using namespace pradis::elements;

namespace {

/// A linear element f = 5 u + 0.5 v + a (the terms of the blocks it has) whose
/// Jacobian goes bad from time t_bad on: mode 0 dF/dv NaN, 1 dF/dv +inf,
/// 2 dF/da NaN, 3 dF/da -inf. Adr/Ign select the blocks: (1, 0) K, C and M;
/// (2, 3) C only; (3, 0) M only.
template <int Adr, int Ign>
struct ep_bad_block {
  static constexpr pradis::passport passport{.name = Adr == 1 ? "EPBADKCM" : Adr == 2 ? "EPBADC" : "EPBADM",
                                             .ext = 1,
                                             .par = 2,
                                             .adr = Adr,
                                             .ign = Ign};
  static constexpr element_help help{.title = "test: a NaN or infinite dF/dv or dF/da",
                                     .name = "Test element whose viscosity or inertia block goes bad",
                                     .field = "tests",
                                     .dofs = "1 - the DOF",
                                     .parameters = "1 - mode\n2 - time from which it is bad",
                                     .work = "",
                                     .special = "by design"};
  struct parameters {
    double mode = 0, t_bad = 0;
  };
  parameters p;
  explicit ep_bad_block(parameters q) : p(q) {}
  static ep_bad_block from_parameters(std::span<const double> v) { return ep_bad_block({v[0], v[1]}); }
  void evaluate(const local_input<ep_bad_block>& in, local_output<ep_bad_block>& out, element_context& ctx) const {
    const bool bad = ctx.time >= p.t_bad;
    const int mode = static_cast<int>(p.mode);
    double c = 0.5, m = 1.0;
    if (bad && mode == 0) c = std::numeric_limits<double>::quiet_NaN();
    if (bad && mode == 1) c = std::numeric_limits<double>::infinity();
    if (bad && mode == 2) m = std::numeric_limits<double>::quiet_NaN();
    if (bad && mode == 3) m = -std::numeric_limits<double>::infinity();
    out.f(0) = 0.0;
    if constexpr (passport.has_k()) out.f(0) += 5.0 * in.u(0);
    if constexpr (passport.has_c()) out.f(0) += 0.5 * in.v(0);
    if constexpr (passport.has_m()) out.f(0) += in.a(0);
    if (!out.want_jacobian) return;
    if constexpr (passport.has_k()) out.K(0, 0) = 5.0;
    if constexpr (passport.has_c()) out.C(0, 0) = c;
    if constexpr (passport.has_m()) out.M(0, 0) = m;
  }
};
using ep_bad_kcm = ep_bad_block<1, 0>;
using ep_bad_c = ep_bad_block<2, 3>;
using ep_bad_m = ep_bad_block<3, 0>;

using ep_model = model<point_mass, linear_spring, ep_bad_kcm, ep_bad_c, ep_bad_m>;

run_options ep_quick() {
  run_options o;
  o.end = 0.2;
  o.smax = 0.01;
  o.smin = 1e-6;
  return o;
}

/// A healthy oscillator on DOF 'x'.
dof ep_add_oscillator(ep_model& m) {
  const dof x = m.add_dof("x");
  m.add<point_mass>("mass", {1.0}, x);
  m.add<linear_spring>("spring", {10.0}, x, m.ground());
  return x;
}

/// The last non-empty line of a log.
std::string ep_last_line(const std::string& s) {
  std::string t = s;
  while (!t.empty() && t.back() == '\n') t.pop_back();
  const auto p = t.rfind('\n');
  return p == std::string::npos ? t : t.substr(p + 1);
}

/// Runs `m` with the driver Sim; the error thrown and the log text.
struct ep_outcome {
  std::optional<error> e;
  std::string log;
  run_statistics stats;
  double time = -1;
};
template <class Sim>
ep_outcome ep_run(Sim& sim, const run_options& o) {
  std::ostringstream log;
  sim.log().to(log);
  auto e = pradis_test::error_of([&] { sim.run(o); });
  sim.log().silence();
  return {e, log.str(), sim.statistics(), sim.time()};
}
/// Runs `m` with NEWMARK or BDF: first a clean stage to `first_end` if it is > 0,
/// then one stage to END = 0.2; the outcome of the last stage run.
ep_outcome ep_run_with(bool bdf, ep_model& m, double first_end = 0.0) {
  auto stages = [&](auto& sim) {
    if (first_end > 0) {
      run_options o = ep_quick();
      o.end = first_end;
      const ep_outcome r = ep_run(sim, o);
      if (r.e) return r;
    }
    return ep_run(sim, ep_quick());
  };
  if (bdf) {
    bdf_simulation sim(m);
    return stages(sim);
  }
  simulation sim(m, newmark{});
  return stages(sim);
}

/// Adds one element of type E named "bad block" on DOF x.
template <class E>
void ep_add_bad(ep_model& m, dof x, double mode, double t_bad) {
  m.add<E>("bad block", {mode, t_bad}, x);
}

/// A per-test scratch directory, removed when the test ends.
struct ep_scratch {
  std::filesystem::path dir;
  ep_scratch() {
    std::random_device rd;
    dir = std::filesystem::temp_directory_path() / ("pradis_error_paths_" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(dir);
  }
  ep_scratch(const ep_scratch&) = delete;
  ep_scratch& operator=(const ep_scratch&) = delete;
  ~ep_scratch() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
};

}  // namespace

TEST_SUITE("core/error paths") {
  TEST_CASE("a NaN or infinite dF/dv or dF/da entry: code 150 naming the block, the element type and instance") {
    struct case_t {
      int element;  // 0: K, C and M; 1: C only; 2: M only
      double mode;
      const char* type;
      const char* fragment;
    };
    const case_t cases[] = {
        {0, 0, "EPBADKCM", "a Jacobian entry dF/dv is NaN or infinite"},
        {0, 1, "EPBADKCM", "a Jacobian entry dF/dv is NaN or infinite"},
        {0, 2, "EPBADKCM", "a Jacobian entry dF/da is NaN or infinite"},
        {0, 3, "EPBADKCM", "a Jacobian entry dF/da is NaN or infinite"},
        {1, 0, "EPBADC", "a Jacobian entry dF/dv is NaN or infinite"},
        {1, 1, "EPBADC", "a Jacobian entry dF/dv is NaN or infinite"},
        {2, 2, "EPBADM", "a Jacobian entry dF/da is NaN or infinite"},
        {2, 3, "EPBADM", "a Jacobian entry dF/da is NaN or infinite"},
    };
    // When the entry goes bad: 0 at the zero step; 1 during a stage (NEWMARK, whose
    // full Newton evaluates the Jacobian at every iteration; BDF's modified Newton
    // may keep an earlier Jacobian, so it need not see the entry before a refresh);
    // 2 from the start of a second stage, which evaluates a fresh Jacobian
    // (first stage to 0.05 clean, bad from t = 0.0500001 on).
    for (const bool bdf : {false, true})
      for (const int when : {0, 1, 2})
        for (const case_t& c : cases) {
          if (bdf && when == 1) continue;
          CAPTURE(bdf);
          CAPTURE(when);
          CAPTURE(std::string(c.type));
          CAPTURE(c.mode);
          const double t_bad = when == 0 ? 0.0 : when == 1 ? 0.05 : 0.0500001;
          ep_model m;
          const dof x = ep_add_oscillator(m);
          if (c.element == 0) ep_add_bad<ep_bad_kcm>(m, x, c.mode, t_bad);
          if (c.element == 1) ep_add_bad<ep_bad_c>(m, x, c.mode, t_bad);
          if (c.element == 2) ep_add_bad<ep_bad_m>(m, x, c.mode, t_bad);
          const ep_outcome r = ep_run_with(bdf, m, when == 2 ? 0.05 : 0.0);
          REQUIRE(r.e);
          CHECK(r.e->code() == error_code::non_finite);
          CHECK(r.e->number() == 150);
          CHECK(r.e->element_type() == c.type);
          CHECK(r.e->instance() == "bad block");
          CHECK(r.e->message() == c.fragment);
          CHECK(pradis_test::contains(r.e->what(), std::string("in ") + c.type + " 'bad block'"));
          // The error text is the last line of the log.
          CHECK(ep_last_line(r.log) == std::string(r.e->what()));
          // It stops the run where it happens: at the zero step, or at a step after
          // t_bad (not treated as a failed step and cut down to SMIN).
          if (when == 0) {
            CHECK(r.stats.steps == 0);
            CHECK(r.time == 0.0);
          } else {
            CHECK(r.stats.steps > 0);
            CHECK(r.time >= (when == 1 ? 0.04 : 0.05));
            CHECK(r.time < 0.2);
          }
        }
  }

  TEST_CASE("the same elements with finite blocks run to END: the errors above come from the bad entries only") {
    for (const bool bdf : {false, true}) {
      CAPTURE(bdf);
      ep_model m;
      const dof x = ep_add_oscillator(m);
      // mode 9: no block ever goes bad.
      ep_add_bad<ep_bad_kcm>(m, x, 9, 0.0);
      m.add<ep_bad_c>("damper", {9, 0.0}, x);
      m.add<ep_bad_m>("inertia", {9, 0.0}, x);
      const ep_outcome r = ep_run_with(bdf, m, 0.05);
      CHECK_FALSE(r.e.has_value());
      CHECK(r.time == doctest::Approx(0.2));
    }
  }

  TEST_CASE("SMIN <= 0, DRLTU, DABSI or DRLTI < 0, zero Newton tolerance pairs: code 120, the run does not start") {
    struct case_t {
      const char* what;
      run_options o;
      const char* fragment;
    };
    const double nan = std::numeric_limits<double>::quiet_NaN();
    auto with = [](auto change) {
      run_options o = ep_quick();
      change(o);
      return o;
    };
    const case_t cases[] = {
        {"SMIN = 0", with([](run_options& o) { o.smin = 0.0; }), "SMIN = 0 must be > 0"},
        {"SMIN < 0", with([](run_options& o) { o.smin = -1e-4; }), "SMIN = -0.0001 must be > 0"},
        {"SMIN NaN", with([nan](run_options& o) { o.smin = nan; }), "SMIN = nan must be > 0"},
        {"DRLTU < 0", with([](run_options& o) { o.newton.drltu = -0.5; }), "DRLTU = -0.5 must be >= 0"},
        {"DRLTU inf",
         with([](run_options& o) { o.newton.drltu = std::numeric_limits<double>::infinity(); }), "DRLTU = inf must be >= 0"},
        {"DABSI < 0", with([](run_options& o) { o.newton.dabsi = -2.0; }), "DABSI = -2 must be >= 0"},
        {"DRLTI < 0", with([](run_options& o) { o.newton.drlti = -1e-3; }), "DRLTI = -0.001 must be >= 0"},
        {"DRLTI NaN", with([nan](run_options& o) { o.newton.drlti = nan; }), "DRLTI = nan must be >= 0"},
        {"DABSU = DRLTU = 0",
         with([](run_options& o) {
           o.newton.dabsu = 0.0;
           o.newton.drltu = 0.0;
         }),
         "the Newton tolerances DABSU and DRLTU must not both be zero"},
        {"DABSI = DRLTI = 0",
         with([](run_options& o) {
           o.newton.dabsi = 0.0;
           o.newton.drlti = 0.0;
         }),
         "the Newton tolerances DABSI and DRLTI must not both be zero"},
    };
    for (const bool bdf : {false, true})
      for (const case_t& c : cases) {
        CAPTURE(bdf);
        CAPTURE(c.what);
        ep_model m;
        const dof x = ep_add_oscillator(m);
        std::optional<error> e;
        std::string log;
        auto check_refused_then_ok = [&](auto& sim) {
          const ep_outcome r = ep_run(sim, c.o);
          e = r.e;
          log = r.log;
          // Nothing ran.
          CHECK(r.stats.steps == 0);
          CHECK(r.time == 0.0);
          // A valid stage afterwards runs normally.
          run_options ok = ep_quick();
          ok.end = 0.05;
          CHECK_NOTHROW(sim.run(ok));
          CHECK(sim.time() == doctest::Approx(0.05));
          CHECK(std::isfinite(sim.u(x)));
        };
        if (bdf) {
          bdf_simulation sim(m);
          check_refused_then_ok(sim);
        } else {
          simulation sim(m, newmark{});
          check_refused_then_ok(sim);
        }
        REQUIRE(e);
        CHECK(e->code() == error_code::invalid_option);
        CHECK(e->number() == 120);
        CHECK(e->instance().empty());
        CHECK(e->element_type().empty());
        CHECK(pradis_test::contains(e->message(), c.fragment));
        CHECK(e->message().rfind(bdf ? "BDF: " : "NEWMARK", 0) == 0);
        CHECK(ep_last_line(log) == std::string(e->what()));
      }
  }

  TEST_CASE("the Newton tolerances pass with one of each pair zero") {
    // Only both of a pair zero is refused: DABSU = 0 with DRLTU > 0 and DRLTI = 0
    // with DABSI > 0 are valid.
    run_options o = ep_quick();
    o.end = 0.05;
    o.newton.dabsu = 0.0;
    o.newton.drlti = 0.0;
    CHECK_FALSE(check_options(o).has_value());
    ep_model m;
    ep_add_oscillator(m);
    simulation sim(m, newmark{});
    CHECK_NOTHROW(sim.run(o));
    CHECK(sim.time() == doctest::Approx(0.05));
  }

  TEST_CASE("a diagnostics file that cannot be opened: code 160 naming the path, the log unchanged") {
    const ep_scratch tmp;
    const std::string missing_dir = (tmp.dir / "no such dir" / "SYSPRINT.TXT").string();
    SUBCASE("a fresh log stays silent") {
      diagnostics log;
      const auto e = pradis_test::error_of([&] { log.to_file(missing_dir); });
      REQUIRE(e);
      CHECK(e->code() == error_code::io_error);
      CHECK(e->number() == 160);
      CHECK(e->message() == "cannot open diagnostics file '" + missing_dir + "'");
      CHECK_FALSE(log.active());
      CHECK_FALSE(std::filesystem::exists(tmp.dir / "no such dir"));
    }
    SUBCASE("a directory as the file") {
      diagnostics log;
      const std::string d = tmp.dir.string();
      const auto e = pradis_test::error_of([&] { log.to_file(d); });
      REQUIRE(e);
      CHECK(e->code() == error_code::io_error);
      CHECK(pradis_test::contains(e->message(), "cannot open diagnostics file '" + d + "'"));
      CHECK_FALSE(log.active());
    }
    SUBCASE("through a simulation's log, before the run: the run still works") {
      ep_model m;
      ep_add_oscillator(m);
      simulation sim(m, newmark{});
      const auto e = pradis_test::error_of([&] { sim.log().to_file(missing_dir); });
      REQUIRE(e);
      CHECK(e->code() == error_code::io_error);
      CHECK(pradis_test::contains(e->what(), "pradis error 160 (I/O error): cannot open diagnostics file"));
      CHECK(pradis_test::contains(e->message(), missing_dir));
      run_options o = ep_quick();
      o.end = 0.05;
      CHECK_NOTHROW(sim.run(o));
      // A valid path afterwards is opened and written.
      const auto good = tmp.dir / "SYSPRINT.TXT";
      sim.log().to_file(good.string());
      CHECK(sim.log().active());
      sim.log().write("after the failure");
      sim.log().silence();
      CHECK(pradis_test::slurp(good) == "after the failure\n");
    }
  }
}
