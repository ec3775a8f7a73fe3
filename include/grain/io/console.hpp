#pragma once
/// \file console.hpp
/// Console output, and how often output actions run. These helpers only read a simulation.
///
/// | helper | prints |
/// |---|---|
/// | `summary(out = stdout)` | at the start: dimension, shape, particles (and those waiting for their creation time), walls, materials, contact models, search, integrator, time step, the time span of a run() and contacts; at the end: time and steps, wall time, particle-steps per second [1/s], contacts, kinetic energy [J], mean temperature [K] and heat content [J] of thermal runs, and the active, removed and inactive particles when any were removed or wait |
/// | `progress(seconds = 2, out = stderr)` | at most every `seconds` of wall time: t [s], the share of the run done, step, the wall time elapsed and left (a run of `steps(n)` has no end time: t, step and elapsed only) |
/// | `print(columns...)`, `print(FILE*, columns...)`, `print(path, columns...)` | one line of aligned text per call: `time [s]`, `step` and the columns (`io::column` or any column set of csv.hpp), with a header line first; `digits` (6) significant digits, `nan` for a missing value |
///
/// | frequency | calls each action |
/// |---|---|
/// | `every(interval, actions...)` | at the start of a run (t0), every `interval` [s] of simulated time after it (the k-th output at the first step that reaches t0 + k interval, see Every), and at the end |
/// | `every(interval(t), actions...)` | as `every`, with an interval that is a `TimeFunction` of time (a table, a callable), evaluated at each step's time t: an output when t reaches the last due time plus interval(t) (see EveryVarying) |
/// | `every_steps(n, actions...)` | at the start of a run, every n steps after it, and at the end |
///
/// Neither calls its actions twice at one step: not when a run starts where the previous run with
/// the same object ended (no duplicate row at the junction), nor when the end falls on an output.
/// A line of `print` is written whole with one write and flushed; one that cannot be written
/// throws io::WriteError (the file and the reason), and a file keeps the whole lines before it.
///
/// \code
/// sim.run(1.0, io::summary(), io::progress(),
///         io::every_steps(1000, io::print(io::lifecycle_columns(),
///                                         io::particle_columns({7}, io::velocity))));
/// \endcode

#include <grain/core/error.hpp>
#include <grain/core/observer.hpp>
#include <grain/core/time_function.hpp>
#include <grain/io/atomic_file.hpp>
#include <grain/io/csv.hpp>
#include <grain/io/write_error.hpp>

#include <algorithm>
#include <boost/hana/for_each.hpp>
#include <boost/hana/tuple.hpp>
#include <boost/hana/type.hpp>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <locale>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

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
    if (k == 0 || name != "none")
      out += std::string(out.empty() ? "" : ", ") + slots[k] + " " + name;
    ++k;
  });
  return out;
}

namespace detail {

/// A wall-clock duration as text: "12.3 s", "4 min 05 s", "2 h 07 min".
inline std::string duration_text(double seconds) {
  char buf[64];
  if (!(seconds >= 0) || !std::isfinite(seconds)) return "?";
  if (seconds < 60.0) {
    std::snprintf(buf, sizeof buf, "%.1f s", seconds);
  } else if (seconds < 3600.0) {
    const long s = std::lround(seconds);
    std::snprintf(buf, sizeof buf, "%ld min %02ld s", s / 60, s % 60);
  } else {
    const long m = std::lround(seconds / 60.0);
    std::snprintf(buf, sizeof buf, "%ld h %02ld min", m / 60, m % 60);
  }
  return buf;
}

template <class A, class Sim>
void start_action(A& a, const Sim& sim) {
  if constexpr (requires { a.start(sim); }) a.start(sim);
}
template <class A, class Sim>
void finish_action(A& a, const Sim& sim) {
  if constexpr (requires { a.finish(sim); }) a.finish(sim);
}

} // namespace detail

/// Prints a summary when a run starts and when it ends.
struct Summary {
  std::FILE* out = stdout;
  std::chrono::steady_clock::time_point started{};
  double wall0 = 0.0, ps0 = 0.0;
  long steps0 = 0;
  std::size_t removed0 = 0;

