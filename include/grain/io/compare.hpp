#pragma once
/// \file compare.hpp
/// Comparing model variants: one scenario run once for each contact type of a list, with a table
/// of chosen result figures and of the speed of each run.
///
/// \code
/// template <class Contact>
/// using Bed = Simulation<Disk, search::CellList, Contact>;
/// using BOB = Interaction<normal::Hertz<>, tangent::None, rolling::None,
///                         conduction::BatchelorOBrien>;
/// using Pipe = Interaction<normal::Hertz<>, tangent::None, rolling::None,
///                          conduction::ThermalPipe>;
///
/// auto table = io::compare<Bed>(
///     variants<BOB, Pipe>{},
///     [](auto& sim) { /* add materials, particles and walls */ },
///     {.duration = 10.0, .csv = "out/compare.csv"},
///     io::column("mean_temperature [K]", [](const auto& s) { return s.mean_temperature(); }),
///     io::time_to_reach("t_320 [s]", 320.0,
///                       [](const auto& s) { return s.mean_temperature(); }));
/// \endcode
///
/// `io::compare<SimOf>(variants<C1, C2, ...>{}, scenario, options, figures...)` makes, for each
/// contact type C of the list in turn, a simulation of type `SimOf<C>` (an alias template such as
/// `Bed` above, so that shape, search and options are the same for every variant), lets the
/// scenario set it up, runs it and evaluates the figures at the end. Every `SimOf<C>` is a
/// distinct type instantiated at compile time (a fold over the list): no virtual dispatch.
///
/// The scenario is a generic callable in one of two forms:
/// - `[](auto& sim) { ... }`: it adds materials, particles, walls and conditions to a simulation
///   constructed with default parameters, `SimOf<C>{}`;
/// - `[]<class Sim>(std::type_identity<Sim>) { typename Sim::Params p; ...; Sim sim(p, shape);
///   ...; return sim; }`: it constructs the simulation itself (parameters such as the analysis,
///   the time step, gravity, the coefficients of the contact models, or a shape such as
///   `Disk{.thickness = ...}`) and returns it.
/// Set-up and initialisation (`Simulation::initialize`, which fixes the time step and builds the
/// neighbour list) are not timed.
///
/// A figure is an `io::column(name, f)` (f(sim) a number, evaluated on the simulation at the end of
/// its run) or any column set of csv.hpp (`io::heat_flow_columns()`, `io::group_columns(...)`,
/// your own `names`/`values` type); a column set that also has `observe(sim)` is called after
/// every step, like `io::time_to_reach(name, threshold, f)`, the time [s] from the start of the
/// run until f(sim) first reaches `threshold` (interpolated linearly between steps; `nan` if it
/// never does). Every variant must give the same figure names.
///
/// `CompareOptions` (all SI):
/// - `duration`: simulated time of each run [s], > 0; or 0 and `steps`;
/// - `steps`: number of steps of each run, >= 1 (only with `duration` = 0);
/// - `names`: one name per variant; empty (default): each variant is named by the models in
///   which it differs from the others, e.g. "Batchelor-O'Brien, Zhou-Yu-Zulli";
/// - `csv`: path of the table as CSV ("" = none); its folder is made if needed;
/// - `history`, `history_interval`: path prefix and interval [s] > 0 of a CSV history of the
///   figures per variant, `<history><slug of the name>.csv` with `time [s]`, `step` and the
///   figures ("" = none);
/// - `repeats`: runs per variant, >= 1; the table gives the figures of the last run and the time
///   of the fastest;
/// - `out`: console (default stdout): a line per variant as it ends, then the table; nullptr =
///   silent.
///
/// The result, `Comparison`, holds one `ComparisonRow` per variant, in the order of the list:
/// name, figures, time step [s], steps, particles (at the end), wall time of the steps [s] and
/// particle-steps per second [1/s] (the sum over the steps of the number of particles, over that
/// time). The wall time is measured with `std::chrono::steady_clock` around the run, less the time
/// spent in the comparison's own sampling (figures that observe every step, the history).
///
/// The table as CSV (`Comparison::write_csv`, or `options.csv`): `variant`, the figure names,
/// `time_step [s]`, `steps`, `particles`, `wall_time [s]`, `particle_steps_per_second [1/s]`; one
/// row per variant; numbers with 17 significant digits in the "C" locale, `nan` for a missing
/// value.
///
/// Bad input raises grain::InputError before any variant runs: an empty variant or figure list,
/// a non-positive or non-finite duration, a step count below 1 (or both or neither given), names
/// that are not one per variant, empty or repeated, repeats below 1, a history without a positive
/// interval, and an output file that cannot be written. A figure that gives no column, figure
/// names that repeat or name a fixed column are found when the first variant is set up, figures
/// whose names differ between variants when the variant that differs is set up, and figures
/// that give another number of values than of names when the first run ends (all InputError).

