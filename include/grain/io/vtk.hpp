#pragma once
/// \file vtk.hpp
/// Legacy VTK files for ParaView: one particle file, one wall file and (optionally) one contact
/// file per output time, in ASCII or binary, with a choice of particle fields and of a particle
/// group.
///
/// \code
/// sim.run(1.0, io::every(0.01, io::vtk("out/bed")));   // every field, every particle, ASCII
/// sim.run(1.0, io::every(0.01, io::vtk("out/bed", {.fields = io::fields::velocity |
///                                                            io::fields::temperature,
///                                                  .group = "hot",
///                                                  .format = io::VtkFormat::binary})));
/// \endcode
///
/// `vtk("out/bed")` writes out/bed_particles_000000.vtk, out/bed_walls_000000.vtk, ... and the
/// ParaView series files out/bed_particles.vtk.series, out/bed_walls.vtk.series. The points of a
/// particle file are the particle centres [m]; its point fields are chosen from (default
/// `fields::all`: every field the simulation has):
///
/// | field | VTK array | unit |
/// |---|---|---|
/// | `id` | SCALARS long (vtktypeint64 in binary files) | - |
/// | `radius` | SCALARS double | m |
/// | `velocity` | VECTORS double | m/s |
/// | `omega` | VECTORS double (2D: (0, 0, w)) | rad/s |
/// | `force` | VECTORS double, total force of the last step | N |
/// | `torque` | VECTORS double (2D: (0, 0, T)), total torque of the last step | N m |
/// | `mass` | SCALARS double, the particle's mass as its shape defines it (2D: a disk of length `thickness`, or a sphere with `Disk{.sphere_mass = true}`) | kg |
/// | `orientation` | 3D: SCALARS double 4, the unit quaternion (w, x, y, z) that turns body axes into lab axes (ParaView's glyph orientation mode "Quaternion"); 2D: SCALARS double, the angle | -, rad |
/// | `material` | SCALARS int, index into the material table | - |
/// | `temperature` | SCALARS double (thermal simulations only) | K |
/// | `heat_rate` | SCALARS double, net heat flow into the particle (thermal only) | W |
/// | `heat_capacity` | SCALARS double, thermal inertia m c (thermal only) | J/K |
/// | `unwrapped_position` | VECTORS double, with periodic boundaries only: the position as if never wrapped (Simulation::unwrapped_position) | m |
/// | `image` | VECTORS double, with periodic boundaries only: the periodic boxes crossed along x, y, z (whole numbers) | - |
///
/// Vectors always have three components (z = 0 in 2D). Fields are written in the order of the
/// table whatever the order asked. `fields::all` adapts to the simulation; naming a thermal
/// field for a mechanical simulation, or an unknown group, is an `InputError` naming the valid
/// ones, raised when the run starts (VtkWriter::start), before any file is written.
/// `fields::named({"velocity", "temperature"})` builds a set from names (for input files).
///
/// With `group = "name"` a particle file holds only the group's active particles (in the order of
/// `sim.group_indices(name)`) and a contact file only the contacts that touch one of them; wall
/// files are unchanged. `io::vtk(prefix, plane_size, contacts)` is the writer of every field of
/// every particle in ASCII.
///
/// With `resume = true` the writer continues the series of a run restarted from a checkpoint: it
/// keeps the entries of the series files before the time at which it starts, numbers its files
/// on after the last of them and removes the files of the later entries.
///
/// Every file (a frame, a series file) is written under a temporary name (`<file>.tmp`) and
/// renamed over its final name once it is complete (see io/atomic_file.hpp), and a frame is
/// written before the series file that lists it: a run killed at any moment leaves the files it
/// had finished, whole, and series files that name only those. A file that cannot be written (a
/// full disk) throws io::WriteError naming the writer, the file and the reason, and leaves the
/// file of that name as it was.
///
/// Walls: lines in 2D, polygons in 3D, with cell data `wall` (the wall index) and, in thermal
/// simulations, `conducts` and `temperature` [K]. Infinite planes are drawn as squares of side
/// `plane_size` [m] around their point; circles as polygons of `circle_segments` sides. Contacts:
/// see write_contacts_vtk.
///
/// Formats: `VtkFormat::ascii` (the default: readable, and what scripts/grain_plot.py reads) or
/// `VtkFormat::binary` (legacy BINARY: the same keywords, numbers as big-endian IEEE 754 doubles
/// and 32-/64-bit integers: 8 bytes a double instead of up to 24 characters, and some 20 times
/// faster to write and to read). Both are legacy VTK "DataFile Version 3.0" polydata, read by
/// ParaView, VisIt and VTK's vtkPolyDataReader.

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <grain/contact/frame.hpp>
#include <grain/core/error.hpp>
#include <grain/core/vector.hpp>
#include <grain/io/atomic_file.hpp>
#include <grain/io/write_error.hpp>
#include <grain/walls/walls.hpp>
#include <iomanip>
#include <iterator>
#include <limits>
#include <locale>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace grain::io {