  template <class Sim>
  void start(const Sim& sim) {
    started = std::chrono::steady_clock::now();
    wall0 = sim.counters().wall_seconds;
    ps0 = sim.counters().particle_steps;
    steps0 = sim.counters().steps;
    removed0 = sim.removed_ids().size();
    const auto [pp, pw] = sim.contact_counts();
    std::string particles = std::to_string(sim.size()) + " particles";
    if (sim.inactive_count() > 0 || removed0 > 0) {
      particles += " (";
      if (sim.inactive_count() > 0)
        particles += std::to_string(sim.inactive_count()) + " more waiting for their creation time";
      if (removed0 > 0)
        particles += std::string(sim.inactive_count() > 0 ? ", " : "") + std::to_string(removed0) +
                     " removed so far";
      particles += ")";
    }
    // run() sets an end time; steps(n) does not
    char span[160];
    if (sim.end_time() > sim.time())
      std::snprintf(
          span, sizeof span, "t = %.6g s -> %.6g s (%ld steps)", sim.time(), sim.end_time(),
          static_cast<long>(std::llround((sim.end_time() - sim.time()) / sim.time_step())));
    else
      std::snprintf(span, sizeof span, "t = %.6g s", sim.time());
    std::fprintf(out,
                 "grain: %dD %s simulation, %s, %zu walls, %zu materials\n"
                 "       contact: %s\n"
                 "       search: %s (skin %.4g m); integrator: %s\n"
                 "       time step %.6g s (critical %.6g s); %s\n"
                 "       contacts: %zu particle-particle, %zu particle-wall\n",
                 Sim::dimension, Sim::shape_type::name, particles.c_str(), sim.walls().size(),
                 sim.materials().size(), describe_contact<typename Sim::contact_type>().c_str(),
                 Sim::search_type::name, sim.skin(), Sim::integrator_type::name, sim.time_step(),
                 sim.critical_time_step(), span, pp, pw);
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
    std::fprintf(
        out,
        "grain: finished at t = %.6g s after %ld steps; wall time %.3f s (%.3f s in steps, "
        "%ld neighbour rebuilds in all)\n"
        "       %.4g particle-steps per second; contacts: %zu particle-particle, %zu "
        "particle-wall; kinetic energy %.6g J\n",
        sim.time(), sim.counters().steps - steps0, wall, stepping, sim.counters().rebuilds,
        stepping > 0 ? ps / stepping : 0.0, pp, pw, sim.kinetic_energy());
    const std::size_t removed = sim.removed_ids().size();
    if (removed > 0 || sim.inactive_count() > 0)
      std::fprintf(out,
                   "       particles: %zu active, %zu removed (%zu in this run), %zu inactive "
                   "(waiting for their creation time)\n",
                   sim.size(), removed, removed - std::min(removed, removed0),
                   sim.inactive_count());
    if constexpr (Sim::thermal)
      std::fprintf(out, "       mean temperature %.6g K, heat content %.6g J\n",
                   sim.mean_temperature(), sim.thermal_energy());
    std::fflush(out);
  }
};
inline Summary summary(std::FILE* out = stdout) { return Summary{out}; }

/// Prints "t = ... s (x %), step ..., elapsed ..., time left ..." at most every `seconds` of wall
/// time, and at the end (unless just printed). A run of `steps(n)` has no end time: "t = ... s, step ...,
/// elapsed ...".
struct Progress {
  double seconds = 2.0;
  std::FILE* out = stderr;
  std::chrono::steady_clock::time_point started{}, last{};
  double t0 = 0.0, t1 = 0.0; ///< start and end of the run (t1 <= t0: no end time)
  long printed = -1;         ///< step of the last line

