// Contact-law kernels: grain's composed `Interaction<Normal, Tangent, ...>::evaluate` against
// hand-written loops that compute the same laws from the formulas, over the same contact data
// taken from a real simulation state. The design guide (DESIGN.md, "The hot loop") asks for this
// proof: the template layers must compile down to the loop one would write by hand.
//
// What is timed is one pass over a fixed set of contacts (geometry, pair properties, history):
// the contact law, the update of the per-contact history, and the store of the force and of the
// two torques, exactly what the force loop of a step does per contact once the geometry is known
// (the distance test, the geometry and the scatter into particle arrays are not part of it, and
// are the same code for every law). Three variants per law:
//
//   interaction  `Contact::evaluate(g, pair, params, history, dt)`, as Simulation calls it;
//   handwritten  the same maths as plain scalar code on plain arrays, written from the formulas
//                in the models' headers (no grain model type, the same data layout);
//   pairconst    (Hertz only) the hand-written loop with the quantities that depend on the
//                materials alone (Tsuji's alpha, the Mindlin stiffness ratio, ...) computed once
//                per material pair, as the design guide's hot loop does.
//
// Before anything is timed, the variants are run once from the same histories and must agree to
// 1e-10 relative in every force, torque and updated spring (and exactly in the sliding flags);
// otherwise the program aborts with a message (`bench_kernels --check` runs only these checks,
// at every size: the test bench_kernels_check). Every variant then runs the same fixed number of
// passes from the same histories, so that all of them go through the same sequence of contact
// states (springs grow and contacts start to slide over the passes); their timings compare.
//
// Contact sets (the passes run on the calling thread; OMP_NUM_THREADS matters only to the
// simulations that make the sets):
//   Hertz-Mindlin (settle3d's law): settle3d's spheres, lattice closed to 1.001 d so that the
//     neighbours collide at once, after 80 steps (6x6x6: ~300 contacts; 40x40x32: ~1e5);
//   linear spring-dashpot (pack2d's law): pack2d's disks after 60 steps (20x15: ~370 contacts;
//     320x250: ~1e5);
//   conductance (Batchelor-O'Brien, H = 4 k* a, a = sqrt(R* delta)): the Hertz contact set.
// Only particle-particle contacts are used (a wall contact's history is not public; walls hold
// ~2 % of the contacts here).
//
// Counters: contacts_per_s (rate), time_per_contact (CPU time per contact, e.g. "52.6ns"),
// contacts, history_bytes (= sizeof(History), the per-contact state the law keeps).
// Run the realistic sizes on one thread, e.g.
//   OMP_NUM_THREADS=1 build/bench/bench_kernels --benchmark_filter=1e5
//       --benchmark_enable_random_interleaving=true   (one command line)
// (random interleaving alternates the variants' repetitions, which matters on a shared machine).

#include "cases.hpp"
#include <algorithm>
#include <benchmark/benchmark.h>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <grain/models/conduction/batchelor_obrien.hpp>
#include <limits>
#include <map>
#include <numbers>
#include <string>
#include <vector>