#include <grain/core/error.hpp>
#include <grain/io/console.hpp>
#include <grain/io/csv.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <locale>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <system_error>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace grain {

/// A list of types, e.g. the contact types (`Interaction<...>`) that io::compare runs.
template <class... Ts>
struct variants {
  static constexpr std::size_t size = sizeof...(Ts);
};

} // namespace grain

namespace grain::io {

/// How io::compare runs and reports (SI units; see the table in the file comment).
struct CompareOptions {
  double duration = 0.0;            ///< simulated time of each run [s]; 0: `steps` instead
  long steps = 0;                   ///< steps of each run (only with duration = 0)
  std::vector<std::string> names{}; ///< one per variant; empty: from the model names
  std::string csv{};                ///< the table as CSV; "" = none
  std::string history{};            ///< prefix of a CSV history per variant; "" = none
  double history_interval = 0.0;    ///< [s] between two history rows (> 0 with a history)
  int repeats = 1;                  ///< runs per variant; the fastest is reported
  std::FILE* out = stdout;          ///< console; nullptr = silent
};

/// One variant's results.
struct ComparisonRow {
  std::string name;
  std::vector<double> figures;            ///< in the order of Comparison::figures
  double time_step = 0.0;                 ///< [s]
  long steps = 0;                         ///< steps of the run
  std::size_t particles = 0;              ///< active particles at the end
  double seconds = 0.0;                   ///< wall time of the steps [s]
  double particle_steps_per_second = 0.0; ///< [1/s]
  std::string history{};                  ///< path of its CSV history, "" if none
};

/// The results of io::compare: the figure names and one row per variant.
struct Comparison {
  std::vector<std::string> figures;
  std::vector<ComparisonRow> rows;

  /// The row of the variant with this name (InputError if there is none).
  const ComparisonRow& operator[](std::string_view name) const {
    for (const auto& r : rows)
      if (r.name == name) return r;
    std::string known;
    for (const auto& r : rows)
      known += (known.empty() ? "" : ", ") + ("\"" + r.name + "\"");
    throw InputError("grain::io::Comparison: variant = \"" + std::string(name) +
                     "\" is invalid; valid: one of " + known);
  }
  /// The value of figure `figure` for variant `variant` (InputError if either is unknown).
  double figure(std::string_view variant, std::string_view figure) const {
    const ComparisonRow& r = (*this)[variant];
    for (std::size_t k = 0; k < figures.size(); ++k)
      if (figures[k] == figure) return r.figures[k];
    std::string known;
    for (const auto& f : figures)
      known += (known.empty() ? "" : ", ") + ("\"" + f + "\"");
    throw InputError("grain::io::Comparison: figure = \"" + std::string(figure) +
                     "\" is invalid; valid: one of " + known);
  }

  /// Column names of the table (as in the CSV file).
  std::vector<std::string> header() const {
    std::vector<std::string> h{"variant"};
    h.insert(h.end(), figures.begin(), figures.end());
    h.insert(h.end(), {"time_step [s]", "steps", "particles", "wall_time [s]",
                       "particle_steps_per_second [1/s]"});
    return h;
  }