  template <class Sim>
  void start(const Sim& sim) {
    started = last = std::chrono::steady_clock::now();
    t0 = sim.time();
    t1 = sim.end_time(); // run() sets it before the start; steps(n) leaves it at t0 or before
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
    if (printed != sim.step_count()) print(sim, std::chrono::steady_clock::now());
  }

private:
  template <class Sim>
  void print(const Sim& sim, std::chrono::steady_clock::time_point now) {
    printed = sim.step_count();
    const double elapsed = std::chrono::duration<double>(now - started).count();
    const double span = t1 - t0;
    if (span > 0) {
      const double frac = std::clamp((sim.time() - t0) / span, 0.0, 1.0);
      const double left = frac > 0 ? elapsed * (1.0 - frac) / frac : 0.0;
      std::fprintf(out, "  t = %.6g s (%5.1f %%), step %ld, elapsed %s, time left %s\n", sim.time(),
                   100.0 * frac, sim.step_count(), detail::duration_text(elapsed).c_str(),
                   frac > 0 ? detail::duration_text(left).c_str() : "?");
    } else {
      std::fprintf(out, "  t = %.6g s, step %ld, elapsed %s\n", sim.time(), sim.step_count(),
                   detail::duration_text(elapsed).c_str());
    }
    std::fflush(out);
  }
};
inline Progress progress(double seconds = 2.0, std::FILE* out = stderr) {
  return Progress{seconds, out};
}

/// Calls each action at t = start, start + interval, ... (simulated time) and at the end. The
/// k-th output is due at t0 + k interval, t0 the time at the start of the run (the due times are
/// computed, not summed, so that they do not drift over a long run); it runs at the first step
/// whose time reaches the due time less `tolerance` steps (a margin for the rounding of the
/// time, far below one step: an interval that is a whole number of steps gives one output every
/// that many steps, any other interval an output at the first step at or after each due time).
template <class... Actions>
struct Every {
  double interval;
  std::tuple<Actions...> actions;
  double t0 = 0.0;     ///< time at the start of the run (due time number 0)
  long due = 0;        ///< number of the next due time, t0 + due * interval
  long last_step = -1; ///< step of the last call (no second call at the same step)
  /// Share of a time step by which a step may fall short of a due time and still reach it.
  static constexpr double tolerance = 1e-3;

  template <class Sim>
  void start(const Sim& sim) {
    std::apply([&](auto&... a) { (detail::start_action(a, sim), ...); }, actions);
    t0 = sim.time();
    due = 0;
    if (last_step == sim.step_count()) { // continues a run that ended with a call
      advance(sim);
      return;
    }
    (*this)(sim);
  }
  template <class Sim>
  void operator()(const Sim& sim) {
    if (!reached(sim, due)) return;
    fire(sim);
    advance(sim);
  }
  template <class Sim>
  void finish(const Sim& sim) {
    if (last_step != sim.step_count()) fire(sim);
    std::apply([&](auto&... a) { (detail::finish_action(a, sim), ...); }, actions);
  }

private:
  template <class Sim>
  bool reached(const Sim& sim, long k) const {
    return sim.time() + tolerance * sim.time_step() >= t0 + static_cast<double>(k) * interval;
  }
  /// Moves `due` to the first due time after the current step.
  template <class Sim>
  void advance(const Sim& sim) {
    // a first guess from the quotient (an interval below the time step skips many due times),
    // then exact by comparison
    const long lo = due + 1;
    const double q = std::floor((sim.time() - t0) / interval);
    due = std::max(lo, q > 0.0 ? static_cast<long>(q) : 0L);
    while (due > lo && !reached(sim, due - 1))
      --due;
    while (reached(sim, due))
      ++due;
  }
  template <class Sim>
  void fire(const Sim& sim) {
    grain::detail::check_state(sim); // nothing is written from a state gone wrong
    last_step = sim.step_count();
    std::apply([&](auto&... a) { (a(sim), ...); }, actions);
  }
};

/// every(dt, actions...): output actions at a fixed interval of simulated time [s] (and at the
/// start and the end of each run).
template <class... Actions>
Every<std::decay_t<Actions>...> every(double interval, Actions&&... actions) {
  grain::detail::require_positive("grain::io::every", "interval", interval);
  return {interval, {std::forward<Actions>(actions)...}};
}

