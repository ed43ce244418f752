// examples/models/eccentric_shaker.prd: an unbalanced rotor (MEKS: m = 0.5 kg at R = 0.05 m) turned at a constant
// 10 Hz by VSRC on a frame (MASS 20 kg) that a vertical guide (XSRC holding X at 0) lets move only along Y, on a
// mount (SPRING 5e4 N/m, DAMPER 400 N s/m), in the model language.
//
// The laws checked:
// - MEKS's flows (eccentric_mass.hpp) with a_x = 0 and eps = theta'' = 0: the guide carries
//   F_x = -m R omega^2 cos(phi) (the centripetal force), the drive supplies M_z = m R cos(phi) a_y, and the frame
//   obeys (M0 + m) y'' + c y' + k y = m R omega^2 sin(phi), phi = omega t + alpha (the sum of the flows on the frame's
//   DOF vanishes to Newton's residual test).
// - The rotating unbalance: the steady state of that forced oscillator,
//       y = X sin(omega t + alpha - psi), X = m R omega^2 / sqrt((k - M omega^2)^2 + (c omega)^2),
//       tan(psi) = c omega / (k - M omega^2), M = M0 + m
//   (S. S. Rao, Mechanical Vibrations, 5th ed., 2011, section 3.7 "Response of a damped system under rotating
//   unbalance"; W. T. Thomson, Theory of Vibration with Applications, chapter 3, "Rotating unbalance"), and the
//   mean power balance: what the drive puts in, the damper dissipates, c omega^2 X^2 / 2.
// - NEWMARK with BETA = 1/4, GAMMA = 1/2 is the trapezoidal rule for v and for u (average acceleration; T. J. R.
//   Hughes, The Finite Element Method, 2000, chapter 9): on a sequence z^n, z = exp(i omega h), a time derivative
//   becomes the factor (2/h)(z - 1)/(z + 1) = i Omega, Omega = (2/h) tan(omega h / 2). Its steady state to the
//   forcing sampled at the step ends is therefore the closed form above with Omega for omega in the frame's
//   impedance: U_d = m R omega^2 e^(i alpha) / (k - M Omega^2 + i c Omega), velocity i Omega U_d, acceleration
//   -Omega^2 U_d. The run must meet U_d to its Newton residuals and round-off, and the continuous X within the
//   exactly known difference |U_d| - X (the trapezoidal rule's frequency warping, (omega h)^2 / 12 in Omega).
//   The same algebra gives the discrete power balance: mean(T omega) = (Omega / omega) mean(c v^2).
//
// Tolerances follow from the run's settings: the fixed step h = 1 ms (= OUT, 100 samples per revolution), the
// window 3 s < t <= 4 s (10 whole revolutions: the projections on sin and cos and the means of products are
// exact there for a sampled sinusoid), and Newton's residual test DABSI * 1 N + DRLTI * (sum of |flows|)
// (include/pradis/integrators/newton.hpp). A deviation of the samples from U_d has three sources, each bounded:
// - the start transient (the run starts at rest): a free mode of the trapezoidal rule, amplification
//   z_h = (1 + h lambda / 2) / (1 - h lambda / 2), lambda = -zeta omega_n + i omega_d, of initial amplitude at most
//   |U_d| (1 + (Omega + zeta omega_n) / omega_d) (minus the steady state at t = 0), times |z_h|^3000; a factor 2
//   covers the difference of the discrete mode shape from the continuous one (omega_n h = 0.05);
// - a Newton residual rho acts as a force on the frame; the response of a damped oscillator to a force bounded
//   by rho is at most rho times the integral of |impulse response|, 1 / (k zeta sqrt(1 - zeta^2)); a factor 2
//   covers the sum over the steps against the integral;
// - round-off of 64 eps |U_d| per step, decaying like the free mode: 64 eps |U_d| / (1 - |z_h|).
// A projection over whole periods is off by at most 2 sqrt(2) times the largest pointwise deviation (3 taken).

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <numbers>
#include <string>

#include "lang_test_support.hpp"

using namespace pradis;

namespace {
// The file's $DATA.
constexpr double shk_omega = 62.83185307179586;              // rotor speed [rad/s] (10 Hz)
constexpr double shk_m = 0.5, shk_r = 0.05, shk_alpha = 0;   // unbalance mass [kg], radius [m], angle [deg]
constexpr double shk_m0 = 20, shk_k = 5e4, shk_c = 400;      // frame mass [kg], mount [N/m], [N s/m]
// $RUN: the fixed step (= OUT) and Newton's residual test; the window of whole revolutions.
constexpr double shk_h = 1e-3, shk_dabsi = 1e-10, shk_drlti = 1e-12;
constexpr double shk_window_start = 3, shk_window_end = 4;
constexpr const char* shk_run_line = "'NEWMARK (END=4, OUT=1E-3, SMAX=1E-3, ITR=20,";
constexpr double shk_eps = std::numeric_limits<double>::epsilon();
using shk_complex = std::complex<double>;
}  // namespace

