#pragma once
/// \file vtk.hpp
/// Legacy VTK (ASCII) files for ParaView: one particle file and one wall file per output time.
///
/// `vtk("out/bed")` writes out/bed_particles_000000.vtk, out/bed_walls_000000.vtk, ... with
/// particle fields id, radius [m], velocity [m/s], omega [rad/s], force [N] (vectors always have
/// three components; in 2D z = 0 and omega is (0, 0, w)). Infinite planes are drawn as squares of
/// side `plane_size` [m] around their point; circles as polygons of `circle_segments` sides.

#include <grain/core/vector.hpp>
#include <grain/walls/walls.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <locale>
#include <sstream>
#include <stdexcept>
#include <string>
#include <variant>
#include <numbers>
#include <vector>
#include <cstdint>
#include <utility>

namespace grain::io {

namespace detail {

template <class V>
inline void put3(std::ostream& o, const V& v) {
  o << v[0] << ' ' << v[1] << ' ' << (v.size() > 2 ? v[2] : 0.0) << '\n';
}
inline void put_angular(std::ostream& o, double w) { o << "0 0 " << w << '\n'; }
template <class V>
inline void put_angular(std::ostream& o, const V& w) {
  o << w[0] << ' ' << w[1] << ' ' << w[2] << '\n';
}

} // namespace detail

/// Writes the particles of a simulation as legacy VTK polydata.
template <class Sim>
void write_particles_vtk(const Sim& sim, const std::string& path) {
  std::ofstream o(path);
  if (!o) throw std::runtime_error("grain::io::vtk: cannot open '" + path + "' for writing");
  o.imbue(std::locale::classic());
  o << std::setprecision(17);
  const auto& p = sim.particles();
  const std::size_t n = p.size();
  o << "# vtk DataFile Version 3.0\ngrain particles t = " << sim.time() << "\nASCII\n"
    << "DATASET POLYDATA\nPOINTS " << n << " double\n";
  for (std::size_t i = 0; i < n; ++i) detail::put3(o, p.position[i]);
  o << "VERTICES " << n << ' ' << 2 * n << '\n';
  for (std::size_t i = 0; i < n; ++i) o << "1 " << i << '\n';
  o << "POINT_DATA " << n << "\nSCALARS id long 1\nLOOKUP_TABLE default\n";
  for (std::size_t i = 0; i < n; ++i) o << p.id[i] << '\n';
  o << "SCALARS radius double 1\nLOOKUP_TABLE default\n";
  for (std::size_t i = 0; i < n; ++i) o << p.radius[i] << '\n';
  o << "VECTORS velocity double\n";
  for (std::size_t i = 0; i < n; ++i) detail::put3(o, p.velocity[i]);
  o << "VECTORS omega double\n";
  for (std::size_t i = 0; i < n; ++i) detail::put_angular(o, p.omega[i]);
  o << "VECTORS force double\n";
  for (std::size_t i = 0; i < n; ++i) detail::put3(o, p.force[i]);
  if constexpr (requires { p.temperature; p.heat_rate; }) {
    o << "SCALARS temperature double 1\nLOOKUP_TABLE default\n";
    for (std::size_t i = 0; i < n; ++i) o << p.temperature[i] << '\n';
    o << "SCALARS heat_rate double 1\nLOOKUP_TABLE default\n";
    for (std::size_t i = 0; i < n; ++i) o << p.heat_rate[i] << '\n';
  }
}

/// Writes the walls of a simulation as legacy VTK polydata (lines in 2D, polygons in 3D), with
/// the wall index as cell data.
template <class Sim>
void write_walls_vtk(const Sim& sim, const std::string& path, double plane_size = 1.0,
                     int circle_segments = 64) {
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
              if (k < circle_segments) add(x);
              else c.push_back(c.front());
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
  std::ofstream o(path);
  if (!o) throw std::runtime_error("grain::io::vtk: cannot open '" + path + "' for writing");
  o.imbue(std::locale::classic());
  o << std::setprecision(17);
  o << "# vtk DataFile Version 3.0\ngrain walls t = " << sim.time() << "\nASCII\n"
    << "DATASET POLYDATA\nPOINTS " << pts.size() << " double\n";
  for (const auto& x : pts) detail::put3(o, x);
  std::size_t total = 0;
  for (const auto& c : cells) total += c.size() + 1;
  o << (D == 2 ? "LINES " : "POLYGONS ") << cells.size() << ' ' << total << '\n';
  for (const auto& c : cells) {
    o << c.size();
    for (auto k : c) o << ' ' << k;
    o << '\n';
  }
  o << "CELL_DATA " << cells.size() << "\nSCALARS wall int 1\nLOOKUP_TABLE default\n";
  for (auto w : owner) o << w << '\n';
  if constexpr (Sim::thermal) {
    // insulated walls: conducts = 0 and temperature 0
    o << "SCALARS conducts int 1\nLOOKUP_TABLE default\n";
    for (auto w : owner) o << (sim.walls()[w].conducts() ? 1 : 0) << '\n';
    o << "SCALARS temperature double 1\nLOOKUP_TABLE default\n";
    for (auto w : owner) o << (sim.walls()[w].conducts() ? sim.walls()[w].temperature : 0.0) << '\n';
  }
}

/// Writes the contact network of a simulation as legacy VTK polydata: one line per touching
/// contact, from the centre of particle i to the centre of particle j, or to the contact point
/// for a wall contact. Points are the particle centres (in storage order) followed by one point
/// per wall contact. Cell data: `wall` (-1 for a particle pair, else the wall index), `id_i`,
/// `id_j` (-1 for a wall), `normal_force` [N] (repulsive positive), `tangential_force` [N]
/// (vector on i), `overlap` [m], `contact_radius` [m] (as the area model gives it to conduction)
/// and, in a thermal simulation, `heat_rate` [W] (into i).
template <class Sim>
void write_contacts_vtk(const Sim& sim, const std::string& path) {
  constexpr int D = Sim::dimension;
  struct Row {
    std::size_t i, j;
    bool wall;
    grain::Vec<D> point, tangential;
    double normal, overlap, radius, heat;
  };
  std::vector<Row> rows;
  const auto& contact = sim.params().contact;
  const auto& p = sim.particles();
  sim.for_each_contact([&](std::size_t i, std::size_t j, bool wall, const auto& g, const auto& r,
                           double q) {
    const auto pair = sim.contact_pair(i, j, wall);
    using C = typename Sim::contact_type;
    const double a = C::area_model::radius(g, pair, r.normal, contact.area);
    rows.push_back({i, j, wall, g.point, r.tangent.force, r.normal.force, g.overlap, a, q});
  });
  std::ofstream o(path);
  if (!o) throw std::runtime_error("grain::io::vtk: cannot open '" + path + "' for writing");
  o.imbue(std::locale::classic());
  o << std::setprecision(17);
  const std::size_t n = p.size();
  std::size_t extra = 0;
  for (const auto& c : rows) extra += c.wall;
  o << "# vtk DataFile Version 3.0\ngrain contacts t = " << sim.time() << "\nASCII\n"
    << "DATASET POLYDATA\nPOINTS " << n + extra << " double\n";
  for (std::size_t i = 0; i < n; ++i) detail::put3(o, p.position[i]);
  for (const auto& c : rows)
    if (c.wall) detail::put3(o, c.point);
  o << "LINES " << rows.size() << ' ' << 3 * rows.size() << '\n';
  std::size_t next = n;
  for (const auto& c : rows) o << "2 " << c.i << ' ' << (c.wall ? next++ : c.j) << '\n';
  if (rows.empty()) return; // no cell data without cells
  o << "CELL_DATA " << rows.size() << "\nSCALARS wall int 1\nLOOKUP_TABLE default\n";
  for (const auto& c : rows) o << (c.wall ? static_cast<long>(c.j) : -1L) << '\n';
  o << "SCALARS id_i long 1\nLOOKUP_TABLE default\n";
  for (const auto& c : rows) o << p.id[c.i] << '\n';
  o << "SCALARS id_j long 1\nLOOKUP_TABLE default\n";
  for (const auto& c : rows) o << (c.wall ? std::int64_t{-1} : p.id[c.j]) << '\n';
  o << "SCALARS normal_force double 1\nLOOKUP_TABLE default\n";
  for (const auto& c : rows) o << c.normal << '\n';
  o << "VECTORS tangential_force double\n";
  for (const auto& c : rows) detail::put3(o, c.tangential);
  o << "SCALARS overlap double 1\nLOOKUP_TABLE default\n";
  for (const auto& c : rows) o << c.overlap << '\n';
  o << "SCALARS contact_radius double 1\nLOOKUP_TABLE default\n";
  for (const auto& c : rows) o << c.radius << '\n';
  if constexpr (Sim::thermal) {
    o << "SCALARS heat_rate double 1\nLOOKUP_TABLE default\n";
    for (const auto& c : rows) o << c.heat << '\n';
  }
}

namespace detail {
/// Rewrites `prefix_kind.vtk.series` (ParaView's file-series format) with one entry per file.
inline void write_series(const std::string& prefix, const char* kind,
                         const std::vector<std::pair<std::string, double>>& files) {
  std::ofstream o(prefix + "_" + kind + ".vtk.series");
  if (!o) throw std::runtime_error("grain::io::vtk: cannot write '" + prefix + "_" + kind +
                                   ".vtk.series'");
  o.imbue(std::locale::classic());
  o << std::setprecision(17) << "{\n  \"file-series-version\" : \"1.0\",\n  \"files\" : [\n";
  for (std::size_t k = 0; k < files.size(); ++k)
    o << "    { \"name\" : \"" << files[k].first << "\", \"time\" : " << files[k].second << " }"
      << (k + 1 < files.size() ? ",\n" : "\n");
  o << "  ]\n}\n";
}
} // namespace detail

/// Output action: one particle file and one wall file per call, numbered 000000, 000001, ...
struct VtkWriter {
  std::string prefix;
  double plane_size = 1.0;
  bool contacts = false; ///< also write the contact network
  int count = 0;
  std::vector<std::pair<std::string, double>> particle_files{}, wall_files{}, contact_files{};

