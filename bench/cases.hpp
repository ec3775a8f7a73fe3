#pragma once
// The benchmark cases of docs/performance.md, built with grain's public API: settle3d (spheres,
// Hertz-Mindlin, 6 planes) and pack2d (disks, linear spring-dashpot, 4 walls), set up as the
// LIGGGHTS and LAMMPS inputs they are compared with, and the end-of-run figures those inputs
// print.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <grain/grain.hpp>
#include <numbers>

namespace grain::bench {

/// u(n, alpha) = frac(0.5 + n alpha): the R-sequence used for deterministic initial velocities.
inline double rseq(long n, double alpha) {
  const double x = 0.5 + static_cast<double>(n) * alpha;
  return x - std::floor(x);
}

/// Material of both cases (particles and walls): E softened to 1e7 Pa, nu = 0.3, e = 0.5,
/// mu = 0.5, no rolling friction. In 2D the density times the disk thickness (1 mm) gives the
/// areal density 2.5 kg/m^2 of the peer inputs.
inline Material case_material() {
  return {.name = "soft",
          .density = 2500,
          .young = 1e7,
          .poisson = 0.3,
          .restitution = 0.5,
          .friction = 0.5};
}

inline constexpr double case_diameter = 1e-3;    ///< d [m]
inline constexpr double case_time_step = 2.5e-6; ///< dt [s]
inline constexpr double case_v0 = 0.1;           ///< amplitude of the initial velocities [m/s]

// ------------------------------------------------------------------ settle3d

/// LIGGGHTS `model hertz tangential history`: Hertz with Tsuji damping from e (eta_n equals
/// LIGGGHTS' gamma_n), tangential stiffness at the Mindlin ratio (k_t = 8 G* a) and damping at
/// the normal damping ratio (eta_t equals LIGGGHTS' gamma_t).
using Settle3dContact = Interaction<normal::Hertz<>, tangent::SpringDashpotSlider>;
/// The cases' integrator is the peers' `fix nve/sphere`: velocity Verlet whose forces see the
/// half-step velocities (integrate::VelocityVerletHalfStep).
/// `Options`: further Simulation options (e.g. grain::sums<grain::by_id>).
template <class Search = search::CellList, class... Options>
using Settle3d =
    Simulation<Sphere, Search, Settle3dContact, integrate::VelocityVerletHalfStep, Options...>;

namespace detail {
/// The particles and walls of settle3d in `sim` (material m): spheres on the lattice with the
/// R3-sequence velocities; in a thermal simulation columns i < nx/2 at 400 K, the others at 300 K.
template <class Sim>
void fill_settle3d(Sim& sim, std::uint32_t m, int nx, int ny, int nz, bool periodic_xy = false) {
  const double d = case_diameter, r = 0.5 * d, a = 1.02 * d, v0 = case_v0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const long n = i + static_cast<long>(nx) * (j + static_cast<long>(ny) * k);
        const Vec3 v(v0 * (2 * rseq(n, 0.8191725133961645) - 1),
                     v0 * (2 * rseq(n, 0.6710436067037893) - 1),
                     v0 * (2 * rseq(n, 0.5497004779019703) - 1));
        ParticleSpec<3> spec{.position = Vec3((i + 0.5) * a, (j + 0.5) * a, (k + 0.5) * a),
                             .radius = r,
                             .material = m,
                             .velocity = v};
        if constexpr (Sim::thermal) {
          spec.temperature = i < nx / 2 ? 400.0 : 300.0;
          spec.id = n;
        }
        sim.add_particle(spec);
      }
  const Vec3 hi(nx * a, ny * a, nz * a);
  for (int dim = 0; dim < 3; ++dim) {
    if (periodic_xy && dim < 2) {
      sim.set_periodic(dim, 0.0, hi[dim]);
      continue;
    }
    sim.add_wall(walls::Plane{Vec3::Zero(), Vec3::Unit(dim)}, {.name = "low", .material = m});
    sim.add_wall(walls::Plane{hi, -Vec3::Unit(dim)}, {.name = "high", .material = m});
  }
}
} // namespace detail

/// settle3d: spheres d = 1 mm on a simple cubic lattice (spacing 1.02 d) in a box of 6 planes,
/// Hertz-Mindlin with e = 0.5, mu = 0.5, E = 1e7 Pa, nu = 0.3, dt = 2.5e-6 s, gravity -z.
/// Sphere orientations are not integrated (nothing reads them; the peers do not either).
/// `periodic_xy`: periodic along x and y instead of the 4 side planes.
template <class Search = search::CellList, class... Options>
Settle3d<Search, Options...> make_settle3d(int nx, int ny, int nz, bool periodic_xy = false) {
  Settle3d<Search, Options...> sim({.time_step = case_time_step,
                                    .gravity = Vec3(0, 0, -9.81),
                                    .search = {.skin = 0.1 * case_diameter},
                                    .track_orientation = false});
  detail::fill_settle3d(sim, sim.add_material(case_material()), nx, ny, nz, periodic_xy);
  return sim;
}

