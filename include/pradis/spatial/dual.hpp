#pragma once
/// \file
/// Forward-mode automatic differentiation with fixed-size dual numbers: a value and
/// N directional derivatives, no allocation. Nesting (dual<dual<double, N>, N>) gives
/// second derivatives. The corotational beam (BEAM3) differentiates its closed-form
/// gradient with it (first order); its reference test nests it.

#include <array>
#include <cmath>

namespace pradis::spatial {

/// A dual number: value v and the derivatives d[0..N-1] along N seeded directions.
/// S is double or, for second derivatives, another dual.
template <class S, int N>
struct dual {
  S v{};                   ///< value
  std::array<S, N> d{};    ///< derivatives along the seeded directions
  /// Number of derivative directions.
  static constexpr int size = N;

  dual() = default;
  /// A constant (all derivatives zero).
  dual(double x) : v(x) {}  // NOLINT: implicit on purpose, constants mix with duals
  /// A value with zero derivatives.
  static dual constant(const S& x) {
    dual r;
    r.v = x;
    return r;
  }
  /// The independent variable of direction k with value x.
  static dual variable(const S& x, int k) {
    dual r;
    r.v = x;
    r.d[static_cast<std::size_t>(k)] = S(1.0);
    return r;
  }
  /// a += b.
  dual& operator+=(const dual& b) {
    v += b.v;
    for (int k = 0; k < N; ++k) d[k] += b.d[k];
    return *this;
  }
  /// a -= b.
  dual& operator-=(const dual& b) {
    v -= b.v;
    for (int k = 0; k < N; ++k) d[k] -= b.d[k];
    return *this;
  }
};

/// The double value of a double.
inline double value_of(double x) { return x; }
/// The double value of a (nested) dual.
template <class S, int N>
double value_of(const dual<S, N>& x) {
  return value_of(x.v);
}

/// a + b.
template <class S, int N>
dual<S, N> operator+(dual<S, N> a, const dual<S, N>& b) {
  return a += b;
}
/// a - b.
template <class S, int N>
dual<S, N> operator-(dual<S, N> a, const dual<S, N>& b) {
  return a -= b;
}
/// a + c, c a constant.
template <class S, int N>
dual<S, N> operator+(dual<S, N> a, double c) {
  a.v += c;
  return a;
}
/// c + a, c a constant.
template <class S, int N>
dual<S, N> operator+(double c, dual<S, N> a) {
  a.v += c;
  return a;
}
/// a - c, c a constant.
template <class S, int N>
dual<S, N> operator-(dual<S, N> a, double c) {
  a.v -= c;
  return a;
}
/// c - a, c a constant.
template <class S, int N>
dual<S, N> operator-(double c, const dual<S, N>& a) {
  dual<S, N> r = -a;
  r.v += c;
  return r;
}
/// -a.
template <class S, int N>
dual<S, N> operator-(const dual<S, N>& a) {
  dual<S, N> r;
  r.v = -a.v;
  for (int k = 0; k < N; ++k) r.d[k] = -a.d[k];
  return r;
}
/// a b.
template <class S, int N>
dual<S, N> operator*(const dual<S, N>& a, const dual<S, N>& b) {
  dual<S, N> r;
  r.v = a.v * b.v;
  for (int k = 0; k < N; ++k) r.d[k] = a.v * b.d[k] + a.d[k] * b.v;
  return r;
}
/// a c, c a constant.
template <class S, int N>
dual<S, N> operator*(const dual<S, N>& a, double c) {
  dual<S, N> r;
  r.v = a.v * c;
  for (int k = 0; k < N; ++k) r.d[k] = a.d[k] * c;
  return r;
}
/// c a, c a constant.
template <class S, int N>
dual<S, N> operator*(double c, const dual<S, N>& a) {
  return a * c;
}
/// a / b.
template <class S, int N>
dual<S, N> operator/(const dual<S, N>& a, const dual<S, N>& b) {
  dual<S, N> r;
  const S inv = S(1.0) / b.v;
  r.v = a.v * inv;
  for (int k = 0; k < N; ++k) r.d[k] = (a.d[k] - r.v * b.d[k]) * inv;
  return r;
}
/// a / c, c a constant.
template <class S, int N>
dual<S, N> operator/(const dual<S, N>& a, double c) {
  return a * (1.0 / c);
}
/// sqrt(a), a > 0.
template <class S, int N>
dual<S, N> sqrt(const dual<S, N>& a) {
  using std::sqrt;
  dual<S, N> r;
  r.v = sqrt(a.v);
  const S f = S(0.5) / r.v;
  for (int k = 0; k < N; ++k) r.d[k] = a.d[k] * f;
  return r;
}
/// atan(a).
template <class S, int N>
dual<S, N> atan(const dual<S, N>& a) {
  using std::atan;
  dual<S, N> r;
  r.v = atan(a.v);
  const S f = S(1.0) / (S(1.0) + a.v * a.v);
  for (int k = 0; k < N; ++k) r.d[k] = a.d[k] * f;
  return r;
}

}  // namespace pradis::spatial
