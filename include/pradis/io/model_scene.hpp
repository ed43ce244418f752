#pragma once
/// \file
/// The animation geometry of a whole model, drawn by its elements: every
/// element type with a `draw` hook (beams, spring-dampers, joints, sphere
/// contacts, plates) adds its points and cells to one vtk_scene, so a model
/// built in code or from a model file can be written as a VTK time series
/// without describing its geometry a second time.
///
///     pradis::io::vtk_scene scene = pradis::io::model_scene(m);
///     pradis::io::vtk_series vtk("out/vtk", "model", scene);
///     sim.on_output([&](const auto& s) { vtk.write(s); });
///
/// **The hook.** An element type may declare
///
///     template <class Drawer> void draw(Drawer& d) const;
///
/// and call, with its own local DOF numbers (see element_drawer):
/// `d.point(x0, k)`, `d.body_point(x0, k, node, offset)`, then `d.vertex(a)`,
/// `d.line(a, b)`, `d.triangle(a, b, c)` with the indices they returned. The
/// hook is a template, so an element header does not depend on io/.
///
/// Points are shared: two elements that draw the same point (the same DOFs,
/// rotational node, start position and offset, e.g. the common end of two
/// beams) get one scene point; a cell drawn twice (a beam and its inertia
/// element) is kept once.

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <span>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "pradis/io/vtk_series.hpp"
#include "pradis/model/model.hpp"

namespace pradis::io {

/// Builds one scene from the draw hooks of many elements, merging equal points
/// and equal cells. model_scene() uses it; user code rarely needs it.
class scene_builder {
 public:
  /// The scene point for (x0, translational DOFs, node, offset), made on first use.
  int point(const spatial::vec3& x0, const std::array<dof, 3>& x, const rotation_node* n,
            const spatial::vec3& offset) {
    const key k{x0.x(), x0.y(), x0.z(), x[0].index, x[1].index, x[2].index,
                n ? n->q4.index : -1, offset.x(), offset.y(), offset.z()};
    if (auto it = points_.find(k); it != points_.end()) return it->second;
    const int id = n ? scene_.body_point(x0, x, *n, offset) : scene_.point(x0, x);
    points_.emplace(k, id);
    return id;
  }
  /// A cell of the given VTK type, kept once whatever the order of its points;
  /// a cell whose points coincide (an arm of zero length) is left out.
  void cell(vtk_scene::cell_type type, std::vector<int> ids) {
    std::vector<int> sorted = ids;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return;
    if (!cells_.emplace(static_cast<int>(type), sorted).second) return;
    switch (type) {
      case vtk_scene::vertex_cell: scene_.vertex(ids[0]); break;
      case vtk_scene::line_cell: scene_.line(ids[0], ids[1]); break;
      case vtk_scene::triangle_cell: scene_.triangle(ids[0], ids[1], ids[2]); break;
    }
  }
  /// The scene built so far.
  vtk_scene& scene() noexcept { return scene_; }

 private:
  using key = std::tuple<double, double, double, int, int, int, int, double, double, double>;
  vtk_scene scene_;
  std::map<key, int> points_;
  std::set<std::pair<int, std::vector<int>>> cells_;
};

/// What a `draw` hook receives: local DOF numbers (an element instance's, or a node's in its
/// record's order) are turned into the model's DOFs. A node kind's hook is
/// `template <class D> static void draw(const record&, D& d)`; ground_pivot_kind has one.
class dof_drawer {
 public:
  /// The drawer of the DOFs `dofs` (local index -> model DOF) adding to `b`; `who` names the
  /// element or node drawn in the error for a local DOF it does not have (e.g. "MASS 'slider'").
  dof_drawer(scene_builder& b, std::span<const int> dofs, std::string who = {})
      : b_(b), dofs_(dofs), who_(std::move(who)) {}

