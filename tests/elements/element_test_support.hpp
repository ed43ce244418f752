#pragma once
// Shared helpers of the element tests (tests/elements/*.cpp): tight Newton
// options, fixed-step run options, and a check of a pradis::error's code,
// element type, instance and message.

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <sstream>
#include <span>
#include <string>
#include <string_view>
#include <utility>

#include "pradis/pradis.hpp"
#include "testing/test_support.hpp"

namespace pradis_element_tests {

/// Newton tolerances far below every accuracy these tests check: the Newton
/// error is then negligible and the remaining error is the scheme's own.
inline constexpr pradis::newton_options tight_newton{.dabsu = 1e-12, .drltu = 0, .dabsi = 1e-9, .drlti = 0};

/// One stage up to `end` with the nominal step `h` (the kernel keeps it: no
/// element in these scenes recommends a smaller one unless the test says so)
/// and tight Newton tolerances.
inline pradis::run_options fixed_step(double end, double h) {
  return {.end = end, .smax = h, .newton = tight_newton};
}

/// Runs f and returns the pradis::error it throws, or nothing.
template <class F>
std::optional<pradis::error> error_from(F&& f) {
  return pradis_test::error_of(std::forward<F>(f));
}

using pradis_test::inf;
using pradis_test::not_a_number;

/// One degree in radians.
inline constexpr double deg = std::numbers::pi / 180;

/// Bulk modulus (Pa) and density (kg/m^3) of a typical mineral oil.
inline constexpr double oil_b = 1.5e9, oil_rho = 850;
/// The regularised root of the orifice law, r(x) = x / (x^2 + d^2)^(1/4).
inline double reg_root(double x, double d) { return x / std::pow(x * x + d * d, 0.25); }

/// Checks that `e` holds an error with this code, element type and instance,
/// whose message mentions `mention`.
inline void check_error(const std::optional<pradis::error>& e, pradis::error_code code, std::string_view type,
                        std::string_view instance, std::string_view mention) {
  REQUIRE_MESSAGE(e.has_value(), "expected a pradis::error, none was thrown");
  INFO("what(): ", std::string(e->what()));
  CHECK(e->number() == static_cast<int>(code));
  CHECK(e->element_type() == std::string(type));
  CHECK(e->instance() == std::string(instance));
  CHECK_MESSAGE(e->message().find(mention) != std::string::npos, "the message should mention '", std::string(mention),
                "'");
}

/// Places E through the flat path model::add_flat<E>(name, dofs, params), as
/// the model language does, and returns the error it throws, or nothing.
template <class E, class Model>
std::optional<pradis::error> flat_add_error(Model& md, const std::string& name, std::span<const pradis::dof> dofs,
                                            std::span<const double> params) {
  return error_from([&] { md.template add_flat<E>(name, dofs, params); });
}

/// Passes a finite-difference Jacobian check result (testing::jacobian_check_result)
/// through: on failure it records the check's table as a failed CHECK. Returns r.ok.
template <class Result>
bool jacobian_passes(const Result& r) {
  if (r.ok) return true;
  std::ostringstream os;
  r.print(os);
  FAIL_CHECK(os.str());
  return false;
}

/// Discrete angular frequency of the trapezoidal rule (average-acceleration
/// Newmark) for an undamped oscillator of frequency w at step h:
/// tan(wd h / 2) = w h / 2 (Hughes, The Finite Element Method, 9.3: the
/// amplification matrix is the Cayley transform of the exact one, so it keeps
/// the amplitude and the eigenvectors and only shifts the frequency).
/// 0 <= w - wd <= w^3 h^2 / 12 (atan x >= x - x^3 / 3).
inline double trapezoidal_frequency(double w, double h) { return 2.0 / h * std::atan(w * h / 2.0); }

}  // namespace pradis_element_tests
