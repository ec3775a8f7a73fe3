#pragma once
/// \file output.hpp
/// Output of a `BodySystem`: time histories of chosen entities of bodies, springs, torsion
/// springs and joints as CSV columns (the entities of Parmec's HISTORY command), and legacy VTK
/// files of the bodies, springs and joints (next to the particle files of io::vtk).
///
/// ## Histories
/// The column sets `body_history`, `spring_history`, `torsion_history` and `joint_history` plug
/// into io::csv (any number of them in one file), which `io::every` or `io::every_steps` calls at
/// a frequency:
///
/// \code
/// sys.run(1.0, 1e-4,
///         io::every(1e-3, io::csv("out/springs.csv",
///                                 bodies::spring_history({0, 1}, {"STROKE", "F", "SS"}),
///                                 bodies::joint_history({0}, {"JREAC_Z", "|JREAC|"}),
///                                 bodies::body_history({2}, {"PZ", "VZ"}))));
/// \endcode
///
/// One column per item and entity, named `<ENTITY>_<kind><index> [unit]`, e.g. `F_spring0 [N]`,
/// after `time [s]` and `step`. Entities (SI units):
///
/// - body: position `PX PY PZ |P|` [m]; displacement since the history started `DX DY DZ |D|`
///   [m]; velocity `VX VY VZ |V|` [m/s]; angular velocity `OX OY OZ |O|` [rad/s]; force
///   `FX FY FZ |F|` [N] and torque about the centre `TX TY TZ |T|` [N m]: the applied loads of
///   the current configuration (gravity, global damping, springs, torsion springs; joint
///   reactions are impulses and not included);
/// - spring: `LENGTH` [m], `STROKE` [m], total force `F` [N], elastic force `SF` [N], friction
///   force `FF` [N], state code `SS` [-] (spring.hpp);
/// - torsion spring: body 1's axes `ZDIR_X ZDIR_Y ZDIR_Z XDIR_X XDIR_Y XDIR_Z` [-]; angles
///   `ROLL PITCH YAW` [rad]; total torques `TRQTOT_R TRQTOT_P TRQTOT_Y` and elastic torques
///   `TRQSPR_R TRQSPR_P TRQSPR_Y` [N m];
/// - joint: reaction on body 1 `JREAC_X JREAC_Y JREAC_Z |JREAC|` [N] (the mean joint force of
///   the last step).
///
/// Unknown entities and item indices are InputErrors raised when the history starts (before the
/// file is made), naming the valid ones.
///
/// ## VTK
/// `write_bodies_vtk`, `write_meshes_vtk`, `write_springs_vtk`, `write_torsion_springs_vtk` and
/// `write_joints_vtk` write one legacy VTK polydata file each (the conventions of io::vtk:
/// "DataFile Version 3.0", ASCII or BINARY, the time in the header line `grain <kind> t = <time>`):
/// - bodies: the centres as points with one vertex each; point data `body` (int index),
///   `velocity` [m/s], `omega` [rad/s], `force` [N], `torque` [N m] (vectors), `mass` [kg],
///   `orientation` (4 components: the unit quaternion (w, x, y, z) of the reference-frame
///   rotation Lambda), `radius` [m] (the display radius of a body converted from a sphere, 0
///   for a body without a shape);
/// - meshes (the bodies added by `add_mesh_body`; Parmec's 'MESH' output mode): the boundary
///   faces of every mesh as polygons (triangles and quadrilaterals, right-hand normals pointing
///   out of the body) on the surface nodes in world coordinates, x = c + Lambda X (X the node's
///   local coordinates, c and Lambda the body's current pose); each mesh has its own points,
///   meshes in the order of `add_mesh_body`. Cell data `body` (int body index), `color` (int
///   face colour, Parmec's 'COLOR' entity), `velocity` [m/s] (vector: the velocity of the
///   body's material point at the mean of the face's nodes, v + omega x (x_f - c));
/// - springs: one line per spring from point 1 to point 2 (for a point-to-plane spring, to the
///   foot of point 1 on the plane); cell data `spring` (int index), `force` (vector: the force
///   on point 1) [N], `total_force` (F), `elastic_force` (SF), `friction_force` (FF) [N],
///   `stroke` [m], `length` [m], `state` (int SS);
/// - joints: the joint points on body 1 with one vertex each; point data `joint` (int index),
///   `reaction` (vector, on body 1) [N], `gap` [m].
/// A file without cells has no data section. `body_vtk(prefix, format)` is an output action for
/// io::every that writes `prefix_bodies_NNNNNN.vtk` (and `prefix_meshes_...`,
/// `prefix_springs_...`, `prefix_torsion_springs_...`, `prefix_joints_...` if the system has mesh
/// bodies, springs, torsion springs or joints) per call, and the ParaView series files
/// `prefix_<kind>.vtk.series`. As with io::vtk, each file is written under a temporary name and
/// renamed once complete, a frame before the series that lists it (a killed run leaves whole
/// files), and a file that cannot be written throws io::WriteError naming the writer, the file
/// and the reason.