// ------------------------------------------------------------------ thermal3d

/// The conduction law of LIGGGHTS `fix heat/gran/conduction` (contact_area overlap), a
/// user-defined conduction model: H = 4 k1 k2/(k1 + k2) sqrt(A) with A = pi a^2 the area of the
/// circle where the undeformed spheres intersect (a: `area::Geometric`, the lens half chord),
/// i.e. sqrt(pi) times Batchelor-O'Brien with that radius (Chaudhuri et al., Chem. Eng. Sci. 61
/// (2006) 6348).
struct OverlapAreaConduction {
  static constexpr Slot slot = Slot::conduction;
  static constexpr const char* name = "overlap area (LIGGGHTS)";
  static constexpr bool thermal = true;
  static constexpr bool uses_distance = false;
  struct Params {};
  template <int D>
  struct History {};
  static void validate(const Params&) {}
  template <int D>
  static double conductance(const ContactGeometry<D>&, const PairProperties& pair,
                            const HeatContext& c, const Params&, History<D>&) {
    return 4.0 * pair.conductivity_eff * std::sqrt(std::numbers::pi) * c.contact_radius;
  }
};

/// settle3d with LIGGGHTS' heat conduction between particles (walls adiabatic).
using Thermal3dContact = Interaction<normal::Hertz<>, tangent::SpringDashpotSlider, rolling::None,
                                     OverlapAreaConduction, area::Geometric>;
template <class Search = search::CellList>
using Thermal3d = Simulation<Sphere, Search, Thermal3dContact, integrate::VelocityVerletHalfStep>;

/// thermal3d: settle3d plus conduction (k = 1 W/(m K), c = 840 J/(kg K)); particles of lattice
/// columns i < floor(NX/2) start at 400 K (group "hot"), the others at 300 K; ids are the
/// lattice indices.
template <class Search = search::CellList>
Thermal3d<Search> make_thermal3d(int nx, int ny, int nz) {
  Thermal3d<Search> sim({.time_step = case_time_step,
                         .gravity = Vec3(0, 0, -9.81),
                         .search = {.skin = 0.1 * case_diameter},
                         .track_orientation = false});
  Material mat = case_material();
  mat.conductivity = 1.0;
  mat.heat_capacity = 840.0;
  detail::fill_settle3d(sim, sim.add_material(mat), nx, ny, nz);
  return sim;
}

// ------------------------------------------------------------------ pack2d

/// LIGGGHTS `model hooke tangential history` (characteristicVelocity 1 m/s): a linear
/// spring-dashpot whose stiffness is the Hertz-equivalent one at 1 m/s by the energy formulation,
/// K = (16/15)^(4/5) (v R* E*^2 sqrt(m*))^(2/5) (LIGGGHTS' kn), with the damping of e
/// (LIGGGHTS' gamma_n); tangential spring k_t = K and, at the normal damping ratio, eta_t =
/// eta_n (LIGGGHTS' kt = kn, gamma_t = gamma_n).
using Pack2dContact = Interaction<normal::LinearSpringDashpot, tangent::SpringDashpotSlider>;
template <class Search = search::CellList>
using Pack2d = Simulation<Disk, Search, Pack2dContact, integrate::VelocityVerletHalfStep>;

/// Contact coefficients of pack2d (see Pack2dContact), computed per contact from the pair.
inline Pack2dContact::Params pack2d_contact() {
  Pack2dContact::Params c;
  c.normal.reference_velocity = 1.0;
  c.normal.equivalence = normal::Equivalence::energy;
  c.tangent.stiffness_ratio = 1.0;
  return c;
}

/// The same law with its coefficients fixed for contacts of effective radius r_eff and mass
/// m_eff of the pair `pair`: K and eta_n = eta_t from pack2d_contact()'s formulas, evaluated once.
/// For one size of disk these are the constants of a pair type, as LAMMPS' input gives them.
inline Pack2dContact::Params pack2d_constants(const PairProperties& pair, double r_eff,
                                              double m_eff) {
  using Normal = normal::LinearSpringDashpot;
  auto c = pack2d_contact();
  c.normal.stiffness = Normal::stiffness(pair, c.normal, r_eff, m_eff);
  c.normal.damping = Normal::damping(pair, c.normal, c.normal.stiffness, m_eff);
  c.tangent.damping = c.normal.damping; // eta_t = eta_n sqrt(k_t/k_n), k_t = k_n
  return c;
}