  /// The table as aligned text: a header line (the CSV header with the last five names shortened
  /// to `dt [s]`, `steps`, `particles`, `wall [s]`, `particle-steps/s`), a rule and one line per
  /// variant (figures with 6 significant digits, `nan` for a missing value).
  std::string table() const {
    std::vector<std::string> head{"variant"};
    head.insert(head.end(), figures.begin(), figures.end());
    head.insert(head.end(), {"dt [s]", "steps", "particles", "wall [s]", "particle-steps/s"});
    std::vector<std::vector<std::string>> cells{head};
    for (const auto& r : rows) {
      std::vector<std::string> line{r.name};
      for (double v : r.figures)
        line.push_back(number(v, "%.6g"));
      line.push_back(number(r.time_step, "%.4g"));
      line.push_back(std::to_string(r.steps));
      line.push_back(std::to_string(r.particles));
      line.push_back(number(r.seconds, "%.3f"));
      line.push_back(number(r.particle_steps_per_second, "%.4g"));
      cells.push_back(std::move(line));
    }
    std::vector<std::size_t> width(cells[0].size(), 0);
    for (const auto& line : cells)
      for (std::size_t k = 0; k < line.size(); ++k)
        width[k] = std::max(width[k], line[k].size());
    std::string text;
    for (std::size_t l = 0; l < cells.size(); ++l) {
      for (std::size_t k = 0; k < cells[l].size(); ++k) {
        const std::string pad(width[k] - cells[l][k].size(), ' ');
        text += k == 0 ? cells[l][k] + pad : "  " + pad + cells[l][k];
      }
      text += '\n';
      if (l == 0) {
        std::size_t total = 0;
        for (std::size_t w : width)
          total += w + 2;
        text += std::string(total - 2, '-') + '\n';
      }
    }
    return text;
  }

  /// Writes the table as CSV (header row, one row per variant). InputError if the file cannot be
  /// written.
  void write_csv(const std::string& path) const {
    std::ofstream file = open_output(path, "grain::io::Comparison::write_csv");
    write_csv(file);
    file.flush();
    if (!file)
      throw InputError("grain::io::Comparison::write_csv: path = \"" + path +
                       "\" could not be written; valid: a writable file");
  }
  /// Writes the table as CSV to a stream.
  void write_csv(std::ostream& o) const {
    o.imbue(std::locale::classic());
    o.precision(17);
    const auto h = header();
    for (std::size_t k = 0; k < h.size(); ++k)
      o << (k ? "," : "") << detail::quoted(h[k]);
    o << '\n';
    for (const auto& r : rows) {
      o << detail::quoted(r.name);
      for (double v : r.figures) {
        o << ',';
        detail::write_number(o, v);
      }
      o << ',';
      detail::write_number(o, r.time_step);
      o << ',' << r.steps << ',' << r.particles << ',';
      detail::write_number(o, r.seconds);
      o << ',';
      detail::write_number(o, r.particle_steps_per_second);
      o << '\n';
    }
  }

  /// Opens `path` for writing (its folder made if needed); InputError naming `who` if it cannot.
  static std::ofstream open_output(const std::string& path, const std::string& who) {
    const std::filesystem::path p(path);
    std::error_code ec;
    if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path(), ec);
    std::error_code not_there;
    std::ofstream file;
    if (!ec && !path.empty() && !std::filesystem::is_directory(p, not_there)) file.open(path);
    if (ec || !file.is_open())
      throw InputError(who + ": path = \"" + path +
                       "\" is invalid; valid: a file that can be written (its folder is made "
                       "if needed)");
    return file;
  }

private:
  static std::string number(double v, const char* format) {
    if (std::isnan(v)) return "nan";
    char buf[64];
    std::snprintf(buf, sizeof buf, format, v);
    return buf;
  }
};

/// The figure of `time_to_reach`: the time [s] from the start of the run until f(sim) first
/// reaches the threshold, from below if it starts below, from above if it starts above;
/// interpolated linearly between the two steps around the crossing; `nan` if it does not.
template <class F>
struct TimeToReach {
  std::string name;
  double threshold;
  F f;
  double start_time = 0.0, last_time = 0.0, last_value = 0.0;
  double reached = std::numeric_limits<double>::quiet_NaN();
  bool rising = true;