#include <grain/bodies/system.hpp>
#include <grain/core/error.hpp>
#include <grain/io/vtk.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iomanip>
#include <span>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace grain::bodies {

/// What a history column set reads.
enum class HistorySource : std::uint8_t { body, spring, torsion_spring, joint };

namespace detail {

struct EntityInfo {
  const char* name;
  const char* unit;
};

inline constexpr std::array<EntityInfo, 24> body_entities{{
    {"PX", "m"},      {"PY", "m"},    {"PZ", "m"},     {"|P|", "m"},    {"DX", "m"},
    {"DY", "m"},      {"DZ", "m"},    {"|D|", "m"},    {"VX", "m/s"},   {"VY", "m/s"},
    {"VZ", "m/s"},    {"|V|", "m/s"}, {"OX", "rad/s"}, {"OY", "rad/s"}, {"OZ", "rad/s"},
    {"|O|", "rad/s"}, {"FX", "N"},    {"FY", "N"},     {"FZ", "N"},     {"|F|", "N"},
    {"TX", "N m"},    {"TY", "N m"},  {"TZ", "N m"},   {"|T|", "N m"},
}};
inline constexpr std::array<EntityInfo, 6> spring_entities{{
    {"LENGTH", "m"},
    {"STROKE", "m"},
    {"F", "N"},
    {"SF", "N"},
    {"FF", "N"},
    {"SS", ""},
}};
inline constexpr std::array<EntityInfo, 15> torsion_entities{{
    {"ZDIR_X", ""},
    {"ZDIR_Y", ""},
    {"ZDIR_Z", ""},
    {"XDIR_X", ""},
    {"XDIR_Y", ""},
    {"XDIR_Z", ""},
    {"ROLL", "rad"},
    {"PITCH", "rad"},
    {"YAW", "rad"},
    {"TRQTOT_R", "N m"},
    {"TRQTOT_P", "N m"},
    {"TRQTOT_Y", "N m"},
    {"TRQSPR_R", "N m"},
    {"TRQSPR_P", "N m"},
    {"TRQSPR_Y", "N m"},
}};
inline constexpr std::array<EntityInfo, 4> joint_entities{{
    {"JREAC_X", "N"},
    {"JREAC_Y", "N"},
    {"JREAC_Z", "N"},
    {"|JREAC|", "N"},
}};

inline std::span<const EntityInfo> entities_of(HistorySource s) {
  switch (s) {
  case HistorySource::body:
    return body_entities;
  case HistorySource::spring:
    return spring_entities;
  case HistorySource::torsion_spring:
    return torsion_entities;
  case HistorySource::joint:
    return joint_entities;
  }
  return {};
}
inline const char* source_name(HistorySource s) {
  switch (s) {
  case HistorySource::body:
    return "body";
  case HistorySource::spring:
    return "spring";
  case HistorySource::torsion_spring:
    return "torsion";
  case HistorySource::joint:
    return "joint";
  }
  return "";
}

/// Component c (0, 1, 2; 3 = the norm) of a vector.
inline double component(const Vec3& v, std::size_t c) {
  return c < 3 ? v[static_cast<int>(c)] : v.norm();
}

} // namespace detail

/// A CSV column set (see io::csv): chosen entities of chosen bodies, springs, torsion springs or
/// joints of a BodySystem.
struct HistoryColumns {
  HistorySource source = HistorySource::body;
  std::vector<std::size_t> items{};
  std::vector<std::string> entities{};
  std::vector<std::size_t> codes_{}; ///< entity indices into the source's table
  std::vector<Vec3> reference_{};    ///< body positions when the history started

