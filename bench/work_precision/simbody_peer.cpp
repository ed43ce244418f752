// Simbody models of the work-precision problems top, topx and chain (simbody_peer.h),
// compiled only when Simbody is found (PRADIS_WP_SIMBODY), as a module that
// work_precision loads at run time.
//
// Each run builds its system, so that the measured CPU time contains the model's
// set-up as it does for the pradis runs (model assembly) and the SUNDIALS runs
// (IDACreate / CVodeCreate); TimeStepper is not used, the integrator is stepped to
// the final time directly (Integrator::setFinalTime, stepTo), without
// interpolation to the report time.

#include "simbody_peer.h"

#include <Simbody.h>

#include <cmath>
#include <exception>
#include <memory>
#include <vector>

namespace {

using namespace SimTK;

enum class integrator { rkm, cpodes };

struct result {
  bool ok = false;
  long steps = 0, iterations = 0, realizations = 0;
  std::vector<double> z;
};

/// The C interface's view of a result.
int give(const result& r, double* z, long* counters) {
  counters[0] = r.steps, counters[1] = r.iterations, counters[2] = r.realizations;
  for (std::size_t i = 0; i < r.z.size(); ++i) z[i] = r.z[i];
  return r.ok ? 1 : 0;
}

std::unique_ptr<Integrator> make_integrator(integrator in, const MultibodySystem& sys, double accuracy) {
  std::unique_ptr<Integrator> i;
  if (in == integrator::rkm)
    i = std::make_unique<RungeKuttaMersonIntegrator>(sys);
  else
    i = std::make_unique<CPodesIntegrator>(sys, CPodes::BDF, CPodes::Newton);
  i->setAccuracy(accuracy);
  i->setInternalStepLimit(100000000);
  return i;
}

/// Integrates sys from s to t_end; calls out(state) at the end.
template <class Out>
result integrate(integrator in, double accuracy, double t_end, const MultibodySystem& sys, const State& s, Out&& out) {
  result r;
  try {
    std::unique_ptr<Integrator> integ = make_integrator(in, sys, accuracy);
    integ->setFinalTime(t_end);
    integ->setAllowInterpolation(false);
    integ->initialize(s);
    // RKM ends the simulation at the final time; CPodes returns ReachedReportTime there.
    while (!integ->isSimulationOver() && integ->getTime() < t_end) integ->stepTo(t_end, t_end);
    r.ok = std::abs(integ->getTime() - t_end) <= 1e-12 * t_end;
    r.steps = integ->getNumStepsTaken();
    r.iterations = integ->getNumIterations();
    r.realizations = integ->getNumRealizations();
    const State& e = integ->getState();
    sys.realize(e, Stage::Velocity);
    out(e, r.z);
  } catch (const std::exception&) {
    r.ok = false;
  }
  return r;
}

/// (q with the scalar last, omega_b) of a body.
void rotation_state(const State& s, const MobilizedBody& b, std::vector<double>& z) {
  const Rotation& r = b.getBodyRotation(s);
  const Quaternion q = r.convertRotationToQuaternion();  // (w, x, y, z)
  const Vec3 wb = ~r * b.getBodyAngularVelocity(s);
  z = {q[1], q[2], q[3], q[0], wb[0], wb[1], wb[2]};
}

/// The top's joint: the force -(k p_B + c v_B) on the tip B of the body.
class tip_spring : public Force::Custom::Implementation {
 public:
  tip_spring(const MobilizedBody& b, const Vec3& tip, double k, double c) : b_(b), tip_(tip), k_(k), c_(c) {}
  void calcForce(const State& s, Vector_<SpatialVec>& body_forces, Vector_<Vec3>&, Vector&) const override {
    const Vec3 p = b_.findStationLocationInGround(s, tip_), v = b_.findStationVelocityInGround(s, tip_);
    b_.applyForceToBodyPoint(s, tip_, -(k_ * p + c_ * v), body_forces);
  }
  Real calcPotentialEnergy(const State& s) const override {
    const Vec3 p = b_.findStationLocationInGround(s, tip_);
    return 0.5 * k_ * (~p * p);
  }