  template <class Sim>
  void start(const Sim& sim) {
    start_time = last_time = sim.time();
    last_value = static_cast<double>(f(sim));
    rising = last_value < threshold;
    reached = last_value == threshold ? 0.0 : std::numeric_limits<double>::quiet_NaN();
  }
  template <class Sim>
  void observe(const Sim& sim) {
    if (!std::isnan(reached)) return;
    const double t = sim.time(), v = static_cast<double>(f(sim));
    if (rising ? v >= threshold : v <= threshold) {
      const double share = v != last_value ? (threshold - last_value) / (v - last_value) : 1.0;
      reached = last_time + share * (t - last_time) - start_time;
    }
    last_time = t;
    last_value = v;
  }
  template <class Sim>
  void names(const Sim&, std::vector<std::string>& out) const {
    out.push_back(name);
  }
  template <class Sim>
  void values(const Sim&, std::vector<double>& out) const {
    out.push_back(reached);
  }
};

/// time_to_reach(name, threshold, f): a figure, the time [s] from the start of a run until f(sim)
/// first reaches `threshold` (a finite number in the unit of f), or `nan`.
template <class F>
TimeToReach<F> time_to_reach(std::string name, double threshold, F f) {
  if (name.empty())
    throw InputError("grain::io::time_to_reach: name = \"\" is invalid; valid: a non-empty name");
  grain::detail::require_finite("grain::io::time_to_reach '" + name + "'", "threshold", threshold);
  return {std::move(name), threshold, std::move(f)};
}

namespace detail {

/// The models of a contact type, one name per slot.
template <class Contact>
std::array<std::string, 5> model_names() {
  return {Contact::normal_model::name, Contact::tangent_model::name, Contact::rolling_model::name,
          Contact::conduction_model::name, Contact::area_model::name};
}

/// Default names: the models in which a variant differs from the others ("none" kept), or the
/// whole description when all are alike; repeated names get " #k" (k from 1).
template <class... Contacts>
std::vector<std::string> default_names() {
  const std::vector<std::array<std::string, 5>> models{model_names<Contacts>()...};
  const std::vector<std::string> full{describe_contact<Contacts>()...};
  std::vector<std::string> names;
  for (std::size_t v = 0; v < models.size(); ++v) {
    std::string name;
    for (std::size_t s = 0; s < 5; ++s) {
      bool differs = false;
      for (const auto& m : models)
        differs = differs || m[s] != models[0][s];
      if (differs) name += (name.empty() ? "" : ", ") + models[v][s];
    }
    names.push_back(name.empty() ? full[v] : name);
  }
  const std::vector<std::string> plain = names;
  for (std::size_t v = 0; v < names.size(); ++v)
    if (std::count(plain.begin(), plain.end(), plain[v]) > 1)
      names[v] +=
          " #" + std::to_string(std::count(
                     plain.begin(), plain.begin() + static_cast<std::ptrdiff_t>(v) + 1, plain[v]));
  return names;
}

/// A file-name part made of a variant name: lower-case letters, digits and single '_'.
inline std::string slug(const std::string& name) {
  std::string s;
  for (char ch : name) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (std::isalnum(c))
      s += static_cast<char>(std::tolower(c));
    else if (!s.empty() && s.back() != '_')
      s += '_';
  }
  while (!s.empty() && s.back() == '_')
    s.pop_back();
  return s.empty() ? "variant" : s;
}

/// The figures of a run as a column set for io::csv (the history), by reference.
template <class Tuple>
struct FigureRef {
  Tuple* figures;
  template <class Sim>
  void names(const Sim& sim, std::vector<std::string>& out) const {
    names_of_all(*figures, sim, out);
  }
  template <class Sim>
  void values(const Sim& sim, std::vector<double>& out) const {
    values_of_all(*figures, sim, out);
  }
};

/// An observer that may be absent and whose calls are timed (the time is taken off the run's).
template <class Observer>
struct Timed {
  std::optional<Observer> observer;
  double* seconds;

