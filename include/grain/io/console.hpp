#pragma once
/// \file console.hpp
/// Console output: a summary at the start and end of a run, a progress line with the time left,
/// and `every(interval, actions...)` to call output actions at a fixed simulated-time interval.
/// These helpers only read a simulation.

#include <boost/hana/for_each.hpp>
#include <boost/hana/tuple.hpp>
#include <boost/hana/type.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>
#include <utility>

namespace grain::io {

/// "normal: Hertz, tangent: spring-dashpot-slider, ..." for the models of an Interaction (the
/// slots left at their `None` default are omitted).
template <class Contact>
std::string describe_contact() {
  namespace hana = boost::hana;
  constexpr auto models =
      hana::tuple_t<typename Contact::normal_model, typename Contact::tangent_model,
                    typename Contact::rolling_model, typename Contact::conduction_model,
                    typename Contact::area_model>;
  const char* slots[] = {"normal", "tangent", "rolling", "conduction", "area"};
  std::string out;
  int k = 0;
  hana::for_each(models, [&](auto t) {
    using M = typename decltype(t)::type;
    const std::string name = M::name;
    if (k == 0 || name != "none") out += std::string(out.empty() ? "" : ", ") + slots[k] + " " + name;
    ++k;
  });
  return out;
}

/// Prints a summary when a run starts and when it ends.
struct Summary {
  std::FILE* out = stdout;
  std::chrono::steady_clock::time_point started{};
  double wall0 = 0.0, ps0 = 0.0;
  long steps0 = 0;

  template <class Sim>
  void start(const Sim& sim) {
    started = std::chrono::steady_clock::now();
    wall0 = sim.counters().wall_seconds;
    ps0 = sim.counters().particle_steps;
    steps0 = sim.counters().steps;
    const auto [pp, pw] = sim.contact_counts();
    std::fprintf(out,
                 "grain: %dD %s simulation, %zu particles, %zu walls, %zu materials\n"
                 "       contact: %s\n"
                 "       search: %s (skin %.4g m); integrator: %s\n"
                 "       time step %.6g s (critical %.6g s); t = %.6g s -> %.6g s (%ld steps)\n"
                 "       contacts: %zu particle-particle, %zu particle-wall\n",
                 Sim::dimension, Sim::shape_type::name, sim.size(), sim.walls().size(),
                 sim.materials().size(), describe_contact<typename Sim::contact_type>().c_str(),
                 Sim::search_type::name, sim.skin(),
                 Sim::integrator_type::name, sim.time_step(), sim.critical_time_step(), sim.time(),
                 sim.end_time(),
                 static_cast<long>(std::llround((sim.end_time() - sim.time()) / sim.time_step())),
                 pp, pw);
    if constexpr (Sim::thermal) {
      static constexpr const char* kinds[] = {"automatic", "mechanical", "thermal",
                                              "thermo-mechanical"};
      std::fprintf(out,
                   "       analysis: %s; mean temperature %.6g K, heat content %.6g J; thermal "
                   "time scale R^2 rho c/k %.4g s, conduction limit %.4g s\n",
                   kinds[static_cast<int>(sim.analysis())], sim.mean_temperature(),
                   sim.thermal_energy(), sim.thermal_time_step(), sim.conduction_time_step());
    }
    std::fflush(out);
  }
  template <class Sim>
  void operator()(const Sim&) const {}
  template <class Sim>
  void finish(const Sim& sim) {
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const double stepping = sim.counters().wall_seconds - wall0;
    const double ps = sim.counters().particle_steps - ps0;
    const auto [pp, pw] = sim.contact_counts();
    std::fprintf(out,
                 "grain: finished at t = %.6g s after %ld steps; wall time %.3f s (%.3f s in steps, "
                 "%ld neighbour rebuilds in all)\n"
                 "       %.4g particle-steps per second; contacts: %zu particle-particle, %zu "
                 "particle-wall; kinetic energy %.6g J\n",
                 sim.time(), sim.counters().steps - steps0, wall, stepping, sim.counters().rebuilds,
                 stepping > 0 ? ps / stepping : 0.0, pp, pw, sim.kinetic_energy());
    if constexpr (Sim::thermal)
      std::fprintf(out, "       mean temperature %.6g K, heat content %.6g J\n",
                   sim.mean_temperature(), sim.thermal_energy());
    std::fflush(out);
  }
};
inline Summary summary(std::FILE* out = stdout) { return Summary{out}; }

/// Prints "t = ... (x %), step ..., time left ..." at most every `seconds` of wall time.
struct Progress {
  double seconds = 2.0;
  std::FILE* out = stderr;
  std::chrono::steady_clock::time_point started{}, last{};
  double t0 = 0.0;

  template <class Sim>
  void start(const Sim& sim) {
    started = last = std::chrono::steady_clock::now();
    t0 = sim.time();
  }
  template <class Sim>
  void operator()(const Sim& sim) {
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last).count() < seconds) return;
    last = now;
    print(sim, now);
  }
  template <class Sim>
  void finish(const Sim& sim) {
    print(sim, std::chrono::steady_clock::now());
  }

private:
  template <class Sim>
  void print(const Sim& sim, std::chrono::steady_clock::time_point now) const {
    const double elapsed = std::chrono::duration<double>(now - started).count();
    const double span = sim.end_time() - t0;
    const double frac = span > 0 ? (sim.time() - t0) / span : 1.0;
    const double left = frac > 0 ? elapsed * (1.0 - frac) / frac : 0.0;
    std::fprintf(out, "  t = %.6g s (%5.1f %%), step %ld, elapsed %.1f s, time left %.1f s\n",
                 sim.time(), 100.0 * frac, sim.step_count(), elapsed, left);
    std::fflush(out);
  }
};
inline Progress progress(double seconds = 2.0, std::FILE* out = stderr) {
  return Progress{seconds, out};
}

/// Calls each action at t = start, start + interval, ... (simulated time) and at the end.
template <class... Actions>
struct Every {
  double interval;
  std::tuple<Actions...> actions;
  double next = 0.0;
  double last_fired = -1.0;

  template <class Sim>
  void start(const Sim& sim) {
    std::apply([&](auto&... a) { (start_one(a, sim), ...); }, actions);
    next = sim.time();
    (*this)(sim);
  }
  template <class Sim>
  void operator()(const Sim& sim) {
    if (sim.time() + 1e-9 * sim.time_step() < next) return;
    fire(sim);
    while (next <= sim.time() + 1e-9 * sim.time_step()) next += interval;
  }
  template <class Sim>
  void finish(const Sim& sim) {
    if (last_fired != sim.time()) fire(sim);
    std::apply([&](auto&... a) { (finish_one(a, sim), ...); }, actions);
  }

private:
  template <class Sim>
  void fire(const Sim& sim) {
    last_fired = sim.time();
    std::apply([&](auto&... a) { (a(sim), ...); }, actions);
  }
  template <class A, class Sim>
  static void start_one(A& a, const Sim& sim) {
    if constexpr (requires { a.start(sim); }) a.start(sim);
  }
  template <class A, class Sim>
  static void finish_one(A& a, const Sim& sim) {
    if constexpr (requires { a.finish(sim); }) a.finish(sim);
  }
};

/// every(dt, actions...): output actions at a fixed interval of simulated time [s].
template <class... Actions>
Every<std::decay_t<Actions>...> every(double interval, Actions&&... actions) {
  return {interval, {std::forward<Actions>(actions)...}};
}

} // namespace grain::io
