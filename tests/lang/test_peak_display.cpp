// The 'PEAK display: a displacement source u(t) = cos(2 pi t) (XSRC, exact at
// every output row) sampled every 1 ms. On [0.1, 0.9] its largest value is
// cos(0.2 pi) = 0.809017 at t = 0.1 (and 0.9; the first sample counts), it is at
// or above 1/2 on [0.1, 1/6] and [5/6, 0.9] (each 1/15 s: the first is the
// longest, the total 2/15 s); the crossings are interpolated linearly, which is
// off by at most h^2 |u''| / (8 |u'|) = 1.4e-7 s here (post.hpp). The velocity
// -2 pi sin(2 pi t) has its largest magnitude 2 pi at t = 0.25 (MAGNITUDE=1,
// returned with its sign). The CSV holds the same numbers; the error paths are
// located at the display.

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "lang_test_support.hpp"

using namespace pradis;

namespace {
std::string source_model(const std::string& print) {
  return "$FRAGMENT:\n#STRUCTURE:\n    Mass 'MASS (1; 1)\n    Drive 'XSRC (1; 1, 1, 90, 0)\n#OUTPUT:\n"
         "    X 'X (1; 1)\n    V 'X (1; 2)\n$RUN:\n    Go 'NEWMARK (END=1, OUT=0.001, SMAX=0.001)\n$PRINT:\n" +
         print + "$END\n";
}
constexpr double pi = std::numbers::pi;
}  // namespace

TEST_SUITE("lang/peak") {
  TEST_CASE("'PEAK finds the peak and the time above a threshold of an exactly known output") {
    const auto dir = lang_test::scratch_dir("peak");
    auto s = lang_test::build(source_model("    Crest 'PEAK (X; THRESHOLD=0.5, START=0.1, END=0.9)\n"
                                           "    Speed 'PEAK (V; MAGNITUDE=1)\n"));
    std::ostringstream log;
    s->run({.output_dir = dir.string(), .stem = "m", .plot = false, .log = &log});
    const auto& sum = s->summaries();
    REQUIRE(sum.size() == 2);
    const lang::peak_summary& x = sum[0];
    CHECK(x.display == "Crest");
    CHECK(x.output == "X");
    CHECK(x.peak.value == doctest::Approx(std::cos(0.2 * pi)).epsilon(1e-12));
    CHECK(x.peak.time == doctest::Approx(0.1).epsilon(1e-12));
    REQUIRE(x.longest.found());
    CHECK(std::abs(x.longest.start - 0.1) < 1e-12);
    CHECK(std::abs(x.longest.end - 1.0 / 6) < 1e-6);
    CHECK(std::abs(x.longest.duration - 1.0 / 15) < 1e-6);
    CHECK(std::abs(x.total - 2.0 / 15) < 2e-6);
    const lang::peak_summary& v = sum[1];
    CHECK(v.peak.value == doctest::Approx(-2 * pi).epsilon(1e-9));
    CHECK(v.peak.time == doctest::Approx(0.25).epsilon(1e-9));
    CHECK_FALSE(v.threshold.has_value());
    CHECK(log.str().find("PEAK: X: peak 0.80901") != std::string::npos);

    // The CSV: a header and one row per output, the same numbers.
    const std::string csv = lang_test::slurp(dir / "m.Crest.csv");
    CHECK(csv.rfind("output,peak,t_peak,threshold,longest,longest_start,longest_end,total_above\nX,", 0) == 0);
    std::istringstream row(csv.substr(csv.find("\nX,") + 3));
    std::vector<double> f;
    for (std::string cell; std::getline(row, cell, ',');) f.push_back(std::stod(cell));
    REQUIRE(f.size() == 7);
    CHECK(f[0] == x.peak.value);
    CHECK(f[2] == 0.5);
    CHECK(f[3] == x.longest.duration);
    CHECK(f[6] == x.total);
    // Without a threshold the time columns are nan.
    const std::string speed = lang_test::slurp(dir / "m.Speed.csv");
    CHECK(speed.find("V,") != std::string::npos);
    CHECK(speed.find("nan") != std::string::npos);
    std::filesystem::remove_all(dir);
  }

  TEST_CASE("'PEAK errors: a window without rows, keys of other programs, MAGNITUDE out of range, labels") {
    std::string e = lang_test::error_of(source_model("    Late 'PEAK (X; START=5, END=6)\n"));
    CHECK(e.find("test.prd:11:5") != std::string::npos);
    CHECK(e.find("no output row between START and END") != std::string::npos);
    e = lang_test::error_of(source_model("    T 'TABL (X; THRESHOLD=1)\n"));
    CHECK(e.find("test.prd:11:") != std::string::npos);
    CHECK(e.find("unknown key THRESHOLD of TABL") != std::string::npos);
    e = lang_test::error_of(source_model("    P 'PEAK (X; MAGNITUDE=2)\n"));
    CHECK(e.find("MAGNITUDE") != std::string::npos);
    e = lang_test::error_of(source_model("    P 'PEAK (Y; THRESHOLD=1)\n"));
    CHECK(e.find("no output labelled 'Y'") != std::string::npos);
    e = lang_test::error_of(source_model("    P 'PEAK (X; THRESHOLT=1)\n"));
    CHECK(e.find("did you mean 'THRESHOLD'") != std::string::npos);
  }
}
