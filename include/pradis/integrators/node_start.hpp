#pragma once
/// \file
/// The nodes at the zero step (core/node_kind.hpp): the start velocities of the
/// hidden DOFs, the start of the slaved DOFs, and the rows and kinds of both in
/// the consistent initial derivatives (initialisation.hpp, initial_derivatives).

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

#include "pradis/assembly/assembler.hpp"
#include "pradis/core/diagnostics.hpp"
#include "pradis/core/element.hpp"
#include "pradis/core/node_kind.hpp"
#include "pradis/integrators/options.hpp"

namespace pradis::detail {
/// The start velocities of the nodes' hidden DOFs (core/node_kind.hpp), made
/// consistent with the nodes' own equations before the zero step solves for the
/// accelerations. The initial conditions set the velocities of the other DOFs; a
/// hidden DOF starts at K::start with velocity 0, which the node's equation may
/// contradict (h' = x with x(0) != 0). For each node, the velocities v_h of its
/// free hidden DOFs are solved from its hidden rows, f_h(u, v) = 0, by Newton
/// steps with the block dF_h/dv_h of K::evaluate (at most 4 steps; one for an
/// equation linear in v, as the rotational norm equation, which gives
/// q4' = -(q1 q1' + q2 q2' + q3 q3') / q4). A node whose block is singular (below
/// 1e-8 of its rows' largest dF/dv entry: a rotational node at 180 degrees, or an
/// equation that does not hold the hidden velocities) keeps them as they are. An
/// initial velocity that an element set on a hidden DOF (set_v, per DOF: the
/// setting instance) and that the node's equation replaces is logged as a warning.
template <class Model, class Assembler>
void hidden_dof_velocities(const Model& m, const Assembler& as, global_state& s, double dabsi, diagnostics& log,
                           const std::vector<std::string>& set_v = {}) {
  element_context ctx("node", "", &log);
  m.for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& nodes) {
    constexpr int n = K::size;
    using small_matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, n, n>;
    std::array<int, static_cast<std::size_t>(n)> hid{};  // the node's free hidden DOFs with a row of its own
    std::array<int, static_cast<std::size_t>(n)> dof{};  // their global DOFs
    const node_call call{dabsi, true};
    node_values<n> x;
    node_flows<n> out;
    for (const auto& node : nodes) {
      int nh = 0;
      for (int k = 0; k < n; ++k) {
        const auto kk = static_cast<std::size_t>(k);
        if (!K::hidden[kk] || !K::rows[kk] || as.equation_of(node.dofs[kk]) < 0) continue;
        hid[static_cast<std::size_t>(nh)] = k;
        dof[static_cast<std::size_t>(nh++)] = node.dofs[kk];
      }
      if (nh == 0) continue;
      std::array<double, static_cast<std::size_t>(n)> before{};
      for (int i = 0; i < nh; ++i)
        before[static_cast<std::size_t>(i)] = s.v(dof[static_cast<std::size_t>(i)]);
      for (int it = 0; it < 4; ++it) {
        gather_node<n>(node.dofs, s, x);
        out.f.setZero();
        out.K.setZero();
        out.C.setZero();
        K::evaluate(node, x, call, out, ctx);
        small_matrix c(nh, nh);
        Eigen::Matrix<double, Eigen::Dynamic, 1, 0, n, 1> f(nh);
        double big = 0;
        for (int i = 0; i < nh; ++i) {
          const int r = hid[static_cast<std::size_t>(i)];
          f(i) = out.f(r);
          big = std::max(big, out.C.row(r).cwiseAbs().maxCoeff());
          for (int j = 0; j < nh; ++j) c(i, j) = out.C(r, hid[static_cast<std::size_t>(j)]);
        }
        const double top = c.cwiseAbs().maxCoeff();
        if (!(top > 0) || !std::isfinite(big)) break;
        Eigen::FullPivLU<small_matrix> lu(c);
        lu.setThreshold(1e-8 * big / top);
        if (lu.rank() < nh) break;
        const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, n, 1> dv = lu.solve(-f);
        if (!dv.allFinite()) break;
        double change = 0;
        for (int i = 0; i < nh; ++i) {
          const auto d = static_cast<Eigen::Index>(dof[static_cast<std::size_t>(i)]);
          s.v(d) += dv(i);
          change = std::max(change, std::abs(dv(i)) / (1.0 + std::abs(s.v(d))));
        }
        if (change <= 1e-15) break;
      }
      for (int i = 0; i < nh; ++i) {
        const int d = dof[static_cast<std::size_t>(i)];
        const double v0 = before[static_cast<std::size_t>(i)], v = s.v(d);
        if (static_cast<std::size_t>(d) < set_v.size() && !set_v[static_cast<std::size_t>(d)].empty() &&
            std::abs(v - v0) > 1e-12 * (1.0 + std::abs(v0)))
          log.write("warning: the initial velocity " + detail::num(v0) + " set by '" +
                    set_v[static_cast<std::size_t>(d)] + "' on DOF '" + m.dof_name(d) + "' is not kept: it is the " +
                    "hidden DOF of a " + std::string(K::label) + " node, whose equation gives " + detail::num(v));
      }
    }
  });
}