  template <class Sim>
  void start(const Sim& sim) {
    timed([&](auto& o) { start_action(o, sim); });
  }
  template <class Sim>
  void operator()(const Sim& sim) {
    timed([&](auto& o) { o(sim); });
  }
  template <class Sim>
  void finish(const Sim& sim) {
    timed([&](auto& o) { finish_action(o, sim); });
  }

private:
  template <class G>
  void timed(G&& g) {
    if (!observer) return;
    const auto t0 = std::chrono::steady_clock::now();
    g(*observer);
    *seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  }
};

template <class C, class Sim>
void observe_figure(C& c, const Sim& sim) {
  if constexpr (requires { c.observe(sim); }) c.observe(sim);
}

/// Calls observe(sim) of the figures that have it.
template <class Tuple>
struct ObserveFigures {
  Tuple* figures;
  template <class Sim>
  void operator()(const Sim& sim) {
    std::apply([&](auto&... c) { (observe_figure(c, sim), ...); }, *figures);
  }
};

template <class C, class Sim>
concept observes = requires(C& c, const Sim& s) {
  c.observe(s);
};
/// True if a figure of the tuple observes every step.
template <class Tuple, class Sim>
struct any_observes;
template <class... Cs, class Sim>
struct any_observes<std::tuple<Cs...>, Sim> : std::bool_constant<(observes<Cs, Sim> || ...)> {};

/// A simulation of type Sim made by the scenario (either form).
template <class Sim, class Scenario>
Sim make_simulation(Scenario& scenario) {
  if constexpr (std::invocable<Scenario&, std::type_identity<Sim>>) {
    static_assert(std::is_same_v<std::invoke_result_t<Scenario&, std::type_identity<Sim>>, Sim>,
                  "grain::io::compare: a scenario called with std::type_identity<Sim> must "
                  "return the Sim it made");
    return scenario(std::type_identity<Sim>{});
  } else {
    static_assert(std::invocable<Scenario&, Sim&>,
                  "grain::io::compare: the scenario must be a generic callable, "
                  "[](auto& sim) { ... } (sets up a default-constructed simulation) or "
                  "[]<class Sim>(std::type_identity<Sim>) { ...; return sim; }");
    Sim sim;
    scenario(sim);
    return sim;
  }
}

/// The column names of the figures, checked: every figure gives at least one, no name repeats
/// or takes the name of a fixed column (InputError otherwise).
template <class Tuple, class Sim>
void checked_names(const Tuple& figures, const Sim& sim, std::vector<std::string>& names) {
  std::size_t k = 0;
  auto one = [&](const auto& c) {
    const std::size_t before = names.size();
    column_names(c, sim, names);
    if (names.size() == before)
      throw InputError("grain::io::compare: figure " + std::to_string(k) +
                       " gives no column, which is invalid; valid: at least one name per "
                       "figure, e.g. io::column(name, f)");
    ++k;
  };
  std::apply([&](const auto&... c) { (one(c), ...); }, figures);
  static const char* fixed[] = {"variant",   "time_step [s]", "steps",
                                "particles", "wall_time [s]", "particle_steps_per_second [1/s]"};
  for (std::size_t a = 0; a < names.size(); ++a) {
    bool clash = false;
    for (const char* x : fixed)
      clash = clash || names[a] == x;
    for (std::size_t b = 0; b < a; ++b)
      clash = clash || names[a] == names[b];
    if (clash)
      throw InputError("grain::io::compare: figure name \"" + names[a] +
                       "\" is repeated or names a fixed column, which is invalid; valid: "
                       "distinct names other than variant, time_step [s], steps, particles, "
                       "wall_time [s] and particle_steps_per_second [1/s]");
  }
}