  /// Validates the items and entities against the system and captures the reference positions.
  void start(const BodySystem& s) {
    const std::string obj =
        std::string("grain::bodies::") + detail::source_name(source) + "_history";
    const std::size_t n = source == HistorySource::body             ? s.bodies().size()
                          : source == HistorySource::spring         ? s.spring_count()
                          : source == HistorySource::torsion_spring ? s.torsion_spring_count()
                                                                    : s.joint_count();
    if (items.empty())
      throw InputError(obj + ": number of items = 0 is invalid; valid range: [1, inf)");
    for (std::size_t k = 0; k < items.size(); ++k)
      grain::detail::require(items[k] < n, obj, "item", items[k],
                             "[0, " + std::to_string(n) + ") (a " + detail::source_name(source) +
                                 " index)");
    if (entities.empty())
      throw InputError(obj + ": number of entities = 0 is invalid; valid range: [1, inf)");
    const auto table = detail::entities_of(source);
    codes_.clear();
    for (const std::string& e : entities) {
      const auto it = std::find_if(table.begin(), table.end(),
                                   [&](const detail::EntityInfo& x) { return e == x.name; });
      if (it == table.end()) {
        std::string valid;
        for (const auto& x : table)
          valid += (valid.empty() ? "" : ", ") + std::string(x.name);
        throw InputError(obj + ": entity = '" + e + "' is invalid; valid values: " + valid);
      }
      codes_.push_back(static_cast<std::size_t>(it - table.begin()));
    }
    reference_.clear();
    if (source == HistorySource::body)
      for (const std::size_t i : items)
        reference_.push_back(s.bodies().position[i]);
  }

  void names(const BodySystem&, std::vector<std::string>& out) const {
    const auto table = detail::entities_of(source);
    for (const std::size_t i : items)
      for (const std::size_t c : codes_) {
        std::string name =
            std::string(table[c].name) + "_" + detail::source_name(source) + std::to_string(i);
        if (*table[c].unit) name += std::string(" [") + table[c].unit + "]";
        out.push_back(std::move(name));
      }
  }

  void values(const BodySystem& s, std::vector<double>& out) const {
    for (std::size_t k = 0; k < items.size(); ++k)
      for (const std::size_t c : codes_)
        out.push_back(value(s, k, c));
  }

private:
  double value(const BodySystem& s, std::size_t k, std::size_t c) const {
    const std::size_t i = items[k];
    switch (source) {
    case HistorySource::body: {
      const RigidBodies& b = s.bodies();
      const std::size_t q = c / 4, comp = c % 4;
      const Vec3 v = q == 0   ? b.position[i]
                     : q == 1 ? Vec3(b.position[i] - reference_[k])
                     : q == 2 ? b.velocity[i]
                     : q == 3 ? b.omega[i]
                     : q == 4 ? b.force[i]
                              : b.torque[i];
      return detail::component(v, comp);
    }
    case HistorySource::spring: {
      const SpringResult& r = s.spring_result(i);
      switch (c) {
      case 0:
        return r.length;
      case 1:
        return r.stroke;
      case 2:
        return r.total;
      case 3:
        return r.elastic;
      case 4:
        return r.friction;
      default:
        return static_cast<double>(s.spring_state(i).code);
      }
    }
    case HistorySource::torsion_spring: {
      const TorsionResult& r = s.torsion_result(i);
      if (c < 3) return r.z[static_cast<int>(c)];
      if (c < 6) return r.x[static_cast<int>(c - 3)];
      if (c < 9) return r.angles[static_cast<int>(c - 6)];
      if (c < 12) return r.total_torque[static_cast<int>(c - 9)];
      return r.spring_torque[static_cast<int>(c - 12)];
    }
    case HistorySource::joint:
      return detail::component(s.joint_result(i).reaction, c);
    }
    return 0.0;
  }
};

/// Entities (see the file comment) of the bodies `items`.
inline HistoryColumns body_history(std::vector<std::size_t> items,
                                   std::vector<std::string> entities) {
  return {HistorySource::body, std::move(items), std::move(entities)};
}
/// Entities of the springs `items`.
inline HistoryColumns spring_history(std::vector<std::size_t> items,
                                     std::vector<std::string> entities) {
  return {HistorySource::spring, std::move(items), std::move(entities)};
}
/// Entities of the torsion springs `items`.
inline HistoryColumns torsion_history(std::vector<std::size_t> items,
                                      std::vector<std::string> entities) {
  return {HistorySource::torsion_spring, std::move(items), std::move(entities)};
}
/// Entities of the joints `items`.
inline HistoryColumns joint_history(std::vector<std::size_t> items,
                                    std::vector<std::string> entities) {
  return {HistorySource::joint, std::move(items), std::move(entities)};
}