/// Encoding of the numbers of a legacy VTK file.
enum class VtkFormat {
  ascii, ///< text, 17 significant digits
  binary ///< big-endian binary (legacy VTK BINARY)
};

/// A set of particle fields for the VTK particle files: `fields::velocity | fields::temperature`.
struct Fields {
  std::uint32_t bits = 0;
  constexpr Fields operator|(Fields o) const { return {bits | o.bits}; }
  /// True if every field of `f` is in the set.
  constexpr bool has(Fields f) const { return (bits & f.bits) == f.bits; }
  constexpr bool operator==(const Fields&) const = default;
};

namespace fields {
inline constexpr Fields id{1u << 0}, radius{1u << 1}, velocity{1u << 2}, omega{1u << 3},
    force{1u << 4}, torque{1u << 5}, mass{1u << 6}, orientation{1u << 7}, material{1u << 8},
    temperature{1u << 9}, heat_rate{1u << 10}, heat_capacity{1u << 11};
/// The fields of every simulation.
inline constexpr Fields mechanical =
    id | radius | velocity | omega | force | torque | mass | orientation | material;
/// The fields of a thermal simulation only.
inline constexpr Fields thermal = temperature | heat_rate | heat_capacity;
/// Every field the simulation has (the thermal ones only in a thermal simulation): the default.
inline constexpr Fields all{1u << 31};
/// No field: the particle files hold the centres only.
inline constexpr Fields none{};

/// Names of the fields, in the order of their bits (and of the columns of a particle file).
inline constexpr std::array<const char*, 12> names{
    "id",   "radius",      "velocity", "omega",       "force",     "torque",
    "mass", "orientation", "material", "temperature", "heat_rate", "heat_capacity"};

/// The set of the named fields ("all" for fields::all); throws InputError naming the valid names
/// for an unknown one.
inline Fields named(const std::vector<std::string>& list) {
  Fields f;
  for (const auto& s : list) {
    if (s == "all") {
      f = f | all;
      continue;
    }
    const auto it = std::find(names.begin(), names.end(), s);
    if (it == names.end()) {
      std::string valid;
      for (const char* n : names)
        valid += std::string(n) + ", ";
      throw InputError("grain::io::fields::named: field = '" + s +
                       "' is invalid; valid values: " + valid + "all");
    }
    f = f | Fields{1u << (it - names.begin())};
  }
  return f;
}
} // namespace fields

