#pragma once
/// \file
/// Numeric kernels of the sparse LU: power-of-two equilibration of the matrix values and the
/// row-oriented elimination with the static pivot test. Allocation-free.

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "pradis/core/error.hpp"
#include "pradis/linalg/lu_symbolic.hpp"
#include "pradis/linalg/sparsity.hpp"

namespace pradis::linalg::detail {

/// 2^-e with m = f 2^e, f in [0.5, 1) (so m 2^-e is in [0.5, 1)); 1 for m == 0. The exponent
/// is clamped so that the scale is a normal, finite double. Bit arithmetic on the IEEE 754
/// exponent field (a library frexp/ldexp per row and column would cost as much as a small
/// refactorisation).
inline double inverse_power_of_two(double m) {
  const auto biased = static_cast<int>((std::bit_cast<std::uint64_t>(m) >> 52) & 0x7ff);  // m >= 0
  if (biased == 0 || biased == 0x7ff) {  // zero, subnormal (rare) or not finite
    if (!(m > 0) || !std::isfinite(m)) return 1.0;
    int e = 0;
    (void)std::frexp(m, &e);
    return std::ldexp(1.0, std::clamp(-e, -1022, 1023));
  }
  // m = 1.f * 2^(biased - 1023) = 0.1f * 2^(biased - 1022): e = biased - 1022, 2^-e has the
  // biased exponent 1023 - e = 2045 - biased, which is in [1, 2044] here.
  return std::bit_cast<double>(static_cast<std::uint64_t>(2045 - biased) << 52);
}

/// Equilibrates `values` (CSR order of `a`) and loads the factor storage: rs[r] scales row r
/// so that its largest magnitude is in [0.5, 1), then cs[j] scales column j of the row-scaled
/// matrix likewise (all 1 when `on` is false). Writes the scaled values rs_r a_rj cs_j (exact:
/// powers of two) to `scaled` and to their factor slots fv[a_map[q]] (the other slots are set
/// to 0), and per row their largest magnitude (1 for an all-zero row) and 1-norm. Throws
/// pradis::error(error_code::non_finite, msg, {}, {}, row) for a NaN or infinite value.
inline void equilibrate(const sparsity_pattern& a, std::span<const double> values, bool on, double* rs, double* cs,
                        double* scaled, double* row_max, double* row_norm1, const int* a_map, double* fv,
                        std::size_t nnz_factor) {
  const int n = a.n;
  const int* const rp = a.row_ptr.data();
  const int* const ac = a.col.data();
  std::fill(cs, cs + n, on ? 0.0 : 1.0);
  for (int r = 0; r < n; ++r) {
    double m = 0, sum = 0;
    for (int q = rp[r]; q < rp[r + 1]; ++q) {
      m = std::max(m, std::abs(values[q]));
      sum += std::abs(values[q]);  // NaN or inf propagates here (std::max may drop a NaN)
    }
    if (!std::isfinite(sum)) {  // a non-finite entry, or an overflowing sum of finite ones
      for (int q = rp[r]; q < rp[r + 1]; ++q)
        if (!std::isfinite(values[q]))
          throw error(error_code::non_finite,
                      "matrix entry (row " + std::to_string(r) + ", column " + std::to_string(ac[q]) + ") is " +
                          std::to_string(values[q]),
                      {}, {}, r);
    }
    double s = 1.0;
    if (on) {
      s = inverse_power_of_two(m);
      for (int q = rp[r]; q < rp[r + 1]; ++q) cs[ac[q]] = std::max(cs[ac[q]], s * std::abs(values[q]));
    }
    rs[r] = s;
  }
  if (on)
    for (int j = 0; j < n; ++j) cs[j] = inverse_power_of_two(cs[j]);
  std::fill(fv, fv + nnz_factor, 0.0);
  for (int r = 0; r < n; ++r) {
    double m = 0, s1 = 0;
    const double s = rs[r];
    for (int q = rp[r]; q < rp[r + 1]; ++q) {
      const double v = values[q] * s * cs[ac[q]];
      scaled[q] = v;
      fv[a_map[q]] = v;
      m = std::max(m, std::abs(v));
      s1 += std::abs(v);
    }
    row_max[r] = m > 0 ? m : 1.0;
    row_norm1[r] = s1;
  }
}

/// Outcome of eliminate(): perturbation count, first perturbed original row, growth, and on
/// failure the elimination step with its pivot and scale (failed_step = -1 when none).
struct elimination_result {
  long perturbed = 0;
  int first_perturbed = -1;
  double growth = 0;
  int failed_step = -1;
  double failed_pivot = 0;
  double failed_scale = 0;
};

/// Row-oriented (IKJ) LU in place on the factor values `fv` (already holding A, permuted):
/// factor row i is scattered into the dense work vector `w`; for each k of its L pattern in
/// ascending order, l_ik = w_k / u_kk and l_ik * (row k of U) is subtracted; the row is
/// gathered back. The symbolic phase guarantees that row k of U lies inside the pattern of row
/// i, so only the row's own positions of `w` are used.
///
/// Pivot test with scale = max(row_max[r] of the original row r, max |u_ij| of the eliminated
/// row): a pivot with |pivot| <= threshold * scale is replaced by
/// sign(pivot) * perturbation * scale when static_pivoting, else elimination stops there
/// (failed_step); a non-finite pivot or row always stops it.
inline elimination_result eliminate(const lu_structure& s, double* fv, double* w, const double* row_max,
                                    double threshold, double perturbation, bool static_pivoting) {
  elimination_result res;
  const int n = static_cast<int>(s.perm.size());
  const int* const fc = s.f_col.data();
  const int* const fp = s.f_ptr.data();
  const int* const dp = s.d_pos.data();
  for (int i = 0; i < n; ++i) {
    const int b = fp[i], d = dp[i], e = fp[i + 1];
    for (int p = b; p < e; ++p) w[fc[p]] = fv[p];
    for (int p = b; p < d; ++p) {
      const int k = fc[p];
      const double l = w[k] / fv[dp[k]];
      w[k] = l;
      const int ke = fp[k + 1];
      for (int q = dp[k] + 1; q < ke; ++q) w[fc[q]] -= l * fv[q];
    }
    double umax = 0;
    for (int p = b; p < d; ++p) fv[p] = w[fc[p]];
    for (int p = d; p < e; ++p) {
      const double v = w[fc[p]];
      fv[p] = v;
      umax = std::max(umax, std::abs(v));
    }
    const int r = s.perm[i];
    const double piv = fv[d];
    const double scale = std::max(row_max[r], umax);
    if (!std::isfinite(piv) || !std::isfinite(umax) || (!static_pivoting && !(std::abs(piv) > threshold * scale))) {
      res.failed_step = i;
      res.failed_pivot = piv;
      res.failed_scale = scale;
      return res;
    }
    res.growth = std::max(res.growth, umax / row_max[r]);
    if (!(std::abs(piv) > threshold * scale)) {
      fv[d] = (piv < 0 ? -perturbation : perturbation) * scale;
      if (res.perturbed++ == 0) res.first_perturbed = r;
    }
  }
  return res;
}

}  // namespace pradis::linalg::detail