/// The world points of spring i as drawn: point 1 and point 2 (for a point-to-plane spring, the
/// foot of point 1 on the plane) [m].
inline std::pair<Vec3, Vec3> spring_line(const BodySystem& s, std::size_t i) {
  auto [p1, p2] = s.spring_points(i);
  if (s.spring_params(i).geometry == SpringGeometry::point_to_plane) {
    const SpringLink& l = s.spring_link(i);
    const Vec3 n = l.body2 == world
                       ? l.normal2
                       : Vec3(rotation(s.bodies(), static_cast<std::size_t>(l.body2)) * l.normal2);
    p2 = p1 - n.dot(p1 - p2) * n;
  }
  return {p1, p2};
}

/// Writes the bodies of a system as legacy VTK polydata (see the file comment).
inline void write_bodies_vtk(const BodySystem& s, const std::string& path,
                             io::VtkFormat format = io::VtkFormat::ascii,
                             const std::vector<std::size_t>& subset = {},
                             const std::vector<Vec3>* start = nullptr) {
  namespace d = grain::io::detail;
  const RigidBodies& b = s.bodies();
  std::vector<std::size_t> all;
  if (subset.empty())
    for (std::size_t i = 0; i < b.size(); ++i)
      all.push_back(i);
  const std::vector<std::size_t>& ids = subset.empty() ? all : subset;
  const std::size_t n = ids.size();
  d::LegacyVtkFile o(path, format, "bodies", s.time(), "grain::bodies::write_bodies_vtk");
  o.points(n, [&](std::size_t k) { return d::xyz(b.position[ids[k]]); });
  o.vertices(n);
  if (n == 0) return o.close(path);
  o.line("POINT_DATA " + std::to_string(n));
  o.field("body", n, [&](std::size_t k) { return static_cast<int>(ids[k]); });
  o.field("velocity", n, [&](std::size_t k) { return d::xyz(b.velocity[ids[k]]); });
  o.field("omega", n, [&](std::size_t k) { return d::xyz(b.omega[ids[k]]); });
  o.field("force", n, [&](std::size_t k) { return d::xyz(b.force[ids[k]]); });
  o.field("torque", n, [&](std::size_t k) { return d::xyz(b.torque[ids[k]]); });
  o.field("mass", n, [&](std::size_t k) { return b.mass[ids[k]]; });
  o.field("orientation", n, [&](std::size_t k) {
    const std::size_t i = ids[k];
    return d::orientation_value(Eigen::Quaterniond(b.orientation[i] * b.axes[i].conjugate()));
  });
  o.field("radius", n, [&](std::size_t k) { return b.radius[ids[k]]; });
  if (start)
    o.field("displacement", n, [&](std::size_t k) {
      const std::size_t i = ids[k];
      return d::xyz(Vec3(i < start->size() ? Vec3(b.position[i] - (*start)[i]) : Vec3::Zero()));
    });
  o.close(path);
}

/// Writes the boundary surfaces of the mesh bodies of a system, in world coordinates at the
/// bodies' current poses, as legacy VTK polydata (see the file comment).
inline void write_meshes_vtk(const BodySystem& s, const std::string& path,
                             io::VtkFormat format = io::VtkFormat::ascii,
                             const std::vector<std::size_t>& subset = {}) {
  namespace d = grain::io::detail;
  const RigidBodies& b = s.bodies();
  std::vector<Vec3> pts;
  std::vector<std::vector<std::size_t>> cells;
  std::vector<int> body, color;
  std::vector<Vec3> velocity;
  for (std::size_t k = 0; k < s.mesh_count(); ++k) {
    const std::size_t i = s.mesh_body_index(k);
    if (!subset.empty() && std::find(subset.begin(), subset.end(), i) == subset.end()) continue;
    const MeshSurface& m = s.mesh_surface(k);
    const Eigen::Matrix3d r = rotation(b, i);
    const std::size_t base = pts.size();
    for (const Vec3& x : m.nodes)
      pts.push_back(b.position[i] + r * x);
    for (std::size_t f = 0; f < m.faces.size(); ++f) {
      std::vector<std::size_t> cell;
      Vec3 centroid = Vec3::Zero();
      for (const std::uint32_t v : m.faces[f]) {
        cell.push_back(base + v);
        centroid += pts[base + v];
      }
      centroid /= static_cast<double>(cell.size());
      cells.push_back(std::move(cell));
      body.push_back(static_cast<int>(i));
      color.push_back(m.colors[f]);
      velocity.push_back(point_velocity(b, i, centroid));
    }
  }
  d::LegacyVtkFile o(path, format, "meshes", s.time(), "grain::bodies::write_meshes_vtk");
  o.points(pts.size(), [&](std::size_t k) { return d::xyz(pts[k]); });
  o.cells("POLYGONS", cells);
  const std::size_t m = cells.size();
  if (m == 0) return o.close(path);
  o.line("CELL_DATA " + std::to_string(m));
  o.field("body", m, [&](std::size_t k) { return body[k]; });
  o.field("color", m, [&](std::size_t k) { return color[k]; });
  o.field("velocity", m, [&](std::size_t k) { return d::xyz(velocity[k]); });
  o.close(path);
}