/// Runs one variant `repeats` times; fills `row` and, for the first variant, `figure_names`.
template <class Sim, class Scenario, class Tuple>
void run_variant(Scenario& scenario, const CompareOptions& o, const Tuple& figures,
                 ComparisonRow& row, std::vector<std::string>& figure_names, bool first) {
  for (int rep = 0; rep < o.repeats; ++rep) {
    Sim sim = make_simulation<Sim>(scenario);
    if (!sim.initialized()) sim.initialize();
    Tuple f = figures; // fresh state for every run
    start_all(f, sim);
    std::vector<std::string> names;
    checked_names(f, sim, names); // at least one figure (checked before), each with a name
    if (first && rep == 0) {
      figure_names = names;
    } else if (names != figure_names) {
      throw InputError("grain::io::compare: variant \"" + row.name + "\" gives " +
                       std::to_string(names.size()) +
                       " figures that differ from those of the "
                       "first variant; valid: the same figure names for every variant");
    }

    double sampling = 0.0; // [s] spent in the comparison's own observers
    using HistoryWriter = decltype(every(1.0, csv(std::string{}, FigureRef<Tuple>{nullptr})));
    Timed<HistoryWriter> history{std::nullopt, &sampling};
    if (!o.history.empty() && rep == 0)
      history.observer.emplace(every(o.history_interval, csv(row.history, FigureRef<Tuple>{&f})));
    Timed<ObserveFigures<Tuple>> observe{std::nullopt, &sampling};
    if constexpr (any_observes<Tuple, Sim>::value)
      observe.observer.emplace(ObserveFigures<Tuple>{&f});

    const long steps0 = sim.step_count();
    const double ps0 = sim.counters().particle_steps;
    const auto t0 = std::chrono::steady_clock::now();
    if (o.duration > 0.0)
      sim.run(o.duration, observe, history);
    else
      sim.steps(o.steps, observe, history);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() - sampling;

    std::vector<double> values;
    values_of_all(f, sim, values);
    if (values.size() != names.size())
      throw InputError("grain::io::compare: the figures of variant \"" + row.name + "\" gave " +
                       std::to_string(values.size()) + " values for " +
                       std::to_string(names.size()) +
                       " names, which is invalid; valid: one value per name");
    row.figures = values;
    row.time_step = sim.time_step();
    row.steps = sim.step_count() - steps0;
    row.particles = sim.size();
    const double ps = sim.counters().particle_steps - ps0;
    if (rep == 0 || seconds < row.seconds) {
      row.seconds = seconds;
      row.particle_steps_per_second = seconds > 0.0 ? ps / seconds : 0.0;
    }
  }
}

/// Checks the run options of io::compare (duration or steps, repeats, history interval);
/// throws InputError naming `who`.
inline void check_compare_options(const CompareOptions& o, const std::string& who) {
  if (o.duration != 0.0 || o.steps == 0)
    grain::detail::require(std::isfinite(o.duration) && o.duration > 0.0 && o.steps == 0, who,
                           "duration", o.duration,
                           "(0, inf) s, with steps = 0 (or duration = 0 and steps >= 1)");
  else if (o.steps < 1)
    grain::detail::require(false, who, "steps", o.steps, "[1, inf) (with duration = 0)");
  grain::detail::require(o.repeats >= 1, who, "repeats", o.repeats, "[1, inf)");
  if (!o.history.empty())
    grain::detail::require(std::isfinite(o.history_interval) && o.history_interval > 0.0, who,
                           "history_interval", o.history_interval,
                           "(0, inf) s when a history is written");
}

/// The names of the variants: `o.names`, checked (one per variant, non-empty, distinct;
/// InputError naming `who` otherwise), or, if empty, those made of the models.
template <class... Contacts>
std::vector<std::string> variant_names(const CompareOptions& o, const std::string& who) {
  constexpr std::size_t n = sizeof...(Contacts);
  std::vector<std::string> names;
  if (o.names.empty()) {
    if constexpr (n > 0) names = default_names<Contacts...>();
    return names;
  }
  if (o.names.size() != n)
    throw InputError(who + ": names has " + std::to_string(o.names.size()) +
                     " entries, which is invalid; valid: one per variant (" + std::to_string(n) +
                     "), or none for names made of the models");
  names = o.names;
  for (std::size_t v = 0; v < n; ++v) {
    if (names[v].empty())
      throw InputError(who + ": names[" + std::to_string(v) +
                       "] = \"\" is invalid; valid: a non-empty name");
    for (std::size_t w = 0; w < v; ++w)
      if (names[w] == names[v])
        throw InputError(who + ": names[" + std::to_string(v) + "] = \"" + names[v] +
                         "\" is invalid; valid: a name no other variant has");
  }
  return names;
}