namespace {

using namespace grain;

// ============================================================== contact data

/// The touching particle-particle contacts of a simulation state: geometry, an index into a
/// small table of distinct pair properties (as the simulation looks them up by material pair),
/// and the contact history from the simulation's list.
template <class Sim>
struct ContactSet {
  static constexpr int D = Sim::D;
  using Contact = typename Sim::contact_type;
  using History = typename Sim::History;
  std::vector<ContactGeometry<D>> geometry;
  std::vector<std::uint32_t> pair_index;
  std::vector<PairProperties> pairs;
  std::vector<History> history;
  typename Contact::Params params;
  double dt = 0.0;
  std::size_t size() const { return geometry.size(); }
};

template <class Sim>
ContactSet<Sim> collect(const Sim& sim) {
  constexpr int D = Sim::D;
  ContactSet<Sim> s;
  s.params = sim.params().contact;
  s.dt = sim.time_step();
  const NeighborList& list = sim.neighbor_list();
  const auto& histories = sim.histories();
  sim.for_each_contact(
      [&](std::size_t i, std::size_t j, bool wall, const ContactGeometry<D>& g, const auto&) {
        if (wall) return;
        // the list entry of (i, j): rows hold their partners in ascending order
        const auto first = list.partners.begin() + list.offsets[i];
        const auto last = list.partners.begin() + list.offsets[i + 1];
        const auto e =
            static_cast<std::size_t>(std::lower_bound(first, last, j) - list.partners.begin());
        const PairProperties pp = sim.contact_pair(i, j, false);
        std::size_t k = 0;
        while (k < s.pairs.size() && std::memcmp(&s.pairs[k], &pp, sizeof pp) != 0)
          ++k;
        if (k == s.pairs.size()) s.pairs.push_back(pp);
        s.geometry.push_back(g);
        s.pair_index.push_back(static_cast<std::uint32_t>(k));
        s.history.push_back(histories[e]);
      });
  return s;
}

using HertzSim = bench::Settle3d<>;
using LinearSim = bench::Pack2d<>;

/// Hertz-Mindlin contacts: settle3d with the lattice closed from 1.02 d to 1.001 d (the walls
/// stay where they are), 80 steps.
ContactSet<HertzSim> hertz_contacts(int nx, int ny, int nz) {
  auto sim = bench::make_settle3d(nx, ny, nz);
  for (auto& x : sim.particles().position)
    x *= 1.001 / 1.02;
  sim.steps(80);
  return collect(sim);
}

/// Linear spring-dashpot contacts: pack2d after 60 steps.
ContactSet<LinearSim> linear_contacts(int nx, int ny) {
  auto sim = bench::make_pack2d(nx, ny);
  sim.steps(60);
  return collect(sim);
}

/// Builds each contact set once per process (the realistic ones take seconds).
template <class F>
const auto& cached(const std::string& key, F make) {
  using Set = decltype(make());
  static std::map<std::string, Set> sets;
  auto it = sets.find(key);
  if (it == sets.end()) it = sets.emplace(key, make()).first;
  return it->second;
}

/// What a pass stores per contact.
template <int D>
struct Output {
  std::vector<Vec<D>> force;
  std::vector<Angular<D>> torque_i, torque_j;
  explicit Output(std::size_t n)
      : force(n, Vec<D>::Zero()), torque_i(n, zero<Angular<D>>()), torque_j(n, zero<Angular<D>>()) {
  }
};

// ============================================================== (a) the composed Interaction

/// One pass of `Contact::evaluate` over the set, updating the histories `h`.
template <class Sim>
void interaction_pass(const ContactSet<Sim>& s, std::vector<typename Sim::History>& h,
                      Output<Sim::D>& out) {
  using Contact = typename Sim::contact_type;
  const std::size_t n = s.size();
  for (std::size_t c = 0; c < n; ++c) {
    const auto r = Contact::evaluate(s.geometry[c], s.pairs[s.pair_index[c]], s.params, h[c], s.dt);
    out.force[c] = r.force;
    out.torque_i[c] = r.torque_i;
    out.torque_j[c] = r.torque_j;
  }
}

// ============================================================== (b) hand-written laws

/// Plain per-contact state of a spring-dashpot-slider: the tangential spring elongation xi [m]
/// and whether the contact slid at the last pass (the same bytes as grain's history).
template <int D>
struct PlainSpring {
  double xi[D];
  bool sliding;
};
static_assert(sizeof(PlainSpring<3>) == sizeof(HertzSim::History));
static_assert(sizeof(PlainSpring<2>) == sizeof(LinearSim::History));

template <class Sim>
std::vector<PlainSpring<Sim::D>> plain_histories(const ContactSet<Sim>& s) {
  std::vector<PlainSpring<Sim::D>> h(s.size());
  for (std::size_t c = 0; c < s.size(); ++c) {
    for (int d = 0; d < Sim::D; ++d)
      h[c].xi[d] = s.history[c].tangent.spring[d];
    h[c].sliding = s.history[c].tangent.sliding;
  }
  return h;
}

/// Tangential spring-dashpot with Coulomb truncation, D = 2 or 3, given the normal force fn, the
/// spring k_t and dashpot eta_t (stick_slip.hpp): xi is turned into the tangent plane at
/// constant length, xi += v_slip dt, F_t = -eta_t v_t - k_t xi; if |F_t| > mu max(fn, 0)
/// (mu = mu_d after a sliding pass, else mu_s) the contact slides: F_t is scaled to
/// mu_d max(fn, 0) and the spring set to hold it alone, xi = -F_t / k_t. Returns F_t in f.
template <int D>
inline void spring_slider(const ContactGeometry<D>& g, double fn, double kt, double eta_t,
                          double mu_d, double mu_s, double dt, PlainSpring<D>& h, double* f) {
  const double* n = g.normal.data();
  double xi[D];
  double old2 = 0.0, xn = 0.0;
  for (int d = 0; d < D; ++d) {
    xi[d] = h.xi[d];
    old2 += xi[d] * xi[d];
    xn += xi[d] * n[d];
  }
  if (old2 > 0.0) {
    double new2 = 0.0;
    for (int d = 0; d < D; ++d) {
      xi[d] -= xn * n[d];
      new2 += xi[d] * xi[d];
    }
    const double scale = new2 > 0.0 ? std::sqrt(old2 / new2) : 0.0;
    for (int d = 0; d < D; ++d)
      xi[d] *= scale;
  }
  double f2 = 0.0;
  for (int d = 0; d < D; ++d) {
    xi[d] += g.slip_velocity[d] * dt;
    f[d] = -eta_t * g.tangential_velocity[d] - kt * xi[d];
    f2 += f[d] * f[d];
  }
  const double fc = std::max(fn, 0.0); // only a compressive normal force carries friction
  const double limit = (h.sliding ? mu_d : mu_s) * fc;
  h.sliding = f2 > limit * limit;
  if (h.sliding) {
    const double scale = mu_d * fc / std::sqrt(f2);
    for (int d = 0; d < D; ++d) {
      f[d] *= scale;
      xi[d] = -f[d] / kt;
    }
  }
  for (int d = 0; d < D; ++d)
    h.xi[d] = xi[d];
}

/// Total force on i, F = F_t - fn n, and the torques arm_i x F_t, arm_j x (-F_t) (3D).
inline void store3(const ContactGeometry<3>& g, double fn, const double* ft, Output<3>& out,
                   std::size_t c) {
  const double* n = g.normal.data();
  const double* ai = g.arm_i.data();
  const double* aj = g.arm_j.data();
  out.force[c] = Vec3(ft[0] - fn * n[0], ft[1] - fn * n[1], ft[2] - fn * n[2]);
  out.torque_i[c] = Vec3(ai[1] * ft[2] - ai[2] * ft[1], ai[2] * ft[0] - ai[0] * ft[2],
                         ai[0] * ft[1] - ai[1] * ft[0]);
  out.torque_j[c] = Vec3(aj[2] * ft[1] - aj[1] * ft[2], aj[0] * ft[2] - aj[2] * ft[0],
                         aj[1] * ft[0] - aj[0] * ft[1]);
}

/// Hertz with Tsuji damping and the Mindlin spring-dashpot-slider (settle3d's law), from the
/// formulas of hertz.hpp, hertz_damping.hpp and spring_dashpot_slider.hpp:
///   K_hz = 4/3 E* sqrt(R*),  F_n = K_hz delta^(3/2) + eta_n d(delta)/dt,
///   eta_n = alpha sqrt(m* K_hz) delta^(1/4),  alpha = sqrt(5) |ln e| / sqrt(ln^2 e + pi^2),
///   k_n = 3/2 K_hz sqrt(delta),  k_t = (1 - nu)/(1 - nu/2) k_n,  eta_t = eta_n sqrt(k_t / k_n).
void hertz_handwritten_pass(const ContactSet<HertzSim>& s, std::vector<PlainSpring<3>>& h,
                            Output<3>& out) {
  constexpr double pi2 = std::numbers::pi * std::numbers::pi;
  const std::size_t n = s.size();
  for (std::size_t c = 0; c < n; ++c) {
    const ContactGeometry<3>& g = s.geometry[c];
    const PairProperties& pp = s.pairs[s.pair_index[c]];
    const double khz = 4.0 / 3.0 * pp.young_eff * std::sqrt(g.r_eff);
    const double sd = std::sqrt(g.overlap);
    const double lne = pp.log_restitution;
    const double alpha = std::sqrt(5.0) * std::abs(lne) / std::sqrt(lne * lne + pi2);
    const double eta_n = alpha * std::sqrt(g.m_eff * khz * sd);
    const double fn = khz * g.overlap * sd + eta_n * g.normal_velocity;
    const double kn = 1.5 * khz * sd;
    const double nu = pp.poisson_avg;
    const double kt = (1.0 - nu) / (1.0 - 0.5 * nu) * kn;
    const double eta_t = eta_n * std::sqrt(kt / kn);
    double ft[3];
    spring_slider<3>(g, fn, kt, eta_t, pp.friction, std::max(pp.friction_static, pp.friction), s.dt,
                     h[c], ft);
    store3(g, fn, ft, out, c);
  }
}

/// The constants of a material pair for the Hertz-Mindlin law.
struct HertzPairConstants {
  double k43e;      ///< 4/3 E* [Pa]
  double alpha;     ///< Tsuji's alpha from e
  double kt_ratio;  ///< k_t / k_n = (1 - nu)/(1 - nu/2)
  double eta_ratio; ///< eta_t / eta_n = sqrt(k_t / k_n)
  double mu_d, mu_s;
};

std::vector<HertzPairConstants> hertz_constants(const std::vector<PairProperties>& pairs) {
  std::vector<HertzPairConstants> k;
  for (const auto& pp : pairs) {
    const double lne = pp.log_restitution, nu = pp.poisson_avg;
    const double q = (1.0 - nu) / (1.0 - 0.5 * nu);
    k.push_back({4.0 / 3.0 * pp.young_eff,
                 std::sqrt(5.0) * std::abs(lne) /
                     std::sqrt(lne * lne + std::numbers::pi * std::numbers::pi),
                 q, std::sqrt(q), pp.friction, std::max(pp.friction_static, pp.friction)});
  }
  return k;
}

/// The hand-written Hertz-Mindlin law with the per-pair constants precomputed: per contact, only
/// what depends on R*, m*, delta and the velocities is computed (two square roots fewer, and no
/// divisions, in the normal and damping coefficients).
void hertz_pairconst_pass(const ContactSet<HertzSim>& s, const std::vector<HertzPairConstants>& k,
                          std::vector<PlainSpring<3>>& h, Output<3>& out) {
  const std::size_t n = s.size();
  for (std::size_t c = 0; c < n; ++c) {
    const ContactGeometry<3>& g = s.geometry[c];
    const HertzPairConstants& pk = k[s.pair_index[c]];
    const double khz = pk.k43e * std::sqrt(g.r_eff);
    const double sd = std::sqrt(g.overlap);
    const double eta_n = pk.alpha * std::sqrt(g.m_eff * khz * sd);
    const double fn = khz * g.overlap * sd + eta_n * g.normal_velocity;
    const double kt = pk.kt_ratio * 1.5 * khz * sd;
    double ft[3];
    spring_slider<3>(g, fn, kt, pk.eta_ratio * eta_n, pk.mu_d, pk.mu_s, s.dt, h[c], ft);
    store3(g, fn, ft, out, c);
  }
}

/// Linear spring-dashpot at the Hertz-equivalent stiffness (energy formulation) with a linear
/// spring-dashpot-slider (pack2d's law, 2D), from linear_spring_dashpot.hpp and
/// hertz_equivalent.hpp:
///   K = (16/15)^(4/5) (v R* E*^2 sqrt(m*))^(2/5),  F_n = K delta + eta_n d(delta)/dt,
///   eta_n = 2 zeta sqrt(m* K),  zeta = -ln e / sqrt(ln^2 e + pi^2),
///   k_t = ratio K,  eta_t = eta_n sqrt(k_t / K).
/// v (`reference_velocity`) and the ratio (`stiffness_ratio`, > 0) are pack2d's parameters.
void linear_handwritten_pass(const ContactSet<LinearSim>& s, std::vector<PlainSpring<2>>& h,
                             Output<2>& out) {
  constexpr double pi2 = std::numbers::pi * std::numbers::pi;
  const double v = s.params.normal.reference_velocity;
  const double ratio = s.params.tangent.stiffness_ratio;
  const std::size_t n = s.size();
  for (std::size_t c = 0; c < n; ++c) {
    const ContactGeometry<2>& g = s.geometry[c];
    const PairProperties& pp = s.pairs[s.pair_index[c]];
    const double k = 1.0529869257785707 *
                     std::pow(v * g.r_eff * pp.young_eff * pp.young_eff * std::sqrt(g.m_eff), 0.4);
    const double lne = pp.log_restitution;
    const double zeta = -lne / std::sqrt(lne * lne + pi2);
    const double eta_n = 2.0 * zeta * std::sqrt(g.m_eff * k);
    const double fn = k * g.overlap + eta_n * g.normal_velocity;
    const double kt = ratio * k;
    const double eta_t = eta_n * std::sqrt(kt / k);
    double ft[2];
    spring_slider<2>(g, fn, kt, eta_t, pp.friction, std::max(pp.friction_static, pp.friction), s.dt,
                     h[c], ft);
    const double* nv = g.normal.data();
    out.force[c] = Vec2(ft[0] - fn * nv[0], ft[1] - fn * nv[1]);
    out.torque_i[c] = g.arm_i[0] * ft[1] - g.arm_i[1] * ft[0];
    out.torque_j[c] = g.arm_j[1] * ft[0] - g.arm_j[0] * ft[1];
  }
}

// ============================================================== the check before timing

inline double magnitude(double x) { return std::abs(x); }
template <int D>
inline double magnitude(const Vec<D>& x) {
  return x.norm();
}

/// Largest relative difference of two arrays of vectors; each difference is relative to the
/// larger of the two values, floored at 1e-9 of the largest value in the arrays (so that a force
/// that vanishes by cancellation does not count as a relative error).
template <class T>
double max_relative(const std::vector<T>& a, const std::vector<T>& b) {
  double big = 0.0;
  for (const auto& x : a)
    big = std::max(big, magnitude(x));
  double worst = 0.0;
  for (std::size_t c = 0; c < a.size(); ++c) {
    const double scale = std::max({magnitude(a[c]), magnitude(b[c]), 1e-9 * big});
    if (scale > 0.0) worst = std::max(worst, magnitude(T(a[c] - b[c])) / scale);
  }
  return worst;
}

[[noreturn]] void fail(const std::string& what) {
  std::fprintf(stderr, "bench_kernels: %s\n", what.c_str());
  std::abort();
}

/// Forces that nearly cancel (the elastic and the damping part of a normal force just after
/// first touch and just before separation) keep fewer digits than their parts: in settle3d's
/// contact set, forces of 1e-6 of the largest differ by up to 3e-12 between the variants. A
/// difference in the formulas shows up many orders of magnitude above this tolerance.
constexpr double tolerance = 1e-10;

/// Compares one pass of two variants (outputs and updated springs); aborts on a mismatch, else
/// returns the largest relative difference.
template <int D>
double check_pass(const std::string& what, const Output<D>& a, const Output<D>& b,
                  const std::vector<std::array<double, D>>& xi_a, const std::vector<bool>& slide_a,
                  const std::vector<PlainSpring<D>>& hb) {
  std::vector<Vec<D>> xa(xi_a.size()), xb(hb.size());
  std::size_t flags = 0;
  for (std::size_t c = 0; c < hb.size(); ++c) {
    xa[c] = Eigen::Map<const Vec<D>>(xi_a[c].data());
    xb[c] = Eigen::Map<const Vec<D>>(hb[c].xi);
    flags += slide_a[c] != hb[c].sliding;
  }
  const double ef = max_relative(a.force, b.force);
  const double eti = max_relative(a.torque_i, b.torque_i);
  const double etj = max_relative(a.torque_j, b.torque_j);
  const double ex = max_relative(xa, xb);
  if (!(ef <= tolerance && eti <= tolerance && etj <= tolerance && ex <= tolerance) || flags > 0) {
    char msg[400];
    std::snprintf(msg, sizeof msg,
                  "%s: the variants disagree on the first pass (largest relative differences: "
                  "force %.3g, torque_i %.3g, torque_j %.3g, spring %.3g; sliding flags differ "
                  "in %zu of %zu contacts; tolerance %.0e)",
                  what.c_str(), ef, eti, etj, ex, flags, hb.size(), tolerance);
    fail(msg);
  }
  return std::max({ef, eti, etj, ex});
}

template <class Sim>
void split_history(const std::vector<typename Sim::History>& h,
                   std::vector<std::array<double, Sim::D>>& xi, std::vector<bool>& sliding) {
  xi.resize(h.size());
  sliding.resize(h.size());
  for (std::size_t c = 0; c < h.size(); ++c) {
    xi[c] = h[c].tangent.spring;
    sliding[c] = h[c].tangent.sliding;
  }
}

/// First pass of the interaction and of each hand-written variant from the same histories; prints
/// how closely they agree (to stderr, once per contact set).
template <class Sim, class... Passes>
void check_variants(const std::string& what, const ContactSet<Sim>& s, Passes&&... passes) {
  if (s.size() == 0) fail(what + ": no contacts");
  Output<Sim::D> ref(s.size());
  auto h = s.history;
  interaction_pass(s, h, ref);
  std::vector<std::array<double, Sim::D>> xi;
  std::vector<bool> sliding;
  split_history<Sim>(h, xi, sliding);
  std::string agree;
  (
      [&] {
        Output<Sim::D> out(s.size());
        auto hp = plain_histories(s);
        passes(hp, out);
        char d[32];
        std::snprintf(d, sizeof d, " %.2g", check_pass<Sim::D>(what, ref, out, xi, sliding, hp));
        agree += d;
      }(),
      ...);
  std::size_t slid = 0;
  for (const bool b : sliding)
    slid += b;
  std::fprintf(stderr,
               "bench_kernels: %s: %zu contacts (%zu sliding after the first pass), %zu pair "
               "type(s); hand-written variants agree with Interaction to%s (relative)\n",
               what.c_str(), s.size(), slid, s.pairs.size(), agree.c_str());
}

// ============================================================== the benchmarks

/// Sets the counters of a kernel benchmark that made one pass over n contacts per iteration.
void set_counters(benchmark::State& state, std::size_t n, std::size_t history_bytes) {
  const double visits = static_cast<double>(n) * static_cast<double>(state.iterations());
  state.counters["contacts_per_s"] = benchmark::Counter(visits, benchmark::Counter::kIsRate);
  // seconds per contact, shown with an SI prefix (e.g. "52.6ns")
  state.counters["time_per_contact"] =
      benchmark::Counter(visits, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["contacts"] = static_cast<double>(n);
  state.counters["history_bytes"] = static_cast<double>(history_bytes);
}

/// The sizes: name, lattice, passes per benchmark run (fixed, so that every variant goes through
/// the same contact states) and repetitions (several at the realistic size: the machine is
/// shared, compare medians).
struct Size3 {
  const char* name;
  int nx, ny, nz;
  long passes;
  int repetitions;
};
struct Size2 {
  const char* name;
  int nx, ny;
  long passes;
  int repetitions;
};
constexpr Size3 hertz_sizes[] = {{"tiny", 6, 6, 6, 2000, 1}, {"contacts1e5", 40, 40, 32, 200, 5}};
constexpr Size2 linear_sizes[] = {{"tiny", 20, 15, 2000, 1}, {"contacts1e5", 320, 250, 200, 5}};

const ContactSet<HertzSim>& hertz_set(const Size3& z) {
  return cached(std::string("hertz/") + z.name, [&] {
    auto s = hertz_contacts(z.nx, z.ny, z.nz);
    const auto k = hertz_constants(s.pairs);
    check_variants(
        std::string("Hertz-Mindlin ") + z.name, s,
        [&](auto& h, auto& out) { hertz_handwritten_pass(s, h, out); },
        [&](auto& h, auto& out) { hertz_pairconst_pass(s, k, h, out); });
    return s;
  });
}

const ContactSet<LinearSim>& linear_set(const Size2& z) {
  return cached(std::string("linear/") + z.name, [&] {
    auto s = linear_contacts(z.nx, z.ny);
    check_variants(std::string("linear spring-dashpot ") + z.name, s,
                   [&](auto& h, auto& out) { linear_handwritten_pass(s, h, out); });
    return s;
  });
}

/// Runs `pass(histories, output)` once per iteration from a fresh copy of the histories.
template <class Set, class H, class Pass>
void run_passes(benchmark::State& state, const Set& s, std::vector<H> h, Pass&& pass) {
  Output<Set::D> out(s.size());
  for (auto _ : state) {
    pass(h, out);
    benchmark::DoNotOptimize(out.force.data());
    benchmark::ClobberMemory();
  }
  set_counters(state, s.size(), sizeof(typename Set::History));
}

void hertz_interaction(benchmark::State& state, Size3 z) {
  const auto& s = hertz_set(z);
  run_passes(state, s, s.history, [&](auto& h, auto& out) { interaction_pass(s, h, out); });
}
void hertz_handwritten(benchmark::State& state, Size3 z) {
  const auto& s = hertz_set(z);
  run_passes(state, s, plain_histories(s),
             [&](auto& h, auto& out) { hertz_handwritten_pass(s, h, out); });
}
void hertz_pairconst(benchmark::State& state, Size3 z) {
  const auto& s = hertz_set(z);
  const auto k = hertz_constants(s.pairs);
  run_passes(state, s, plain_histories(s),
             [&](auto& h, auto& out) { hertz_pairconst_pass(s, k, h, out); });
}
void linear_interaction(benchmark::State& state, Size2 z) {
  const auto& s = linear_set(z);
  run_passes(state, s, s.history, [&](auto& h, auto& out) { interaction_pass(s, h, out); });
}
void linear_handwritten(benchmark::State& state, Size2 z) {
  const auto& s = linear_set(z);
  run_passes(state, s, plain_histories(s),
             [&](auto& h, auto& out) { linear_handwritten_pass(s, h, out); });
}

// ------------------------------------------------------------ conductance

/// The Hertz-Mindlin contact with Batchelor-O'Brien conduction and no area correction: the
/// conductance of a touching contact is H = 4 k* a, a = sqrt(R* delta).
using ConductionContact = Interaction<normal::Hertz<>, tangent::SpringDashpotSlider, rolling::None,
                                      conduction::BatchelorOBrien>;

/// The Hertz contact set with conducting materials (k = 1 W/(m K) for both: k* = 0.5).
std::vector<PairProperties> conducting(std::vector<PairProperties> pairs) {
  for (auto& pp : pairs) {
    pp.conductivity_i = pp.conductivity_j = 1.0;
    pp.conductivity_eff = 0.5;
  }
  return pairs;
}

/// `Contact::conductance` as the simulation calls it for a touching pair of spheres (cylinder
/// length 0, no fluid cell). The normal result is not used by area::None. A pass reads two
/// doubles of each 280-byte geometry record, so at the realistic size both variants are bound by
/// memory traffic; in the simulation the conductance is computed from the geometry at hand.
void conductance_interaction_pass(const ContactSet<HertzSim>& s,
                                  const std::vector<PairProperties>& pairs,
                                  std::vector<double>& H) {
  ConductionContact::Params params{};
  ConductionContact::History<3> h{};
  const NormalResult normal{};
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < s.size(); ++c)
    H[c] = ConductionContact::conductance(s.geometry[c], pairs[s.pair_index[c]], normal, params, h,
                                          s.dt, 0.0, inf);
}

void conductance_handwritten_pass(const ContactSet<HertzSim>& s,
                                  const std::vector<PairProperties>& pairs,
                                  std::vector<double>& H) {
  for (std::size_t c = 0; c < s.size(); ++c) {
    const ContactGeometry<3>& g = s.geometry[c];
    H[c] = 4.0 * pairs[s.pair_index[c]].conductivity_eff *
           std::sqrt(g.r_eff * std::max(g.overlap, 0.0));
  }
}

/// The conductances of both variants on the Hertz contact set of size z (aborts if they
/// disagree); returns the interaction's.
std::vector<double> checked_conductances(const Size3& z) {
  const auto& s = hertz_set(z);
  const auto pairs = conducting(s.pairs);
  std::vector<double> H(s.size()), check(s.size());
  conductance_interaction_pass(s, pairs, H);
  conductance_handwritten_pass(s, pairs, check);
  if (max_relative(H, check) > tolerance) fail("conductance: the variants disagree");
  return H;
}

void conductance(benchmark::State& state, Size3 z, bool handwritten) {
  const auto& s = hertz_set(z);
  const auto pairs = conducting(s.pairs);
  std::vector<double> H = checked_conductances(z);
  for (auto _ : state) {
    if (handwritten)
      conductance_handwritten_pass(s, pairs, H);
    else
      conductance_interaction_pass(s, pairs, H);
    benchmark::DoNotOptimize(H.data());
    benchmark::ClobberMemory();
  }
  set_counters(state, s.size(), sizeof(ConductionContact::History<3>));
}

// ------------------------------------------------------------ registration

void register_all() {
  // every benchmark makes a fixed number of passes (the conductance, 10 times cheaper, ten
  // times as many)
  auto reg = [](const std::string& name, long passes, int reps, auto fn) {
    auto* b = benchmark::RegisterBenchmark(name.c_str(), fn);
    b->Iterations(passes)->Unit(benchmark::kMicrosecond);
    if (reps > 1) b->Repetitions(reps);
  };
  for (const Size3& z : hertz_sizes) {
    const std::string size = std::string("/") + z.name;
    reg("hertz_mindlin/interaction" + size, z.passes, z.repetitions,
        [z](benchmark::State& st) { hertz_interaction(st, z); });
    reg("hertz_mindlin/handwritten" + size, z.passes, z.repetitions,
        [z](benchmark::State& st) { hertz_handwritten(st, z); });
    reg("hertz_mindlin/pairconst" + size, z.passes, z.repetitions,
        [z](benchmark::State& st) { hertz_pairconst(st, z); });
  }
  for (const Size2& z : linear_sizes) {
    const std::string size = std::string("/") + z.name;
    reg("linear_spring_dashpot/interaction" + size, z.passes, z.repetitions,
        [z](benchmark::State& st) { linear_interaction(st, z); });
    reg("linear_spring_dashpot/handwritten" + size, z.passes, z.repetitions,
        [z](benchmark::State& st) { linear_handwritten(st, z); });
  }
  for (const Size3& z : hertz_sizes) {
    const std::string size = std::string("/") + z.name;
    reg("conductance/interaction" + size, 10 * z.passes, z.repetitions,
        [z](benchmark::State& st) { conductance(st, z, false); });
    reg("conductance/handwritten" + size, 10 * z.passes, z.repetitions,
        [z](benchmark::State& st) { conductance(st, z, true); });
  }
}

/// Makes every contact set and runs the agreement checks of all variants, without timing.
void check_all() {
  for (const Size3& z : hertz_sizes) {
    hertz_set(z);
    checked_conductances(z);
  }
  for (const Size2& z : linear_sizes)
    linear_set(z);
}

} // namespace

int main(int argc, char** argv) {
  // --check: only the agreement checks at every size (a test; aborts on a disagreement)
  if (argc == 2 && std::strcmp(argv[1], "--check") == 0) {
    check_all();
    return 0;
  }
  register_all();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
