// CRAIGBAMPTON("k.mtx", "m.mtx", modes, dof, ...) in $DATA (lang/data_files.hpp):
// a linear elastic part's K and M read from Matrix Market files and reduced
// (linalg::craig_bampton) to FLEX3's parameters; errors located in the matrix
// file or at the argument; examples/models/flex_cantilever.prd reaches the
// beam-theory tip deflection and slope of a cantilever (Timoshenko and Gere,
// Mechanics of Materials: d = P L^3 / (3 E I), phi = P L^2 / (2 E I)).

#include <cmath>

#include "../../bench/spun_bar.hpp"
#include "lang_test_support.hpp"
#include "pradis/elements/spatial/beam_matrices.hpp"
#include "pradis/io/matrix_market.hpp"
#include "pradis/linalg/reduction.hpp"

using namespace pradis;
using lang_test::memory_loader;

namespace {
// The steel beam of examples/models/flex_cantilever_{k,m}.mtx (their comment lines):
// the spun bar's section, 1 m, 8 elements.
elements::beam_matrices cb_steel_beam() { return spun_bar::bar_matrices(8); }

// The Matrix Market text of `a` (symmetric), through io::write_matrix_market.
std::string cb_mtx_text(const Eigen::MatrixXd& a, const std::string& tag) {
  const auto path = (lang_test::scratch_dir("cb_" + tag) / "a.mtx").string();
  io::write_matrix_market(path, a, true);
  return pradis_test::slurp(path);
}

// In-memory k.mtx and m.mtx of the steel beam (unless replaced).
std::map<std::string, std::string> cb_files() {
  const auto bm = cb_steel_beam();
  return {{"k.mtx", cb_mtx_text(bm.k, "k")}, {"m.mtx", cb_mtx_text(bm.m, "m")}};
}

// The cantilever of flex_cantilever.prd with `call` as its Beam definition.
std::string cb_model(const std::string& call) {
  return "$DATA\n  Beam = " + call + R"(
$FRAGMENT
#STRUCTURE
  Cantilever 'FLEX3 (0 0 0 0 0 0 1 2 3 4 5 6; 0, 0, 0, 1, 0, 0, Beam)
  Tip load 'F (2; 1)
#OUTPUT
  Tip Y 'X (2; 1)
$RUN
  Calc 'NEWMARK (END=0.01, OUT=1E-3, SMAX=1E-3)
$END
)";
}
const std::string cb_ends = "1, 2, 3, 4, 5, 6, 49, 50, 51, 52, 53, 54";

std::string cb_error(const std::string& call, std::map<std::string, std::string> files = cb_files()) {
  return lang_test::error_of(cb_model(call), memory_loader(std::move(files)));
}
// Expects the error of `call` at `where` (line:column of test.prd, or a file:line:column) with `part` in it.
void cb_expect(const std::string& call, const std::string& where, const std::string& part,
               std::map<std::string, std::string> files = cb_files()) {
  const std::string e = cb_error(call, std::move(files));
  CAPTURE(call);
  CAPTURE(e);
  const std::string at = where.find(".mtx") == std::string::npos ? "test.prd:" + where : where;
  CHECK(e.rfind(at + ": error: ", 0) == 0);
  CHECK(e.find(part) != std::string::npos);
}
}  // namespace