  /// A point that starts at x0 and moves by the translational DOFs at local
  /// indices k, k+1, k+2 (X, Y, Z). Returns its scene index.
  int point(const spatial::vec3& x0, int k) { return point_at(x0, {k, k + 1, k + 2}); }
  /// point() with any three local DOFs (X, Y, Z), e.g. a composite's part
  /// mapped into the composite (elements/composite.hpp).
  int point_at(const spatial::vec3& x0, const std::array<int, 3>& k) {
    return b_.point(x0, translations(k), nullptr, spatial::vec3::Zero());
  }
  /// A point fixed in a body (element_drawer::body_point) with any three local DOFs
  /// and the rotational node given by its local slot (q1..q3 at s.q1.., q4 at s.q4).
  int body_point_at(const spatial::vec3& x0, const std::array<int, 3>& k, rotation_slot s,
                    const spatial::vec3& offset) {
    const rotation_node n{global(s.q1), global(s.q1 + 1), global(s.q1 + 2), global(s.q4), -1};
    return b_.point(x0, translations(k), &n, offset);
  }
  /// A vertex cell (a sphere's centre, a mass).
  void vertex(int a) { b_.cell(vtk_scene::vertex_cell, {a}); }
  /// A line cell (a beam, a spring, a body's arm to a joint).
  void line(int a, int b) { b_.cell(vtk_scene::line_cell, {a, b}); }
  /// A triangle cell (a plate).
  void triangle(int a, int b, int c) { b_.cell(vtk_scene::triangle_cell, {a, b, c}); }

 private:
  dof global(int k) const {
    if (k < 0 || static_cast<std::size_t>(k) >= dofs_.size())
      throw error(error_code::invalid_model,
                  "the draw hook of " + (who_.empty() ? std::string("a node") : who_) + " asks for local DOF " +
                      std::to_string(k) + ", which is not one of its " + std::to_string(dofs_.size()) + " DOFs (0.." +
                      std::to_string(static_cast<long>(dofs_.size()) - 1) + ")");
    return dof{dofs_[static_cast<std::size_t>(k)]};
  }
  std::array<dof, 3> translations(const std::array<int, 3>& k) const {
    return {global(k[0]), global(k[1]), global(k[2])};
  }
  scene_builder& b_;
  std::span<const int> dofs_;
  std::string who_;
};

/// What an element's `draw` hook receives: dof_drawer over the DOFs of one instance of E.
template <class E>
class element_drawer : public dof_drawer {
 public:
  /// The drawer of instance `in` adding to `b`.
  element_drawer(scene_builder& b, const element_instance<E>& in)
      : dof_drawer(b, in.dofs, std::string(E::passport.name) + " '" + in.name + "'") {}
  /// A point fixed in a body: the reference point starts at x0 and moves by the
  /// translational DOFs at local k, k+1, k+2, and the body turns with the
  /// element's rotational node `node` (an index into E::rotation_nodes); the point
  /// sits at `offset` in the body frame: p = x0 + x + R(q) offset.
  int body_point(const spatial::vec3& x0, int k, int node, const spatial::vec3& offset) {
    static_assert(HasRotationNodes<E>, "body_point needs an element with rotational nodes");
    return body_point_at(x0, {k, k + 1, k + 2}, E::rotation_nodes.at(static_cast<std::size_t>(node)), offset);
  }
};

/// Whether node kind K draws its nodes (has `template <class D> static void draw(const record&, D&)`).
template <class K>
concept drawable_node_kind = requires(const typename K::record& r, dof_drawer& d) { K::draw(r, d); };

/// Whether element type E draws itself (has `template <class D> void draw(D&) const`).
/// A composite (elements/composite.hpp) draws its parts that do.
template <class E>
concept drawable = requires(const E& e, element_drawer<E>& d) { e.draw(d); };

/// The animation geometry of model m: the points and cells drawn by every
/// instance of every drawable element type, in the order the model lists them,
/// then by every node of a drawable node kind (a ground pivot: the body's arm).
/// Elements without a hook (masses on scalar DOFs, sources, rigid bodies, which
/// carry no position of their own) draw nothing; a rigid body shows through the
/// joints, springs and contacts attached to it.
template <class Model>
vtk_scene model_scene(const Model& m) {
  scene_builder b;
  m.for_each_instances([&](const auto& v) {
    using I = typename std::decay_t<decltype(v)>::value_type;
    using E = decltype(I::element);
    if constexpr (drawable<E>)
      for (const auto& in : v) {
        element_drawer<E> d(b, in);
        in.element.draw(d);
      }
  });
  m.for_each_node_kind([&]<class K>(std::type_identity<K>, const auto& nodes) {
    if constexpr (drawable_node_kind<K>)
      for (const auto& node : nodes) {
        std::string who;
        if constexpr (requires { node.name; }) who = "node '" + node.name + "'";
        dof_drawer d(b, node.dofs, std::move(who));
        K::draw(node, d);
      }
  });
  return std::move(b.scene());
}

}  // namespace pradis::io
