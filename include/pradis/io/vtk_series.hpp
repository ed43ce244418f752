#pragma once
/// \file
/// Animation export: the motion of a model's points, beams, bodies and
/// triangles as a VTK time series that ParaView opens: one UnstructuredGrid
/// file per frame (`<name>_<k>.vtu`, ASCII XML) and the collection
/// `<name>.pvd` that lists them with their times.
///
///     pradis::io::vtk_scene scene;
///     const int a = scene.point({0, 0, 0}, {m.ground(), m.ground(), m.ground()});
///     const int b = scene.body_point({0, 0, 0.5}, {x, y, z}, node, {0, 0, 0.5});
///     scene.line(a, b);
///     pradis::io::vtk_series vtk("out", "top", scene);
///     sim.on_output([&](const auto& s) { vtk.write(s); });
///
/// Each frame carries the point positions, their displacements from the first
/// frame and their velocities (point data "displacement" and "velocity").

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "pradis/core/error.hpp"
#include "pradis/model/model.hpp"
#include "pradis/spatial/node_state.hpp"

namespace pradis::io {

/// The geometry of an animation: points that the model's DOFs move, and the
/// cells that join them (vertices, lines, triangles).
class vtk_scene {
 public:
  /// VTK cell types used here.
  enum cell_type : int { vertex_cell = 1, line_cell = 3, triangle_cell = 5 };

  /// A point that starts at x0 and moves by the translational DOFs x (X, Y, Z;
  /// a component on the ground stays fixed). Returns its index.
  int point(const spatial::vec3& x0, const std::array<dof, 3>& x) {
    check_finite(x0, "point");
    points_.push_back({x0, x, std::nullopt, spatial::vec3::Zero()});
    return static_cast<int>(points_.size()) - 1;
  }
  /// A point fixed in a body: the body's reference point starts at x0, moves by
  /// x and turns with the rotational node n; the point sits at `offset` in the
  /// body frame: p = x0 + x + R(q) offset (the convention of BODY3's attachments).
  int body_point(const spatial::vec3& x0, const std::array<dof, 3>& x, const rotation_node& n,
                 const spatial::vec3& offset) {
    check_finite(x0, "body point");
    check_finite(offset, "body point offset");
    points_.push_back({x0, x, n, offset});
    return static_cast<int>(points_.size()) - 1;
  }
  /// A vertex cell at point a (a body's reference point, a mass).
  void vertex(int a) { add_cell(vertex_cell, {a}); }
  /// A line cell from point a to point b (a beam, a link).
  void line(int a, int b) { add_cell(line_cell, {a, b}); }
  /// A triangle cell (a plate, a face of a body).
  void triangle(int a, int b, int c) { add_cell(triangle_cell, {a, b, c}); }

  /// Number of points.
  std::size_t points() const noexcept { return points_.size(); }
  /// Number of cells.
  std::size_t cells() const noexcept { return types_.size(); }
  /// Point indices of all cells, one after the other.
  const std::vector<int>& connectivity() const noexcept { return connectivity_; }
  /// End offset of each cell in connectivity().
  const std::vector<int>& offsets() const noexcept { return offsets_; }
  /// VTK type of each cell.
  const std::vector<int>& types() const noexcept { return types_; }

  /// Position and velocity of point i in the current state of `sim`.
  template <class Sim>
  spatial::point_motion motion(const Sim& sim, std::size_t i) const {
    const auto& p = points_.at(i);
    if (p.node) return spatial::body_point(sim, p.x, *p.node, p.x0, p.offset);
    return {p.x0 + spatial::vec3(sim.u(p.x[0]), sim.u(p.x[1]), sim.u(p.x[2])),
            spatial::vec3(sim.v(p.x[0]), sim.v(p.x[1]), sim.v(p.x[2]))};
  }

 private:
  struct entry {
    spatial::vec3 x0;
    std::array<dof, 3> x;
    std::optional<rotation_node> node;
    spatial::vec3 offset;
  };
  static void check_finite(const spatial::vec3& v, const char* what) {
    if (!v.allFinite()) throw error(error_code::invalid_model, std::string("vtk_scene: a ") + what + " is not finite");
  }
  void add_cell(int type, std::initializer_list<int> ids) {
    for (int i : ids)
      if (i < 0 || static_cast<std::size_t>(i) >= points_.size())
        throw error(error_code::invalid_model, "vtk_scene: a cell refers to point " + std::to_string(i) +
                                                   ", but the scene has " + std::to_string(points_.size()) +
                                                   " points (0-based)");
    connectivity_.insert(connectivity_.end(), ids);
    offsets_.push_back(static_cast<int>(connectivity_.size()));
    types_.push_back(type);
  }
  std::vector<entry> points_;
  std::vector<int> connectivity_, offsets_, types_;
};

/// A VTK time series written frame by frame: `write(sim)` writes
/// `<dir>/<name>_<k>.vtu` and rewrites `<dir>/<name>.pvd` (through a temporary
/// file and a rename), so the collection on disk is always complete up to the
/// last frame. A file that cannot be written throws pradis::error (io_error).
class vtk_series {
 public:
  /// Creates the directory if needed. `name` must not be empty or contain a path separator.
  vtk_series(std::filesystem::path dir, std::string name, vtk_scene scene)
      : dir_(std::move(dir)), name_(std::move(name)), scene_(std::move(scene)) {
    if (name_.empty() || name_.find_first_of("/\\") != std::string::npos)
      throw error(error_code::invalid_option, "vtk_series: the name '" + name_ + "' must be a plain file name");
    std::error_code ec;
    std::filesystem::create_directories(dir_, ec);
    if (ec) throw error(error_code::io_error, "cannot create the directory '" + dir_.string() + "': " + ec.message());
  }

