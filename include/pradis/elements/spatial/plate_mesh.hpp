#pragma once
/// \file
/// Mesh helpers for TRIPL (plate.hpp): the unique sides of a triangle mesh with their
/// signs, the model DOFs of vertices and sides with boundary conditions, one TRIPL per
/// triangle, and a structured rectangular mesh. docs/plates.md.

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "pradis/core/error.hpp"
#include "pradis/elements/spatial/plate.hpp"
#include "pradis/model/model.hpp"

namespace pradis::elements {

/// A triangle mesh: vertex coordinates and triangles (three vertex indices each, 0-based,
/// in any orientation; each triangle's normal follows its own vertex order).
struct plate_mesh {
  std::vector<spatial::vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
};

/// The sides of a mesh: each unique side once, as (lower, higher) vertex index; for each
/// triangle the index of its sides 1-2, 2-3, 3-1 and their signs (+1 if the triangle
/// traverses the side from the lower to the higher vertex number, else -1), and how many
/// triangles share each side (1 on the boundary).
struct plate_sides {
  std::vector<std::array<int, 2>> sides;
  std::vector<std::array<int, 3>> of_triangle;
  std::vector<std::array<double, 3>> signs;
  std::vector<int> use_count;
  /// Whether side k is on the boundary (used by one triangle only).
  bool on_boundary(int k) const { return use_count[static_cast<std::size_t>(k)] == 1; }
};

/// Finds the unique sides of a mesh. Code 110 (invalid model) for a vertex index out of
/// range or a triangle with a repeated vertex.
inline plate_sides find_plate_sides(const plate_mesh& mesh) {
  plate_sides out;
  std::map<std::pair<int, int>, int> index;
  const int nv = static_cast<int>(mesh.vertices.size());
  for (const auto& t : mesh.triangles) {
    std::array<int, 3> ids{};
    std::array<double, 3> sg{};
    for (std::size_t k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      if (a < 0 || a >= nv || b < 0 || b >= nv || a == b)
        throw error(error_code::invalid_model, "plate mesh: a triangle has a vertex index out of range or repeated");
      const std::pair<int, int> key{std::min(a, b), std::max(a, b)};
      auto [it, added] = index.try_emplace(key, static_cast<int>(out.sides.size()));
      if (added) {
        out.sides.push_back({key.first, key.second});
        out.use_count.push_back(0);
      }
      ids[k] = it->second;
      ++out.use_count[static_cast<std::size_t>(it->second)];
      sg[k] = a < b ? 1.0 : -1.0;
    }
    out.of_triangle.push_back(ids);
    out.signs.push_back(sg);
  }
  return out;
}

/// Which DOFs of a plate mesh are fixed (connected to the ground): per vertex its X, Y, Z
/// translations, per side its rotation. Empty vectors fix nothing.
struct plate_fixity {
  std::vector<std::array<bool, 3>> vertex;
  std::vector<bool> side;
};

/// Boundary conditions on the boundary of a mesh (the sides used by one triangle and
/// their vertices): all translations of the boundary vertices fixed; with `clamped`
/// also the rotations of the boundary sides (simply supported otherwise: the boundary
/// sides rotate freely).
inline plate_fixity boundary_fixity(const plate_mesh& mesh, const plate_sides& s, bool clamped) {
  plate_fixity f;
  f.vertex.assign(mesh.vertices.size(), {false, false, false});
  f.side.assign(s.sides.size(), false);
  for (std::size_t k = 0; k < s.sides.size(); ++k) {
    if (s.use_count[k] != 1) continue;
    f.side[k] = clamped;
    for (int v : s.sides[k]) f.vertex[static_cast<std::size_t>(v)] = {true, true, true};
  }
  return f;
}

/// The model DOFs of a plate mesh (the ground where fixed) and its TRIPL instances.
struct plate_dofs {
  std::vector<std::array<dof, 3>> vertex;  ///< X, Y, Z translation of each vertex
  std::vector<dof> side;                   ///< rotation of each side (about the axis lower -> higher vertex)
  std::vector<element_ref<triangle_plate>> elements;
};

/// Material and load of every triangle of a mesh.
struct plate_material {
  double e = 0, nu = 0, h = 0, rho = 0;  ///< Young's modulus, Poisson's ratio, thickness, density
  double pressure = 0;                    ///< uniform pressure along each triangle's normal [Pa]
};

/// Adds a plate mesh to a model: 3 DOFs per vertex (named `<prefix>v<i>.x` ...) and one
/// per side (`<prefix>s<k>`) unless fixed, and one TRIPL `<prefix><t>` per triangle with
/// the side signs of find_plate_sides. Returns the DOF handles.
template <class Model>
plate_dofs add_plate_mesh(Model& m, const plate_mesh& mesh, const plate_sides& s, const plate_material& mat,
                          const plate_fixity& fix = {}, const std::string& prefix = "plate") {
  plate_dofs out;
  static const char* axis[3] = {".x", ".y", ".z"};
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    std::array<dof, 3> d{};
    for (std::size_t c = 0; c < 3; ++c)
      d[c] = !fix.vertex.empty() && fix.vertex[i][c] ? m.ground() : m.add_dof(prefix + "v" + std::to_string(i) + axis[c]);
    out.vertex.push_back(d);
  }
  for (std::size_t k = 0; k < s.sides.size(); ++k)
    out.side.push_back(!fix.side.empty() && fix.side[k] ? m.ground() : m.add_dof(prefix + "s" + std::to_string(k)));
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tr = mesh.triangles[t];
    const auto& v1 = mesh.vertices[static_cast<std::size_t>(tr[0])];
    const auto& v2 = mesh.vertices[static_cast<std::size_t>(tr[1])];
    const auto& v3 = mesh.vertices[static_cast<std::size_t>(tr[2])];
    const auto& sg = s.signs[t];
    const triangle_plate::parameters p{mat.e,  mat.nu, mat.h,  mat.rho, v1.x(), v1.y(), v1.z(), v2.x(), v2.y(),
                                       v2.z(), v3.x(), v3.y(), v3.z(),  sg[0],  sg[1],  sg[2],  mat.pressure};
    const auto& a = out.vertex[static_cast<std::size_t>(tr[0])];
    const auto& b = out.vertex[static_cast<std::size_t>(tr[1])];
    const auto& c = out.vertex[static_cast<std::size_t>(tr[2])];
    const auto& sd = s.of_triangle[t];
    out.elements.push_back(m.template add<triangle_plate>(
        prefix + std::to_string(t), p, a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2],
        out.side[static_cast<std::size_t>(sd[0])], out.side[static_cast<std::size_t>(sd[1])],
        out.side[static_cast<std::size_t>(sd[2])]));
  }
  return out;
}

/// A structured mesh of the rectangle [0, a] x [0, b] in the XY plane (Z = 0): nx x ny
/// cells, each split into two triangles by its diagonal from (i, j) to (i + 1, j + 1)
/// (counter-clockwise, normal +Z). Vertex (i, j), 0 <= i <= nx, 0 <= j <= ny, has index
/// j (nx + 1) + i. Code 110 for nx or ny < 1 or a non-positive side.
inline plate_mesh rectangular_plate_mesh(double a, double b, int nx, int ny) {
  if (nx < 1 || ny < 1 || !(a > 0) || !(b > 0))
    throw error(error_code::invalid_model, "rectangular plate mesh: needs a, b > 0 and at least one cell each way");
  plate_mesh m;
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.vertices.emplace_back(a * i / nx, b * j / ny, 0.0);
  const auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

}  // namespace pradis::elements