/// The start of the nodes' slaved DOFs (core/node_kind.hpp, K::slaved): the positions
/// that meet the node's equation, u_k -= c_k (exact: c_k = u_k - g_k), then the
/// velocities of dc/dt = 0, v_k = -sum_j dc_k/du_j v_j over the node's other DOFs
/// (after hidden_dof_velocities, which sets the rotational q4'). A slaved DOF moved by
/// more than 1e-9 (1 + |u|) is logged as a warning, naming the initial condition the
/// equation replaces (set_u, set_v: per DOF, the setting instance, if any).
template <class Model, class Assembler>
void slaved_dof_start(const Model& m, const Assembler& as, global_state& s, double dabsi, diagnostics& log,
                      const std::vector<std::string>& set_u = {}, const std::vector<std::string>& set_v = {}) {
  element_context ctx("node", "", &log);
  m.for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& nodes) {
    if constexpr (SlavingNodeKind<K>) {
      constexpr int n = K::size;
      const node_call call{dabsi, true};
      node_values<n> x;
      node_flows<n> out;
      auto load = [&](const auto& node) {
        gather_node<n>(node.dofs, s, x);
        out.f.setZero();
        out.K.setZero();
        out.C.setZero();
        K::evaluate(node, x, call, out, ctx);
      };
      auto note = [&](int d, const char* what, double before, double after, const std::vector<std::string>& set) {
        if (!(std::abs(after - before) > 1e-9 * (1.0 + std::abs(before)))) return;
        const std::string by = static_cast<std::size_t>(d) < set.size() && !set[static_cast<std::size_t>(d)].empty()
                                   ? " set by '" + set[static_cast<std::size_t>(d)] + "'"
                                   : "";
        log.write("warning: the initial " + std::string(what) + " " + detail::num(before) + by + " of DOF '" +
                  m.dof_name(d) + "' is not kept: it is a slaved DOF of a " + std::string(K::label) +
                  " node, whose equation gives " + detail::num(after));
      };
      for (const auto& node : nodes) {
        load(node);
        for (int k = 0; k < n; ++k) {
          if (!slaved_dof<K>(k) || as.equation_of(node.dofs[static_cast<std::size_t>(k)]) < 0) continue;
          const int d = node.dofs[static_cast<std::size_t>(k)];
          const double before = s.u(d);
          s.u(d) -= out.f(k);
          note(d, "displacement", before, s.u(d), set_u);
        }
        load(node);
        for (int k = 0; k < n; ++k) {
          if (!slaved_dof<K>(k) || as.equation_of(node.dofs[static_cast<std::size_t>(k)]) < 0) continue;
          const int d = node.dofs[static_cast<std::size_t>(k)];
          const double before = s.v(d);
          double v = 0;
          for (int j = 0; j < n; ++j)
            if (!slaved_dof<K>(j)) v -= out.K(k, j) * x.v(j);
          s.v(d) = v;
          note(d, "velocity", before, v, set_v);
        }
      }
    }
  });
}

