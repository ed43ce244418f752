// examples/models/rolling_ball.prd: CSPHPL in the model language. A solid sphere
// thrown sliding without spin at v0 decelerates by mu g and rolls from
// t* = 2 v0 / (7 mu g) at 5/7 v0 (Routh, Dynamics of a System of Rigid Bodies, 1905,
// part II, section 243); rolling, the friction force vanishes.

#include <cmath>
#include <memory>

#include "lang_test_support.hpp"

using namespace pradis;

using lang_test::column;

TEST_SUITE("lang/contact") {
  TEST_CASE("examples/models/rolling_ball.prd: the thrown ball rolls at 5/7 v0 from 2 v0 / (7 mu g)") {
    auto s = std::make_unique<lang::session>(lang::parse_file((lang_test::models_dir() / "rolling_ball.prd").string()));
    s->run({.write_files = false});
    const auto& t = s->results();
    const std::size_t vx = column(t, "X velocity"), wy = column(t, "Spin about Y"), ft = column(t, "Friction force"),
                      stick = column(t, "Stick"), normal = column(t, "Normal force");
    const double v0 = 1, mu = 0.2, g = 9.81, r = 0.1, t_roll = 2 * v0 / (7 * mu * g);
    std::size_t first_stick = 1;  // row 0 is t = 0, where the unloaded stick spring counts as sticking
    while (first_stick + 1 < t.rows() && t.at(first_stick, stick) != 1.0) ++first_stick;
    CHECK(std::abs(t.at(first_stick, 0) - t_roll) < 2e-3);  // within two steps of 1 ms
    const std::size_t last = t.rows() - 1;
    CHECK(t.at(last, vx) == doctest::Approx(5 * v0 / 7).epsilon(1e-4));
    CHECK(t.at(last, wy) * r == doctest::Approx(5 * v0 / 7).epsilon(1e-4));
    CHECK(std::abs(t.at(last, ft)) < 1e-4 * mu * g);
    CHECK(t.at(last, normal) == doctest::Approx(g).epsilon(1e-6));
  }
}
