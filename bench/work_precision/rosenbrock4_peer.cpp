// Boost.Odeint rosenbrock4 for the work-precision benchmark, compiled as C++17
// (see rosenbrock4_peer.h).
#include "rosenbrock4_peer.h"

#include <boost/numeric/odeint.hpp>
#include <cstddef>
#include <exception>
#include <utility>
#include <vector>

namespace {
namespace odeint = boost::numeric::odeint;
using vec = boost::numeric::ublas::vector<double>;
using mat = boost::numeric::ublas::matrix<double>;
}  // namespace

extern "C" wp_r4_result wp_rosenbrock4(int n, double* y, double t0, double t1, double atol, double rtol, double h0,
                                       wp_r4_rhs f, wp_r4_jacobian jac, void* user) {
  wp_r4_result r{0, 0, 1};
  const auto un = static_cast<std::size_t>(n);
  vec x(un);
  for (std::size_t i = 0; i < un; ++i) x[i] = y[i];
  std::vector<double> in(un), out(un), j(un * un), dfdt(un);
  auto rhs = [&](const vec& s, vec& ds, double t) {
    for (std::size_t i = 0; i < un; ++i) in[i] = s[i];
    f(user, t, in.data(), out.data());
    for (std::size_t i = 0; i < un; ++i) ds[i] = out[i];
  };
  auto jacobian = [&](const vec& s, mat& jm, double t, vec& dt) {
    for (std::size_t i = 0; i < un; ++i) in[i] = s[i];
    jac(user, t, in.data(), j.data(), dfdt.data());
    ++r.jacobians;
    for (std::size_t a = 0; a < un; ++a) {
      dt[a] = dfdt[a];
      for (std::size_t b = 0; b < un; ++b) jm(a, b) = j[a * un + b];
    }
  };
  try {
    r.steps = static_cast<long>(odeint::integrate_adaptive(odeint::make_controlled<odeint::rosenbrock4<double>>(atol, rtol),
                                                           std::make_pair(rhs, jacobian), x, t0, t1, h0));
  } catch (const std::exception&) {
    r.ok = 0;
  }
  for (std::size_t i = 0; i < un; ++i) y[i] = x[i];
  return r;
}