/// Calls each action at the start of a run, then at intervals that follow a function of time
/// (a table, a ramp, a user's callable; Parmec's output interval given as a time series or a
/// callback), and at the end. The interval is evaluated at the time of each step, t: an output
/// is due when t reaches the last due time t_k plus interval(t) (less `tolerance` steps), and
/// the due time then advances by that interval, t_(k+1) = t_k + interval(t) (by whole intervals
/// when one is shorter than the step). A constant interval gives the due times of `every`. An
/// interval that is not finite and > 0 when it is evaluated throws InputError naming the time.
template <class... Actions>
struct EveryVarying {
  TimeFunction interval;
  std::tuple<Actions...> actions;
  double last_due = 0.0; ///< time of the last due output [s]
  long last_step = -1;   ///< step of the last call (no second call at the same step)
  static constexpr double tolerance = 1e-3;

  template <class Sim>
  void start(const Sim& sim) {
    std::apply([&](auto&... a) { (detail::start_action(a, sim), ...); }, actions);
    if (last_step == sim.step_count()) return; // continues a run that ended with a call
    last_due = sim.time();
    fire(sim);
  }
  template <class Sim>
  void operator()(const Sim& sim) {
    const double t = sim.time() + tolerance * sim.time_step();
    const double dt = interval(sim.time());
    if (!(std::isfinite(dt) && dt > 0.0))
      throw InputError("grain::io::every: interval = " + grain::detail::to_text(dt) +
                       " s at t = " + grain::detail::to_text(sim.time()) +
                       " s is invalid; valid range: (0, inf) s");
    if (t < last_due + dt) return;
    last_due += dt * std::max(1.0, std::floor((t - last_due) / dt));
    fire(sim);
  }
  template <class Sim>
  void finish(const Sim& sim) {
    if (last_step != sim.step_count()) fire(sim);
    std::apply([&](auto&... a) { (detail::finish_action(a, sim), ...); }, actions);
  }

private:
  template <class Sim>
  void fire(const Sim& sim) {
    grain::detail::check_state(sim);
    last_step = sim.step_count();
    std::apply([&](auto&... a) { (a(sim), ...); }, actions);
  }
};

/// every(interval(t), actions...): output actions at an interval that is a function of time
/// [s] (see EveryVarying); a plain number picks the fixed-interval `every` above.
template <class... Actions>
EveryVarying<std::decay_t<Actions>...> every(const TimeFunction& interval, Actions&&... actions) {
  return {interval, {std::forward<Actions>(actions)...}};
}

/// Calls each action at the start of a run, every `steps` steps after it and at the end.
template <class... Actions>
struct EverySteps {
  long steps;
  std::tuple<Actions...> actions;
  long next = 0;
  long last_step = -1; ///< step of the last call (no second call at the same step)

  template <class Sim>
  void start(const Sim& sim) {
    std::apply([&](auto&... a) { (detail::start_action(a, sim), ...); }, actions);
    if (last_step != sim.step_count()) fire(sim);
    next = sim.step_count() + steps;
  }
  template <class Sim>
  void operator()(const Sim& sim) {
    if (sim.step_count() < next) return;
    fire(sim);
    next = sim.step_count() + steps;
  }
  template <class Sim>
  void finish(const Sim& sim) {
    if (last_step != sim.step_count()) fire(sim);
    std::apply([&](auto&... a) { (detail::finish_action(a, sim), ...); }, actions);
  }

private:
  template <class Sim>
  void fire(const Sim& sim) {
    grain::detail::check_state(sim); // nothing is written from a state gone wrong
    last_step = sim.step_count();
    std::apply([&](auto&... a) { (a(sim), ...); }, actions);
  }
};

/// every_steps(n, actions...): output actions every n steps (and at the start and the end of
/// each run); n >= 1.
template <class... Actions>
EverySteps<std::decay_t<Actions>...> every_steps(long n, Actions&&... actions) {
  if (n < 1)
    throw InputError("grain::io::every_steps: n = " + std::to_string(n) +
                     " is invalid; valid range: [1, inf) steps");
  return {n, {std::forward<Actions>(actions)...}};
}

