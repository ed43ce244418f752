// examples/models/pneumatic_cylinder.prd: a compressor (PNQ) feeds a vented manifold (PNVOL,
// PNORF) that raises a 10 kg load on a double-acting cylinder with a closed rod-side chamber
// (PNCYL) and a 7.5 kg table on a single-acting cylinder with a return spring (PNCHP), all
// isothermal, in the model language. The laws checked:
// - ISO 6358-1:2013, section 3: a choked orifice (P_dn / P_up <= b) passes q = C rho0 P_up
//   (T = T0, rho0 = 1.185 kg/m^3). The vent is choked all the time, so at the steady state,
//   where it passes the compressor's flow q, the manifold and the chambers fed from it are at
//   P = q / (C rho0) (no flow through the valves).
// - The chamber law of docs/domains-electric-pneumatic.md ("Chambers"): m = rho(P) V with
//   rho = rho0 (P / P0)^(1/n), rho0 = P0 / (R T0), so for n = 1 the ideal-gas law at constant
//   temperature m = P V / (R T0) (Boyle-Mariotte; e.g. Cengel and Boles, Thermodynamics, 2015,
//   section 3-6): the closed chamber B keeps P_B V_B = P0 VB0 at every instant, and every
//   chamber's air gain equals the integral of the mass flow into it.
// - Newton's second law on the two loads with the documented piston forces (same page):
//   m x'' = A1 pA - A2 pB - m g - c x' (PNCYL) and m x'' = A p - m g - k x - c x' (PNCHP).
// - The static equilibrium at the end: A1 pA - A2 pB = m g with Boyle in chamber B gives the
//   rod's position, A (p - p0) = k x the table's.

#include <algorithm>
#include <cmath>
#include <memory>

#include "lang_test_support.hpp"

using namespace pradis;

namespace {
// The file's $DATA.
constexpr double pcy_q = 2.844e-2, pcy_c_vent = 4e-8, pcy_b = 0.3, pcy_p0 = 2.4525e5;
constexpr double pcy_a1 = 8e-4, pcy_a2 = 4e-4, pcy_v0 = 4e-5, pcy_m_load = 10, pcy_w_load = 98.1, pcy_c_guide = 500;
constexpr double pcy_a_ram = 3e-4, pcy_m_table = 7.5, pcy_w_table = 73.575, pcy_k = 5000, pcy_c_table = 300;
constexpr double pcy_tol = 1e-8;  // DRLTX = DABSX of both stages
// Air, the atmosphere and the ISO 6358 reference density (pradis/elements/pneumatic/gas.hpp).
constexpr double pcy_atm = 101325, pcy_r = 287.05, pcy_t0 = 293.15, pcy_rho0 = 1.185;

/// The local error tolerance of a gauge pressure p: DABSX times the pneumatic nominal 1e5 Pa
/// plus DRLTX |p| (docs/domains.md, "DABSX potential + DRLTX |v|").
double pcy_weight(double p) { return pcy_tol * 1e5 + pcy_tol * std::abs(p); }

/// Simpson's rule over the rows a..b (an even count of equal intervals) of column c.
double pcy_simpson(const io::table& t, std::size_t c, std::size_t a, std::size_t b) {
  REQUIRE((b - a) % 2 == 0);
  const double h = (t.at(b, 0) - t.at(a, 0)) / static_cast<double>(b - a);
  double s = t.at(a, c) + t.at(b, c);
  for (std::size_t r = a + 1; r < b; ++r) s += ((r - a) % 2 == 1 ? 4.0 : 2.0) * t.at(r, c);
  return s * h / 3;
}
}  // namespace