namespace detail {

static_assert(sizeof(int) == 4, "grain::io::vtk: VTK's int is 32 bits");

/// The fields to write for a simulation of type Sim: `f` with fields::all expanded; throws
/// InputError for a field the simulation does not have.
template <class Sim>
Fields resolve_fields(Fields f, const char* who) {
  constexpr Fields available =
      Sim::thermal ? fields::mechanical | fields::thermal : fields::mechanical;
  if (f.has(fields::all)) return available;
  const std::uint32_t missing = f.bits & ~available.bits;
  if (missing == 0) return f;
  const int k = std::countr_zero(missing);
  const std::string name = k < static_cast<int>(fields::names.size())
                               ? fields::names[k]
                               : "(bit " + std::to_string(k) + ")";
  std::string valid;
  for (std::size_t b = 0; b < fields::names.size(); ++b)
    if (available.has(Fields{1u << b}))
      valid += (valid.empty() ? "" : ", ") + std::string(fields::names[b]);
  throw InputError(std::string(who) + ": field = '" + name + "' is invalid" +
                   (Sim::thermal ? "" : " for a mechanical simulation") +
                   "; valid values: " + valid + ", all" +
                   (Sim::thermal ? ""
                                 : " (temperature, heat_rate and heat_capacity need a "
                                   "thermal simulation)"));
}

/// One legacy VTK polydata file being written. Keyword lines are text in both formats; numbers
/// are text (one tuple per line) or big-endian binary, each binary block ending with a newline.
/// The file is written under a temporary name and takes its own by close() (AtomicFile); `who`
/// names the writer in the messages of a failed write.
class LegacyVtkFile {
public:
  LegacyVtkFile(const std::string& path, VtkFormat format, const char* kind, double time,
                const char* who = "grain::io::vtk")
      : binary_(format == VtkFormat::binary), file_(who, path, binary_), out_(file_.stream()) {
    out_.imbue(std::locale::classic());
    out_ << std::setprecision(17) << "# vtk DataFile Version 3.0\ngrain " << kind << " t = " << time
         << '\n'
         << (binary_ ? "BINARY" : "ASCII") << "\nDATASET POLYDATA\n";
  }

  /// Writes a keyword line.
  void line(const std::string& text) { out_ << text << '\n'; }

  /// POINTS section: n points, at(k) their coordinates (std::array<double, 3>).
  template <class F>
  void points(std::size_t n, F at) {
    line("POINTS " + std::to_string(n) + " double");
    for (std::size_t k = 0; k < n; ++k)
      tuple(at(k));
    end_block();
  }

  /// A cell section ("VERTICES", "LINES", "POLYGONS"): cells.size() cells of point indices.
  template <class Cell>
  void cells(const char* keyword, const std::vector<Cell>& cells) {
    std::size_t total = 0;
    for (const auto& c : cells)
      total += c.size() + 1;
    line(std::string(keyword) + ' ' + std::to_string(cells.size()) + ' ' + std::to_string(total));
    for (const auto& c : cells) {
      value(static_cast<std::int32_t>(c.size()));
      for (const auto k : c)
        value(index32(k));
      end_tuple();
    }
    end_block();
  }
  /// VERTICES section: one vertex per point 0 .. n-1.
  void vertices(std::size_t n) {
    line("VERTICES " + std::to_string(n) + ' ' + std::to_string(2 * n));
    for (std::size_t k = 0; k < n; ++k) {
      value(std::int32_t{1});
      value(index32(k));
      end_tuple();
    }
    end_block();
  }

  /// One data array of n tuples, at(k) the tuple k: a double, std::int64_t or int (SCALARS 1),
  /// a std::array<double, 3> (VECTORS) or another std::array<double, C> (SCALARS C).
  template <class F>
  void field(const char* name, std::size_t n, F at) {
    using T = std::decay_t<decltype(at(std::size_t{0}))>;
    if constexpr (std::is_same_v<T, std::array<double, 3>>) {
      line(std::string("VECTORS ") + name + " double");
    } else {
      const char* type = "double";
      std::size_t comps = 1;
      if constexpr (std::is_same_v<T, std::int64_t>)
        type = binary_ ? "vtktypeint64" : "long";
      else if constexpr (std::is_same_v<T, int>)
        type = "int";
      else if constexpr (!std::is_same_v<T, double>)
        comps = std::tuple_size_v<T>;
      line(std::string("SCALARS ") + name + ' ' + type + ' ' + std::to_string(comps) +
           "\nLOOKUP_TABLE default");
    }
    for (std::size_t k = 0; k < n; ++k)
      tuple(at(k));
    end_block();
  }

  /// Flushes and closes the file and gives it its name (`path`, the name it was opened with);
  /// throws WriteError if anything could not be written, leaving the file of that name as it was.
  void close([[maybe_unused]] const std::string& path) { file_.commit(); }

private:
  bool binary_;
  AtomicFile file_;
  std::ostream& out_;
  std::string buffer_{}; // binary block being built
  bool first_ = true;    // no value yet on the current ASCII line