/// Writes the springs of a system as legacy VTK polydata: one line per spring.
inline void write_springs_vtk(const BodySystem& s, const std::string& path,
                              io::VtkFormat format = io::VtkFormat::ascii) {
  namespace d = grain::io::detail;
  const std::size_t m = s.spring_count();
  std::vector<Vec3> pts;
  std::vector<std::array<std::size_t, 2>> lines;
  for (std::size_t i = 0; i < m; ++i) {
    const auto [p1, p2] = spring_line(s, i);
    lines.push_back({pts.size(), pts.size() + 1});
    pts.push_back(p1);
    pts.push_back(p2);
  }
  d::LegacyVtkFile o(path, format, "springs", s.time(), "grain::bodies::write_springs_vtk");
  o.points(pts.size(), [&](std::size_t k) { return d::xyz(pts[k]); });
  o.cells("LINES", lines);
  if (m == 0) return o.close(path);
  o.line("CELL_DATA " + std::to_string(m));
  o.field("spring", m, [](std::size_t k) { return static_cast<int>(k); });
  o.field("force", m, [&](std::size_t k) { return d::xyz(s.spring_result(k).force); });
  o.field("total_force", m, [&](std::size_t k) { return s.spring_result(k).total; });
  o.field("elastic_force", m, [&](std::size_t k) { return s.spring_result(k).elastic; });
  o.field("friction_force", m, [&](std::size_t k) { return s.spring_result(k).friction; });
  o.field("stroke", m, [&](std::size_t k) { return s.spring_result(k).stroke; });
  o.field("length", m, [&](std::size_t k) { return s.spring_result(k).length; });
  o.field("state", m, [&](std::size_t k) { return s.spring_state(k).code; });
  o.close(path);
}

/// Writes the ball joints of a system as legacy VTK polydata: one vertex per joint.
inline void write_joints_vtk(const BodySystem& s, const std::string& path,
                             io::VtkFormat format = io::VtkFormat::ascii) {
  namespace d = grain::io::detail;
  const std::size_t n = s.joint_count();
  d::LegacyVtkFile o(path, format, "joints", s.time(), "grain::bodies::write_joints_vtk");
  o.points(n, [&](std::size_t k) { return d::xyz(s.joint_points(k).first); });
  o.vertices(n);
  if (n == 0) return o.close(path);
  o.line("POINT_DATA " + std::to_string(n));
  o.field("joint", n, [](std::size_t k) { return static_cast<int>(k); });
  o.field("reaction", n, [&](std::size_t k) { return d::xyz(s.joint_result(k).reaction); });
  o.field("gap", n, [&](std::size_t k) { return s.joint_result(k).gap; });
  o.close(path);
}