/// Aligned text lines: time, step and the given columns (io::column or column sets), a header
/// line first; on a stream (stdout by default) or, if `path` is set, in a text file.
template <class... Columns>
struct Print {
  std::FILE* out = stdout;
  std::string path{}; ///< a text file to write instead of `out`, if not empty
  std::tuple<Columns...> columns;
  int digits = 6;                            ///< significant digits, [1, 17]
  std::shared_ptr<detail::LineFile> file_{}; ///< the file at `path`, if set
  std::vector<std::size_t> widths_{};
  std::vector<double> cells_{};
  bool started_ = false;

  template <class Sim>
  void start(const Sim& sim) {
    if (started_) return; // a later run goes on below the same header
    grain::detail::require_in("grain::io::print", "digits", digits, 1, 17, "[1, 17]");
    detail::start_all(columns, sim);
    std::vector<std::string> names{"time [s]", "step"};
    detail::names_of_all(columns, sim, names);
    if (!path.empty()) {
      detail::require_output_folder("grain::io::print", path);
      file_ = std::make_shared<detail::LineFile>("grain::io::print", path);
    }
    const std::size_t numeric = static_cast<std::size_t>(digits) + 7; // -1.23457e-05
    widths_.clear();
    for (std::size_t k = 0; k < names.size(); ++k)
      widths_.push_back(std::max(names[k].size(), k == 1 ? std::size_t{9} : numeric));
    std::string line;
    for (std::size_t k = 0; k < names.size(); ++k)
      append(line, names[k], k);
    emit(line);
    started_ = true;
  }

  template <class Sim>
  void operator()(const Sim& sim) {
    if (!started_) start(sim);
    cells_.clear();
    detail::values_of_all(columns, sim, cells_);
    if (cells_.size() + 2 != widths_.size())
      throw std::logic_error("grain::io::print: the columns gave " + std::to_string(cells_.size()) +
                             " values for " + std::to_string(widths_.size() - 2) +
                             " names; a column set must give one value per name");
    std::string line;
    append(line, number(sim.time()), 0);
    append(line, std::to_string(sim.step_count()), 1);
    for (std::size_t k = 0; k < cells_.size(); ++k)
      append(line, number(cells_[k]), k + 2);
    emit(line);
  }

private:
  std::string number(double v) const {
    if (std::isnan(v)) return "nan";
    std::ostringstream s;
    s.imbue(std::locale::classic());
    s.precision(digits);
    s << v;
    return s.str();
  }
  void append(std::string& line, const std::string& cell, std::size_t k) const {
    if (k > 0) line += "  ";
    if (cell.size() < widths_[k]) line.append(widths_[k] - cell.size(), ' ');
    line += cell;
  }
  /// Writes a line with its line break in one write and flushes it; throws WriteError if it did
  /// not reach the file or stream (a file then keeps the whole lines before it).
  void emit(std::string line) const {
    line += '\n';
    if (file_) return file_->write(line);
    errno = 0;
    if (std::fwrite(line.data(), 1, line.size(), out) != line.size() || std::fflush(out) == EOF)
      throw detail::write_error("grain::io::print", target(), errno);
  }
  /// The file or stream written, for messages.
  std::string target() const {
    if (file_) return path;
    return out == stdout ? "stdout" : out == stderr ? "stderr" : "the given FILE* stream";
  }
};

/// print(columns...): aligned text lines on stdout (use with io::every or io::every_steps).
template <class... Columns>
requires(detail::column_like<Columns>&&...) Print<Columns...> print(Columns... columns) {
  return {stdout, {}, {std::move(columns)...}};
}
/// print(out, columns...): aligned text lines on a stream (stdout, stderr, a FILE*).
template <class... Columns>
requires(detail::column_like<Columns>&&...) Print<Columns...> print(std::FILE* out,
                                                                    Columns... columns) {
  return {out, {}, {std::move(columns)...}};
}
/// print(path, columns...): aligned text lines in a text file (made with its folders).
template <class... Columns>
requires(detail::column_like<Columns>&&...) Print<Columns...> print(std::string path,
                                                                    Columns... columns) {
  if (path.empty())
    throw InputError("grain::io::print: path = \"\" is invalid; valid: a file name (or give a "
                     "FILE* such as stdout)");
  return {stdout, std::move(path), {std::move(columns)...}};
}

} // namespace grain::io