  static std::int32_t index32(std::size_t k) {
    if (k > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
      throw std::runtime_error("grain::io::vtk: point index " + std::to_string(k) +
                               " does not fit the 32-bit cells of a legacy VTK file");
    return static_cast<std::int32_t>(k);
  }
  template <class T>
  void value(T x) {
    if (binary_) {
      unsigned char b[sizeof(T)];
      std::memcpy(b, &x, sizeof(T));
      if constexpr (std::endian::native == std::endian::little) std::reverse(b, b + sizeof(T));
      buffer_.append(reinterpret_cast<const char*>(b), sizeof(T));
    } else {
      if (!first_) out_ << ' ';
      out_ << x;
      first_ = false;
    }
  }
  template <class T>
  void tuple(const T& x) {
    if constexpr (std::is_arithmetic_v<T>)
      value(x);
    else
      for (const double c : x)
        value(c);
    end_tuple();
  }
  void end_tuple() {
    if (!binary_) out_ << '\n';
    first_ = true;
  }
  void end_block() {
    if (!binary_) return;
    out_.write(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    out_ << '\n';
    buffer_.clear();
  }
};

/// Three components of a position or force (z = 0 in 2D), or of an angular quantity (2D: (0, 0,
/// w)).
inline std::array<double, 3> xyz(const Vec2& v) { return {v[0], v[1], 0.0}; }
inline std::array<double, 3> xyz(const Vec3& v) { return {v[0], v[1], v[2]}; }
inline std::array<double, 3> xyz(double w) { return {0.0, 0.0, w}; }
/// Orientation: the angle [rad] in 2D, the quaternion (w, x, y, z) in 3D.
inline double orientation_value(double angle) { return angle; }
inline std::array<double, 4> orientation_value(const Eigen::Quaterniond& q) {
  return {q.w(), q.x(), q.y(), q.z()};
}

} // namespace detail

/// Writes the particles of a simulation as legacy VTK polydata: their centres as points with one
/// vertex each, and the chosen point fields (see the table above). With a `group` name, only the
/// group's active particles, in the order of `sim.group_indices(group)`; an unknown group or a
/// field the simulation does not have is an InputError.
template <class Sim>
void write_particles_vtk(const Sim& sim, const std::string& path, Fields fields = io::fields::all,
                         VtkFormat format = VtkFormat::ascii, const std::string& group = "") {
  const Fields f = detail::resolve_fields<Sim>(fields, "grain::io::write_particles_vtk");
  const auto& p = sim.particles();
  const std::vector<std::uint32_t>* subset = group.empty() ? nullptr : &sim.group_indices(group);
  const std::size_t n = subset ? subset->size() : p.size();
  const auto at = [subset](std::size_t k) -> std::size_t { return subset ? (*subset)[k] : k; };
  detail::LegacyVtkFile o(path, format, "particles", sim.time());
  o.points(n, [&](std::size_t k) { return detail::xyz(p.position[at(k)]); });
  o.vertices(n);
  if (f == io::fields::none) return o.close(path);
  o.line("POINT_DATA " + std::to_string(n));
  using io::fields::names;
  auto field = [&](Fields which, auto value) { // value(i) of particle i, if `which` is asked
    if (!f.has(which)) return;
    o.field(names[std::countr_zero(which.bits)], n, [&](std::size_t k) { return value(at(k)); });
  };
  field(io::fields::id, [&](std::size_t i) { return std::int64_t{p.id[i]}; });
  field(io::fields::radius, [&](std::size_t i) { return p.radius[i]; });
  field(io::fields::velocity, [&](std::size_t i) { return detail::xyz(p.velocity[i]); });
  field(io::fields::omega, [&](std::size_t i) { return detail::xyz(p.omega[i]); });
  field(io::fields::force, [&](std::size_t i) { return detail::xyz(p.force[i]); });
  field(io::fields::torque, [&](std::size_t i) { return detail::xyz(p.torque[i]); });
  field(io::fields::mass, [&](std::size_t i) { return p.mass[i]; });
  field(io::fields::orientation,
        [&](std::size_t i) { return detail::orientation_value(p.orientation[i]); });
  field(io::fields::material, [&](std::size_t i) { return static_cast<int>(p.material[i]); });
  if constexpr (Sim::thermal) {
    field(io::fields::temperature, [&](std::size_t i) { return p.temperature[i]; });
    field(io::fields::heat_rate, [&](std::size_t i) { return p.heat_rate[i]; });
    field(io::fields::heat_capacity, [&](std::size_t i) { return p.heat_capacity[i]; });
  }
  if (sim.periodic().on) { // where the wrapped particles would be, and the boxes they crossed
    o.field("unwrapped_position", n,
            [&](std::size_t k) { return detail::xyz(sim.unwrapped_position(at(k))); });
    o.field("image", n, [&](std::size_t k) {
      const auto c = sim.image(at(k));
      std::array<double, 3> v{0.0, 0.0, 0.0};
      for (std::size_t d = 0; d < c.size(); ++d)
        v[d] = static_cast<double>(c[d]);
      return v;
    });
  }
  o.close(path);
}

/// Writes the walls of a simulation as legacy VTK polydata (lines in 2D, polygons in 3D), with
/// the wall index and `present` (1 while the wall takes part in contacts, 0 while it is switched
/// off, not yet created or removed) as cell data (and, in a thermal simulation, `conducts` and
/// `temperature` [K]; an insulated wall has conducts = 0 and temperature 0).
template <class Sim>
void write_walls_vtk(const Sim& sim, const std::string& path, double plane_size = 1.0,
                     int circle_segments = 64, VtkFormat format = VtkFormat::ascii) {
  constexpr int D = Sim::dimension;
  using V = grain::Vec<D>;
  grain::detail::require(circle_segments >= 3, "grain::io::write_walls_vtk", "circle_segments",
                         circle_segments, "[3, inf)");
  std::vector<V> pts;
  std::vector<std::vector<std::size_t>> cells;
  std::vector<std::size_t> owner;
  for (std::size_t w = 0; w < sim.walls().size(); ++w) {
    std::visit(
        [&](const auto& g) {
          using G = std::decay_t<decltype(g)>;
          std::vector<std::size_t> c;
          auto add = [&](const V& x) {
            c.push_back(pts.size());
            pts.push_back(x);
          };
          if constexpr (std::is_same_v<G, grain::walls::Segment>) {
            add(g.a);
            add(g.b);
          } else if constexpr (std::is_same_v<G, grain::walls::Circle>) {
            for (int k = 0; k <= circle_segments; ++k) {
              const double a = 2.0 * std::numbers::pi * (k % circle_segments) / circle_segments;
              V x;
              x << g.center[0] + g.radius * std::cos(a), g.center[1] + g.radius * std::sin(a);
              if (k < circle_segments)
                add(x);
              else
                c.push_back(c.front());
            }
          } else if constexpr (std::is_same_v<G, grain::walls::Plane>) {
            grain::Vec3 u = g.normal.unitOrthogonal(), v = g.normal.cross(u);
            const double h = 0.5 * plane_size;
            add(g.point + h * (u + v));
            add(g.point + h * (-u + v));
            add(g.point + h * (-u - v));
            add(g.point + h * (u - v));
          } else {
            add(g.a);
            add(g.b);
            add(g.c);
          }
          cells.push_back(c);
          owner.push_back(w);
        },
        sim.walls()[w].geometry);
  }
  detail::LegacyVtkFile o(path, format, "walls", sim.time());
  o.points(pts.size(), [&](std::size_t k) { return detail::xyz(pts[k]); });
  o.cells(D == 2 ? "LINES" : "POLYGONS", cells);
  const std::size_t m = cells.size();
  o.line("CELL_DATA " + std::to_string(m));
  o.field("wall", m, [&](std::size_t c) { return static_cast<int>(owner[c]); });
  o.field("present", m, [&](std::size_t c) { return sim.walls()[owner[c]].present ? 1 : 0; });
  if constexpr (Sim::thermal) {
    const auto& walls = sim.walls();
    o.field("conducts", m, [&](std::size_t c) { return walls[owner[c]].conducts() ? 1 : 0; });
    o.field("temperature", m, [&](std::size_t c) {
      return walls[owner[c]].conducts() ? walls[owner[c]].temperature : 0.0;
    });
  }
  o.close(path);
}

/// Writes the contact network of a simulation as legacy VTK polydata: one line per touching
/// contact, from the centre of particle i to the centre of particle j, or to the contact point
/// for a wall contact. Points are the particle centres (in storage order) followed by one point
/// per wall contact. Cell data: `wall` (-1 for a particle pair, else the wall index), `id_i`,
/// `id_j` (-1 for a wall), `normal_force` [N] (repulsive positive), `normal_viscous` [N] (its
/// dashpot part; normal_force - normal_viscous is the elastic part), `tangential_force` [N]
/// (vector on i), `normal` (unit, from i to its partner), `force_local` [N] (the force on i in
/// the contact frame of contact/frame.hpp: normal, tangent 1, tangent 2; 2D: normal, tangent, 0),
/// `overlap` [m], `contact_radius` [m] (as the area model gives it to conduction) and, in a
/// thermal simulation, `heat_rate` [W] (into i). With a `group` name, only the contacts
/// that touch a particle of the group (the points are still every particle centre).
template <class Sim>
void write_contacts_vtk(const Sim& sim, const std::string& path,
                        VtkFormat format = VtkFormat::ascii, const std::string& group = "") {
  constexpr int D = Sim::dimension;
  struct Row {
    std::size_t i, j;
    bool wall;
    grain::Vec<D> point, tangential, direction, local;
    double normal, viscous, overlap, radius, heat;
  };
  const auto& p = sim.particles();
  const std::size_t n = p.size();
  std::vector<char> member;
  if (!group.empty()) {
    member.assign(n, 0);
    for (const auto i : sim.group_indices(group))
      member[i] = 1;
  }
  std::vector<Row> rows;
  sim.for_each_contact(
      [&](std::size_t i, std::size_t j, bool wall, const auto& g, const auto& r, double q) {
        if (!member.empty() && !member[i] && (wall || !member[j])) return;
        const auto pair = sim.contact_pair(i, j, wall);
        using C = typename Sim::contact_type;
        const auto mj = wall ? sim.walls()[j].options.material : p.material[j];
        const double a =
            C::area_model::radius(g, pair, r.normal, sim.contact_params(p.material[i], mj).area);
        const auto frame = ContactFrame<D>::from_normal(g.normal);
        rows.push_back({i, j, wall, g.point, r.tangent.force, g.normal, frame.to_local(r.force),
                        r.normal.force, r.normal.viscous, g.overlap, a, q});
      });
  std::vector<std::size_t> wall_points;
  std::vector<std::array<std::size_t, 2>> lines;
  lines.reserve(rows.size());
  for (std::size_t c = 0; c < rows.size(); ++c) {
    if (rows[c].wall) wall_points.push_back(c);
    lines.push_back({rows[c].i, rows[c].wall ? n + wall_points.size() - 1 : rows[c].j});
  }
  detail::LegacyVtkFile o(path, format, "contacts", sim.time());
  o.points(n + wall_points.size(), [&](std::size_t k) {
    return detail::xyz(k < n ? p.position[k] : rows[wall_points[k - n]].point);
  });
  o.cells("LINES", lines);
  const std::size_t m = rows.size();
  if (m == 0) return o.close(path); // no cell data without cells
  o.line("CELL_DATA " + std::to_string(m));
  o.field("wall", m,
          [&](std::size_t c) { return rows[c].wall ? static_cast<int>(rows[c].j) : -1; });
  o.field("id_i", m, [&](std::size_t c) { return std::int64_t{p.id[rows[c].i]}; });
  o.field("id_j", m, [&](std::size_t c) {
    return rows[c].wall ? std::int64_t{-1} : std::int64_t{p.id[rows[c].j]};
  });
  o.field("normal_force", m, [&](std::size_t c) { return rows[c].normal; });
  o.field("normal_viscous", m, [&](std::size_t c) { return rows[c].viscous; });
  o.field("tangential_force", m, [&](std::size_t c) { return detail::xyz(rows[c].tangential); });
  o.field("normal", m, [&](std::size_t c) { return detail::xyz(rows[c].direction); });
  o.field("force_local", m, [&](std::size_t c) { return detail::xyz(rows[c].local); });
  o.field("overlap", m, [&](std::size_t c) { return rows[c].overlap; });
  o.field("contact_radius", m, [&](std::size_t c) { return rows[c].radius; });
  if constexpr (Sim::thermal) o.field("heat_rate", m, [&](std::size_t c) { return rows[c].heat; });
  o.close(path);
}

namespace detail {
/// Rewrites `prefix_kind.vtk.series` (ParaView's file-series format) with one entry per file,
/// under a temporary name renamed over the old series once complete (AtomicFile). Throws
/// WriteError naming `who` if the file could not be written, leaving the old series as it was.
inline void write_series(const std::string& prefix, const char* kind,
                         const std::vector<std::pair<std::string, double>>& files,
                         const char* who = "grain::io::vtk") {
  const std::string path = prefix + "_" + kind + ".vtk.series";
  AtomicFile file(who, path);
  std::ostream& o = file.stream();
  o.imbue(std::locale::classic());
  o << std::setprecision(17) << "{\n  \"file-series-version\" : \"1.0\",\n  \"files\" : [\n";
  for (std::size_t k = 0; k < files.size(); ++k)
    o << "    { \"name\" : \"" << files[k].first << "\", \"time\" : " << files[k].second << " }"
      << (k + 1 < files.size() ? ",\n" : "\n");
  o << "  ]\n}\n";
  file.commit();
}
/// The entries (file name, time) of `prefix_kind.vtk.series` as write_series writes them; none
/// if there is no such file.
inline std::vector<std::pair<std::string, double>> read_series(const std::string& prefix,
                                                               const char* kind) {
  std::vector<std::pair<std::string, double>> files;
  std::ifstream in(prefix + "_" + kind + ".vtk.series");
  if (!in) return files;
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string name_key = "\"name\" : \"", time_key = "\"time\" : ";
  for (std::size_t at = text.find(name_key); at != std::string::npos;
       at = text.find(name_key, at)) {
    const std::size_t a = at + name_key.size(), b = text.find('"', a);
    const std::size_t t = b == std::string::npos ? b : text.find(time_key, b);
    if (t == std::string::npos) break;
    std::istringstream number(text.substr(t + time_key.size(), 32));
    number.imbue(std::locale::classic());
    double time = 0.0;
    if (!(number >> time)) break;
    files.emplace_back(text.substr(a, b - a), time);
    at = t;
  }
  return files;
}
} // namespace detail

/// Options of io::vtk (every one has a default: `io::vtk(prefix, {.format = ...})`).
struct VtkOptions {
  double plane_size = 1.0;         ///< side [m] of the square drawn for an infinite plane
  bool contacts = false;           ///< also write the contact network
  Fields fields = io::fields::all; ///< particle fields
  std::string group{};             ///< only this group's particles (and their contacts); "" = all
  VtkFormat format = VtkFormat::ascii; ///< of every file
  /// Continue the series of an earlier run (a run restarted from a checkpoint): keep the entries
  /// of its series files before the time at which the writer starts, go on numbering after them,
  /// and remove the files of the later entries.
  bool resume = false;
};

/// Output action: one particle file and one wall file (and contact file) per call, numbered
/// 000000, 000001, ..., and their series files.
struct VtkWriter {
  std::string prefix;
  VtkOptions options{};
  int count = 0;
  std::vector<std::pair<std::string, double>> particle_files{}, wall_files{}, contact_files{};

