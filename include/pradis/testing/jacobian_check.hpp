#pragma once
/// \file
/// Finite-difference Jacobian checker: the manual's section 3.6.8 test harness,
/// automated. For an element at a state (u, v, a, t) it perturbs the
/// displacement, velocity and acceleration of every local DOF by central
/// differences, compares the numerical derivatives with every block the passport
/// declares, reports per-entry absolute and relative differences, checks that
/// the difference shrinks when the perturbation shrinks, and checks that blocks
/// ADR/IGN declare absent, and entries outside the structure an element declares
/// (jacobian_entry, core/element.hpp), really are zero.
///
///     pradis::testing::jacobian_checker<pradis::elements::planar_link> chk(link);
///     auto r = chk.check(state);
///     if (!r.ok) r.print(std::cerr);

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "pradis/core/element.hpp"

namespace pradis::testing {

/// Options of the check.
struct jacobian_check_options {
  double rel_step = 1e-6;    ///< perturbation relative to |x|
  double abs_step = 1e-6;    ///< perturbation floor
  double tolerance = 1e-6;   ///< allowed |numeric - analytic| relative to the block's largest entry
  double zero_floor = 1e-9;  ///< absolute floor below which differences count as zero
};

/// One compared entry.
struct jacobian_entry {
  char block = 'K';      ///< 'K' (dF/du), 'C' (dF/dv), 'M' (dF/da)
  int row = 0, col = 0;  ///< local flow index and local DOF index (0-based)
  double analytic = 0;   ///< the element's value (0 for an absent block)
  double numeric = 0;    ///< central difference at the nominal step
  double numeric_coarse = 0;  ///< central difference at 10 times the step
  bool declared = true;  ///< whether the passport declares the block
  /// |numeric - analytic|.
  double abs_diff() const { return std::abs(numeric - analytic); }
  /// |numeric - analytic| / |numeric| (or the absolute difference when |numeric| is tiny).
  double rel_diff() const { return std::abs(numeric) > 1e-150 ? abs_diff() / std::abs(numeric) : abs_diff(); }
};

/// Result of a check.
struct jacobian_check_result {
  bool ok = true;                       ///< every entry within tolerance and every declared structure held
  std::vector<jacobian_entry> entries;  ///< every compared entry
  std::vector<std::string> problems;  ///< one sentence per failure
  double max_scaled_error = 0;        ///< max |diff| / block scale over all entries

  /// Prints the table of numerical versus analytical derivatives.
  void print(std::ostream& os) const {
    os << "block row col      numerical     analytical     difference  rel.diff\n";
    for (const auto& e : entries) {
      if (e.numeric == 0 && e.analytic == 0) continue;
      os << "  " << e.block << (e.declared ? ' ' : '*') << std::setw(4) << e.row + 1 << std::setw(4) << e.col + 1
         << std::scientific << std::setprecision(6) << std::setw(15) << e.numeric << std::setw(15) << e.analytic
         << std::setw(15) << e.numeric - e.analytic << std::setprecision(2) << std::setw(10) << e.rel_diff()
         << std::defaultfloat << '\n';
    }
    os << "(* = block declared absent by ADR/IGN; must be zero)\n";
    for (const auto& p : problems) os << "problem: " << p << '\n';
    os << (ok ? "Jacobian OK\n" : "Jacobian WRONG\n");
  }
};

/// Checker for element type E. Owns a work and state vector for the element,
/// runs its NEWINT hook once, then checks states.
template <Element E>
class jacobian_checker {
 public:
  using traits = element_traits<E>;
  static constexpr int n = traits::n;

  /// Prepares the element (runs new_integration if it has one). `npar` is the
  /// parameter count (default: the element's parameter_count() if it has one,
  /// as model::add asks, else PAR). Throws pradis::error if the parameters are bad.
  explicit jacobian_checker(E e, int npar = -1, jacobian_check_options o = {})
      : e_(std::move(e)),
        o_(o),
        npar_(npar >= 0 ? npar : default_count(e_)),
        work_(static_cast<std::size_t>(E::passport.work_size(npar_)), 0.0),
        old_(static_cast<std::size_t>(E::passport.state_size(npar_)), 0.0),
        new_(old_.size(), 0.0) {
    ctx_ = element_context(E::passport.name, "checked");
    ctx_.work = work_;
    ctx_.old_state = old_;
    ctx_.new_state = new_;
    ctx_.npar = npar_;
    ctx_.nstep = 0;  // NEWINT of the zero step, then the zero-step hook, as in a run
    if constexpr (HasNewIntegration<E>) {
      ctx_.newint = true;
      e_.new_integration(ctx_);
      ctx_.newint = false;
    }
    if constexpr (HasZeroStep<E>) {
      initial_values<n> iv;
      e_.zero_step(iv, ctx_);
    }
    ctx_.nstep = 1;
  }

  jacobian_checker(const jacobian_checker&) = delete;
  jacobian_checker& operator=(const jacobian_checker&) = delete;