/// Sets the history path of every row, `<history><slug of the name>.csv` (a repeated slug gets
/// "_2", "_3", ...), and creates each file, so that a bad path fails before any variant runs.
inline void open_histories(Comparison& result, const CompareOptions& o, const std::string& who) {
  std::vector<std::string> used;
  for (auto& row : result.rows) {
    std::string s = slug(row.name);
    for (int k = 2; std::find(used.begin(), used.end(), s) != used.end(); ++k)
      s = slug(row.name) + "_" + std::to_string(k);
    used.push_back(s);
    row.history = o.history + s + ".csv";
    Comparison::open_output(row.history, who + " (history)");
  }
}

/// Prints the table to `o.out` (if any) and writes it as CSV to `table_file` (if open); throws
/// InputError naming `who` if the CSV could not be written.
inline void report_comparison(const Comparison& result, const CompareOptions& o,
                              std::optional<std::ofstream>& table_file, const std::string& who) {
  if (o.out) {
    std::fprintf(o.out, "%s", result.table().c_str());
    std::fflush(o.out);
  }
  if (table_file) {
    result.write_csv(*table_file);
    table_file->flush();
    if (!*table_file)
      throw InputError(who + ": csv = \"" + o.csv +
                       "\" could not be written; valid: a writable "
                       "file");
  }
}

} // namespace detail

/// Runs the scenario for each contact type of `variants<Contacts...>` as a `SimOf<Contact>` and
/// returns the table of the figures and of the speed of each run (see the file comment). Prints
/// the table to `options.out` and writes it to `options.csv` if given. InputError on bad input.
template <template <class> class SimOf, class... Contacts, class Scenario, class... Figures>
Comparison compare(variants<Contacts...>, Scenario&& scenario, const CompareOptions& options,
                   Figures... figures) {
  const std::string who = "grain::io::compare";
  constexpr std::size_t n = sizeof...(Contacts);
  if constexpr (n == 0)
    throw InputError(who + ": variants = <> (empty) is invalid; valid: at least one contact "
                           "type, e.g. variants<Interaction<normal::Hertz<>>>");
  if constexpr (sizeof...(Figures) == 0)
    throw InputError(who + ": figures = {} (none) is invalid; valid: at least one figure, e.g. "
                           "io::column(name, f)");
  const CompareOptions& o = options;
  detail::check_compare_options(o, who);
  const std::vector<std::string> names = detail::variant_names<Contacts...>(o, who);

  Comparison result;
  result.rows.resize(n);
  for (std::size_t v = 0; v < n; ++v)
    result.rows[v].name = names[v];
  // output files first: a bad path fails before any variant runs
  std::optional<std::ofstream> table_file;
  if (!o.csv.empty()) table_file.emplace(Comparison::open_output(o.csv, who + " (csv)"));
  if (!o.history.empty()) detail::open_histories(result, o, who);

  const std::tuple<Figures...> figure_set{std::move(figures)...};
  std::size_t v = 0;
  auto run_one = [&]<class Contact>(std::type_identity<Contact>) {
    detail::run_variant<SimOf<Contact>>(scenario, o, figure_set, result.rows[v], result.figures,
                                        v == 0);
    if (o.out) {
      const auto& r = result.rows[v];
      std::fprintf(o.out, "compare: %zu/%zu %s: %ld steps of %zu particles in %.3f s\n", v + 1, n,
                   r.name.c_str(), r.steps, r.particles, r.seconds);
      std::fflush(o.out);
    }
    ++v;
  };
  (run_one(std::type_identity<Contacts>{}), ...);
  (void)run_one; // an empty list runs nothing

  detail::report_comparison(result, o, table_file, who);
  return result;
}

} // namespace grain::io