TEST_SUITE("lang/pneumatic cylinder") {
  TEST_CASE("examples/models/pneumatic_cylinder.prd: steady state, Boyle, Newton, mass balance") {
    auto s = std::make_unique<lang::session>(
        lang::parse_file((lang_test::models_dir() / "pneumatic_cylinder.prd").string()));
    s->run({.write_files = false});
    const auto& t = s->results();
    const auto col = [&](const char* label) { return lang_test::column(t, label); };
    const std::size_t pm = col("Manifold pressure"), pa = col("Pressure A"), pb = col("Pressure B"),
                      x = col("Rod position"), v = col("Rod speed"), acc = col("Rod acceleration"),
                      va = col("Volume A"), vb = col("Volume B"), pr = col("Ram pressure"), xt = col("Table position"),
                      vt = col("Table speed"), at = col("Table acceleration"), mr = col("Ram air mass"),
                      mm = col("Manifold air mass"), qv = col("Vent flow"), ratio = col("Vent pressure ratio"),
                      qa = col("Valve A flow"), qr = col("Valve R flow");
    // t = 0, every 10 us to 0.04 s (stage Start), every 0.5 ms to 2 s (stage Lifting).
    REQUIRE(t.rows() == 7921);
    const std::size_t split = 4000, last = t.rows() - 1;
    REQUIRE(t.at(split, 0) == doctest::Approx(0.04).epsilon(1e-12));
    REQUIRE(t.at(last, 0) == doctest::Approx(2.0).epsilon(1e-12));

    // Along the run. The work entries (flows) come from the last Newton evaluation of a step,
    // whose correction the Newton test holds below a fraction of the error weight (in its
    // norm): 10 DRLTX relative covers it (vent law measured 1.8e-8). Chamber B's mass is
    // conserved by m' = 0 up to the integration error, a few DRLTX over the run (measured
    // 2.8e-8; 2.3e-9 at DRLTX = 1e-9). The loads' rows are linear in the unknowns, so
    // Newton's last solve leaves them satisfied to round-off (measured 3.2e-11 N and
    // 1.2e-11 N, for forces of up to 400 N).
    const double boyle0 = (pcy_atm + pcy_p0) * pcy_v0;
    double err_vent = 0, err_boyle = 0, err_rod = 0, err_table = 0, max_ratio = 0;
    for (std::size_t r = 0; r <= last; ++r) {
      const double p_abs = pcy_atm + t.at(r, pm);
      err_vent = std::max(err_vent, std::abs(t.at(r, qv) / (pcy_c_vent * pcy_rho0 * p_abs) - 1));
      max_ratio = std::max(max_ratio, t.at(r, ratio));
      err_boyle = std::max(err_boyle, std::abs((pcy_atm + t.at(r, pb)) * t.at(r, vb) / boyle0 - 1));
      err_rod = std::max(err_rod, std::abs(pcy_m_load * t.at(r, acc) - (pcy_a1 * t.at(r, pa) - pcy_a2 * t.at(r, pb) -
                                                                          pcy_w_load - pcy_c_guide * t.at(r, v))));
      err_table = std::max(err_table, std::abs(pcy_m_table * t.at(r, at) -
                                               (pcy_a_ram * t.at(r, pr) - pcy_w_table - pcy_k * t.at(r, xt) -
                                                pcy_c_table * t.at(r, vt))));
    }
    CHECK(max_ratio <= pcy_b);  // choked at every sample (the premise of the vent law)
    CHECK(err_vent < 10 * pcy_tol);
    CHECK(err_boyle < 10 * pcy_tol);
    CHECK(err_rod < 1e-8);
    CHECK(err_table < 1e-8);

    // The steady state at 2 s: each pressure within its error weight (6e-3 Pa at 5e5 Pa;
    // measured 1.6e-4 Pa), chamber B's within its own plus the A1/A2 times amplified one of
    // chamber A (measured 2.4e-5 Pa).
    const double p_end = pcy_q / (pcy_c_vent * pcy_rho0) - pcy_atm;  // 4.98675e5 Pa gauge
    const double w = pcy_weight(p_end);
    CHECK(std::abs(t.at(last, pm) - p_end) < w);
    CHECK(std::abs(t.at(last, pa) - p_end) < w);
    CHECK(std::abs(t.at(last, pr) - p_end) < w);
    CHECK(std::abs(t.at(last, qv) / pcy_q - 1) < 10 * pcy_tol + w / (pcy_atm + p_end));
    const double pb_end = (pcy_a1 * p_end - pcy_w_load) / pcy_a2;  // 7.521e5 Pa gauge
    const double wb = pcy_weight(pb_end) + pcy_a1 / pcy_a2 * w;
    CHECK(std::abs(t.at(last, pb) - pb_end) < wb);
    // Rod: V_B = P0 VB0 / P_B, x = (VB0 - V_B) / A2 = 59.39 mm. Its error is V_B / A2 times
    // the relative errors of Boyle's product and of P_B (bound 5.0e-9 m; measured 9.7e-10 m).
    const double vb_end = boyle0 / (pcy_atm + pb_end), x_end = (pcy_v0 - vb_end) / pcy_a2;
    CHECK(std::abs(t.at(last, x) - x_end) < vb_end / pcy_a2 * (10 * pcy_tol + wb / (pcy_atm + pb_end)));
    // Table: A (p - p0) = k x, x = 15.21 mm, within A w / k = 3.6e-10 m (measured 6.5e-13 m).
    const double xt_end = pcy_a_ram * (p_end - pcy_p0) / pcy_k;
    CHECK(std::abs(t.at(last, xt) - xt_end) < pcy_a_ram * w / pcy_k);

    // Mass balance of each chamber and of the whole system against Simpson's rule over the
    // sampled flows, stage by stage: chamber A (m = P V / (R T0) from the cylinder's pressure
    // and volume) against valve A, the ram (its own mass entry) against valve R, the manifold
    // against q - vent - valve A - valve R, all four chambers against q t - the vent's outflow.
    // Within 1e-6 of each gain: the quadrature error on these samples and the integration
    // error together (measured 9.4e-8, 2.7e-9, 2.2e-7 and 1.0e-7).
    const auto integral = [&](std::size_t c) { return pcy_simpson(t, c, 0, split) + pcy_simpson(t, c, split, last); };
    const auto mass_a = [&](std::size_t r) { return (pcy_atm + t.at(r, pa)) * t.at(r, va) / (pcy_r * pcy_t0); };
    const auto mass_b = [&](std::size_t r) { return (pcy_atm + t.at(r, pb)) * t.at(r, vb) / (pcy_r * pcy_t0); };
    const double gain_a = mass_a(last) - mass_a(0), gain_r = t.at(last, mr) - t.at(0, mr),
                 gain_m = t.at(last, mm) - t.at(0, mm), gain_b = mass_b(last) - mass_b(0);
    const double in_a = integral(qa), in_r = integral(qr), out_vent = integral(qv), delivered = pcy_q * t.at(last, 0);
    CHECK(std::abs(gain_a - in_a) < 1e-6 * gain_a);
    CHECK(std::abs(gain_r - in_r) < 1e-6 * gain_r);
    CHECK(std::abs(gain_m - (delivered - out_vent - in_a - in_r)) < 1e-6 * gain_m);
    const double gain = gain_a + gain_b + gain_r + gain_m;
    CHECK(std::abs(gain - (delivered - out_vent)) < 1e-6 * gain);
  }
}