  /// Checks the fields and the group when the run starts, before any file is written (called
  /// by Simulation::run and steps, and by io::every for the actions it wraps); with
  /// `options.resume`, a writer that has written nothing yet takes up the earlier series.
  template <class Sim>
  void start(const Sim& sim) {
    detail::resolve_fields<Sim>(options.fields, "grain::io::vtk");
    if (!options.group.empty()) (void)sim.group(options.group);
    if (options.resume && count == 0 && particle_files.empty()) resume(sim);
    detail::require_output_folder("grain::io::vtk", prefix);
  }

  template <class Sim>
  void operator()(const Sim& sim) {
    const std::filesystem::path base(prefix);
    if (base.has_parent_path()) std::filesystem::create_directories(base.parent_path());
    const std::string stem = base.filename().string();
    std::ostringstream num;
    num << std::setw(6) << std::setfill('0') << count++;
    write_particles_vtk(sim, prefix + "_particles_" + num.str() + ".vtk", options.fields,
                        options.format, options.group);
    particle_files.emplace_back(stem + "_particles_" + num.str() + ".vtk", sim.time());
    detail::write_series(prefix, "particles", particle_files);
    if (!sim.walls().empty()) {
      write_walls_vtk(sim, prefix + "_walls_" + num.str() + ".vtk", options.plane_size, 64,
                      options.format);
      wall_files.emplace_back(stem + "_walls_" + num.str() + ".vtk", sim.time());
      detail::write_series(prefix, "walls", wall_files);
    }
    if (options.contacts) {
      write_contacts_vtk(sim, prefix + "_contacts_" + num.str() + ".vtk", options.format,
                         options.group);
      contact_files.emplace_back(stem + "_contacts_" + num.str() + ".vtk", sim.time());
      detail::write_series(prefix, "contacts", contact_files);
    }
  }

private:
  /// Keeps the series entries of the frames before the current time (half a step's margin: the
  /// frame of the current step is written again) and numbers on after the last one kept.
  template <class Sim>
  void resume(const Sim& sim) {
    const double before = sim.time() - 0.5 * sim.time_step();
    const std::filesystem::path base(prefix);
    const std::string stem = base.filename().string();
    auto take_up = [&](const char* kind, std::vector<std::pair<std::string, double>>& files) {
      files = detail::read_series(prefix, kind);
      if (files.empty()) return;
      const auto later = std::find_if(files.begin(), files.end(),
                                      [&](const auto& f) { return !(f.second < before); });
      const std::vector<std::pair<std::string, double>> dropped(later, files.end());
      files.erase(later, files.end());
      // the series of the entries kept first, then the files it no longer names: a series never
      // names a removed file, also when the run is killed in between
      detail::write_series(prefix, kind, files);
      for (const auto& f : dropped) // only files this writer names
        if (f.first.rfind(stem + "_" + kind + "_", 0) == 0 &&
            f.first.find('/') == std::string::npos) {
          std::error_code ignored;
          std::filesystem::remove(base.parent_path() / f.first, ignored);
        }
    };
    take_up("particles", particle_files);
    take_up("walls", wall_files);
    take_up("contacts", contact_files);
    // the next number: after that of the last particle file kept
    count = static_cast<int>(particle_files.size());
    if (!particle_files.empty()) {
      const std::string& last = particle_files.back().first;
      const std::size_t digits = stem.size() + std::string("_particles_").size();
      int n = 0;
      const auto [end, err] = std::from_chars(last.data() + std::min(digits, last.size()),
                                              last.data() + last.size(), n);
      // a number of its own (>= 0), of which the next one is an int too
      if (err == std::errc{} && std::string_view(end, last.data() + last.size()) == ".vtk" &&
          last.rfind(stem + "_particles_", 0) == 0 && n >= 0 && n < std::numeric_limits<int>::max())
        count = n + 1;
    }
  }
};
/// vtk(prefix, options): an output action writing legacy VTK files `prefix_particles_NNNNNN.vtk`
/// and `prefix_walls_NNNNNN.vtk`, and the ParaView series files `prefix_particles.vtk.series` and
/// `prefix_walls.vtk.series` (rewritten after every frame: open them to see the whole run as
/// one time-dependent source). With `contacts = true` also `prefix_contacts_NNNNNN.vtk` and its
/// series (see write_contacts_vtk). See VtkOptions for the fields, group and format.
inline VtkWriter vtk(std::string prefix, VtkOptions options) {
  return VtkWriter{std::move(prefix), std::move(options)};
}
/// vtk(prefix, plane_size, contacts): every field of every particle, in ASCII.
inline VtkWriter vtk(std::string prefix, double plane_size = 1.0, bool contacts = false) {
  return vtk(std::move(prefix), VtkOptions{.plane_size = plane_size, .contacts = contacts});
}

} // namespace grain::io
