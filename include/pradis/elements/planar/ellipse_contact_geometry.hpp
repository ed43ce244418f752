#pragma once
/// \file
/// Geometry of an ellipse in plane motion against one straight segment: the
/// support point, the penetration and their exact derivatives with respect to
/// the body's DOFs (dx, dy, dphi). Used by ELLPL (ellipse_contact.hpp).

#include <cmath>

namespace pradis::elements::detail {

/// One segment P -> Q of a polyline: start point, unit tangent t = (Q - P)/L,
/// left normal n = (-t_y, t_x) (the side the ellipse must stay on) and length L.
struct contact_segment {
  double px = 0, py = 0;  ///< start point P [m]
  double tx = 1, ty = 0;  ///< unit tangent
  double nx = 0, ny = 1;  ///< unit left normal
  double length = 0;      ///< L [m]

  /// The segment from (x1, y1) to (x2, y2); the caller checks L > 0.
  static contact_segment between(double x1, double y1, double x2, double y2) {
    contact_segment s;
    s.px = x1;
    s.py = y1;
    const double dx = x2 - x1, dy = y2 - y1, l = std::hypot(dx, dy);
    s.length = l;
    s.tx = dx / l;
    s.ty = dy / l;
    s.nx = -s.ty;
    s.ny = s.tx;
    return s;
  }
};

/// The deepest point of an ellipse (centre c, angle phi, semi-axes a along the
/// body's x axis and b along its y axis) in the direction -n of a segment, with
///
///     d     = R(phi)^T (-n)                       (the direction in body axes)
///     w     = sqrt(a^2 d_x^2 + b^2 d_y^2)         (the support function)
///     s     = (a^2 d_x, b^2 d_y) / w              (the support point, body axes)
///     delta = w - (c - P).n                       (penetration, > 0 in contact)
///
/// Since d' = (d_y, -d_x) along phi: w' = (a^2 - b^2) d_x d_y / w and
/// w'' = (a^2 - b^2)(d_y^2 - d_x^2) / w - w'^2 / w. With q = (dx, dy, dphi):
/// d delta/dq = (-n_x, -n_y, w'), d^2 delta/dphi^2 = w''. The support point's
/// offset r = R s satisfies r.n = -w and r x t = w, so the tangential velocity of
/// the contact point is v_t = (t_x, t_y, w).q'.
struct ellipse_support {
  double w = 0, dw = 0, ddw = 0;  ///< support function and its first two phi-derivatives [m]
  double sx = 0, sy = 0;          ///< support point in body axes [m]
  double rx = 0, ry = 0;          ///< support point offset R s in global axes [m]
  double delta = 0;               ///< penetration [m] (negative: gap)
  double along = 0;               ///< position of the support point along the segment, (c + r - P).t [m]

  static ellipse_support at(double cx, double cy, double phi, double a, double b, const contact_segment& g) {
    ellipse_support e;
    const double cp = std::cos(phi), sp = std::sin(phi);
    const double dx = -(cp * g.nx + sp * g.ny), dy = sp * g.nx - cp * g.ny;
    const double a2 = a * a, b2 = b * b;
    e.w = std::sqrt(a2 * dx * dx + b2 * dy * dy);
    e.dw = (a2 - b2) * dx * dy / e.w;
    e.ddw = (a2 - b2) * (dy * dy - dx * dx) / e.w - e.dw * e.dw / e.w;
    e.sx = a2 * dx / e.w;
    e.sy = b2 * dy / e.w;
    e.rx = cp * e.sx - sp * e.sy;
    e.ry = sp * e.sx + cp * e.sy;
    e.delta = e.w - ((cx - g.px) * g.nx + (cy - g.py) * g.ny);
    e.along = (cx + e.rx - g.px) * g.tx + (cy + e.ry - g.py) * g.ty;
    return e;
  }
};

}  // namespace pradis::elements::detail