 private:
  const MobilizedBody& b_;
  Vec3 tip_;
  double k_, c_;
};

struct top_parameters {
  double m, l, j1, j3, w3, theta0, k, c, g;
};

result top(integrator in, double accuracy, double t_end, const top_parameters& p) {
  MultibodySystem sys;
  SimbodyMatterSubsystem matter(sys);
  GeneralForceSubsystem forces(sys);
  Force::UniformGravity gravity(forces, matter, Vec3(0, 0, -p.g));
  // Body frame at the centre of mass, axes = principal axes (Z the symmetry axis).
  const Body::Rigid body(MassProperties(p.m, Vec3(0), Inertia(p.j1, p.j1, p.j3)));
  MobilizedBody::Free b(matter.updGround(), Transform(), body, Transform());
  Force::Custom joint(forces, new tip_spring(b, Vec3(0, 0, -p.l), p.k, p.c));
  State s = sys.realizeTopology();
  const Rotation tilt(p.theta0, XAxis);
  const Vec3 axis0 = tilt * Vec3(0, 0, 1);  // (0, -sin theta0, cos theta0)
  b.setQToFitTransform(s, Transform(tilt, p.l * axis0));  // the tip at the origin
  b.setUToFitAngularVelocity(s, p.w3 * axis0);              // omega_b = (0, 0, w3); the centre of mass at rest
  return integrate(in, accuracy, t_end, sys, s,
                   [&](const State& e, std::vector<double>& z) { rotation_state(e, b, z); });
}

result top_exact(integrator in, double accuracy, double t_end, const top_parameters& p) {
  MultibodySystem sys;
  SimbodyMatterSubsystem matter(sys);
  GeneralForceSubsystem forces(sys);
  Force::UniformGravity gravity(forces, matter, Vec3(0, 0, -p.g));
  // Body frame at the centre of mass; the Ball's outboard frame at the tip (0, 0, -l).
  const Body::Rigid body(MassProperties(p.m, Vec3(0), Inertia(p.j1, p.j1, p.j3)));
  MobilizedBody::Ball b(matter.updGround(), Transform(), body, Transform(Vec3(0, 0, -p.l)));
  State s = sys.realizeTopology();
  const Rotation tilt(p.theta0, XAxis);
  b.setQToFitRotation(s, tilt);
  b.setUToFitAngularVelocity(s, p.w3 * (tilt * Vec3(0, 0, 1)));  // omega_b = (0, 0, w3)
  return integrate(in, accuracy, t_end, sys, s,
                   [&](const State& e, std::vector<double>& z) { rotation_state(e, b, z); });
}

result chain(integrator in, double accuracy, double t_end, int n, double l, double m, double g) {
  MultibodySystem sys;
  SimbodyMatterSubsystem matter(sys);
  GeneralForceSubsystem forces(sys);
  Force::UniformGravity gravity(forces, matter, Vec3(0, -g, 0));
  // Link j: frame at its hinge, the point mass at (l, 0, 0); Pin about Z.
  const Body::Rigid link(MassProperties(m, Vec3(l, 0, 0), Inertia(Vec3(l, 0, 0), m)));
  std::vector<MobilizedBody::Pin> pins;
  pins.reserve(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    MobilizedBody& parent = j == 0 ? static_cast<MobilizedBody&>(matter.updGround()) : pins.back();
    pins.emplace_back(parent, Transform(Vec3(j == 0 ? 0 : l, 0, 0)), link, Transform());
  }
  State s = sys.realizeTopology();  // all angles and rates 0: horizontal, at rest
  return integrate(in, accuracy, t_end, sys, s, [&](const State& e, std::vector<double>& z) {
    z.assign(static_cast<std::size_t>(2 * n), 0.0);
    double th = 0, om = 0;
    for (int j = 0; j < n; ++j) {
      th += pins[static_cast<std::size_t>(j)].getAngle(e);
      om += pins[static_cast<std::size_t>(j)].getRate(e);
      z[static_cast<std::size_t>(j)] = th;
      z[static_cast<std::size_t>(n + j)] = om;
    }
  });
}

}  // namespace

extern "C" __attribute__((visibility("default"))) int wp_simbody_top(int in, double accuracy, double t_end,
                                                                      const double* p, double* z, long* counters) {
  const top_parameters tp{p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8]};
  return give(top(in == wp_simbody_rkm ? integrator::rkm : integrator::cpodes, accuracy, t_end, tp), z, counters);
}

extern "C" __attribute__((visibility("default"))) int wp_simbody_top_exact(int in, double accuracy, double t_end,
                                                                            const double* p, double* z,
                                                                            long* counters) {
  const top_parameters tp{p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8]};
  return give(top_exact(in == wp_simbody_rkm ? integrator::rkm : integrator::cpodes, accuracy, t_end, tp), z,
              counters);
}

extern "C" __attribute__((visibility("default"))) int wp_simbody_chain(int in, double accuracy, double t_end, int n,
                                                                        double l, double m, double g, double* z,
                                                                        long* counters) {
  return give(chain(in == wp_simbody_rkm ? integrator::rkm : integrator::cpodes, accuracy, t_end, n, l, m, g), z,
              counters);
}