/// The rows of the nodes' hidden and slaved DOFs (core/node_kind.hpp) in the zero
/// step's matrix and right-hand side: such a DOF's unknown is its acceleration, from
/// its node's equation differentiated once more (K::zero_step_row; for the
/// rotational q4, d2(Lq)/dt2 = 0).
template <class Model, class Assembler>
void hidden_dof_rows(const Model& m, const Assembler& as, const global_state& s, std::vector<double>& j,
                     std::vector<double>& rhs) {
  const auto& pat = as.pattern();
  m.for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& nodes) {
    constexpr int n = K::size;
    node_values<n> x;
    Eigen::Matrix<double, n, 1> row;
    for (const auto& node : nodes)
      for (int h = 0; h < n; ++h) {
        if (!owned_dof<K>(h)) continue;
        const int eh = as.equation_of(node.dofs[static_cast<std::size_t>(h)]);
        if (eh < 0) continue;
        gather_node<n>(node.dofs, s, x);
        double r = 0;
        zero_step_row_of<K>(node, x, h, row, r);
        for (int q = pat.row_ptr[static_cast<std::size_t>(eh)]; q < pat.row_ptr[static_cast<std::size_t>(eh) + 1]; ++q)
          j[static_cast<std::size_t>(q)] = 0.0;
        for (int k = 0; k < n; ++k) {
          const int ec = as.equation_of(node.dofs[static_cast<std::size_t>(k)]);
          if (ec >= 0) j[static_cast<std::size_t>(pat.find(eh, ec))] = row(k);
        }
        rhs[static_cast<std::size_t>(eh)] = r;
      }
  });
}

/// The zero step's kinds of the nodes' DOFs (core/node_kind.hpp): a hidden DOF is
/// inertial (its unknown is its acceleration, hidden_dof_rows); with
/// K::inertial_block, another DOF of the node is inertial when the assembled inertia
/// block (mvals) has an entry in its row in any of the node's columns (a rotational
/// node's own diagonal E(q)-entry may vanish, e.g. at 180 degrees).
template <class Model, class Assembler>
void mark_node_kinds(const Model& m, const Assembler& as, const std::vector<double>& mvals, std::vector<char>& kind) {
  const auto& pat = as.pattern();
  m.for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& nodes) {
    constexpr int n = K::size;
    for (const auto& node : nodes)
      for (int r = 0; r < n; ++r) {
        const int er = as.equation_of(node.dofs[static_cast<std::size_t>(r)]);
        if (er < 0) continue;
        if (owned_dof<K>(r)) {
          kind[static_cast<std::size_t>(er)] = 1;
          continue;
        }
        if (!K::inertial_block) continue;
        for (int c = 0; c < n; ++c) {
          const int ec = as.equation_of(node.dofs[static_cast<std::size_t>(c)]);
          const int q = ec >= 0 ? pat.find(er, ec) : -1;
          if (q >= 0 && mvals[static_cast<std::size_t>(q)] != 0.0) kind[static_cast<std::size_t>(er)] = 1;
        }
      }
  });
}

/// Per DOF: whether it is a slaved DOF of a node (core/node_kind.hpp, K::slaved). The drivers
/// leave them out of their error tests (they follow their node's other DOFs).
template <class Model>
std::vector<char> slaved_dofs(const Model& m) {
  std::vector<char> out(static_cast<std::size_t>(m.dof_count()), 0);
  m.for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& nodes) {
    for (const auto& node : nodes)
      for (int k = 0; k < K::size; ++k)
        if (slaved_dof<K>(k)) out[static_cast<std::size_t>(node.dofs[static_cast<std::size_t>(k)])] = 1;
  });
  return out;
}

}  // namespace pradis::detail
