#pragma once
// Simbody models of three work-precision problems (simbody_peer.cpp), built as a
// loadable module with a plain C interface. Why a module: Simbody's CPodes is a
// fork of SUNDIALS CVODE and libSimTKmath exports the same N_V* vector symbols as
// SUNDIALS 6 with a different N_Vector layout; linked into one executable with
// SUNDIALS, whichever library comes first in the link serves both and the other
// crashes. work_precision therefore dlopen()s this module with RTLD_DEEPBIND, which
// makes the module and Simbody's libraries resolve their symbols among themselves.
//
// Each function builds the multibody system, integrates it from t = 0 to t_end
// with the given Simbody integrator at accuracy `accuracy`
// (Integrator::setAccuracy), writes the compared state of work_precision.cpp to z
// and the counters (steps taken, Newton iterations of CPodes (0 for RKM),
// realizations of the equations of motion) to counters[0..2], and returns 1 if the
// integration reached t_end (0 otherwise, also on an exception).
//   top, topx: z[0..6] = (q1, q2, q3, q4, w1, w2, w3), the quaternion of the body's
//          rotation R_GB with the scalar part last (pradis's convention; Simbody's
//          Quaternion is (w, x, y, z)) and the body angular velocity
//          omega_b = R_GB^T w_GB;
//   chain: z[0..2n-1] = (theta_1..theta_n, theta_1'..theta_n'), the absolute link
//          angles from +X and their rates (chain_reference.hpp): sums of the Pin
//          mobilizers' relative angles and rates.
// The free body of the benchmark (inertias (2, 1, 2/3)) has no Simbody model: its
// inertias violate the triangle inequality I1 <= I2 + I3 (2 > 1 + 2/3), no mass
// distribution has them, and Simbody's Inertia refuses them.

#ifdef __cplusplus
extern "C" {
#endif

/// Integrators: 0 RungeKuttaMersonIntegrator, 1 CPodesIntegrator (BDF, Newton).
enum { wp_simbody_rkm = 0, wp_simbody_cpodes = 1 };

/// Heavy top of examples/spinning_top with its penalty joint, p = (m, l, j1, j3, w3,
/// theta0, k, c, g): mass m, centre of mass l from the tip along body Z, inertias
/// (j1, j1, j3) about the centre of mass, the tip held at the ground origin by the
/// force -(k p_B + c v_B) (p_B, v_B: position and velocity of the tip), gravity -g Z;
/// tilted by theta0 about X, spinning at w3 about its axis. Free mobilizer: the same
/// equations as rigid::top_rhs.
int wp_simbody_top(int integrator, double accuracy, double t_end, const double* p, double* z, long* counters);
typedef int (*wp_simbody_top_fn)(int, double, double, const double*, double*, long*);

/// The same top on an exact spherical joint: a Ball mobilizer at the tip (p as for
/// wp_simbody_top; k and c unused). z as for wp_simbody_top.
int wp_simbody_top_exact(int integrator, double accuracy, double t_end, const double* p, double* z, long* counters);

/// Planar pendulum chain of chain_reference.hpp: n point masses m on massless links
/// of length l, the first hinged at the ground origin, released horizontally from
/// rest under gravity -g Y; Pin mobilizers (exact joints).
int wp_simbody_chain(int integrator, double accuracy, double t_end, int n, double l, double m, double g, double* z,
                     long* counters);
typedef int (*wp_simbody_chain_fn)(int, double, double, int, double, double, double, double*, long*);

#ifdef __cplusplus
}
#endif