/// Torsion springs as points (`BodySystem::torsion_point`: the reference point given, or the
/// midpoint of the two bodies' centres) with one vertex each; point data
/// `torsion_spring` (int index), `torque` (vector, on body 1) [N m], `xdir`, `ydir`, `zdir`
/// (body 1's axes of the spring, world) [-], `roll`, `pitch`, `yaw` [rad], `spring_torque` and
/// `total_torque` (3 components: the elastic and the total torque of the roll, pitch and yaw
/// laws) [N m].
inline void write_torsion_springs_vtk(const BodySystem& s, const std::string& path,
                                      io::VtkFormat format = io::VtkFormat::ascii) {
  namespace d = grain::io::detail;
  const std::size_t n = s.torsion_spring_count();
  d::LegacyVtkFile o(path, format, "torsion_springs", s.time(),
                     "grain::bodies::write_torsion_springs_vtk");
  o.points(n, [&](std::size_t k) { return d::xyz(s.torsion_point(k)); });
  o.vertices(n);
  if (n == 0) return o.close(path);
  o.line("POINT_DATA " + std::to_string(n));
  o.field("torsion_spring", n, [](std::size_t k) { return static_cast<int>(k); });
  o.field("torque", n, [&](std::size_t k) { return d::xyz(s.torsion_result(k).torque); });
  o.field("xdir", n, [&](std::size_t k) { return d::xyz(s.torsion_result(k).x); });
  o.field("ydir", n, [&](std::size_t k) { return d::xyz(s.torsion_result(k).y); });
  o.field("zdir", n, [&](std::size_t k) { return d::xyz(s.torsion_result(k).z); });
  o.field("roll", n, [&](std::size_t k) { return s.torsion_result(k).angles[0]; });
  o.field("pitch", n, [&](std::size_t k) { return s.torsion_result(k).angles[1]; });
  o.field("yaw", n, [&](std::size_t k) { return s.torsion_result(k).angles[2]; });
  o.field("spring_torque", n,
          [&](std::size_t k) { return d::xyz(s.torsion_result(k).spring_torque); });
  o.field("total_torque", n,
          [&](std::size_t k) { return d::xyz(s.torsion_result(k).total_torque); });
  o.close(path);
}

/// The files of a BodyVtkWriter (a bit set).
enum BodyVtkFiles : unsigned {
  bodies_file = 1,
  meshes_file = 2,
  springs_file = 4,
  torsion_springs_file = 8,
  joints_file = 16,
  all_body_files = 31
};

/// Output action (for io::every): the bodies file, and the meshes, springs, torsion-springs and
/// joints files if the system has them, numbered 000000, 000001, ..., and their series files.
/// `subset` (body indices; empty: all) restricts the bodies and meshes files to those bodies
/// (Parmec's OUTPUT subsets); `files` selects the files (BodyVtkFiles). The bodies file has a
/// `displacement` field: from the position at the writer's first call.
struct BodyVtkWriter {
  std::string prefix;
  io::VtkFormat format = io::VtkFormat::ascii;
  int count = 0;
  std::vector<std::pair<std::string, double>> body_files{}, mesh_files{}, spring_files{},
      torsion_files{}, joint_files{};
  std::vector<std::size_t> subset{};
  unsigned files = all_body_files;
  std::vector<Vec3> start{};

  void operator()(const BodySystem& s) {
    for (std::size_t i = start.size(); i < s.bodies().size(); ++i)
      start.push_back(s.bodies().position[i]);
    const std::filesystem::path base(prefix);
    if (base.has_parent_path()) std::filesystem::create_directories(base.parent_path());
    const std::string stem = base.filename().string();
    std::ostringstream num;
    num << std::setw(6) << std::setfill('0') << count++;
    const auto one = [&](const char* kind, auto write, auto& files) {
      const std::string name = std::string("_") + kind + "_" + num.str() + ".vtk";
      write(s, prefix + name, format);
      files.emplace_back(stem + name, s.time());
      io::detail::write_series(prefix, kind, files, "grain::bodies::body_vtk");
    };
    const auto bodies = [this](const BodySystem& x, const std::string& p, io::VtkFormat f) {
      write_bodies_vtk(x, p, f, subset, &start);
    };
    const auto meshes = [this](const BodySystem& x, const std::string& p, io::VtkFormat f) {
      write_meshes_vtk(x, p, f, subset);
    };
    if (files & bodies_file) one("bodies", bodies, body_files);
    if ((files & meshes_file) && s.mesh_count() > 0) one("meshes", meshes, mesh_files);
    if ((files & springs_file) && s.spring_count() > 0)
      one("springs", write_springs_vtk, spring_files);
    if ((files & torsion_springs_file) && s.torsion_spring_count() > 0)
      one("torsion_springs", write_torsion_springs_vtk, torsion_files);
    if ((files & joints_file) && s.joint_count() > 0) one("joints", write_joints_vtk, joint_files);
  }
};

/// body_vtk(prefix, format): an output action writing the VTK files of a BodySystem.
inline BodyVtkWriter body_vtk(std::string prefix, io::VtkFormat format = io::VtkFormat::ascii) {
  return BodyVtkWriter{std::move(prefix), format};
}

} // namespace grain::bodies