  /// The element being checked.
  const E& element() const noexcept { return e_; }
  /// The state of the last accepted step (OLD) the checked evaluations see; zero
  /// unless a test sets it, e.g. to check the Jacobian of a stick or slip mode.
  std::span<double> old_state() noexcept { return old_; }
  /// The state the last evaluation wrote (NEW).
  std::span<const double> new_state() const noexcept { return new_; }

  /// Flows at a state (no Jacobian).
  typename traits::vector flows(const local_input<E>& in) {
    local_output<E> out;
    out.want_jacobian = false;
    e_.evaluate(in, out, ctx_);
    return out.f;
  }

  /// Checks the Jacobian at one state.
  jacobian_check_result check(const local_input<E>& at) {
    jacobian_check_result r;
    local_output<E> ana;
    ana.clear();
    ctx_.time = at.t;
    e_.evaluate(at, ana, ctx_);
    check_block<'K'>(at, ana, r);
    check_block<'C'>(at, ana, r);
    check_block<'M'>(at, ana, r);
    return r;
  }

 private:
  template <char B>
  static double& component(local_input<E>& in, int j) {
    if constexpr (B == 'K') return in.u(j);
    if constexpr (B == 'C') return in.v(j);
    if constexpr (B == 'M') return in.a(j);
  }

  template <char B>
  void check_block(const local_input<E>& at, const local_output<E>& ana, jacobian_check_result& r) {
    constexpr bool declared = B == 'K' ? traits::has_k : (B == 'C' ? traits::has_c : traits::has_m);
    typename traits::matrix a = traits::matrix::Zero();
    if constexpr (B == 'K' && traits::has_k) a = ana.K;
    if constexpr (B == 'C' && traits::has_c) a = ana.C;
    if constexpr (B == 'M' && traits::has_m) a = ana.M;
    typename traits::matrix num, coarse;
    for (int j = 0; j < n; ++j) {
      local_input<E> x = at;
      const double x0 = component<B>(x, j);
      const double h = o_.abs_step + o_.rel_step * std::abs(x0);
      num.col(j) = central<B>(x, j, x0, h);
      coarse.col(j) = central<B>(x, j, x0, 10 * h);
    }
    // Scale: the largest entry of the analytic or numeric block (or 1 if the block is all zero).
    const double scale = std::max({a.cwiseAbs().maxCoeff(), num.cwiseAbs().maxCoeff(), 1e-300});
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        jacobian_entry e{B, i, j, a(i, j), num(i, j), coarse(i, j), declared};
        r.entries.push_back(e);
        const double d = e.abs_diff();
        const double allowed = o_.tolerance * scale + o_.zero_floor;
        r.max_scaled_error = std::max(r.max_scaled_error, d / std::max(scale, 1e-300));
        if (!jacobian_entry_of(e_, i, j) && (std::abs(e.numeric) > allowed || std::abs(e.analytic) > allowed)) {
          r.ok = false;
          r.problems.push_back(std::string("dF") + std::to_string(i + 1) + "/d" + var<B>() + std::to_string(j + 1) +
                               " lies outside the structure the element declares (jacobian_entry) but is not zero:"
                               " analytic " + std::to_string(e.analytic) + ", numeric " + std::to_string(e.numeric));
        } else if (!declared && std::abs(e.numeric) > allowed) {
          r.ok = false;
          r.problems.push_back(std::string("block ") + B + " is declared absent by ADR/IGN but dF" +
                               std::to_string(i + 1) + "/d" + var<B>() + std::to_string(j + 1) + " = " +
                               std::to_string(e.numeric));
        } else if (declared && d > allowed) {
          // A real error does not shrink when the step shrinks; truncation error does.
          const double dc = std::abs(e.numeric_coarse - e.analytic);
          r.ok = false;
          r.problems.push_back(std::string("d F") + std::to_string(i + 1) + "/d" + var<B>() + std::to_string(j + 1) +
                               ": analytic " + std::to_string(e.analytic) + ", numeric " + std::to_string(e.numeric) +
                               (d < 0.5 * dc ? " (difference shrinks with the step: loosen the tolerance?)"
                                             : " (difference does not shrink with the step)"));
        }
      }
  }

  template <char B>
  static const char* var() {
    return B == 'K' ? "u" : (B == 'C' ? "v" : "a");
  }

  template <char B>
  typename traits::vector central(local_input<E>& x, int j, double x0, double h) {
    component<B>(x, j) = x0 + h;
    const typename traits::vector fp = flows(x);
    component<B>(x, j) = x0 - h;
    const typename traits::vector fm = flows(x);
    component<B>(x, j) = x0;
    return (fp - fm) / (2 * h);
  }

  E e_;
  jacobian_check_options o_;
  static int default_count(const E& e) {
    if constexpr (requires { e.parameter_count(); })
      return e.parameter_count();
    else
      return E::passport.par;
  }
  int npar_ = 0;
  std::vector<double> work_, old_, new_;
  element_context ctx_;
};

}  // namespace pradis::testing