/// pack2d: disks d = 1 mm, 1 mm thick (m = pi r^2 x 2.5 kg/m^2, I = 1/2 m r^2), on a square
/// lattice (spacing 1.001 d) in a box of 4 walls, linear spring-dashpot with e = 0.5, mu = 0.5,
/// dt = 2.5e-6 s, gravity -y. The walls are segments that reach one diameter beyond the box, so
/// that every disk inside meets them as the infinite planes of the peer inputs. They have a
/// material of their own with the disks' properties, so that disk-disk contacts (R* = r/2, m* =
/// m/2) and disk-wall contacts (R* = r, m* = m) each get their constant coefficients
/// (pack2d_constants; `per_contact` = true computes them in every contact instead, as LIGGGHTS
/// does: the same values).
template <class Search = search::CellList>
Pack2d<Search> make_pack2d(int nx, int ny, bool per_contact = false) {
  const double d = case_diameter, r = 0.5 * d, a = 1.001 * d, v0 = case_v0;
  Pack2d<Search> sim({.time_step = case_time_step,
                      .gravity = Vec2(0, -9.81),
                      .contact = pack2d_contact(),
                      .search = {.skin = 0.1 * d},
                      .track_orientation = false},
                     Disk{.thickness = 1e-3});
  const auto m = sim.add_material(case_material());
  auto wall_material = case_material();
  wall_material.name = "wall";
  const auto mw = sim.add_material(wall_material);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const long n = i + static_cast<long>(nx) * j;
      const Vec2 v(v0 * (2 * rseq(n, 0.7548776662466927) - 1),
                   v0 * (2 * rseq(n, 0.5698402909980532) - 1));
      sim.add_particle({.position = Vec2((i + 0.5) * a, (j + 0.5) * a),
                        .radius = r,
                        .material = m,
                        .velocity = v});
    }
  if (!per_contact) {
    const double mass = sim.particles().mass[0];
    sim.set_pair_parameters(m, m, pack2d_constants(sim.pair_properties(m, m), 0.5 * r, 0.5 * mass));
    sim.set_pair_parameters(m, mw, pack2d_constants(sim.pair_properties(m, mw), r, mass));
  }
  const double lx = nx * a, ly = ny * a, e = d;
  sim.add_wall(walls::Segment{Vec2(-e, 0), Vec2(lx + e, 0)}, {.name = "bottom", .material = mw});
  sim.add_wall(walls::Segment{Vec2(-e, ly), Vec2(lx + e, ly)}, {.name = "top", .material = mw});
  sim.add_wall(walls::Segment{Vec2(0, -e), Vec2(0, ly + e)}, {.name = "left", .material = mw});
  sim.add_wall(walls::Segment{Vec2(lx, -e), Vec2(lx, ly + e)}, {.name = "right", .material = mw});
  return sim;
}

// ------------------------------------------------------------------ end-of-run figures

/// The figures the peer inputs print (LIGGGHTS/LAMMPS `compute contact/atom`, `ke`,
/// `erotate/sphere`, `reduce ave`).
struct Figures {
  std::size_t contacts = 0; ///< particle pairs with |x_i - x_j| <= r_i + r_j
  double kinetic = 0.0;     ///< sum 1/2 m v^2 [J]
  double rotational = 0.0;  ///< sum 1/2 (0.4 m r^2) |w|^2 [J], 0.4 also in 2D
  double mean_height = 0.0; ///< mean of the last coordinate (z in 3D, y in 2D) [m]
  std::size_t outside = 0;  ///< particles with a non-finite position or outside `lo`..`hi`
};

/// End-of-run figures of a simulation; `lo`, `hi` are the corners of the box the particles must
/// stay in. Contacts are counted over the neighbour list, which holds every touching pair.
template <class Sim>
Figures figures(const Sim& sim, const Vec<Sim::D>& lo, const Vec<Sim::D>& hi) {
  Figures f;
  const auto& p = sim.particles();
  const auto& list = sim.neighbor_list();
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (auto e = list.offsets[i]; e < list.offsets[i + 1]; ++e) {
      const std::size_t j = list.partners[e];
      const double rs = p.radius[i] + p.radius[j];
      f.contacts += (p.position[j] - p.position[i]).squaredNorm() <= rs * rs;
    }
    f.kinetic += 0.5 * p.mass[i] * p.velocity[i].squaredNorm();
    f.rotational += 0.5 * 0.4 * p.mass[i] * p.radius[i] * p.radius[i] * squared_norm(p.omega[i]);
    f.mean_height += p.position[i][Sim::D - 1];
    const auto& x = p.position[i];
    f.outside +=
        !(x.allFinite() && (x.array() >= lo.array()).all() && (x.array() <= hi.array()).all());
  }
  if (n > 0) f.mean_height /= static_cast<double>(n);
  return f;
}

} // namespace grain::bench
