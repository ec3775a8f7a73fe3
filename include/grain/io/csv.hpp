#pragma once
/// \file csv.hpp
/// Time histories as CSV files: one row per call (use with `io::every(interval, ...)`), a header
/// row first, every row flushed at once, so that a run that stops halfway leaves a valid file up
/// to that time. Values are written with 17 significant digits in the "C" locale.
///
/// \code
/// sim.run(1.0, io::every(1e-2, io::history("out/global.csv"),
///                        io::csv("out/probe.csv",
///                                io::column("x_7 [m]", [](const auto& s) {
///                                  return s.particles().position[s.index_of(7)].x(); }))));
/// \endcode
///
/// `io::history(path)` writes the global quantities of a simulation (SI units):
///
/// | column | meaning |
/// |---|---|
/// | `time [s]`, `step` | simulated time and step count |
/// | `particles` | number of particles |
/// | `contacts_pp`, `contacts_pw` | touching particle-particle and particle-wall contacts |
/// | `kinetic_energy [J]` | translational + rotational |
/// | `potential_energy [J]` | gravitational, relative to the origin |
/// | `elastic_energy [J]` | stored in the contacts |
/// | `mean_temperature [K]`, `heat_content [J]`, `heat_inflow [W]` | thermal simulations only: mean particle temperature, sum m c T, and the sum of the particles' heat rates (what walls, convection and dissipation bring in; exchanges between particles cancel) |
///
/// `io::csv(path, columns...)` writes `time [s]`, `step` and the given columns, each a header and
/// a function of the simulation returning a number (`io::column(name, f)`).

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <locale>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

namespace grain::io {

/// A CSV column: its header and a function of the simulation that returns its value.
template <class F>
struct Column {
  std::string name;
  F value;
};
template <class F>
Column<F> column(std::string name, F f) {
  return {std::move(name), std::move(f)};
}

/// The writer behind `io::csv` and `io::history`.
template <bool Global, class... Columns>
struct CsvWriter {
  std::string path;
  std::tuple<Columns...> columns;
  std::shared_ptr<std::ofstream> out{};

  template <class Sim>
  void start(const Sim& sim) {
    if (out) return; // a later run appends to the same file
    const std::filesystem::path p(path);
    if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
    out = std::make_shared<std::ofstream>(path);
    if (!*out) throw std::runtime_error("grain::io::csv: cannot open '" + path + "' for writing");
    out->imbue(std::locale::classic());
    *out << "time [s],step";
    if constexpr (Global) {
      *out << ",particles,contacts_pp,contacts_pw,kinetic_energy [J],potential_energy [J],"
              "elastic_energy [J]";
      if constexpr (Sim::thermal) *out << ",mean_temperature [K],heat_content [J],heat_inflow [W]";
    }
    std::apply([&](const auto&... c) { ((*out << ',' << quoted(c.name)), ...); }, columns);
    *out << '\n';
    out->flush();
    (void)sim;
  }

  template <class Sim>
  void operator()(const Sim& sim) {
    if (!out) start(sim);
    std::ostringstream row;
    row.imbue(std::locale::classic());
    row.precision(17);
    row << sim.time() << ',' << sim.step_count();
    if constexpr (Global) {
      const auto [pp, pw] = sim.contact_counts();
      row << ',' << sim.size() << ',' << pp << ',' << pw << ',' << sim.kinetic_energy() << ','
          << sim.potential_energy() << ',' << sim.elastic_energy();
      if constexpr (Sim::thermal) {
        double inflow = 0.0;
        for (double q : sim.particles().heat_rate) inflow += q;
        row << ',' << sim.mean_temperature() << ',' << sim.thermal_energy() << ',' << inflow;
      }
    }
    std::apply([&](const auto&... c) { ((row << ',' << static_cast<double>(c.value(sim))), ...); },
               columns);
    row << '\n';
    *out << row.str();
    out->flush();
  }

private:
  static std::string quoted(const std::string& s) {
    if (s.find_first_of(",\"\n") == std::string::npos) return s;
    std::string q = "\"";
    for (char ch : s) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
    return q + "\"";
  }
};

/// csv(path, columns...): time, step and the given columns, one row per call.
template <class... Columns>
CsvWriter<false, Columns...> csv(std::string path, Columns... columns) {
  return {std::move(path), {std::move(columns)...}};
}

/// history(path, columns...): the global quantities of the simulation (table in the file
/// comment), then the given columns.
template <class... Columns>
CsvWriter<true, Columns...> history(std::string path, Columns... columns) {
  return {std::move(path), {std::move(columns)...}};
}

} // namespace grain::io