TEST_SUITE("lang/eccentric shaker") {
  TEST_CASE("examples/models/eccentric_shaker.prd: MEKS's flows, the steady state of the rotating unbalance (the "
            "trapezoidal rule's closed form and the continuous one) and the power balance") {
    const std::string text = lang_test::slurp(lang_test::models_dir() / "eccentric_shaker.prd");
    REQUIRE(text.find(shk_run_line) != std::string::npos);  // the settings the tolerances come from
    auto s = std::make_unique<lang::session>(
        lang::parse_file((lang_test::models_dir() / "eccentric_shaker.prd").string()));
    s->run({.write_files = false});
    const io::table& t = s->results();
    const auto col = [&](const char* label) { return lang_test::column(t, label); };
    const std::size_t th = col("Rotor angle"), w = col("Rotor speed"), y = col("Frame position"),
                      v = col("Frame velocity"), a = col("Frame acceleration"), fk = col("Mount force"),
                      fc = col("Damping force"), torque = col("Drive torque"), guide = col("Guide force"),
                      steps = col("Steps");
    const std::size_t last = t.rows() - 1;
    REQUIRE(t.rows() == 4001);           // t = 0 and every 1 ms to 4 s
    REQUIRE(t.at(last, steps) == 4000);  // the fixed step throughout

    const double mass = shk_m0 + shk_m, f0 = shk_m * shk_r * shk_omega * shk_omega;
    const double alpha = shk_alpha * std::numbers::pi / 180;

    // Every sample: MEKS's flows and the frame's balance.
    int angle_off = 0, guide_off = 0, torque_off = 0, mount_off = 0;
    double newton_ratio = 0, flows_max = 0;
    for (std::size_t r = 0; r <= last; ++r) {
      const double time = t.at(r, 0), phi = t.at(r, th) + alpha, ay = t.at(r, a);
      CHECK(t.at(r, w) == shk_omega);
      angle_off += std::abs(t.at(r, th) - shk_omega * time) > 4 * shk_eps * shk_omega * time;
      // MEKS's F_x and M_z with a_x = 0, eps = 0 (their flows are the sources' reactions).
      guide_off += std::abs(t.at(r, guide) + f0 * std::cos(phi)) > 16 * shk_eps * f0;
      torque_off += std::abs(t.at(r, torque) - shk_m * shk_r * std::cos(phi) * ay) >
                    16 * shk_eps * shk_m * shk_r * std::abs(ay);
      mount_off += std::abs(t.at(r, fk) - shk_k * t.at(r, y)) > 4 * shk_eps * shk_k * std::abs(t.at(r, y)) ||
                   std::abs(t.at(r, fc) - shk_c * t.at(r, v)) > 4 * shk_eps * shk_c * std::abs(t.at(r, v));
      // The frame's DOF: MASS, MEKS's F_y, SPRING and DAMPER flows.
      const double f_mass = shk_m0 * ay, f_meks = shk_m * (ay - shk_r * shk_omega * shk_omega * std::sin(phi));
      const double flows = std::abs(f_mass) + std::abs(f_meks) + std::abs(t.at(r, fk)) + std::abs(t.at(r, fc));
      flows_max = std::max(flows_max, flows);
      newton_ratio = std::max(newton_ratio, std::abs(f_mass + f_meks + t.at(r, fk) + t.at(r, fc)) /
                                                (shk_dabsi + shk_drlti * flows));
    }
    CHECK(angle_off == 0);
    CHECK(guide_off == 0);
    CHECK(torque_off == 0);
    CHECK(mount_off == 0);
    CHECK(newton_ratio <= 1);

    // The closed forms: the trapezoidal rule's steady state U_d and the continuous one U_c.
    const double omega_big = 2 / shk_h * std::tan(shk_omega * shk_h / 2);
    const shk_complex force = f0 * std::polar(1.0, alpha), i1(0, 1);
    const shk_complex u_d = force / (shk_k - mass * omega_big * omega_big + i1 * shk_c * omega_big);
    const shk_complex u_c = force / (shk_k - mass * shk_omega * shk_omega + i1 * shk_c * shk_omega);
    const double x_c = f0 / std::hypot(shk_k - mass * shk_omega * shk_omega, shk_c * shk_omega);
    const double psi_c = std::atan2(shk_c * shk_omega, shk_k - mass * shk_omega * shk_omega);
    REQUIRE(std::abs(std::abs(u_c) - x_c) <= 4 * shk_eps * x_c);
    REQUIRE(std::abs(std::arg(u_c) + psi_c) <= 4 * shk_eps * std::numbers::pi);

    // The bound on the samples' deviation from U_d in the window (see the top of the file).
    const double wn = std::sqrt(shk_k / mass), zeta = shk_c / (2 * std::sqrt(shk_k * mass));
    const double wd = wn * std::sqrt(1 - zeta * zeta);
    const shk_complex lambda(-zeta * wn, wd);
    const double zh = std::abs((1.0 + shk_h * lambda / 2.0) / (1.0 - shk_h * lambda / 2.0));
    const double n_start = std::round(shk_window_start / shk_h);
    const double e_transient = 2 * std::abs(u_d) * (1 + (omega_big + zeta * wn) / wd) * std::pow(zh, n_start);
    const double rho = shk_dabsi + shk_drlti * flows_max;
    const double e_residual = 2 * rho / (shk_k * zeta * std::sqrt(1 - zeta * zeta));
    const double e_roundoff = 64 * shk_eps * std::abs(u_d) / (1 - zh);
    const double e_u = e_transient + e_residual + e_roundoff;

    // Projections and means over the 10 revolutions of the window.
    double ps = 0, pc = 0, p_in = 0, p_damper = 0, pointwise = 0;
    int n = 0;
    for (std::size_t r = 0; r <= last; ++r) {
      const double time = t.at(r, 0);
      if (!(time > shk_window_start + shk_h / 2 && time <= shk_window_end + shk_h / 2)) continue;
      ++n;
      const double yr = t.at(r, y);
      ps += yr * std::sin(shk_omega * time);
      pc += yr * std::cos(shk_omega * time);
      p_in += t.at(r, torque) * shk_omega;
      p_damper += t.at(r, fc) * t.at(r, v);
      pointwise = std::max(pointwise, std::abs(yr - (u_d * std::exp(i1 * (shk_omega * time))).imag()));
    }
    REQUIRE(n == 1000);
    // y = Im(U e^(i omega t)) = Re(U) sin(omega t) + Im(U) cos(omega t).
    const shk_complex u_meas(2 * ps / n, 2 * pc / n);
    p_in /= n;
    p_damper /= n;
    const double e_proj = 3 * e_u;
    MESSAGE("shaker: X = ", x_c, " m, psi = ", psi_c, " rad (continuous); the trapezoidal rule's |U_d| = ",
            std::abs(u_d), " m (", std::abs(u_d) / x_c - 1, " relative); measured |U| = ", std::abs(u_meas),
            ", off U_d by ", std::abs(u_meas - u_d), " m (bound ", e_proj, ": transient ", e_transient,
            ", residuals ", e_residual, ", round-off ", e_roundoff, "), pointwise ", pointwise, " m; off U_c by ",
            std::abs(u_meas - u_c), " m; Newton's balance at ", newton_ratio, " of its tolerance");
    CHECK(pointwise <= e_u);
    CHECK(std::abs(u_meas - u_d) <= e_proj);
    // The continuous closed form: amplitude and phase within the warping's exactly known share.
    CHECK(std::abs(std::abs(u_meas) - x_c) <= std::abs(std::abs(u_d) - x_c) + e_proj);
    CHECK(std::abs(std::arg(u_meas) + psi_c) <= std::abs(std::arg(u_d) - std::arg(u_c)) + e_proj / std::abs(u_d));
    // ... and the run resolves that share: it is what separates the run from X.
    CHECK(std::abs(u_meas - u_d) < 1e-3 * std::abs(u_meas - u_c));

    // The power balance. The relative error of a velocity (acceleration) amplitude is at most (1 + omega_n / Omega)
    // (its square) times e_u / |U_d|; the input is linear in the acceleration's component in phase with cos(phi),
    // |U_d| sin(psi_d) of the amplitude, the dissipation quadratic in the velocity.
    const double psi_d = -std::arg(u_d * std::polar(1.0, -alpha));
    const double rel = e_u / std::abs(u_d), grow = 1 + wn / omega_big;
    const double p_closed = shk_c * omega_big * omega_big * std::norm(u_d) / 2;
    const double p_cont = shk_c * shk_omega * shk_omega * x_c * x_c / 2;
    const double tol_p = p_closed * (rel * grow * grow / std::abs(std::sin(psi_d)) + 3 * rel * grow) * 2;
    MESSAGE("power: the drive puts in ", p_in, " W, the damper takes ", p_damper, " W (ratio ", p_in / p_damper,
            ", Omega / omega = ", omega_big / shk_omega, "); trapezoidal closed form ", p_closed,
            " W, continuous c omega^2 X^2 / 2 = ", p_cont, " W");
    CHECK(std::abs(p_in - omega_big / shk_omega * p_damper) <= tol_p);
    CHECK(std::abs(p_damper - p_closed) <= tol_p);
    CHECK(std::abs(p_damper - p_cont) <= std::abs(p_closed - p_cont) + tol_p);
  }
}