  template <class Sim>
  void operator()(const Sim& sim) {
    const std::filesystem::path base(prefix);
    if (base.has_parent_path()) std::filesystem::create_directories(base.parent_path());
    const std::string stem = base.filename().string();
    std::ostringstream num;
    num << std::setw(6) << std::setfill('0') << count++;
    write_particles_vtk(sim, prefix + "_particles_" + num.str() + ".vtk");
    particle_files.emplace_back(stem + "_particles_" + num.str() + ".vtk", sim.time());
    detail::write_series(prefix, "particles", particle_files);
    if (!sim.walls().empty()) {
      write_walls_vtk(sim, prefix + "_walls_" + num.str() + ".vtk", plane_size);
      wall_files.emplace_back(stem + "_walls_" + num.str() + ".vtk", sim.time());
      detail::write_series(prefix, "walls", wall_files);
    }
    if (contacts) {
      write_contacts_vtk(sim, prefix + "_contacts_" + num.str() + ".vtk");
      contact_files.emplace_back(stem + "_contacts_" + num.str() + ".vtk", sim.time());
      detail::write_series(prefix, "contacts", contact_files);
    }
  }
};
/// vtk(prefix): an output action writing legacy VTK files `prefix_particles_NNNNNN.vtk` and
/// `prefix_walls_NNNNNN.vtk`, and the ParaView series files `prefix_particles.vtk.series` and
/// `prefix_walls.vtk.series` (rewritten after every frame: open them to see the whole run as
/// one time-dependent source). With `contacts = true` also `prefix_contacts_NNNNNN.vtk` and its
/// series (see write_contacts_vtk).
inline VtkWriter vtk(std::string prefix, double plane_size = 1.0, bool contacts = false) {
  return VtkWriter{std::move(prefix), plane_size, contacts};
}

} // namespace grain::io