TEST_SUITE("lang/CRAIGBAMPTON") {
  TEST_CASE("CRAIGBAMPTON gives the lower triangles of craig_bampton's K_r and M_r, exactly") {
    const auto bm = cb_steel_beam();
    std::vector<int> boundary;
    for (int d : {0, 1, 2, 3, 4, 5, 48, 49, 50, 51, 52, 53}) boundary.push_back(d);
    const linalg::reduced_part r = linalg::craig_bampton(bm.k, bm.m, boundary, 2);
    const lang::ast::program prog =
        lang::parse_string(cb_model("CRAIGBAMPTON(\"k.mtx\", \"m.mtx\", 2, " + cb_ends + ")"), "test.prd",
                           memory_loader(cb_files()));
    REQUIRE(prog.data.size() == 1);
    const auto& v = prog.data[0].values;
    REQUIRE(v.size() == 2 * 14 * 15 / 2);  // FLEX3's 216 parameters less the 6 positions
    std::size_t at = 0;
    double worst = 0;
    for (const Eigen::MatrixXd* a : {&r.k, &r.m})
      for (Eigen::Index i = 0; i < 14; ++i)
        for (Eigen::Index j = 0; j <= i; ++j) worst = std::max(worst, std::abs(v[at++].number - (*a)(i, j)));
    CHECK(worst == 0.0);  // %.17g files read back exactly, the same reduction
    CHECK(v[0].loc.line == 2);
    CHECK(v[0].loc.col == 10);  // every number is located at the call
  }

  TEST_CASE("examples/models/flex_cantilever.prd: tip deflection P L^3/(3EI), slope P L^2/(2EI), energy P d/2") {
    // The committed matrix files are the beam their comment describes.
    const auto bm = cb_steel_beam();
    const auto dir = lang_test::models_dir();
    CHECK((io::read_matrix_market((dir / "flex_cantilever_k.mtx").string()) - bm.k).cwiseAbs().maxCoeff() == 0.0);
    CHECK((io::read_matrix_market((dir / "flex_cantilever_m.mtx").string()) - bm.m).cwiseAbs().maxCoeff() == 0.0);

    auto s = std::make_unique<lang::session>(lang::parse_file((dir / "flex_cantilever.prd").string()));
    s->run({.write_files = false});
    const auto& t = s->results();
    const std::size_t last = t.rows() - 1;
    const double p = 1, l = 1, ei = spun_bar::steel.e * spun_bar::steel.iz;
    const double d = p * l * l * l / (3 * ei), phi = p * l * l / (2 * ei);
    const double q3 = t.at(last, lang_test::column(t, "Tip q3")), lq = t.at(last, lang_test::column(t, "Tip norm"));
    // The Guyan part is the exact static condensation; the corotational frame adds
    // terms of order (d/L)^2 = 1.4e-8 relative; the damped motion has decayed
    // (damping ratio ~0.3 of the 17 Hz mode, 17 periods).
    CHECK(t.at(last, lang_test::column(t, "Tip Y")) == doctest::Approx(d).epsilon(1e-6));
    CHECK(2 * std::asin(q3 / lq) == doctest::Approx(phi).epsilon(1e-6));
    CHECK(t.at(last, lang_test::column(t, "Strain energy")) == doctest::Approx(p * d / 2).epsilon(1e-6));
    CHECK(t.rows() > 10);
  }

  TEST_CASE("CRAIGBAMPTON mistakes: each is reported at the argument, in the matrix file or at the call") {
    const std::string ok_k = "\"k.mtx\", \"m.mtx\", ";
    // Arguments (the call is at 2:10; its first file name at 2:23).
    cb_expect("CRAIGBAMPTON(\"none.mtx\", \"m.mtx\", 2, 1)", "2:23", "cannot read the matrix file 'none.mtx'");
    cb_expect("CRAIGBAMPTON(\"k.mtx\", 2, 1)", "2:32", "CRAIGBAMPTON needs two file names in double quotes");
    cb_expect("CRAIGBAMPTON(\"k.mtx\")", "2:10", "CRAIGBAMPTON needs two matrix files");
    cb_expect("CRAIGBAMPTON(\"\", \"m.mtx\", 2, 1)", "2:23", "CRAIGBAMPTON with an empty file name");
    cb_expect("CRAIGBAMPTON(" + ok_k + "2, 1", "2:45", "expected ',' or ')' in CRAIGBAMPTON");
    cb_expect("CRAIGBAMPTON(" + ok_k + "2)", "2:10", "needs the number of modes and at least one boundary DOF");
    cb_expect("CRAIGBAMPTON(" + ok_k + "Modes, 1)", "2:41", "takes numbers after its file names, not a $DATA name");
    cb_expect("CRAIGBAMPTON(" + ok_k + "2.5, 1)", "2:41", "number of modes of CRAIGBAMPTON must be a whole number in 0..54");
    cb_expect("CRAIGBAMPTON(" + ok_k + "2, 1, 55)", "2:47", "boundary DOF 55 of CRAIGBAMPTON is not a whole number in 1..54");
    cb_expect("CRAIGBAMPTON(" + ok_k + "2, 0)", "2:44", "boundary DOF 0 of CRAIGBAMPTON is not a whole number");
    cb_expect("CRAIGBAMPTON(" + ok_k + "2, 1, 2, 1)", "2:50", "boundary DOF 1 of CRAIGBAMPTON is given twice (also as boundary DOF 1)");
    // The reduction (at the call): a boundary that does not hold the part, too many
    // modes, matrices of different sizes.
    cb_expect("CRAIGBAMPTON(" + ok_k + "2, 1)", "2:10",
              "CRAIGBAMPTON cannot reduce 'k.mtx' and 'm.mtx': the interior stiffness K_ii is not positive definite");
    cb_expect("CRAIGBAMPTON(" + ok_k + "43, " + cb_ends + ")", "2:10", "43 modes asked for, the part has 42 interior DOFs");
    auto files = cb_files();
    files["m.mtx"] = cb_mtx_text(Eigen::MatrixXd::Identity(6, 6), "m6");
    cb_expect("CRAIGBAMPTON(" + ok_k + "0, 1)", "2:10", "K (54 x 54) and M (6 x 6) must be square and of one size", files);
    // Defects in a matrix file, at its line and column, naming the call.
    files = cb_files();
    files["k.mtx"] = "%%MatrixMarket matrix coordinate real symmetric\n2 2 2\n1 1 4\n2 1 x\n";
    cb_expect("CRAIGBAMPTON(" + ok_k + "0, 1)", "k.mtx:4:5",
              "'x' is not a finite number (in the matrix file read by CRAIGBAMPTON at test.prd:2:10)", files);
    files["k.mtx"] = "%%MatrixMarket matrix coordinate real symmetric\n3001 3001 0\n";
    cb_expect("CRAIGBAMPTON(" + ok_k + "0, 1)", "k.mtx:2:1", "the row count '3001' is not a whole number in 1..3000", files);
    files["k.mtx"] = "";
    cb_expect("CRAIGBAMPTON(" + ok_k + "0, 1)", "k.mtx:1:1", "not a Matrix Market file", files);
    // A reduction of the wrong size for FLEX3 (Guyan, no modes): the element's count rule at its line.
    const std::string e = cb_error("CRAIGBAMPTON(" + ok_k + "0, " + cb_ends + ")");
    CHECK(e.rfind("test.prd:5:", 0) == 0);
    CHECK(e.find("216") != std::string::npos);
  }
}