  /// Writes one frame of the current state of `sim` (at sim.time()).
  template <class Sim>
  void write(const Sim& sim) {
    const std::size_t n = scene_.points();
    std::vector<spatial::point_motion> m;
    m.reserve(n);
    for (std::size_t i = 0; i < n; ++i) m.push_back(scene_.motion(sim, i));
    write(sim.time(), m);
  }
  /// Writes one frame at time t from the motions of the scene's points (one per
  /// point, in order: e.g. recorded earlier with vtk_scene::motion). A count that
  /// is not the scene's is invalid_model (110).
  void write(double t, std::span<const spatial::point_motion> m) {
    if (m.size() != scene_.points())
      throw error(error_code::invalid_model, "vtk_series: a frame has " + std::to_string(m.size()) +
                                                 " point motions, but the scene has " +
                                                 std::to_string(scene_.points()) + " points");
    char index[32];
    std::snprintf(index, sizeof index, "_%06zu.vtu", times_.size());
    const std::string file = name_ + index;
    {
      std::ofstream o(dir_ / file);
      if (!o) throw error(error_code::io_error, "cannot write '" + (dir_ / file).string() + "'");
      write_frame(o, m);
      o.close();
      if (!o) throw error(error_code::io_error, "writing '" + (dir_ / file).string() + "' failed");
    }
    times_.push_back(t);
    files_.push_back(file);
    write_collection();
  }
  /// Number of frames written.
  std::size_t frames() const noexcept { return times_.size(); }
  /// Path of the collection file `<dir>/<name>.pvd`.
  std::filesystem::path collection() const { return dir_ / (name_ + ".pvd"); }
  /// The scene.
  const vtk_scene& scene() const noexcept { return scene_; }

 private:
  void write_frame(std::ostream& o, std::span<const spatial::point_motion> m) {
    const std::size_t n = m.size();
    if (first_.empty())
      for (const auto& p : m) first_.push_back(p.position);
    o.precision(17);
    o << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <UnstructuredGrid>\n"
      << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << scene_.cells() << "\">\n"
      << "      <PointData Vectors=\"velocity\">\n";
    const auto vectors = [&](const char* name, auto get) {
      o << "        <DataArray type=\"Float64\" Name=\"" << name << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
      for (std::size_t i = 0; i < n; ++i) {
        const spatial::vec3 v = get(i);
        o << "          " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
      }
      o << "        </DataArray>\n";
    };
    vectors("displacement", [&](std::size_t i) -> spatial::vec3 { return m[i].position - first_[i]; });
    vectors("velocity", [&](std::size_t i) -> spatial::vec3 { return m[i].velocity; });
    o << "      </PointData>\n      <Points>\n";
    vectors("position", [&](std::size_t i) -> spatial::vec3 { return m[i].position; });
    o << "      </Points>\n      <Cells>\n";
    const auto ints = [&](const char* type, const char* name, const std::vector<int>& v) {
      o << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\" format=\"ascii\">\n         ";
      for (int x : v) o << ' ' << x;
      o << "\n        </DataArray>\n";
    };
    ints("Int32", "connectivity", scene_.connectivity());
    ints("Int32", "offsets", scene_.offsets());
    ints("UInt8", "types", scene_.types());
    o << "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  }
  void write_collection() const {
    const std::filesystem::path path = collection(), temp = dir_ / (name_ + ".pvd.part");
    {
      std::ofstream o(temp);
      if (!o) throw error(error_code::io_error, "cannot write '" + temp.string() + "'");
      o.precision(17);
      o << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
      for (std::size_t k = 0; k < times_.size(); ++k)
        o << "    <DataSet timestep=\"" << times_[k] << "\" group=\"\" part=\"0\" file=\"" << files_[k] << "\"/>\n";
      o << "  </Collection>\n</VTKFile>\n";
      o.close();
      if (!o) throw error(error_code::io_error, "writing '" + temp.string() + "' failed");
    }
    std::error_code ec;
    std::filesystem::rename(temp, path, ec);
    if (ec) throw error(error_code::io_error, "cannot rename '" + temp.string() + "' to '" + path.string() + "': " +
                                                  ec.message());
  }

  std::filesystem::path dir_;
  std::string name_;
  vtk_scene scene_;
  std::vector<double> times_;
  std::vector<std::string> files_;
  std::vector<spatial::vec3> first_;  // positions in the first frame
};

}  // namespace pradis::io
