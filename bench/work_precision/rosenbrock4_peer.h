/* Boost.Odeint rosenbrock4 behind a plain C interface. Boost 1.74's uBLAS (which
   rosenbrock4 needs) does not compile as C++20 (it calls std::allocator members
   removed in C++20), so rosenbrock4_peer.cpp is built as C++17 in its own static
   library and the C++20 benchmark calls it through this header only. */
#ifndef PRADIS_WP_ROSENBROCK4_PEER_H
#define PRADIS_WP_ROSENBROCK4_PEER_H

#ifdef __cplusplus
extern "C" {
#endif

/* dy/dt = f(t, y) for a system of n equations. */
typedef void (*wp_r4_rhs)(void* user, double t, const double* y, double* dydt);
/* df/dy (n x n, row-major, into jac) and df/dt (into dfdt). */
typedef void (*wp_r4_jacobian)(void* user, double t, const double* y, double* jac, double* dfdt);

/* Counters of one integration. */
typedef struct wp_r4_result {
  long steps;     /* accepted steps (odeint's integrate_adaptive count) */
  long jacobians; /* Jacobian evaluations = LU factorisations (one per attempted step) */
  int ok;         /* 1 on success, 0 if odeint threw (e.g. too many step size reductions) */
} wp_r4_result;

/* Integrates y from t0 to t1 (y: n values, overwritten with y(t1)) by the
   controlled rosenbrock4 stepper of Boost.Odeint with absolute and relative
   tolerances atol, rtol and initial step h0. */
wp_r4_result wp_rosenbrock4(int n, double* y, double t0, double t1, double atol, double rtol, double h0,
                            wp_r4_rhs f, wp_r4_jacobian jac, void* user);

#ifdef __cplusplus
}
#endif
#endif
