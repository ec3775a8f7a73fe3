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

/// Output action: one particle file and one wall file per call, numbered 000000, 000001, ...
struct VtkWriter {
  std::string prefix;
  double plane_size = 1.0;
  int count = 0;

  template <class Sim>
  void operator()(const Sim& sim) {
    const std::filesystem::path base(prefix);
    if (base.has_parent_path()) std::filesystem::create_directories(base.parent_path());
    std::ostringstream num;
    num << std::setw(6) << std::setfill('0') << count++;
    write_particles_vtk(sim, prefix + "_particles_" + num.str() + ".vtk");
    if (!sim.walls().empty())
      write_walls_vtk(sim, prefix + "_walls_" + num.str() + ".vtk", plane_size);
  }
};
/// vtk(prefix): an output action writing legacy VTK files `prefix_particles_NNNNNN.vtk` and
/// `prefix_walls_NNNNNN.vtk`.
inline VtkWriter vtk(std::string prefix, double plane_size = 1.0) {
  return VtkWriter{std::move(prefix), plane_size};
}

} // namespace grain::io
